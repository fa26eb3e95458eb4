// SPDX-License-Identifier: GPL-2.0
/*
 * Bit timing: the chip's limits, CNF1..CNF3 encoding with the data sheet's
 * and AN739's rules, decoding, and the calculator against the kernel's
 * choices as can-calc-bit-timing prints them (core_bittiming_vectors.h).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <setjmp.h>
#include <cmocka.h>

#include "mcp2510_core.h"
#include "mcp2510_sim.h"
#include "core_bittiming_vectors.h"

static struct can_bittiming timing(u32 prop, u32 ps1, u32 ps2, u32 sjw,
				   u32 brp)
{
	struct can_bittiming bt = {
		.prop_seg = prop, .phase_seg1 = ps1, .phase_seg2 = ps2,
		.sjw = sjw, .brp = brp,
	};
	return bt;
}

static void test_const_matches_the_chip(void **state)
{
	const struct can_bittiming_const *c = &mcp2510_bittiming_const;

	(void)state;
	assert_string_equal(c->name, "mcp2510");
	assert_int_equal(c->tseg1_min, 3);
	assert_int_equal(c->tseg1_max, 16);
	assert_int_equal(c->tseg2_min, 2);
	assert_int_equal(c->tseg2_max, 8);
	assert_int_equal(c->sjw_max, 4);
	assert_int_equal(c->brp_min, 1);
	assert_int_equal(c->brp_max, 64);
	assert_int_equal(c->brp_inc, 1);
}

/* AN739 example 2: 125 kbit/s at 16 MHz is CNF1 0x07, CNF2 0x90, CNF3 0x02 */
static void test_an739_example(void **state)
{
	struct can_bittiming bt = timing(1, 3, 3, 1, 8), back;
	u8 cnf[3];

	(void)state;
	assert_int_equal(mcp2510_bittiming_encode(&bt, 0, cnf), 0);
	assert_int_equal(cnf[0], 0x07);
	assert_int_equal(cnf[1], 0x90);
	assert_int_equal(cnf[2], 0x02);

	mcp2510_bittiming_decode(cnf, 16000000, &back);
	assert_int_equal(back.bitrate, 125000);
	assert_int_equal(back.tq, 1000);
	assert_int_equal(back.prop_seg, 1);
	assert_int_equal(back.phase_seg1, 3);
	assert_int_equal(back.phase_seg2, 3);
	assert_int_equal(back.sjw, 1);
	assert_int_equal(back.brp, 8);
	assert_int_equal(back.sample_point, 625);
}

static void test_encode_fields_and_flags(void **state)
{
	struct can_bittiming bt = timing(8, 8, 8, 4, 64);
	u8 cnf[3];

	(void)state;
	assert_int_equal(mcp2510_bittiming_encode(&bt, 0, cnf), 0);
	assert_int_equal(cnf[0], 0xff);		/* SJW 4, BRP 64 */
	assert_int_equal(cnf[1], 0xbf);		/* BTLMODE, PS1 8, PRSEG 8 */
	assert_int_equal(cnf[2], 0x07);		/* PS2 8 */

	assert_int_equal(mcp2510_bittiming_encode(&bt, CAN_CTRLMODE_3_SAMPLES,
						  cnf), 0);
	assert_int_equal(cnf[1], 0xff);		/* ... and SAM */

	/* the shortest bit the constants allow: TSEG1 3, PS2 2 */
	bt = timing(1, 2, 2, 1, 1);
	assert_int_equal(mcp2510_bittiming_encode(&bt, 0, cnf), 0);
	assert_int_equal(cnf[0], 0x00);
	assert_int_equal(cnf[1], 0x88);
	assert_int_equal(cnf[2], 0x01);
}

