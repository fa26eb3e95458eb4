// SPDX-License-Identifier: GPL-2.0
/*
 * Board profiles for SPI time: what a Raspberry Pi class board's SPI
 * controller (spi-bcm2835 under the SPI core, chip select on a GPIO) and
 * its interrupt path cost, on a stock kernel, on PREEMPT_RT and on an
 * older, slower ARM board with the same controller.  docs/performance.md
 * gives the source of every figure; where nothing is published the value
 * is the one that flatters this project's driver least (it packs several
 * chip-select periods into one message, so per-transfer and chip-select
 * costs are taken high and the per-message cost low).
 */
#include "sim_private.h"

/* spi-bcm2835 (Linux 6.1): polling_limit_us = 30 at 9 clocks a byte */
#define SIM_BCM2835_HZ_PER_BYTE	300000U
#define SIM_BCM2835_IDLE_CLOCKS	1U
#define SIM_BCM2835_DMA_MIN_LEN	96U

static const struct sim_spi_timing sim_spi_profiles[SIM_SPI_PROFILE_COUNT] = {
	[SIM_SPI_PROFILE_PI] = {
		.enabled = true,
		.msg_ns = 5000,
		.cs_setup_ns = 1000,
		.cs_hold_ns = 3000,
		.xfer_ns = 4000,
		.irq_latency_ns = 4000,
		.irq_latency_p99_ns = 20000,
		.wake_ns = 16000,
		.wake_p99_ns = 100000,
		.dma_ns = 15000,
	},
	[SIM_SPI_PROFILE_PI_RT] = {
		.enabled = true,
		.msg_ns = 6000,
		.cs_setup_ns = 1000,
		.cs_hold_ns = 3000,
		.xfer_ns = 4500,
		.irq_latency_ns = 5000,
		.irq_latency_p99_ns = 12000,
		.wake_ns = 12000,
		.wake_p99_ns = 35000,
		.dma_ns = 15000,
	},
	[SIM_SPI_PROFILE_SLOW] = {
		.enabled = true,
		.msg_ns = 20000,
		.cs_setup_ns = 2000,
		.cs_hold_ns = 6000,
		.xfer_ns = 10000,
		.irq_latency_ns = 10000,
		.irq_latency_p99_ns = 50000,
		.wake_ns = 40000,
		.wake_p99_ns = 300000,
		.dma_ns = 40000,
	},
};

static const char *const sim_spi_profile_names[SIM_SPI_PROFILE_COUNT] = {
	[SIM_SPI_PROFILE_NONE] = "none",
	[SIM_SPI_PROFILE_PI] = "pi",
	[SIM_SPI_PROFILE_PI_RT] = "pi-rt",
	[SIM_SPI_PROFILE_SLOW] = "slow",
};

static u32 sim_spi_scaled(u32 ns, u32 scale_pct)
{
	return (u32)sim_div_u64((u64)ns * scale_pct, 100);
}

int sim_spi_profile_timing(unsigned int profile, u32 scale_pct,
			   struct sim_spi_timing *t)
{
	const struct sim_spi_timing *p;

	if (profile >= SIM_SPI_PROFILE_COUNT ||
	    scale_pct < SIM_SPI_SCALE_MIN_PCT ||
	    scale_pct > SIM_SPI_SCALE_MAX_PCT)
		return -EINVAL;
	p = &sim_spi_profiles[profile];
	memset(t, 0, sizeof(*t));
	if (!p->enabled)
		return 0;
	t->enabled = true;
	t->msg_ns = sim_spi_scaled(p->msg_ns, scale_pct);
	t->cs_setup_ns = sim_spi_scaled(p->cs_setup_ns, scale_pct);
	t->cs_hold_ns = sim_spi_scaled(p->cs_hold_ns, scale_pct);
	t->xfer_ns = sim_spi_scaled(p->xfer_ns, scale_pct);
	t->irq_latency_ns = sim_spi_scaled(p->irq_latency_ns, scale_pct);
	t->irq_latency_p99_ns = sim_spi_scaled(p->irq_latency_p99_ns, scale_pct);
	t->wake_ns = sim_spi_scaled(p->wake_ns, scale_pct);
	t->wake_p99_ns = sim_spi_scaled(p->wake_p99_ns, scale_pct);
	t->dma_ns = sim_spi_scaled(p->dma_ns, scale_pct);
	/* the same controller driver on every board */
	t->idle_clocks = SIM_BCM2835_IDLE_CLOCKS;
	t->poll_hz_per_byte = SIM_BCM2835_HZ_PER_BYTE;
	t->dma_min_len = SIM_BCM2835_DMA_MIN_LEN;
	return 0;
}

const char *sim_spi_profile_name(unsigned int profile)
{
	return profile < SIM_SPI_PROFILE_COUNT ? sim_spi_profile_names[profile] :
						 NULL;
}

int sim_spi_profile_find(const char *name, size_t len)
{
	unsigned int n;
	size_t i;

	for (n = 0; n < SIM_SPI_PROFILE_COUNT; n++) {
		const char *s = sim_spi_profile_names[n];

		for (i = 0; i < len && s[i] && s[i] == name[i]; i++)
			;
		if (i == len && !s[i])
			return (int)n;
	}
	return -EINVAL;
}
