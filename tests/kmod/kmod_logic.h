/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The simulated SPI controller's own decisions, kept apart from the
 * kernel objects they serve so that a host test can compile and check
 * them (tests/unit/test_kmod_logic.c): how a message's transfers become
 * chip-select-low periods, how bus time follows the kernel's clock, and
 * when an interrupt line is handed to Linux.  Like the model, nothing
 * here needs more than mcp2510_compat.h.
 */
#ifndef MCP2510_SIM_KMOD_LOGIC_H
#define MCP2510_SIM_KMOD_LOGIC_H

#include "../sim/mcp2510_sim.h"

#ifdef __KERNEL__
#include <linux/irq.h>
#include <linux/math64.h>
#else
/* the kernel's trigger type values (include/linux/irq.h) */
#define IRQ_TYPE_EDGE_RISING	0x00000001
#define IRQ_TYPE_EDGE_FALLING	0x00000002
#define IRQ_TYPE_EDGE_BOTH	(IRQ_TYPE_EDGE_FALLING | IRQ_TYPE_EDGE_RISING)
#define IRQ_TYPE_LEVEL_HIGH	0x00000004
#define IRQ_TYPE_LEVEL_LOW	0x00000008
#define IRQ_TYPE_SENSE_MASK	0x0000000f
static inline u64 div_u64(u64 dividend, u32 divisor)
{
	return dividend / divisor;
}
#endif

/* ---- Chip-select periods ------------------------------------------------ */

/* What the period logic needs of one struct spi_transfer. */
struct mcp2510_sim_xfer {
	const void *tx;		/* NULL: the controller clocks out zeros */
	u32 len;
	u32 speed_hz;
	bool cs_change;		/* CS rises after this transfer (but for the last) */
	bool last;		/* the message's last transfer: CS rises anyway */
};

/*
 * The chip acts on whole CS-low periods, so a message's transfers are
 * gathered into one buffer until CS rises, and each then takes its share
 * of what came back, in order.
 */
struct mcp2510_sim_period {
	u8 *tx, *rx;
	size_t cap;
	size_t len;		/* bytes gathered for the period under way */
	size_t given;		/* bytes of it handed back to transfers */
	u64 clock_ns;		/* its transfers' time under the SPI timing in force */
};

void mcp2510_sim_period_init(struct mcp2510_sim_period *p, u8 *tx, u8 *rx,
			     size_t cap);
/*
 * Gather one transfer: 1 when CS rises after it (run the period now), 0
 * when the period goes on, -EMSGSIZE when it does not fit.
 */
int mcp2510_sim_period_add(struct mcp2510_sim_period *p,
			   const struct mcp2510_sim_xfer *x,
			   struct sim_spi_bus *sb, u32 chip_max_hz);
/* After the period ran: the next transfer's share of MISO (rx may be NULL). */
void mcp2510_sim_period_give(struct mcp2510_sim_period *p, void *rx, u32 len);
/* Start gathering the next period. */
void mcp2510_sim_period_next(struct mcp2510_sim_period *p);

/* ---- Bus time ----------------------------------------------------------- */

/*
 * Bus time follows a real clock slowed down by time_scale:
 *	model = base_model_ns + (real - base_real_ns) / time_scale,
 * rebased whenever time_scale changes, so bus time never jumps.  The
 * model may lag the clock by MCP2510_SIM_MAX_LAG_NS of real time at most;
 * beyond, bus time stalls (kmod_clock.c says why) and stalls counts it:
 * a measurement taken across a stall is not one of the bus's real pace.
 */
#define MCP2510_SIM_MAX_LAG_NS	10000000ULL

struct mcp2510_sim_clock {
	u64 base_real_ns;
	u64 base_model_ns;
	u32 time_scale;
	u64 stalls;
};

void mcp2510_sim_clock_start(struct mcp2510_sim_clock *c, u64 real,
			     u32 time_scale);
void mcp2510_sim_clock_set_scale(struct mcp2510_sim_clock *c, u64 real,
				 u32 time_scale);
/* Bus time at real, for a model whose next event is next_event (U64_MAX: none). */
u64 mcp2510_sim_clock_model(struct mcp2510_sim_clock *c, u64 real,
			    u64 next_event);
/* The real time bus time reaches model (at once if past); false if out of reach. */
bool mcp2510_sim_clock_real(const struct mcp2510_sim_clock *c, u64 model,
			    u64 *real);

/* ---- Interrupt lines ------------------------------------------------------ */

/* One output pin as the interrupt controller sees it. */
struct mcp2510_sim_line {
	bool level;		/* true: the pin is high */
	bool masked;
	bool edge_pending;
	bool due_set;		/* a delivery is scheduled for due_ns */
	unsigned int type;	/* IRQ_TYPE_* */
	u32 edge_miss;		/* falling edges still to drop */
	u64 due_ns;		/* real time the scheduled delivery is due */
	u64 delivered;		/* interrupts handed to the flow handler */
	u64 edges_missed;	/* falling edges dropped for edge_miss */
};

bool mcp2510_sim_line_asserted(const struct mcp2510_sim_line *line);
/* The pin moves to level: an edge of the line's type is latched. */
void mcp2510_sim_line_set_level(struct mcp2510_sim_line *line, bool level);
/*
 * Something changed (pin, mask) at real time now: true when the line
 * wants delivery, which is then due delay_ns later (or at an earlier time
 * already scheduled).  The caller schedules a pass at line->due_ns.
 */
bool mcp2510_sim_line_kick(struct mcp2510_sim_line *line, u64 now,
			   u64 delay_ns);
/*
 * A delivery pass at real time now: true when the line is to be handed
 * to Linux (and counted); a line still waiting lowers *next_due to its
 * due time.  A level line still asserted when it is unmasked again is
 * delivered again after the delay: kick it then.
 */
bool mcp2510_sim_line_take(struct mcp2510_sim_line *line, u64 now,
			   u64 *next_due);

#endif /* MCP2510_SIM_KMOD_LOGIC_H */