static void test_encode_refuses_broken_timing(void **state)
{
	static const struct {
		const char *why;
		u32 prop, ps1, ps2, sjw, brp;
	} bad[] = {
		{ "PRSEG 0", 0, 4, 2, 1, 1 },
		{ "PRSEG 9", 9, 4, 2, 1, 1 },
		{ "PS1 0", 4, 0, 2, 1, 1 },
		{ "PS1 9", 4, 9, 2, 1, 1 },
		{ "PS2 1 (below IPT)", 4, 4, 1, 1, 1 },
		{ "PS2 9", 8, 8, 9, 1, 1 },
		{ "SJW 0", 4, 4, 3, 0, 1 },
		{ "SJW 5", 8, 8, 8, 5, 1 },
		{ "BRP 0", 4, 4, 3, 1, 0 },
		{ "BRP 65", 4, 4, 3, 1, 65 },
		{ "PRSEG + PS1 < PS2", 1, 2, 4, 1, 1 },
		{ "PRSEG + PS1 below tseg1_min", 1, 1, 2, 1, 1 },
		{ "PS2 == SJW", 4, 4, 2, 2, 1 },
		{ "PS2 < SJW", 4, 4, 3, 4, 1 },
	};
	unsigned int i;
	u8 cnf[3];

	(void)state;
	for (i = 0; i < ARRAY_SIZE(bad); i++) {
		struct can_bittiming bt = timing(bad[i].prop, bad[i].ps1,
						 bad[i].ps2, bad[i].sjw,
						 bad[i].brp);

		if (mcp2510_bittiming_encode(&bt, 0, cnf) != -EINVAL)
			fail_msg("accepted: %s", bad[i].why);
	}
}

/* Without BTLMODE the chip makes PS2 the larger of PS1 and IPT (2 TQ). */
static void test_decode_without_btlmode(void **state)
{
	const u8 short_ps1[3] = { 0x00, 0x01, 0x05 };	/* PS1 1, PRSEG 2 */
	const u8 long_ps1[3] = { 0x00, 0x28, 0x05 };	/* PS1 6, PRSEG 1 */
	struct can_bittiming bt;

	(void)state;
	mcp2510_bittiming_decode(short_ps1, 16000000, &bt);
	assert_int_equal(bt.phase_seg2, 2);
	mcp2510_bittiming_decode(long_ps1, 16000000, &bt);
	assert_int_equal(bt.phase_seg2, 6);
}

/* The datasheet's limits and AN739's rules, checked independently. */
static void assert_chip_can_run(const struct can_bittiming *bt)
{
	assert_in_range(bt->prop_seg, 1, 8);
	assert_in_range(bt->phase_seg1, 1, 8);
	assert_in_range(bt->phase_seg2, 2, 8);
	assert_in_range(bt->sjw, 1, 4);
	assert_in_range(bt->brp, 1, 64);
	assert_true(bt->prop_seg + bt->phase_seg1 >= bt->phase_seg2);
	assert_true(bt->phase_seg2 > bt->sjw);
}

/* name the pair that failed */
#define vector_assert(v, cond) do {					\
	if (!(cond))							\
		fail_msg("osc %u Hz, %u bit/s: %s", (v)->osc_hz,	\
			 (v)->bitrate, #cond);				\
} while (0)

static void check_vector(const struct bt_vector *v)
{
	struct can_bittiming bt = { .bitrate = v->bitrate }, back;
	u8 cnf[3];
	int err;

	err = mcp2510_bittiming_calc(v->osc_hz / 2, &bt);
	if (!v->possible) {
		vector_assert(v, err == -EDOM);
		return;
	}
	vector_assert(v, err == 0);
	assert_chip_can_run(&bt);
	vector_assert(v, mcp2510_bittiming_encode(&bt, 0, cnf) == 0);

	vector_assert(v, bt.bitrate == v->real_bitrate);
	vector_assert(v, bt.sample_point == v->sample_point);
	if (v->tie) {
		/* same result, Linux 6.1 keeps the smaller prescaler */
		vector_assert(v, bt.brp < v->brp);
	} else {
		vector_assert(v, bt.tq == v->tq);
		vector_assert(v, bt.prop_seg == v->prop_seg);
		vector_assert(v, bt.phase_seg1 == v->phase_seg1);
		vector_assert(v, bt.phase_seg2 == v->phase_seg2);
		vector_assert(v, bt.sjw == v->sjw);
		vector_assert(v, bt.brp == v->brp);
		vector_assert(v, cnf[0] == v->cnf1);
		vector_assert(v, cnf[1] == v->cnf2);
		vector_assert(v, cnf[2] == v->cnf3);
	}

	mcp2510_bittiming_decode(cnf, v->osc_hz, &back);
	vector_assert(v, back.bitrate == bt.bitrate);
	vector_assert(v, back.sample_point == bt.sample_point);
	vector_assert(v, back.brp == bt.brp);
	vector_assert(v, back.prop_seg == bt.prop_seg);
	vector_assert(v, back.phase_seg1 == bt.phase_seg1);
	vector_assert(v, back.phase_seg2 == bt.phase_seg2);
	vector_assert(v, back.sjw == bt.sjw);
}

