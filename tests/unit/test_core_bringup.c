// SPDX-License-Identifier: GPL-2.0
/*
 * Bring-up against the chip model: reset and detection (a missing or dead
 * chip is -ENODEV), modes and their timeout, start/stop, sleep and
 * wake-up, transport errors, the variant table, pins and the register
 * dump.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

#define MS	1000000ULL

static u8 opmode(const struct ch_node *node)
{
	return sim_chip_opmode(&node->sim);
}

static void test_variant_table(void **state)
{
	const struct mcp2510_variant *v;

	(void)state;
	v = mcp2510_variant_get(MCP2510_MODEL_MCP2510);
	assert_string_equal(v->name, "mcp2510");
	assert_false(v->has_buffer_instrs);
	assert_false(v->has_one_shot);
	v = mcp2510_variant_get(MCP2510_MODEL_MCP2515);
	assert_string_equal(v->name, "mcp2515");
	assert_true(v->has_buffer_instrs);
	assert_true(v->has_one_shot);
	v = mcp2510_variant_get(MCP2510_MODEL_MCP25625);
	assert_string_equal(v->name, "mcp25625");
	assert_true(v->has_buffer_instrs);
	assert_null(mcp2510_variant_get(MCP2510_MODEL_MCP25625 + 1));
}

static void test_init_checks_its_arguments(void **state)
{
	static const struct mcp2510_events none;
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct mcp2510_chip chip;
	const struct mcp2510_variant *v =
		mcp2510_variant_get(MCP2510_MODEL_MCP2510);

	(void)state;
	assert_int_equal(mcp2510_init(&chip, v, 999999, rig->node[0].core.ops,
				      &none, NULL), -EINVAL);
	assert_int_equal(mcp2510_init(&chip, v, 25000001,
				      rig->node[0].core.ops, &none, NULL),
			 -EINVAL);
	assert_int_equal(mcp2510_init(&chip, NULL, 16000000,
				      rig->node[0].core.ops, &none, NULL),
			 -EINVAL);
	assert_int_equal(mcp2510_init(&chip, v, 16000000, NULL, &none, NULL),
			 -EINVAL);
	ch_rig_free(rig);
}

static void test_reset_finds_the_chip(void **state)
{
	enum mcp2510_model models[] = { MCP2510_MODEL_MCP2510,
					MCP2510_MODEL_MCP2515 };
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		struct ch_rig *rig = ch_rig_new(1, models[i]);
		struct ch_node *node = &rig->node[0];

		/* straight after power-on: the start-up timer still runs */
		assert_false(sim_chip_ready(&node->sim));
		assert_int_equal(mcp2510_hw_reset(&node->core), 0);
		assert_true(sim_chip_ready(&node->sim));
		assert_int_equal(opmode(node), MCP2510_MODE_CONFIG);
		ch_rig_free(rig);
	}
}

/*
 * Start and restart on chips whose buffers, filters and masks hold
 * garbage (unknown at power-on, DS21801 register legends "x"), under both
 * readings of what RESET leaves there.  The core checks only registers
 * with a reset value (CANSTAT, CANCTRL), and the one transmit buffer
 * state it keeps across the reset, each buffer's TXP, matches the chip's
 * TXBnCTRL (R/W-0 at reset); the receive modes are programmed.
 */
static void test_start_with_power_up_garbage(void **state)
{
	unsigned int round, n;

	(void)state;
	for (round = 0; round < 4; round++) {
		struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2515);
		struct ch_node *node = &rig->node[0];

		for (n = 0; n < round; n++) {
			sim_chip_power(&node->sim, false);
			sim_chip_power(&node->sim, true);
		}
		sim_chip_faults(&node->sim)->reset_keeps_unknown = round & 1;
		assert_int_equal(ch_start(node, 500000, 0), 0);
		assert_int_equal(mcp2510_restart(&node->core), 0);
		assert_int_equal(opmode(node), MCP2510_MODE_NORMAL);
		for (n = 0; n < MCP2510_TXB_COUNT; n++)
			assert_int_equal(sim_chip_peek(&node->sim,
						       MCP2510_REG_TXBCTRL(n)),
					 FIELD_PREP(MCP2510_TXBCTRL_TXP_MASK,
						    node->core.tx.prio[n]));
		assert_int_equal(sim_chip_peek(&node->sim, MCP2510_REG_RXBCTRL(0)) &
				 MCP2510_RXBCTRL_RXM_MASK, 0);
		assert_int_equal(sim_chip_peek(&node->sim, MCP2510_REG_CANINTF), 0);
		ch_rig_free(rig);
	}
}

