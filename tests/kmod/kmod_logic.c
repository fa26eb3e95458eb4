// SPDX-License-Identifier: GPL-2.0
/*
 * The simulated SPI controller's decisions that need no kernel object:
 * kmod_logic.h says what each does; kmod_spi.c, kmod_clock.c and
 * kmod_irq.c apply them to the kernel's structures.
 */
#include "kmod_logic.h"

/* ---- Chip-select periods ------------------------------------------------ */

void mcp2510_sim_period_init(struct mcp2510_sim_period *p, u8 *tx, u8 *rx,
			     size_t cap)
{
	p->tx = tx;
	p->rx = rx;
	p->cap = cap;
	mcp2510_sim_period_next(p);
}

int mcp2510_sim_period_add(struct mcp2510_sim_period *p,
			   const struct mcp2510_sim_xfer *x,
			   struct sim_spi_bus *sb, u32 chip_max_hz)
{
	if (x->len > p->cap - p->len)
		return -EMSGSIZE;
	if (x->tx)
		memcpy(p->tx + p->len, x->tx, x->len);
	else
		memset(p->tx + p->len, 0, x->len);
	p->len += x->len;
	/* each transfer pays its own set-up and may ask for its own clock */
	p->clock_ns += sim_spi_xfer_ns(sb, x->len, x->speed_hz, chip_max_hz);
	return x->last || x->cs_change;
}

void mcp2510_sim_period_give(struct mcp2510_sim_period *p, void *rx, u32 len)
{
	if (rx)
		memcpy(rx, p->rx + p->given, len);
	p->given += len;
}

void mcp2510_sim_period_next(struct mcp2510_sim_period *p)
{
	p->len = 0;
	p->given = 0;
	p->clock_ns = 0;
}

/* ---- Bus time ----------------------------------------------------------- */

void mcp2510_sim_clock_start(struct mcp2510_sim_clock *c, u64 real,
			     u32 time_scale)
{
	c->base_real_ns = real;
	c->base_model_ns = 0;
	c->time_scale = time_scale;
	c->stalls = 0;
}

static u64 clock_unclamped(const struct mcp2510_sim_clock *c, u64 real)
{
	u64 elapsed = real > c->base_real_ns ? real - c->base_real_ns : 0;

	return c->base_model_ns + div_u64(elapsed, c->time_scale);
}

void mcp2510_sim_clock_set_scale(struct mcp2510_sim_clock *c, u64 real,
				 u32 time_scale)
{
	c->base_model_ns = clock_unclamped(c, real);
	c->base_real_ns = real;
	c->time_scale = time_scale;
}

u64 mcp2510_sim_clock_model(struct mcp2510_sim_clock *c, u64 real,
			    u64 next_event)
{
	u64 now = clock_unclamped(c, real);
	u64 max_lag = div_u64(MCP2510_SIM_MAX_LAG_NS, c->time_scale);

	if (next_event == U64_MAX || now <= next_event + max_lag)
		return now;
	/* the model is too far behind: bus time stalls where it may lag to */
	c->base_model_ns = next_event + max_lag;
	c->base_real_ns = real;
	c->stalls++;
	return c->base_model_ns;
}

bool mcp2510_sim_clock_real(const struct mcp2510_sim_clock *c, u64 model,
			    u64 *real)
{
	u64 ahead = model > c->base_model_ns ? model - c->base_model_ns : 0;

	/* ktime_t is signed: a time past its range is as good as never */
	if (__builtin_mul_overflow(ahead, (u64)c->time_scale, real) ||
	    __builtin_add_overflow(*real, c->base_real_ns, real) ||
	    *real > U64_MAX >> 1)
		return false;
	return true;
}

/* ---- Interrupt lines ------------------------------------------------------ */

bool mcp2510_sim_line_asserted(const struct mcp2510_sim_line *line)
{
	switch (line->type & IRQ_TYPE_SENSE_MASK) {
	case IRQ_TYPE_LEVEL_LOW:
		return !line->level;
	case IRQ_TYPE_LEVEL_HIGH:
		return line->level;
	default:
		return line->edge_pending;
	}
}

static bool line_wants_delivery(const struct mcp2510_sim_line *line)
{
	return !line->masked && mcp2510_sim_line_asserted(line);
}

void mcp2510_sim_line_set_level(struct mcp2510_sim_line *line, bool level)
{
	bool rising = level && !line->level;
	bool falling = !level && line->level;

	line->level = level;
	if (!(rising && (line->type & IRQ_TYPE_EDGE_RISING)) &&
	    !(falling && (line->type & IRQ_TYPE_EDGE_FALLING)))
		return;
	if (falling && line->edge_miss) {
		line->edge_miss--;
		line->edges_missed++;
		return;
	}
	line->edge_pending = true;
}

bool mcp2510_sim_line_kick(struct mcp2510_sim_line *line, u64 now,
			   u64 delay_ns)
{
	if (!line_wants_delivery(line))
		return false;
	if (!line->due_set || line->due_ns > now + delay_ns) {
		line->due_ns = now + delay_ns;
		line->due_set = true;
	}
	return true;
}

bool mcp2510_sim_line_take(struct mcp2510_sim_line *line, u64 now,
			   u64 *next_due)
{
	if (!line_wants_delivery(line)) {
		/* deasserted or masked meanwhile: the next kick starts afresh */
		line->due_set = false;
		return false;
	}
	if (line->due_set && line->due_ns > now) {
		if (line->due_ns < *next_due)
			*next_due = line->due_ns;
		return false;
	}
	line->due_set = false;
	line->delivered++;
	return true;
}
