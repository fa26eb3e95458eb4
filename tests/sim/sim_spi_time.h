/* SPDX-License-Identifier: GPL-2.0 */
/*
 * SPI time: what a chip-select period, a message and an interrupt cost on
 * a board (sim_spi_time.c), and the board profiles (sim_spi_profile.c).
 */
#ifndef MCP2510_SIM_SPI_TIME_H
#define MCP2510_SIM_SPI_TIME_H

#include "mcp2510_compat.h"

struct sim_chip;

/*
 * The model's transfers take no time of their own; a harness that wants
 * SPI to cost what it costs on a board keeps one struct sim_spi_bus per
 * SPI controller and asks it when each chip-select-low period ends.  The
 * chip then acts (sim_chip_spi()) at that time, when CS rises.  A message
 * is one or more periods: its host overhead comes first, then per period
 * CS setup, each transfer's cost (sim_spi_xfer_ns()), CS hold.  Messages
 * to any chip on the controller queue behind each other.  With enabled
 * false everything happens at the time asked for, as without this.
 *
 * The costs follow a controller driver like spi-bcm2835 under the SPI
 * core (docs/performance.md gives each profile's figures and sources):
 * every transfer pays the driver's set-up; bytes take 8 clocks plus
 * idle_clocks; a transfer of at least speed / poll_hz_per_byte bytes runs
 * interrupt-driven and pays a thread wake-up, one of at least dma_min_len
 * bytes runs by DMA (no idle clock) and pays dma_ns.  Wake-ups and
 * interrupt latency are drawn from a distribution with the given median
 * and 99th percentile and a tail beyond (sim_spi_draw()), from the bus's
 * seeded generator, so a run repeats for a seed.
 */
struct sim_spi_timing {
	bool enabled;
	u32 msg_ns;		/* host cost of one message: queueing, set-up, completion */
	u32 cs_setup_ns;	/* CS falling edge to the first SCK edge */
	u32 cs_hold_ns;		/* last SCK edge to CS rising, plus CS high time */
	u32 ctlr_max_hz;	/* the controller's fastest SCK; 0: no limit of its own */
	u32 irq_latency_ns;	/* INT falling to the hard interrupt handler: median */
	u32 irq_latency_p99_ns;	/* its 99th percentile; <= median: constant */
	u32 wake_ns;		/* a handler thread waking after its interrupt: median */
	u32 wake_p99_ns;	/* its 99th percentile; <= median: constant */
	u32 xfer_ns;		/* the controller driver's set-up of one transfer */
	u32 idle_clocks;	/* idle SCK cycles after each byte (not by DMA) */
	u32 poll_hz_per_byte;	/* interrupt-driven from speed / this bytes; 0: never */
	u32 dma_min_len;	/* DMA from this many bytes; 0: never */
	u32 dma_ns;		/* DMA set-up and completion of one transfer */
};

struct sim_spi_bus {
	struct sim_spi_timing timing;
	u64 free_at;		/* the last message handed to the bus ends here */
	u32 rng;		/* the draws' generator state; see sim_spi_seed() */
};

/* One message under way on a struct sim_spi_bus. */
struct sim_spi_msg {
	u64 start;		/* when it got the bus */
	u64 at;			/* end of its last period so far */
};

/* Timing off, bus free, generator at seed 0. */
void sim_spi_bus_init(struct sim_spi_bus *sb);
/* Restart the draws: the same seed gives the same sequence. */
void sim_spi_seed(struct sim_spi_bus *sb, u32 seed);
/* The fastest SCK the chip's data sheet allows: 5 MHz MCP2510, 10 MHz MCP2515. */
u32 sim_chip_sck_max_hz(const struct sim_chip *chip);
/*
 * The clock a transfer asking for speed_hz runs at: no faster than the
 * controller and the chip allow (speed_hz 0: as fast as they allow).
 */
u32 sim_spi_speed_hz(const struct sim_spi_timing *t, u32 speed_hz,
		     u32 chip_max_hz);
/*
 * SCK time of len bytes at that clock, 8 + idle_clocks cycles a byte,
 * rounded up to whole ns; 0 when off.
 */
u64 sim_spi_clock_ns(const struct sim_spi_timing *t, u32 len, u32 speed_hz,
		     u32 chip_max_hz);
/* How the controller runs a transfer of len bytes at speed_hz. */
enum sim_spi_xfer_mode {
	SIM_SPI_POLL,
	SIM_SPI_IRQ,
	SIM_SPI_DMA,
};
enum sim_spi_xfer_mode sim_spi_xfer_mode(const struct sim_spi_timing *t,
					 u32 len, u32 speed_hz,
					 u32 chip_max_hz);
/*
 * One transfer inside a CS-low period: set-up, SCK time and, by its
 * mode, a drawn wake-up or the DMA cost; 0 when off.
 */
u64 sim_spi_xfer_ns(struct sim_spi_bus *sb, u32 len, u32 speed_hz,
		    u32 chip_max_hz);
/* A message wants the bus at now: it starts when the bus is free, after its overhead. */
void sim_spi_msg_begin(struct sim_spi_bus *sb, struct sim_spi_msg *m, u64 now);
/* The next CS-low period, xfer_ns of transfers: returns when CS rises. */
u64 sim_spi_msg_period(const struct sim_spi_bus *sb, struct sim_spi_msg *m,
		       u64 xfer_ns);
/* The message is done: the bus is free at m->at; the chip is charged for it. */
void sim_spi_msg_end(struct sim_spi_bus *sb, struct sim_spi_msg *m,
		     struct sim_chip *chip);
/*
 * One draw from a distribution with this median and 99th percentile:
 * piecewise uniform, half from median / 2 to the median, 49 % up to the
 * 99th percentile, 1 % on to 4 times that (the tail).  p99 <= median:
 * always the median.  *rng advances.
 */
u32 sim_spi_draw(u32 *rng, u32 median, u32 p99);
/* INT falling to the handler thread running: a drawn latency plus wake-up. */
u64 sim_spi_irq_latency_ns(const struct sim_spi_timing *t, u32 *rng);
/* When an interrupt whose line was asserted at asserted_at reaches its handler. */
u64 sim_spi_irq_due(struct sim_spi_bus *sb, u64 asserted_at);

/*
 * Board profiles (sim_spi_profile.c, docs/performance.md): every time
 * constant multiplied by scale_pct / 100 (clock rates and thresholds
 * stay).  SIM_SPI_PROFILE_NONE turns SPI time off.
 */
enum sim_spi_profile {
	SIM_SPI_PROFILE_NONE,
	SIM_SPI_PROFILE_PI,
	SIM_SPI_PROFILE_PI_RT,
	SIM_SPI_PROFILE_SLOW,
	SIM_SPI_PROFILE_COUNT
};

#define SIM_SPI_SCALE_MIN_PCT	10
#define SIM_SPI_SCALE_MAX_PCT	1000
/* 0, or -EINVAL for an unknown profile or a scale out of range. */
int sim_spi_profile_timing(unsigned int profile, u32 scale_pct,
			   struct sim_spi_timing *t);
/* "none", "pi", "pi-rt", "slow"; NULL past the end. */
const char *sim_spi_profile_name(unsigned int profile);
/* The profile called name (len bytes, no NUL needed), or -EINVAL. */
int sim_spi_profile_find(const char *name, size_t len);

#endif /* MCP2510_SIM_SPI_TIME_H */