/* A reset must wait the oscillator start-up, but not for ages. */
static void test_reset_wait_is_short(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	u64 t0;

	(void)state;
	sim_bus_advance(&rig->bus, sim_chip_startup_ns(&node->sim));
	t0 = sim_bus_now(&rig->bus);
	assert_int_equal(mcp2510_hw_reset(&node->core), 0);
	assert_true(sim_bus_now(&rig->bus) - t0 >=
		    sim_chip_startup_ns(&node->sim));
	assert_true(sim_bus_now(&rig->bus) - t0 < 100000);
	ch_rig_free(rig);
}

/*
 * An oscillator that takes longer to start than its frequency promises
 * (here 128 cycles of a 32 kHz clock: 4 ms) is waited for, in steps of at
 * most a millisecond; a chip that never answers is given up on after
 * 50 ms of waiting.
 */
static void test_reset_waits_for_a_slow_oscillator(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	u64 t0, waited;

	(void)state;
	sim_bus_advance(&rig->bus, sim_chip_startup_ns(&node->sim));
	node->sim.osc_hz = 32000;
	t0 = sim_bus_now(&rig->bus);
	assert_int_equal(mcp2510_hw_reset(&node->core), 0);
	waited = sim_bus_now(&rig->bus) - t0;
	assert_true(waited >= sim_chip_startup_ns(&node->sim));
	assert_true(waited < sim_chip_startup_ns(&node->sim) + 1000000);

	sim_chip_power(&node->sim, false);
	t0 = sim_bus_now(&rig->bus);
	assert_int_equal(mcp2510_hw_reset(&node->core), -ENODEV);
	waited = sim_bus_now(&rig->bus) - t0;
	assert_true(waited >= 50000000 && waited < 51000000);
	ch_rig_free(rig);
}

static void test_missing_chip_is_enodev(void **state)
{
	static const int stuck[] = { 0x00, 0xff };
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(stuck); i++) {
		struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
		struct ch_node *node = &rig->node[0];

		node->miso_stuck = stuck[i];
		assert_int_equal(mcp2510_hw_reset(&node->core), -ENODEV);
		assert_int_equal(ch_start(node, 500000, 0), -ENODEV);
		assert_false(node->core.started);
		ch_rig_free(rig);
	}
}

static void test_unpowered_or_garbled_chip_is_enodev(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];

	(void)state;
	sim_chip_power(&node->sim, false);
	assert_int_equal(mcp2510_hw_reset(&node->core), -ENODEV);

	/* wrong reset values: every answer has a bit flipped */
	sim_chip_power(&node->sim, true);
	sim_chip_faults(&node->sim)->spi_corrupt = 1000;
	sim_chip_faults(&node->sim)->spi_corrupt_xor = 0x01;
	assert_int_equal(mcp2510_hw_reset(&node->core), -ENODEV);

	sim_chip_faults(&node->sim)->spi_corrupt = 0;
	assert_int_equal(mcp2510_hw_reset(&node->core), 0);
	ch_rig_free(rig);
}

static void test_modes(void **state)
{
	static const struct {
		u32 ctrlmode;
		u8 mode;
	} cases[] = {
		{ 0, MCP2510_MODE_NORMAL },
		{ CAN_CTRLMODE_LOOPBACK, MCP2510_MODE_LOOPBACK },
		{ CAN_CTRLMODE_LISTENONLY, MCP2510_MODE_LISTEN_ONLY },
		{ CAN_CTRLMODE_3_SAMPLES | CAN_CTRLMODE_BERR_REPORTING,
		  MCP2510_MODE_NORMAL },
	};
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(cases); i++) {
		struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
		struct ch_node *node = &rig->node[0];

		assert_int_equal(ch_start(node, 250000, cases[i].ctrlmode), 0);
		assert_int_equal(opmode(node), cases[i].mode);
		assert_int_equal(node->core.state, CAN_STATE_ERROR_ACTIVE);
		assert_int_equal(sim_chip_bitrate(&node->sim), 250000);
		assert_int_equal(!!(sim_chip_peek(&node->sim, MCP2510_REG_CNF2) &
				    MCP2510_CNF2_SAM),
				 !!(cases[i].ctrlmode & CAN_CTRLMODE_3_SAMPLES));
		assert_int_equal(!!(sim_chip_peek(&node->sim,
						  MCP2510_REG_CANINTE) &
				    MCP2510_INT_MERR),
				 !!(cases[i].ctrlmode &
				    CAN_CTRLMODE_BERR_REPORTING));
		assert_int_equal(ch_start(node, 250000, 0), -EBUSY);
		ch_rig_free(rig);
	}
}

