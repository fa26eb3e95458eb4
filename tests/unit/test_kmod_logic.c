// SPDX-License-Identifier: GPL-2.0
/*
 * The simulated SPI controller's own layer (tests/kmod/kmod_logic.c), on
 * the host: how transfers gather into chip-select periods and where
 * cs_change splits them, what a period's SCK costs, how bus time follows
 * the clock under time_scale and the lag clamp, and when interrupt lines
 * are delivered and redelivered, with and without latency.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim_helpers.h"
#include "../kmod/kmod_logic.h"

#define CAP	16

struct gatherer {
	struct mcp2510_sim_period p;
	u8 tx[CAP], rx[CAP];
	struct sim_spi_bus sb;
};

static void gatherer_init(struct gatherer *g)
{
	memset(g, 0, sizeof(*g));
	mcp2510_sim_period_init(&g->p, g->tx, g->rx, CAP);
}

static int add(struct gatherer *g, const void *tx, u32 len, bool cs_change,
	       bool last)
{
	struct mcp2510_sim_xfer x = {
		.tx = tx, .len = len, .cs_change = cs_change, .last = last,
	};

	return mcp2510_sim_period_add(&g->p, &x, &g->sb, 5000000);
}

/* Transfers without cs_change make one period; MISO goes back in order. */
static void test_gathering(void **state)
{
	static const u8 a[2] = { 0x03, 0x0e }, c[1] = { 0x55 };
	struct gatherer g;
	u8 ra[2], rb[3], rc[1];

	(void)state;
	gatherer_init(&g);
	assert_int_equal(add(&g, a, 2, false, false), 0);
	assert_int_equal(add(&g, NULL, 3, false, false), 0);
	assert_int_equal(add(&g, c, 1, false, true), 1);
	assert_int_equal(g.p.len, 6);
	/* a transfer without tx_buf clocks out zeros */
	assert_memory_equal(g.tx, ((const u8[]){ 0x03, 0x0e, 0, 0, 0, 0x55 }), 6);

	memcpy(g.rx, "\x10\x11\x12\x13\x14\x15", 6);
	mcp2510_sim_period_give(&g.p, ra, 2);
	mcp2510_sim_period_give(&g.p, rb, 3);
	mcp2510_sim_period_give(&g.p, rc, 1);
	assert_memory_equal(ra, "\x10\x11", 2);
	assert_memory_equal(rb, "\x12\x13\x14", 3);
	assert_memory_equal(rc, "\x15", 1);
}

/* cs_change ends a period early; on the last transfer it changes nothing. */
static void test_cs_change_splits(void **state)
{
	static const u8 a[2] = { 0x03, 0x0e }, b[2] = { 0xaa, 0xbb };
	struct gatherer g;
	u8 r[2];

	(void)state;
	gatherer_init(&g);
	assert_int_equal(add(&g, a, 2, true, false), 1);
	assert_int_equal(g.p.len, 2);
	mcp2510_sim_period_give(&g.p, NULL, 2);
	mcp2510_sim_period_next(&g.p);
	assert_int_equal(g.p.len, 0);
	assert_int_equal(add(&g, b, 2, true, true), 1);
	/* the second period starts at the buffer's start */
	assert_memory_equal(g.tx, b, 2);
	g.rx[0] = 0x77;
	g.rx[1] = 0x88;
	mcp2510_sim_period_give(&g.p, r, 2);
	assert_memory_equal(r, "\x77\x88", 2);
}

/*
 * Against the chip: READ CANSTAT split over two transfers reads the
 * register when they share a period, and nothing when cs_change cuts it
 * (the data byte alone is no instruction: MISO stays high).
 */
static void read_canstat(bool split, u8 *out)
{
	static const u8 instr[2] = { MCP2510_INSTR_READ, MCP2510_REG_CANSTAT };
	struct sim_chip chip;
	struct gatherer g;
	int ret;

	assert_int_equal(sim_chip_init(&chip, SIM_MCP2510, SIMH_OSC_16MHZ), 0);
	gatherer_init(&g);
	ret = add(&g, instr, 2, split, false);
	if (ret) {
		sim_chip_spi(&chip, g.p.tx, g.p.rx, g.p.len);
		mcp2510_sim_period_give(&g.p, NULL, 2);
		mcp2510_sim_period_next(&g.p);
	}
	assert_int_equal(add(&g, NULL, 1, false, true), 1);
	sim_chip_spi(&chip, g.p.tx, g.p.rx, g.p.len);
	if (!ret)
		mcp2510_sim_period_give(&g.p, NULL, 2);
	mcp2510_sim_period_give(&g.p, out, 1);
	assert_int_equal(sim_chip_counters(&chip)->spi_transfers, split ? 2 : 1);
}