static void test_calc_matches_the_kernel(void **state)
{
	unsigned int i, possible = 0, ties = 0;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(bt_vectors); i++) {
		const struct bt_vector *v = &bt_vectors[i];

		check_vector(v);
		possible += v->possible;
		ties += v->tie;
	}
	print_message("%u pairs, %u possible, %u ties\n",
		      (unsigned int)ARRAY_SIZE(bt_vectors), possible, ties);
	assert_true(ARRAY_SIZE(bt_vectors) >= 50);
}

static void test_calc_sample_point_and_sjw_requests(void **state)
{
	struct can_bittiming bt = { .bitrate = 500000, .sample_point = 750 };

	(void)state;
	/* 16 MHz: 16 TQ of 125 ns, 12/16 = 75.0 % */
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), 0);
	assert_int_equal(bt.sample_point, 750);
	assert_int_equal(bt.brp, 1);
	assert_int_equal(bt.prop_seg + bt.phase_seg1 + bt.phase_seg2 + 1, 16);
	assert_int_equal(bt.phase_seg2, 4);

	/* SJW asked for is capped at the chip's 4 and at PS2 */
	bt = (struct can_bittiming){ .bitrate = 500000, .sample_point = 750,
				     .sjw = 7 };
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), 0);
	assert_int_equal(bt.sjw, 4);
	bt = (struct can_bittiming){ .bitrate = 500000, .sjw = 3 };
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), 0);
	assert_int_equal(bt.phase_seg2, 2);
	assert_int_equal(bt.sjw, 2);
}

/*
 * Found by tests/fuzz (bittiming): an early sample point made the
 * calculator split off a TSEG1 below the chip's minimum (PROP_SEG 0 at
 * 30 %) or shorter than PS2, timing the encoder then refused.
 */
static void test_calc_early_sample_point(void **state)
{
	struct can_bittiming bt = { .bitrate = 500000, .sample_point = 300 };
	u8 cnf[3];

	(void)state;
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), -EDOM);
	/* 16 quanta at 50.0 % would need PRSEG + PS1 = 7 < PS2 = 8 */
	bt = (struct can_bittiming){ .bitrate = 125000, .sample_point = 500 };
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), -EDOM);

	/* 55 %: 13 quanta of 625 ns, 53.8 %, 1.5 % slow */
	bt = (struct can_bittiming){ .bitrate = 125000, .sample_point = 550 };
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), 0);
	assert_chip_can_run(&bt);
	assert_int_equal(bt.sample_point, 538);
	assert_int_equal(bt.bitrate, 123076);
	assert_int_equal(mcp2510_bittiming_encode(&bt, 0, cnf), 0);
}

static void test_calc_refuses_nonsense(void **state)
{
	struct can_bittiming bt = { .bitrate = 0 };

	(void)state;
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), -EINVAL);
	bt = (struct can_bittiming){ .bitrate = 125000, .sample_point = 1000 };
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), -EINVAL);
	bt = (struct can_bittiming){ .bitrate = 125000 };
	assert_int_equal(mcp2510_bittiming_calc(0, &bt), -EINVAL);
	/* 5 MHz bit rate from an 8 MHz CAN clock: not even 2 TQ */
	bt = (struct can_bittiming){ .bitrate = 5000000 };
	assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), -EDOM);
}

/* ---- The timings on the chip model ------------------------------------- */