static void test_start_refuses(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	struct can_bittiming bad = { .prop_seg = 1, .phase_seg1 = 1,
				     .phase_seg2 = 4, .sjw = 1, .brp = 1 };

	(void)state;
	assert_int_equal(ch_start(node, 500000, CAN_CTRLMODE_ONE_SHOT),
			 -EOPNOTSUPP);
	assert_int_equal(ch_start(node, 500000, CAN_CTRLMODE_FD),
			 -EOPNOTSUPP);
	assert_int_equal(mcp2510_start(&node->core, &bad, 0), -EINVAL);
	assert_false(node->core.started);
	ch_rig_free(rig);
}

static void test_one_shot_on_the_mcp2515(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2515);
	struct ch_node *node = &rig->node[0];

	(void)state;
	assert_int_equal(ch_start(node, 500000, CAN_CTRLMODE_ONE_SHOT), 0);
	assert_true(sim_chip_peek(&node->sim, MCP2510_REG_CANCTRL) &
		    MCP2515_CANCTRL_OSM);
	ch_rig_free(rig);
}

static void test_mode_timeout(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	u64 t0;

	(void)state;
	assert_int_equal(mcp2510_hw_reset(&node->core), 0);
	/* a slow change within the budget is waited for */
	sim_chip_faults(&node->sim)->mode_delay_ns = 3 * MS;
	assert_int_equal(mcp2510_set_mode(&node->core, MCP2510_MODE_LOOPBACK),
			 0);
	assert_int_equal(opmode(node), MCP2510_MODE_LOOPBACK);

	/* one that never comes in time is -ETIMEDOUT, after 10..50 ms */
	sim_chip_faults(&node->sim)->mode_delay_ns = 1000 * MS;
	t0 = sim_bus_now(&rig->bus);
	assert_int_equal(mcp2510_set_mode(&node->core, MCP2510_MODE_CONFIG),
			 -ETIMEDOUT);
	assert_in_range(sim_bus_now(&rig->bus) - t0, 10 * MS, 50 * MS);
	assert_int_equal(mcp2510_set_mode(&node->core, 5), -EINVAL);
	ch_rig_free(rig);
}

static void test_start_times_out_on_a_stuck_mode(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];

	(void)state;
	sim_chip_faults(&node->sim)->mode_delay_ns = 1000 * MS;
	assert_int_equal(ch_start(node, 500000, 0), -ETIMEDOUT);
	assert_false(node->core.started);
	sim_chip_faults(&node->sim)->mode_delay_ns = 0;
	assert_int_equal(ch_start(node, 500000, 0), 0);
	ch_rig_free(rig);
}

static void test_stop_aborts_and_sleeps(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x100, 8, 0);
	unsigned int i;

	(void)state;
	assert_int_equal(ch_start(node, 500000, 0), 0);
	/* a lone node gets no ACK: its frames stay pending */
	for (i = 0; i < 3; i++)
		assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	ch_run(rig, 1 * MS);
	assert_int_equal(mcp2510_stop(&node->core), 0);
	assert_int_equal(node->ev.tx_aborted_count, 3);
	assert_int_equal(mcp2510_tx_free(&node->core), 3);
	assert_int_equal(opmode(node), MCP2510_MODE_SLEEP);
	assert_int_equal(sim_chip_peek(&node->sim, MCP2510_REG_CANINTE), 0);
	assert_int_equal(node->core.state, CAN_STATE_STOPPED);
	assert_int_equal(mcp2510_tx_submit(&node->core, &cf), -ENETDOWN);

	/* and starts again from sleep */
	assert_int_equal(ch_start(node, 500000, 0), 0);
	assert_int_equal(opmode(node), MCP2510_MODE_NORMAL);
	ch_rig_free(rig);
}

