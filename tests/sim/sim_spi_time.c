// SPDX-License-Identifier: GPL-2.0
/*
 * What SPI costs in time: the arithmetic every harness shares, so that the
 * kernel module, the userspace transport and the cmocka harness charge a
 * transfer the same.  mcp2510_sim.h says what the parameters mean.
 */
#include "sim_private.h"

#define SIM_BITS_PER_BYTE	8
#define SIM_MCP2510_SCK_MAX_HZ	5000000U	/* DS21291 SPI AC characteristics */
#define SIM_MCP2515_SCK_MAX_HZ	10000000U	/* DS21801 SPI AC characteristics */

void sim_spi_bus_init(struct sim_spi_bus *sb)
{
	memset(sb, 0, sizeof(*sb));
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

u64 sim_spi_clock_ns(const struct sim_spi_timing *t, u32 len, u32 speed_hz,
		     u32 chip_max_hz)
{
	u64 bits = (u64)len * SIM_BITS_PER_BYTE;
	u32 hz;

	if (!t->enabled || !len)
		return 0;
	hz = sim_spi_speed_hz(t, speed_hz, chip_max_hz);
	if (!hz)
		return 0;	/* nobody set a clock: nothing to charge */
	return sim_div_u64(bits * SIM_NS_PER_SEC + hz - 1, hz);
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
		       u64 clock_ns)
{
	if (sb->timing.enabled)
		m->at += (u64)sb->timing.cs_setup_ns + clock_ns +
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

u64 sim_spi_irq_due(const struct sim_spi_bus *sb, u64 asserted_at)
{
	if (!sb->timing.enabled)
		return asserted_at;
	return asserted_at + sb->timing.irq_latency_ns;
}