static void model_write(struct sim_chip *chip, u8 addr, u8 val)
{
	u8 tx[3] = { MCP2510_INSTR_WRITE, addr, val };

	sim_chip_spi(chip, tx, NULL, sizeof(tx));
}

static u8 model_read(struct sim_chip *chip, u8 addr)
{
	u8 tx[3] = { MCP2510_INSTR_READ, addr, 0 }, rx[3];

	sim_chip_spi(chip, tx, rx, sizeof(tx));
	return rx[2];
}

/* a chip on a bus, CNF1..CNF3 as given, taking any frame into RXB0, normal mode */
static void model_node(struct sim_bus *bus, struct sim_chip *chip, u32 osc_hz,
		       const u8 cnf[3])
{
	assert_int_equal(sim_chip_init(chip, SIM_MCP2515, osc_hz), 0);
	assert_int_equal(sim_bus_attach(bus, chip), 0);
	sim_bus_advance(bus, sim_chip_startup_ns(chip));
	model_write(chip, MCP2510_REG_CNF1, cnf[0]);
	model_write(chip, MCP2510_REG_CNF2, cnf[1]);
	model_write(chip, MCP2510_REG_CNF3, cnf[2]);
	model_write(chip, MCP2510_REG_RXBCTRL(0),
		    FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_ANY));
	model_write(chip, MCP2510_REG_CANCTRL,
		    FIELD_PREP(MCP2510_CANCTRL_REQOP_MASK, MCP2510_MODE_NORMAL));
	sim_bus_advance(bus, 1000000);
	assert_int_equal(sim_chip_opmode(chip), MCP2510_MODE_NORMAL);
}

/* from sends a standard frame with no data: does to take it? */
static bool model_exchange(struct sim_bus *bus, struct sim_chip *from,
			   struct sim_chip *to)
{
	u8 rts = MCP2510_INSTR_RTS | MCP2510_RTS_TXB(0);
	bool got;

	model_write(from, MCP2510_REG_TXBSIDH(0), 0x24);
	model_write(from, MCP2510_REG_TXBSIDH(0) + 1, 0);	/* SIDL */
	model_write(from, MCP2510_REG_TXBDLC(0), 0);
	sim_chip_spi(from, &rts, NULL, 1);
	sim_bus_advance(bus, 10000000);
	got = model_read(to, MCP2510_REG_CANINTF) & MCP2510_INT_RX0;
	model_write(to, MCP2510_REG_CANINTF, 0);
	model_write(from, MCP2510_REG_CANINTF, 0);
	return got && !(model_read(from, MCP2510_REG_TXBCTRL(0)) &
			MCP2510_TXBCTRL_TXREQ);
}

/*
 * What the two drivers program obeys the data sheets' bit timing rules
 * (DS21291 5.8, DS21801 5.3, AN739), which the chip model enforces: this
 * driver's calculator and encoder, mainline mcp251x's registers as
 * can-calc-bit-timing gives them (the vectors' CNF1..CNF3), and mainline
 * under Linux 6.12, whose calculator picks SJW = max(1, min(PS1, PS2 / 2))
 * instead of 1.
 */