static void test_sleep(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2515);
	struct ch_node *node = &rig->node[0];

	(void)state;
	assert_int_equal(ch_start(node, 500000, CAN_CTRLMODE_LOOPBACK), 0);
	assert_int_equal(mcp2510_sleep(&node->core), 0);
	assert_int_equal(opmode(node), MCP2510_MODE_SLEEP);
	ch_rig_free(rig);
}

/*
 * Wake-on-CAN (DS21801 10.2, AN739 "Sleep Mode"): armed, the sleeping
 * chip has WAKIE alone enabled, so only a wake-up asserts INT; the first
 * start of frame on the bus wakes it into listen-only mode and the frame
 * itself is lost.  A WAKIF left over from before does not count.  CNF3's
 * WAKFIL, which both variants have (AN739 register 10), is set at start
 * when asked for.
 */
static void test_wake_on_bus(void **state)
{
	enum mcp2510_model models[] = { MCP2510_MODEL_MCP2510,
					MCP2510_MODEL_MCP2515 };
	struct can_frame cf = ch_frame(0x123, 1, 0);
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		struct ch_rig *rig = ch_rig_new(2, models[i]);
		struct ch_node *a = &rig->node[0], *b = &rig->node[1];

		mcp2510_wake_filter_set(&a->core, true);
		assert_int_equal(ch_start(a, 500000, 0), 0);
		assert_int_equal(ch_start(b, 500000, 0), 0);
		assert_true(sim_chip_peek(&a->sim, MCP2510_REG_CNF3) &
			    MCP2510_CNF3_WAKFIL);
		assert_false(sim_chip_peek(&b->sim, MCP2510_REG_CNF3) &
			     MCP2510_CNF3_WAKFIL);

		/* a WAKIF from before (set by SPI in sleep it would wake) */
		assert_int_equal(mcp2510_reg_modify(&a->core,
						    MCP2510_REG_CANINTF,
						    MCP2510_INT_WAK,
						    MCP2510_INT_WAK), 0);
		assert_int_equal(mcp2510_stop(&a->core), 0);
		assert_int_equal(mcp2510_wake_arm(&a->core), 0);
		assert_int_equal(opmode(a), MCP2510_MODE_SLEEP);
		assert_int_equal(sim_chip_peek(&a->sim, MCP2510_REG_CANINTE),
				 MCP2510_INT_WAK);
		assert_false(ch_int_asserted(a));
		assert_int_equal(mcp2510_wake_ack(&a->core), 0);
		ch_run(rig, 1 * MS);
		assert_int_equal(opmode(a), MCP2510_MODE_SLEEP);

		assert_true(mcp2510_tx_submit(&b->core, &cf) >= 0);
		ch_run(rig, 1 * MS);
		assert_true(ch_int_asserted(a));
		assert_int_equal(opmode(a), MCP2510_MODE_LISTEN_ONLY);
		assert_false(sim_chip_peek(&a->sim, MCP2510_REG_CANINTF) &
			     MCP2510_INT_RX_ALL);
		assert_int_equal(mcp2510_wake_ack(&a->core), 1);
		assert_false(ch_int_asserted(a));
		assert_int_equal(mcp2510_wake_ack(&a->core), 0);

		/* resume: stop and start again, back in normal mode */
		assert_int_equal(mcp2510_stop(&a->core), 0);
		assert_int_equal(ch_start(a, 500000, 0), 0);
		assert_int_equal(opmode(a), MCP2510_MODE_NORMAL);
		assert_true(sim_chip_peek(&a->sim, MCP2510_REG_CNF3) &
			    MCP2510_CNF3_WAKFIL);
		ch_rig_free(rig);
	}
}

