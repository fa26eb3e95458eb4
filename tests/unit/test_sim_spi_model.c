// SPDX-License-Identifier: GPL-2.0
/*
 * The SPI controller model's arithmetic (sim_spi_time.h,
 * sim_spi_profile.c): which transfers spi-bcm2835 polls, runs by interrupt
 * or by DMA, what a transfer and a chip-select period cost, the drawn
 * latencies' median, 99th percentile and tail for a seed, and the board
 * profiles with their cost scale.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim_helpers.h"

#define MCP2510_HZ	5000000
#define MCP2515_HZ	10000000
#define DRAWS		20000

static struct sim_spi_timing profile(unsigned int p, u32 scale_pct)
{
	struct sim_spi_timing t;

	assert_int_equal(sim_spi_profile_timing(p, scale_pct, &t), 0);
	return t;
}

/* polling_limit_us 30 at 9 clocks a byte: below speed / 300000 bytes */
static void test_bcm2835_transfer_modes(void **state)
{
	struct sim_spi_timing t = profile(SIM_SPI_PROFILE_PI, 100);

	(void)state;
	assert_int_equal(sim_spi_xfer_mode(&t, 15, 0, MCP2510_HZ), SIM_SPI_POLL);
	/* the MCP2510's 16-byte TX buffer write goes interrupt-driven */
	assert_int_equal(sim_spi_xfer_mode(&t, 16, 0, MCP2510_HZ), SIM_SPI_IRQ);
	assert_int_equal(sim_spi_xfer_mode(&t, 32, 0, MCP2515_HZ), SIM_SPI_POLL);
	assert_int_equal(sim_spi_xfer_mode(&t, 33, 0, MCP2515_HZ), SIM_SPI_IRQ);
	assert_int_equal(sim_spi_xfer_mode(&t, 96, 0, MCP2515_HZ), SIM_SPI_DMA);
	/* a slower clock asked for lowers the limit */
	assert_int_equal(sim_spi_xfer_mode(&t, 4, 1000000, MCP2510_HZ), SIM_SPI_IRQ);
	t.poll_hz_per_byte = 0;
	assert_int_equal(sim_spi_xfer_mode(&t, 200, 0, MCP2510_HZ), SIM_SPI_POLL);
}

/* set-up, 9 clocks a byte, the wake-up only in interrupt mode */
static void test_transfer_costs(void **state)
{
	struct sim_spi_bus sb;

	(void)state;
	sim_spi_bus_init(&sb);
	sb.timing = profile(SIM_SPI_PROFILE_PI, 100);
	/* READ STATUS: 2 bytes, 18 clocks at 5 MHz */
	assert_int_equal(sim_spi_xfer_ns(&sb, 2, 0, MCP2510_HZ), 4000 + 3600);
	/* READ of a receive buffer: 15 bytes, still polled */
	assert_int_equal(sim_spi_xfer_ns(&sb, 15, 0, MCP2510_HZ), 4000 + 27000);
	/* 16 bytes: the pump thread sleeps for at least half the median wake-up */
	assert_true(sim_spi_xfer_ns(&sb, 16, 0, MCP2510_HZ) >=
		    4000 + 28800 + 8000);
	/* DMA: no idle clock, its own set-up */
	assert_int_equal(sim_spi_xfer_ns(&sb, 100, 0, MCP2515_HZ),
			 4000 + 15000 + 80000);
	/* a period adds CS set-up and CS high time around its transfers */
	{
		struct sim_spi_msg m;

		sim_spi_msg_begin(&sb, &m, 0);
		assert_int_equal(m.at, 5000);
		assert_int_equal(sim_spi_msg_period(&sb, &m, 7600),
				 5000 + 1000 + 7600 + 3000);
	}
	sb.timing.enabled = false;
	assert_int_equal(sim_spi_xfer_ns(&sb, 16, 0, MCP2510_HZ), 0);
}

static int cmp_u32(const void *a, const void *b)
{
	u32 x = *(const u32 *)a, y = *(const u32 *)b;

	return x < y ? -1 : x > y;
}

static u32 *draws(u32 seed, u32 median, u32 p99)
{
	u32 *v = calloc(DRAWS, sizeof(*v));
	unsigned int i;

	assert_non_null(v);
	for (i = 0; i < DRAWS; i++)
		v[i] = sim_spi_draw(&seed, median, p99);
	return v;
}

/* draws at most limit, in 1/1000 */
static unsigned int share_below(const u32 *v, u32 limit)
{
	unsigned int i, n = 0;

	for (i = 0; i < DRAWS; i++)
		n += v[i] <= limit;
	return n * 1000 / DRAWS;
}