static void test_timings_valid_on_the_model(void **state)
{
	unsigned int i, n = 0;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(bt_vectors); i++) {
		const struct bt_vector *v = &bt_vectors[i];
		struct can_bittiming bt = { .bitrate = v->bitrate };
		struct sim_chip chip;
		u8 ours[3], theirs[3] = { v->cnf1, v->cnf2, v->cnf3 };
		u32 sjw612 = v->phase_seg2 / 2 < v->phase_seg1 ?
			     v->phase_seg2 / 2 : v->phase_seg1;

		if (!v->possible)
			continue;
		assert_int_equal(mcp2510_bittiming_calc(v->osc_hz / 2, &bt), 0);
		assert_int_equal(mcp2510_bittiming_encode(&bt, 0, ours), 0);
		sim_chip_init(&chip, SIM_MCP2515, v->osc_hz);
		model_write(&chip, MCP2510_REG_CNF1, ours[0]);
		model_write(&chip, MCP2510_REG_CNF2, ours[1]);
		model_write(&chip, MCP2510_REG_CNF3, ours[2]);
		vector_assert(v, sim_chip_timing_valid(&chip));
		/* the model rounds, the calculator truncates */
		vector_assert(v, sim_chip_bitrate(&chip) - bt.bitrate <= 1);

		model_write(&chip, MCP2510_REG_CNF1, theirs[0]);
		model_write(&chip, MCP2510_REG_CNF2, theirs[1]);
		model_write(&chip, MCP2510_REG_CNF3, theirs[2]);
		vector_assert(v, sim_chip_timing_valid(&chip));
		model_write(&chip, MCP2510_REG_CNF1,
			    FIELD_PREP(MCP2510_CNF1_SJW_MASK, (sjw612 ? sjw612 : 1) - 1) |
			    FIELD_PREP(MCP2510_CNF1_BRP_MASK, v->brp - 1));
		vector_assert(v, sim_chip_timing_valid(&chip));
		n++;
	}
	assert_true(n >= 50);
}

/*
 * The usual rates from a 16 MHz oscillator: a node with this driver's
 * timing and one with mainline's (under 6.1 and 6.12) understand each
 * other both ways on the model's bus.
 */
static void test_usual_rates_communicate(void **state)
{
	static const u32 rates[] = { 125000, 250000, 500000, 1000000 };
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(rates); i++) {
		const struct bt_vector *v = NULL;
		struct can_bittiming bt = { .bitrate = rates[i] };
		struct sim_bus bus;
		struct sim_chip a, b, c;
		u8 ours[3], theirs[3], theirs612[3];
		unsigned int k;
		u32 sjw612;

		for (k = 0; k < ARRAY_SIZE(bt_vectors); k++)
			if (bt_vectors[k].osc_hz == 16000000 &&
			    bt_vectors[k].bitrate == rates[i])
				v = &bt_vectors[k];
		assert_non_null(v);
		assert_int_equal(mcp2510_bittiming_calc(8000000, &bt), 0);
		assert_int_equal(mcp2510_bittiming_encode(&bt, 0, ours), 0);
		theirs[0] = v->cnf1;
		theirs[1] = v->cnf2;
		theirs[2] = v->cnf3;
		memcpy(theirs612, theirs, sizeof(theirs));
		sjw612 = v->phase_seg2 / 2 < v->phase_seg1 ? v->phase_seg2 / 2 :
							      v->phase_seg1;
		theirs612[0] = FIELD_PREP(MCP2510_CNF1_SJW_MASK, (sjw612 ? sjw612 : 1) - 1) |
			       FIELD_PREP(MCP2510_CNF1_BRP_MASK, v->brp - 1);

		sim_bus_init(&bus);
		model_node(&bus, &a, 16000000, ours);
		model_node(&bus, &b, 16000000, theirs);
		model_node(&bus, &c, 16000000, theirs612);
		if (!model_exchange(&bus, &a, &b) || !model_exchange(&bus, &b, &a) ||
		    !model_exchange(&bus, &c, &a) || !model_exchange(&bus, &a, &c))
			fail_msg("%u bit/s: no exchange", rates[i]);
		assert_int_equal(sim_chip_rec(&a) + sim_chip_rec(&b) + sim_chip_rec(&c), 0);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_const_matches_the_chip),
		cmocka_unit_test(test_an739_example),
		cmocka_unit_test(test_encode_fields_and_flags),
		cmocka_unit_test(test_encode_refuses_broken_timing),
		cmocka_unit_test(test_decode_without_btlmode),
		cmocka_unit_test(test_calc_matches_the_kernel),
		cmocka_unit_test(test_calc_sample_point_and_sjw_requests),
		cmocka_unit_test(test_calc_early_sample_point),
		cmocka_unit_test(test_calc_refuses_nonsense),
		cmocka_unit_test(test_timings_valid_on_the_model),
		cmocka_unit_test(test_usual_rates_communicate),
	};

	return cmocka_run_group_tests_name("core_bittiming", tests, NULL, NULL);
}
