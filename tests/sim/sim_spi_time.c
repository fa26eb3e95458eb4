// SPDX-License-Identifier: GPL-2.0
/*
 * What SPI costs in time: the arithmetic every harness shares, so that the
 * kernel module, the userspace transport and the cmocka harness charge a
 * transfer the same.  sim_spi_time.h says what the parameters mean,
 * sim_spi_profile.c gives boards' values.
 */
#include "sim_private.h"

#define SIM_BITS_PER_BYTE	8
#define SIM_MCP2510_SCK_MAX_HZ	5000000U	/* DS21291 SPI AC characteristics */
#define SIM_MCP2515_SCK_MAX_HZ	10000000U	/* DS21801 SPI AC characteristics */

/* sim_spi_draw(): quantiles in 1/65536, and the tail's reach */
#define SIM_DRAW_ONE		65536U
#define SIM_DRAW_MEDIAN		32768U
#define SIM_DRAW_P99		64881U	/* ceil(0.99 * 65536) */
#define SIM_DRAW_TAIL		4U	/* the slowest draw: 4 x the 99th percentile */

void sim_spi_bus_init(struct sim_spi_bus *sb)
{
	memset(sb, 0, sizeof(*sb));
}

void sim_spi_seed(struct sim_spi_bus *sb, u32 seed)
{
	sb->rng = seed;
}

u32 sim_chip_sck_max_hz(const struct sim_chip *chip)
{
	return chip->variant == SIM_MCP2510 ? SIM_MCP2510_SCK_MAX_HZ :
					      SIM_MCP2515_SCK_MAX_HZ;
}

static u32 sim_min_nonzero(u32 a, u32 b)
{
	if (!a)
		return b;
	if (!b)
		return a;
	return a < b ? a : b;
}

u32 sim_spi_speed_hz(const struct sim_spi_timing *t, u32 speed_hz,
		     u32 chip_max_hz)
{
	return sim_min_nonzero(sim_min_nonzero(speed_hz, t->ctlr_max_hz),
			       chip_max_hz);
}

static u64 sim_spi_cycles_ns(u64 cycles, u32 hz)
{
	if (!hz)
		return 0;	/* nobody set a clock: nothing to charge */
	return sim_div_u64(cycles * SIM_NS_PER_SEC + hz - 1, hz);
}

u64 sim_spi_clock_ns(const struct sim_spi_timing *t, u32 len, u32 speed_hz,
		     u32 chip_max_hz)
{
	if (!t->enabled || !len)
		return 0;
	return sim_spi_cycles_ns((u64)len * (SIM_BITS_PER_BYTE + t->idle_clocks),
				 sim_spi_speed_hz(t, speed_hz, chip_max_hz));
}

/*
 * spi-bcm2835's transfer_one(): polling below len = speed / hz_per_byte
 * (its polling_limit_us turned into bytes at 9 clocks a byte), else DMA
 * when the transfer is long enough, else interrupt-driven.
 */
enum sim_spi_xfer_mode sim_spi_xfer_mode(const struct sim_spi_timing *t,
					 u32 len, u32 speed_hz,
					 u32 chip_max_hz)
{
	u32 limit;

	if (!t->poll_hz_per_byte)
		return SIM_SPI_POLL;
	limit = sim_spi_speed_hz(t, speed_hz, chip_max_hz) / t->poll_hz_per_byte;
	if (len < limit)
		return SIM_SPI_POLL;
	if (t->dma_min_len && len >= t->dma_min_len)
		return SIM_SPI_DMA;
	return SIM_SPI_IRQ;
}

u64 sim_spi_xfer_ns(struct sim_spi_bus *sb, u32 len, u32 speed_hz,
		    u32 chip_max_hz)
{
	const struct sim_spi_timing *t = &sb->timing;
	u64 ns;

	if (!t->enabled || !len)
		return 0;
	ns = t->xfer_ns;
	switch (sim_spi_xfer_mode(t, len, speed_hz, chip_max_hz)) {
	case SIM_SPI_DMA:
		/* DMA clocks the bytes back to back */
		return ns + t->dma_ns +
		       sim_spi_cycles_ns((u64)len * SIM_BITS_PER_BYTE,
					 sim_spi_speed_hz(t, speed_hz,
							  chip_max_hz));
	case SIM_SPI_IRQ:
		/* the pump thread sleeps until the FIFO interrupt wakes it */
		ns += sim_spi_draw(&sb->rng, t->wake_ns, t->wake_p99_ns);
		break;
	case SIM_SPI_POLL:
		break;
	}
	return ns + sim_spi_clock_ns(t, len, speed_hz, chip_max_hz);
}

void sim_spi_msg_begin(struct sim_spi_bus *sb, struct sim_spi_msg *m, u64 now)
{
	if (!sb->timing.enabled) {
		m->start = now;
		m->at = now;
		return;
	}
	/* messages from every chip queue on the one bus */
	m->start = now > sb->free_at ? now : sb->free_at;
	m->at = m->start + sb->timing.msg_ns;
}

u64 sim_spi_msg_period(const struct sim_spi_bus *sb, struct sim_spi_msg *m,
		       u64 xfer_ns)
{
	if (sb->timing.enabled)
		m->at += (u64)sb->timing.cs_setup_ns + xfer_ns +
			 sb->timing.cs_hold_ns;
	return m->at;
}

void sim_spi_msg_end(struct sim_spi_bus *sb, struct sim_spi_msg *m,
		     struct sim_chip *chip)
{
	if (!sb->timing.enabled)
		return;
	if (m->at > sb->free_at)
		sb->free_at = m->at;
	chip->counters.spi_busy_ns += m->at - m->start;
}

/* A Weyl sequence through a 32-bit finaliser: every seed, even 0, is fine. */
static u32 sim_spi_random(u32 *rng)
{
	u32 z = *rng += 0x9e3779b9u;

	z = (z ^ (z >> 16)) * 0x85ebca6bu;
	z = (z ^ (z >> 13)) * 0xc2b2ae35u;
	return z ^ (z >> 16);
}

/* from + (to - from) * (q - q0) / (q1 - q0), to >= from */
static u32 sim_spi_lerp(u32 from, u32 to, u32 q, u32 q0, u32 q1)
{
	return from + (u32)sim_div_u64((u64)(to - from) * (q - q0), q1 - q0);
}

u32 sim_spi_draw(u32 *rng, u32 median, u32 p99)
{
	u32 q = sim_spi_random(rng) >> 16;
	u64 top = (u64)p99 * SIM_DRAW_TAIL;

	if (p99 <= median)
		return median;
	if (q < SIM_DRAW_MEDIAN)
		return sim_spi_lerp(median / 2, median, q, 0, SIM_DRAW_MEDIAN);
	if (q < SIM_DRAW_P99)
		return sim_spi_lerp(median, p99, q, SIM_DRAW_MEDIAN,
				    SIM_DRAW_P99);
	return sim_spi_lerp(p99, top > U32_MAX ? U32_MAX : (u32)top, q,
			    SIM_DRAW_P99, SIM_DRAW_ONE);
}

u64 sim_spi_irq_latency_ns(const struct sim_spi_timing *t, u32 *rng)
{
	u64 ns = sim_spi_draw(rng, t->irq_latency_ns, t->irq_latency_p99_ns);

	return ns + sim_spi_draw(rng, t->wake_ns, t->wake_p99_ns);
}

u64 sim_spi_irq_due(struct sim_spi_bus *sb, u64 asserted_at)
{
	if (!sb->timing.enabled)
		return asserted_at;
	return asserted_at + sim_spi_irq_latency_ns(&sb->timing, &sb->rng);
}