/* the median and the 99th percentile asked for, a tail up to 4 x p99 */
static void test_draw_quantiles(void **state)
{
	u32 *v = draws(1, 16000, 100000);

	(void)state;
	assert_in_range(share_below(v, 16000), 490, 510);
	assert_in_range(share_below(v, 100000), 987, 993);
	qsort(v, DRAWS, sizeof(*v), cmp_u32);
	assert_true(v[0] >= 8000);
	assert_true(v[DRAWS - 1] > 200000);
	assert_true(v[DRAWS - 1] <= 400000);
	free(v);
}

/* the same seed, the same sequence; another seed, another one */
static void test_draw_seeded(void **state)
{
	u32 *a = draws(7, 4000, 20000), *b = draws(7, 4000, 20000);
	u32 *c = draws(8, 4000, 20000);
	u32 s = 0;

	(void)state;
	assert_memory_equal(a, b, DRAWS * sizeof(*a));
	assert_memory_not_equal(a, c, DRAWS * sizeof(*a));
	/* no tail asked for: a constant */
	assert_int_equal(sim_spi_draw(&s, 20000, 0), 20000);
	assert_int_equal(sim_spi_draw(&s, 20000, 20000), 20000);
	free(a);
	free(b);
	free(c);
}

/* INT to the handler thread: the interrupt's and the wake-up's draws */
static void test_irq_latency(void **state)
{
	struct sim_spi_bus sb;

	(void)state;
	sim_spi_bus_init(&sb);
	sb.timing = profile(SIM_SPI_PROFILE_PI, 100);
	sim_spi_seed(&sb, 3);
	assert_true(sim_spi_irq_due(&sb, 1000) >= 1000 + 2000 + 8000);
	sb.timing.enabled = false;
	assert_int_equal(sim_spi_irq_due(&sb, 1000), 1000);
}

/* every time constant scales, clocks and thresholds stay */
static void test_profile_scale(void **state)
{
	struct sim_spi_timing h = profile(SIM_SPI_PROFILE_PI, 50);
	struct sim_spi_timing one = profile(SIM_SPI_PROFILE_PI, 100);
	struct sim_spi_timing d = profile(SIM_SPI_PROFILE_PI, 200);
	struct sim_spi_timing t;

	(void)state;
	assert_int_equal(h.msg_ns * 2, one.msg_ns);
	assert_int_equal(d.msg_ns, one.msg_ns * 2);
	assert_int_equal(d.xfer_ns, one.xfer_ns * 2);
	assert_int_equal(d.cs_hold_ns, one.cs_hold_ns * 2);
	assert_int_equal(d.wake_p99_ns, one.wake_p99_ns * 2);
	assert_int_equal(d.irq_latency_ns, one.irq_latency_ns * 2);
	assert_int_equal(d.poll_hz_per_byte, one.poll_hz_per_byte);
	assert_int_equal(d.idle_clocks, 1);
	assert_int_equal(d.ctlr_max_hz, one.ctlr_max_hz);

	t = profile(SIM_SPI_PROFILE_NONE, 100);
	assert_false(t.enabled);
	assert_true(profile(SIM_SPI_PROFILE_PI_RT, 100).wake_p99_ns <
		    one.wake_p99_ns);
	assert_true(profile(SIM_SPI_PROFILE_SLOW, 100).xfer_ns > one.xfer_ns);
	assert_int_equal(sim_spi_profile_timing(SIM_SPI_PROFILE_COUNT, 100, &t),
			 -EINVAL);
	assert_int_equal(sim_spi_profile_timing(SIM_SPI_PROFILE_PI, 5, &t),
			 -EINVAL);
}

static void test_profile_names(void **state)
{
	(void)state;
	assert_int_equal(sim_spi_profile_find("pi", 2), SIM_SPI_PROFILE_PI);
	assert_int_equal(sim_spi_profile_find("pi-rt", 5), SIM_SPI_PROFILE_PI_RT);
	assert_int_equal(sim_spi_profile_find("pi-rt\n", 5), SIM_SPI_PROFILE_PI_RT);
	assert_int_equal(sim_spi_profile_find("slow", 4), SIM_SPI_PROFILE_SLOW);
	assert_int_equal(sim_spi_profile_find("none", 4), SIM_SPI_PROFILE_NONE);
	assert_int_equal(sim_spi_profile_find("pi-", 3), -EINVAL);
	assert_int_equal(sim_spi_profile_find("p", 1), -EINVAL);
	assert_string_equal(sim_spi_profile_name(SIM_SPI_PROFILE_PI_RT), "pi-rt");
	assert_null(sim_spi_profile_name(SIM_SPI_PROFILE_COUNT));
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_bcm2835_transfer_modes),
		cmocka_unit_test(test_transfer_costs),
		cmocka_unit_test(test_draw_quantiles),
		cmocka_unit_test(test_draw_seeded),
		cmocka_unit_test(test_irq_latency),
		cmocka_unit_test(test_profile_scale),
		cmocka_unit_test(test_profile_names),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