static void test_split_read_against_chip(void **state)
{
	u8 v;

	(void)state;
	read_canstat(false, &v);
	assert_int_equal(v, MCP2510_RESET_CANSTAT);
	read_canstat(true, &v);
	assert_int_equal(v, 0xff);
}

static void test_period_too_long(void **state)
{
	struct gatherer g;

	(void)state;
	gatherer_init(&g);
	assert_int_equal(add(&g, NULL, 10, false, false), 0);
	assert_int_equal(add(&g, NULL, 7, false, true), -EMSGSIZE);
	mcp2510_sim_period_next(&g.p);
	assert_int_equal(add(&g, NULL, CAP, false, true), 1);
}

/* Each transfer's clock, clamped to the chip's, adds to the period's SCK time. */
static void test_period_clock(void **state)
{
	struct mcp2510_sim_xfer slow = { .len = 2, .speed_hz = 1000000 };
	struct mcp2510_sim_xfer fast = { .len = 2, .speed_hz = 20000000, .last = true };
	struct gatherer g;

	(void)state;
	gatherer_init(&g);
	assert_int_equal(mcp2510_sim_period_add(&g.p, &slow, &g.sb, 5000000), 0);
	assert_int_equal(mcp2510_sim_period_add(&g.p, &fast, &g.sb, 5000000), 1);
	assert_int_equal(g.p.clock_ns, 0);	/* SPI time off */

	gatherer_init(&g);
	g.sb.timing.enabled = true;
	assert_int_equal(mcp2510_sim_period_add(&g.p, &slow, &g.sb, 5000000), 0);
	assert_int_equal(mcp2510_sim_period_add(&g.p, &fast, &g.sb, 5000000), 1);
	assert_int_equal(g.p.clock_ns, 16000 + 3200);
	mcp2510_sim_period_next(&g.p);
	assert_int_equal(g.p.clock_ns, 0);
}

/* ---- bus time ---- */

static void test_time_scale(void **state)
{
	struct mcp2510_sim_clock c;
	u64 real;

	(void)state;
	mcp2510_sim_clock_start(&c, 1000, 10);
	assert_int_equal(mcp2510_sim_clock_model(&c, 1000, U64_MAX), 0);
	assert_int_equal(mcp2510_sim_clock_model(&c, 51000, U64_MAX), 5000);
	/* a new scale goes on from where bus time stands */
	mcp2510_sim_clock_set_scale(&c, 51000, 1);
	assert_int_equal(mcp2510_sim_clock_model(&c, 51000, U64_MAX), 5000);
	assert_int_equal(mcp2510_sim_clock_model(&c, 52000, U64_MAX), 6000);
	/* and back: the real time a bus time is reached */
	assert_true(mcp2510_sim_clock_real(&c, 7000, &real));
	assert_int_equal(real, 53000);
	mcp2510_sim_clock_set_scale(&c, 53000, 40);
	assert_true(mcp2510_sim_clock_real(&c, 8000, &real));
	assert_int_equal(real, 53000 + 1000 * 40);
	/* a time already past is reached at once */
	assert_true(mcp2510_sim_clock_real(&c, 10, &real));
	assert_int_equal(real, 53000);
	/* beyond what ktime_t holds: never */
	mcp2510_sim_clock_set_scale(&c, 53000, 1000000);
	assert_false(mcp2510_sim_clock_real(&c, U64_MAX / 2, &real));
	assert_int_equal(c.stalls, 0);
}

static void test_lag_clamp(void **state)
{
	const u64 lag = MCP2510_SIM_MAX_LAG_NS;
	struct mcp2510_sim_clock c;

	(void)state;
	mcp2510_sim_clock_start(&c, 0, 1);
	/* up to the lag behind the next event: bus time follows the clock */
	assert_int_equal(mcp2510_sim_clock_model(&c, 100 + lag, 100), 100 + lag);
	assert_int_equal(c.stalls, 0);
	/* more: bus time stalls at the lag, and it is counted */
	assert_int_equal(mcp2510_sim_clock_model(&c, 100 + lag + 5000, 100), 100 + lag);
	assert_int_equal(c.stalls, 1);
	/* from there it follows the clock again */
	assert_int_equal(mcp2510_sim_clock_model(&c, 100 + lag + 5007, U64_MAX),
			 100 + lag + 7);
	assert_int_equal(c.stalls, 1);

	/* the lag is real time: at scale 10 a tenth of it in bus time */
	mcp2510_sim_clock_start(&c, 0, 10);
	assert_int_equal(mcp2510_sim_clock_model(&c, 20 * lag, 0), lag / 10);
	assert_int_equal(c.stalls, 1);
}