static void test_transport_errors_are_eio(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	u64 n;
	u8 v;

	(void)state;
	/* fail each transfer of a start in turn: -EIO, not started */
	for (n = 1;; n++) {
		int err;

		node->xfer_count = 0;
		node->fail_at = n;
		err = ch_start(node, 500000, 0);
		if (!err)
			break;
		assert_true(n < 100);
		assert_int_equal(err, -EIO);
		assert_false(node->core.started);
	}
	assert_true(n > 5);	/* reset, CNF, filters, mode... */
	node->fail_at = 1;
	node->xfer_count = 0;
	assert_int_equal(mcp2510_reg_read(&node->core, 0, &v, 1), -EIO);
	node->xfer_count = 0;
	assert_int_equal(mcp2510_read_status(&node->core, &v), -EIO);
	node->xfer_count = 0;
	node->fail_reaches_chip = true;
	assert_int_equal(mcp2510_reg_modify(&node->core, MCP2510_REG_BFPCTRL,
					    0xff, 0), -EIO);
	ch_rig_free(rig);
}

static void test_register_access(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	u8 dump[MCP2510_REGDUMP_LEN], v = 0;
	const u8 cnf[3] = { 0x12, 0x34, 0x05 };
	struct ch_spi_mark m;
	unsigned int i;

	(void)state;
	assert_int_equal(mcp2510_hw_reset(&node->core), 0);
	assert_int_equal(mcp2510_reg_write(&node->core, MCP2510_REG_CNF3, cnf,
					   3), 0);
	assert_int_equal(mcp2510_reg_modify(&node->core, MCP2510_REG_CNF2,
					    0x0f, 0x0a), 0);
	assert_int_equal(mcp2510_reg_read(&node->core, MCP2510_REG_CNF2, &v,
					  1), 0);
	assert_int_equal(v, 0x3a);

	ch_spi_mark(node, &m);
	assert_int_equal(mcp2510_regs_dump(&node->core, dump), 0);
	m = ch_spi_since(node, &m);
	assert_int_equal(m.transfers, 1);
	assert_int_equal(m.bytes, 2 + MCP2510_REGDUMP_LEN);
	for (i = 0; i < MCP2510_REGDUMP_LEN; i++)
		assert_int_equal(dump[i], sim_chip_peek(&node->sim, i));

	assert_int_equal(mcp2510_reg_read(&node->core, 0, &v, 0), -EINVAL);
	ch_rig_free(rig);
}

static void test_pins(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	unsigned int n;

	(void)state;
	assert_int_equal(ch_start(node, 500000, 0), 0);
	for (n = 0; n < 2; n++) {
		enum sim_pin pin = n ? SIM_PIN_RX1BF : SIM_PIN_RX0BF;

		assert_int_equal(mcp2510_pin_bf_set(&node->core, n, false), 0);
		assert_false(sim_chip_pin(&node->sim, pin));
		assert_int_equal(mcp2510_pin_bf_set(&node->core, n, true), 0);
		assert_true(sim_chip_pin(&node->sim, pin));
	}
	assert_int_equal(mcp2510_pin_bf_set(&node->core, 2, true), -EINVAL);
	for (n = 0; n < 3; n++) {
		assert_int_equal(mcp2510_pin_rts_get(&node->core, n), 1);
		sim_chip_set_rts(&node->sim, n, false);
		assert_int_equal(mcp2510_pin_rts_get(&node->core, n), 0);
	}
	assert_int_equal(mcp2510_pin_rts_get(&node->core, 3), -EINVAL);
	ch_rig_free(rig);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_variant_table),
		cmocka_unit_test(test_init_checks_its_arguments),
		cmocka_unit_test(test_reset_finds_the_chip),
		cmocka_unit_test(test_start_with_power_up_garbage),
		cmocka_unit_test(test_reset_wait_is_short),
		cmocka_unit_test(test_reset_waits_for_a_slow_oscillator),
		cmocka_unit_test(test_missing_chip_is_enodev),
		cmocka_unit_test(test_unpowered_or_garbled_chip_is_enodev),
		cmocka_unit_test(test_modes),
		cmocka_unit_test(test_start_refuses),
		cmocka_unit_test(test_one_shot_on_the_mcp2515),
		cmocka_unit_test(test_mode_timeout),
		cmocka_unit_test(test_start_times_out_on_a_stuck_mode),
		cmocka_unit_test(test_stop_aborts_and_sleeps),
		cmocka_unit_test(test_sleep),
		cmocka_unit_test(test_wake_on_bus),
		cmocka_unit_test(test_transport_errors_are_eio),
		cmocka_unit_test(test_register_access),
		cmocka_unit_test(test_pins),
	};

	return cmocka_run_group_tests_name("core_bringup", tests, NULL, NULL);
}