/* ---- interrupt lines ---- */

static void test_level_redelivery(void **state)
{
	struct mcp2510_sim_line l = { .level = true, .masked = true,
				      .type = IRQ_TYPE_LEVEL_LOW };
	u64 next = U64_MAX;

	(void)state;
	mcp2510_sim_line_set_level(&l, false);
	assert_false(mcp2510_sim_line_kick(&l, 0, 0));	/* masked */
	l.masked = false;
	assert_true(mcp2510_sim_line_kick(&l, 0, 0));
	assert_true(mcp2510_sim_line_take(&l, 0, &next));
	/* the flow handler masks; unmasked while still low, it fires again */
	l.masked = true;
	assert_false(mcp2510_sim_line_take(&l, 0, &next));
	l.masked = false;
	assert_true(mcp2510_sim_line_kick(&l, 0, 0));
	assert_true(mcp2510_sim_line_take(&l, 0, &next));
	assert_int_equal(l.delivered, 2);
	/* released: nothing more */
	mcp2510_sim_line_set_level(&l, true);
	assert_false(mcp2510_sim_line_kick(&l, 0, 0));
	assert_false(mcp2510_sim_line_take(&l, 0, &next));
	assert_int_equal(next, U64_MAX);
}

static void test_edges(void **state)
{
	struct mcp2510_sim_line l = { .level = true,
				      .type = IRQ_TYPE_EDGE_FALLING,
				      .edge_miss = 1 };
	u64 next = U64_MAX;

	(void)state;
	mcp2510_sim_line_set_level(&l, false);	/* dropped by edge_miss */
	assert_int_equal(l.edges_missed, 1);
	assert_false(mcp2510_sim_line_kick(&l, 0, 0));
	mcp2510_sim_line_set_level(&l, true);	/* rising: not this type */
	assert_false(l.edge_pending);
	mcp2510_sim_line_set_level(&l, false);
	assert_true(mcp2510_sim_line_kick(&l, 0, 0));
	assert_true(mcp2510_sim_line_take(&l, 0, &next));
	/* acked: an edge is delivered once, however long the level stays low */
	l.edge_pending = false;
	assert_false(mcp2510_sim_line_kick(&l, 0, 0));
	assert_false(mcp2510_sim_line_take(&l, 0, &next));
	assert_int_equal(l.delivered, 1);
}

static void test_latency(void **state)
{
	struct mcp2510_sim_line l = { .level = true, .type = IRQ_TYPE_LEVEL_LOW };
	u64 next = U64_MAX;

	(void)state;
	mcp2510_sim_line_set_level(&l, false);
	assert_true(mcp2510_sim_line_kick(&l, 1000, 20000));
	/* a second kick does not push the delivery back */
	assert_true(mcp2510_sim_line_kick(&l, 2000, 20000));
	assert_false(mcp2510_sim_line_take(&l, 5000, &next));
	assert_int_equal(next, 21000);
	assert_true(mcp2510_sim_line_take(&l, 21000, &next));
	assert_int_equal(l.delivered, 1);

	/* redelivery waits the latency again */
	assert_true(mcp2510_sim_line_kick(&l, 30000, 20000));
	next = U64_MAX;
	assert_false(mcp2510_sim_line_take(&l, 49999, &next));
	assert_int_equal(next, 50000);

	/* released before it was due: not delivered, and forgotten */
	mcp2510_sim_line_set_level(&l, true);
	next = U64_MAX;
	assert_false(mcp2510_sim_line_take(&l, 60000, &next));
	assert_int_equal(next, U64_MAX);
	assert_false(l.due_set);
	assert_int_equal(l.delivered, 1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_gathering),
		cmocka_unit_test(test_cs_change_splits),
		cmocka_unit_test(test_split_read_against_chip),
		cmocka_unit_test(test_period_too_long),
		cmocka_unit_test(test_period_clock),
		cmocka_unit_test(test_time_scale),
		cmocka_unit_test(test_lag_clamp),
		cmocka_unit_test(test_level_redelivery),
		cmocka_unit_test(test_edges),
		cmocka_unit_test(test_latency),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
