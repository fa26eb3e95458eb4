// SPDX-License-Identifier: GPL-2.0
/*
 * Fault confinement as the core reports it, on a simulated bus: warning
 * and passive for a node nobody acknowledges, bus-off under bus errors
 * and the way back (the chip's own recovery and mcp2510_restart()), bus
 * error reporting and whether a bus error hit the node's own frame, the
 * error counters, one-shot failures, and a state change in the middle of
 * the interrupt pass that handles the one before.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

#define MS		1000000ULL
#define BITRATE		500000

static const struct can_frame *find_error(const struct ch_node *node,
					  canid_t class)
{
	unsigned int i, n = node->ev.error_count;

	for (i = 0; i < n && i < CH_LOG_MAX; i++)
		if (node->ev.error[i].can_id & class)
			return &node->ev.error[i];
	return NULL;
}

/* Every error frame carries TEC/REC and its class. */
static void assert_error_frames_well_formed(const struct ch_node *node)
{
	unsigned int i;

	for (i = 0; i < node->ev.error_count && i < CH_LOG_MAX; i++) {
		const struct can_frame *cf = &node->ev.error[i];

		assert_true(cf->can_id & CAN_ERR_FLAG);
		assert_true(cf->can_id & CAN_ERR_CNT);
		assert_int_equal(cf->len, CAN_ERR_DLC);
	}
}

/* A lone sender: ACK errors take it to error-passive, never to bus-off. */
static void test_lone_node_goes_passive(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x123, 4, 0);
	const struct can_frame *warn, *passive;

	(void)state;
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	ch_run(rig, 50 * MS);

	assert_int_equal(node->ev.state_count, 2);
	assert_int_equal(node->ev.state[0], CAN_STATE_ERROR_WARNING);
	assert_int_equal(node->ev.state[1], CAN_STATE_ERROR_PASSIVE);
	assert_int_equal(node->core.state, CAN_STATE_ERROR_PASSIVE);
	assert_int_equal(node->core.counters.warnings, 1);
	assert_int_equal(node->core.counters.passives, 1);
	assert_int_equal(node->core.counters.bus_offs, 0);

	warn = find_error(node, CAN_ERR_CRTL);
	assert_non_null(warn);
	assert_int_equal(warn->data[1], CAN_ERR_CRTL_TX_WARNING);
	assert_in_range(warn->data[6], 96, 127);
	passive = &node->ev.error[1];
	assert_int_equal(passive->data[1], CAN_ERR_CRTL_TX_PASSIVE);
	assert_true(passive->data[6] >= 128);
	assert_int_equal(passive->data[7], 0);
	assert_error_frames_well_formed(node);

	/* the frame is still queued, nothing was reported sent */
	assert_int_equal(node->ev.tx_done_count, 0);
	assert_int_equal(mcp2510_tx_free(&node->core), 2);
	ch_rig_free(rig);
}

static struct ch_rig *bus_off_rig(u32 bus_errors, u32 ctrlmode)
{
	struct ch_rig *rig = ch_rig_new(2, MCP2510_MODEL_MCP2510);
	struct can_frame cf = ch_frame(0x456, 8, 0);

	assert_int_equal(ch_start(&rig->node[0], BITRATE, ctrlmode), 0);
	assert_int_equal(ch_start(&rig->node[1], BITRATE, 0), 0);
	sim_bus_faults(&rig->bus)->bus_errors = bus_errors;
	assert_true(mcp2510_tx_submit(&rig->node[0].core, &cf) >= 0);
	return rig;
}

/* 32 destroyed attempts (TEC += 8 each) put the sender off the bus. */
static void run_to_bus_off(struct ch_rig *rig)
{
	struct ch_node *node = &rig->node[0];
	unsigned int steps = 0;

	while (node->core.state != CAN_STATE_BUS_OFF) {
		assert_true(ch_step(rig));
		assert_true(++steps < 10000);
	}
	assert_true(sim_chip_bus_off(&node->sim));
	assert_int_equal(node->ev.state_count, 3);
	assert_int_equal(node->ev.state[0], CAN_STATE_ERROR_WARNING);
	assert_int_equal(node->ev.state[1], CAN_STATE_ERROR_PASSIVE);
	assert_int_equal(node->ev.state[2], CAN_STATE_BUS_OFF);
	assert_int_equal(node->core.counters.bus_offs, 1);
	assert_int_equal(node->ev.error[node->ev.error_count - 1].can_id,
			 CAN_ERR_FLAG | CAN_ERR_BUSOFF | CAN_ERR_CNT);
	assert_error_frames_well_formed(node);
}

static void test_bus_off_and_the_chips_own_recovery(void **state)
{
	struct ch_rig *rig = bus_off_rig(32, 0);
	struct ch_node *node = &rig->node[0];
	const struct can_frame *last;

	(void)state;
	run_to_bus_off(rig);
	assert_int_equal(node->ev.tx_done_count, 0);

	/* 128 x 11 recessive bits later the chip is back and sends */
	ch_run_idle(rig, 100 * MS);
	assert_false(sim_chip_bus_off(&node->sim));
	assert_int_equal(node->core.state, CAN_STATE_ERROR_ACTIVE);
	assert_int_equal(node->ev.state[node->ev.state_count - 1],
			 CAN_STATE_ERROR_ACTIVE);
	last = &node->ev.error[node->ev.error_count - 1];
	assert_int_equal(last->can_id, CAN_ERR_FLAG | CAN_ERR_CRTL |
			 CAN_ERR_CNT);
	assert_int_equal(last->data[1], CAN_ERR_CRTL_ACTIVE);
	assert_int_equal(node->ev.tx_done_count, 1);
	assert_int_equal(rig->node[1].ev.rx_count, 1);
	assert_int_equal(node->core.counters.restarts, 0);
	ch_rig_free(rig);
}

/*
 * An interrupt served later than the chip's own recovery (128 x 11 bits,
 * 2.8 ms at 500 kbit/s; 1.4 ms at 1 Mbit/s) finds it error-active with
 * TEC back at 0 and its frame sent.  The bus-off still happened, and is
 * reported, so that the caller applies its restart policy to it.
 */
static void test_bus_off_found_after_the_recovery(void **state)
{
	struct ch_rig *rig = bus_off_rig(32, 0);
	struct ch_node *node = &rig->node[0];
	unsigned int steps = 0;

	(void)state;
	while (node->core.state != CAN_STATE_ERROR_PASSIVE) {
		assert_true(ch_step(rig));
		assert_true(++steps < 10000);
	}
	/* the interrupt waits while the chip goes off the bus and back */
	sim_bus_advance(&rig->bus, 50 * MS);
	assert_false(sim_chip_bus_off(&node->sim));
	assert_int_equal(sim_chip_counters(&node->sim)->frames_tx, 1);
	assert_int_equal(node->ev.state_count, 2);

	ch_run_idle(rig, 10 * MS);
	assert_int_equal(node->ev.state_count, 3);
	assert_int_equal(node->ev.state[2], CAN_STATE_BUS_OFF);
	assert_int_equal(node->core.counters.bus_offs, 1);
	assert_non_null(find_error(node, CAN_ERR_BUSOFF));
	assert_int_equal(node->ev.tx_done_count, 1);
	assert_error_frames_well_formed(node);
	ch_rig_free(rig);
}

/*
 * A node error-passive from its own frames leaves that state by sending:
 * TEC falls one a frame, and however late the interrupts come, that is
 * no bus-off.
 */
static void test_slow_recovery_by_sending_is_no_bus_off(void **state)
{
	struct ch_rig *rig = bus_off_rig(17, 0);
	struct ch_node *node = &rig->node[0];
	unsigned int sent = 0, steps = 0;

	(void)state;
	while (node->core.state != CAN_STATE_ERROR_PASSIVE) {
		assert_true(ch_step(rig));
		assert_true(++steps < 10000);
	}
	/* 136 down to 127: nine frames, three at a time, serviced late */
	while (node->core.state == CAN_STATE_ERROR_PASSIVE && sent < 200) {
		struct can_frame cf = ch_frame(0x456, 8, sent);

		while (mcp2510_tx_submit(&node->core, &cf) >= 0)
			cf = ch_frame(0x456, 8, ++sent);
		sim_bus_advance(&rig->bus, 5 * MS);
		ch_run_idle(rig, 10 * MS);
	}
	assert_int_equal(node->core.state, CAN_STATE_ERROR_WARNING);
	assert_int_equal(node->core.bec.txerr, 127);
	assert_int_equal(node->core.counters.bus_offs, 0);
	assert_null(find_error(node, CAN_ERR_BUSOFF));
	ch_rig_free(rig);
}

/*
 * ifdown while bus-off with a frame pending: DS21801 10.0 holds the sleep
 * request while TXREQ is set, and by default a bus-off chip's buffer
 * counts (sim_chip_faults.mode_change_in_bus_off).  The stop must abort
 * first and not wait for a mode that cannot come.
 */
static void test_stop_in_bus_off(void **state)
{
	struct ch_rig *rig = bus_off_rig(1000, 0);
	struct ch_node *node = &rig->node[0];
	unsigned int n, pending = 0;

	(void)state;
	run_to_bus_off(rig);
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		pending += !!(sim_chip_peek(&node->sim, MCP2510_REG_TXBCTRL(n)) &
			      MCP2510_TXBCTRL_TXREQ);
	assert_int_equal(pending, 1);
	assert_int_equal(mcp2510_stop(&node->core), 0);
	assert_int_equal(sim_chip_opmode(&node->sim), MCP2510_MODE_SLEEP);
	assert_int_equal(node->ev.tx_aborted_count, 1);
	assert_int_equal(node->core.state, CAN_STATE_STOPPED);
	ch_rig_free(rig);
}

/*
 * The halt at bus-off with its first transfer failing.  The chip was not
 * told to abort, so it recovers by itself after 128 x 11 recessive bits
 * and sends its frame: the halt must not have reported that frame
 * aborted, and the frame is reported sent instead.  Tried again, the
 * halt stops the chip.
 */
static void test_halt_failing_gives_up_nothing(void **state)
{
	struct ch_rig *rig = bus_off_rig(32, 0);
	struct ch_node *node = &rig->node[0];

	(void)state;
	run_to_bus_off(rig);
	node->fail_at = node->xfer_count + 1;
	assert_int_equal(mcp2510_halt(&node->core), -EIO);
	assert_int_equal(node->ev.tx_aborted_count, 0);

	ch_run_idle(rig, 100 * MS);
	assert_int_equal(rig->node[1].ev.rx_count, 1);
	assert_int_equal(node->ev.tx_done_count, 1);
	assert_int_equal(node->ev.tx_aborted_count, 0);

	assert_int_equal(mcp2510_halt(&node->core), 0);
	assert_int_equal(sim_chip_opmode(&node->sim), MCP2510_MODE_SLEEP);
	assert_int_equal(node->core.state, CAN_STATE_STOPPED);
	ch_rig_free(rig);
}

static void test_restart_from_bus_off(void **state)
{
	struct ch_rig *rig = bus_off_rig(1000, 0);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x111, 1, 0);
	unsigned int states;

	(void)state;
	run_to_bus_off(rig);
	states = node->ev.state_count;
	assert_int_equal(mcp2510_restart(&node->core), 0);
	assert_int_equal(node->core.state, CAN_STATE_ERROR_ACTIVE);
	assert_int_equal(node->ev.state_count, states + 1);
	assert_int_equal(node->ev.state[states], CAN_STATE_ERROR_ACTIVE);
	assert_false(sim_chip_bus_off(&node->sim));
	assert_int_equal(sim_chip_tec(&node->sim), 0);
	assert_int_equal(node->ev.tx_aborted_count, 1);
	assert_int_equal(node->core.counters.restarts, 1);
	assert_int_equal(sim_chip_opmode(&node->sim), MCP2510_MODE_NORMAL);

	/* the bus works again */
	sim_bus_faults(&rig->bus)->bus_errors = 0;
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	ch_run_idle(rig, 10 * MS);
	assert_int_equal(node->ev.tx_done_count, 1);
	assert_int_equal(rig->node[1].ev.rx_count, 1);
	ch_rig_free(rig);
}

static void test_bus_error_reporting(void **state)
{
	static const u32 modes[] = { 0, CAN_CTRLMODE_BERR_REPORTING };
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(modes); i++) {
		struct ch_rig *rig = bus_off_rig(3, modes[i]);
		struct ch_node *node = &rig->node[0];
		const struct can_frame *berr;

		ch_run_idle(rig, 50 * MS);
		assert_int_equal(node->ev.tx_done_count, 1);
		berr = find_error(node, CAN_ERR_BUSERROR);
		if (!modes[i]) {
			assert_null(berr);
			assert_int_equal(node->core.counters.bus_errors, 0);
		} else {
			assert_non_null(berr);
			assert_int_equal(berr->can_id,
					 CAN_ERR_FLAG | CAN_ERR_PROT |
					 CAN_ERR_BUSERROR | CAN_ERR_CNT);
			assert_true(node->core.counters.bus_errors >= 1);
			assert_true(node->core.counters.bus_errors <= 3);
			assert_error_frames_well_formed(node);
		}
		ch_rig_free(rig);
	}
}

/* Only the node whose own frame was destroyed reports a TX bus error. */
static void test_bus_error_direction(void **state)
{
	struct ch_rig *rig = ch_rig_new(2, MCP2510_MODEL_MCP2510);
	struct ch_node *sender = &rig->node[0], *receiver = &rig->node[1];
	struct can_frame cf = ch_frame(0x456, 8, 0);
	const struct can_frame *berr;

	(void)state;
	assert_int_equal(ch_start(sender, BITRATE, CAN_CTRLMODE_BERR_REPORTING), 0);
	assert_int_equal(ch_start(receiver, BITRATE, CAN_CTRLMODE_BERR_REPORTING), 0);
	sim_bus_faults(&rig->bus)->bus_errors = 3;
	assert_true(mcp2510_tx_submit(&sender->core, &cf) >= 0);
	ch_run_idle(rig, 50 * MS);
	assert_int_equal(receiver->ev.rx_count, 1);

	berr = find_error(sender, CAN_ERR_BUSERROR);
	assert_non_null(berr);
	assert_int_equal(berr->data[2], CAN_ERR_PROT_TX);
	berr = find_error(receiver, CAN_ERR_BUSERROR);
	assert_non_null(berr);
	assert_int_equal(berr->data[2], 0);
	ch_rig_free(rig);
}

static void test_error_counters(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x123, 4, 0);
	struct can_berr_counter bec;

	(void)state;
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	ch_run(rig, 1 * MS);
	assert_int_equal(mcp2510_berr_counter(&node->core, &bec), 0);
	assert_true(bec.txerr > 0);
	assert_int_equal(bec.txerr, sim_chip_tec(&node->sim));
	assert_int_equal(bec.rxerr, sim_chip_rec(&node->sim));
	node->xfer_count = 0;
	node->fail_at = 1;
	assert_int_equal(mcp2510_berr_counter(&node->core, &bec), -EIO);
	ch_rig_free(rig);
}

/* MCP2515 one-shot: a failed frame is dropped by the chip and reported. */
static void test_one_shot_failure_is_reported(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2515);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x321, 2, 0);

	(void)state;
	assert_int_equal(ch_start(node, BITRATE, CAN_CTRLMODE_ONE_SHOT), 0);
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	ch_run(rig, 5 * MS);
	assert_int_equal(node->ev.tx_aborted_count, 1);
	assert_int_equal(node->ev.tx_done_count, 0);
	assert_int_equal(node->core.counters.tx_errors, 1);
	assert_int_equal(mcp2510_tx_free(&node->core), 3);
	assert_false(ch_int_asserted(node));
	ch_rig_free(rig);
}

/*
 * One-shot once the chip is no longer error-active: every pass then reads
 * CANINTF/EFLG instead of READ STATUS, and a dropped frame still has to
 * be seen (TXREQ gone without TXnIF) when its MERRF is handled.
 */
static void test_one_shot_failure_while_warning(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2515);
	struct ch_node *node = &rig->node[0];
	unsigned int i;

	(void)state;
	assert_int_equal(ch_start(node, BITRATE, CAN_CTRLMODE_ONE_SHOT), 0);
	/* TEC +8 per frame: warning after 12, passive after 16 */
	for (i = 0; i < 20; i++) {
		struct can_frame cf = ch_frame(0x321, 2, i);

		assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
		ch_run(rig, 5 * MS);
		assert_int_equal(node->ev.tx_aborted_count, i + 1);
		assert_int_equal(mcp2510_tx_free(&node->core), 3);
	}
	assert_int_equal(node->core.state, CAN_STATE_ERROR_PASSIVE);
	assert_false(ch_int_asserted(node));
	ch_rig_free(rig);
}

/* Let the lone sender's failed attempts go on until EFLG shows @flag. */
static void run_unserviced_until(struct ch_node *node, u8 flag)
{
	struct sim_bus *bus = &node->rig->bus;

	while (!(sim_chip_peek(&node->sim, MCP2510_REG_EFLG) & flag))
		sim_bus_advance_to(bus, sim_bus_next_event(bus));
}

/*
 * Right after the pass read CANINTF and EFLG (its second transfer, after
 * a READ STATUS that showed nothing): TEC crosses 128.
 */
static void passive_within_the_pass(struct ch_node *node)
{
	if (node->xfer_count != 2)
		return;
	node->after_xfer = NULL;
	run_unserviced_until(node, MCP2510_EFLG_TXEP);
}

/*
 * The pass that handles the warning reads CANINTF and EFLG; before it
 * clears ERRIF the chip turns error-passive and raises ERRIF again.  That
 * change must not be cleared with the old one: a lone sender stays at
 * TEC 128 and nothing else would ever interrupt again.
 */
static void test_state_change_during_the_pass(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x123, 4, 0);

	(void)state;
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	run_unserviced_until(node, MCP2510_EFLG_TXWAR);
	assert_false(sim_chip_peek(&node->sim, MCP2510_REG_EFLG) &
		     MCP2510_EFLG_TXEP);

	node->xfer_count = 0;
	node->after_xfer = passive_within_the_pass;
	ch_service(node, 4, NULL);
	assert_null(node->after_xfer);	/* the hook ran */
	assert_true(sim_chip_tec(&node->sim) >= 128);
	/* the state is the one the chip holds after the clear */
	assert_int_equal(node->core.state, CAN_STATE_ERROR_PASSIVE);
	assert_int_equal(node->ev.state_count, 1);
	assert_int_equal(node->ev.state[0], CAN_STATE_ERROR_PASSIVE);
	assert_int_equal(node->core.counters.passives, 1);
	assert_false(ch_int_asserted(node));
	ch_rig_free(rig);
}

/*
 * Two corrupted periods (the soak's fault) at each point of a pass that
 * handles an overflow's ERRIF: whichever reads they hit, the chip is
 * error-active and no state change may be reported.  (A MISO line stuck
 * high reads as a chip with every EFLG flag and counter up; that is for
 * the health check to find.)
 */
static void test_corrupted_reads_keep_the_state(void **state)
{
	static const enum sim_corrupt_kind kinds[] = {
		SIM_CORRUPT_FLIP, SIM_CORRUPT_RANDOM, SIM_CORRUPT_FIXED,
	};
	unsigned int k, i, at;

	(void)state;
	for (k = 0; k < ARRAY_SIZE(kinds); k++) {
		for (at = 0; at < 14; at++) {
			struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
			struct ch_node *node = &rig->node[0];

			assert_int_equal(ch_start(node, BITRATE, 0), 0);
			for (i = 0; i < 3; i++) {
				struct can_frame cf = ch_frame(0x200 + i, 8, i);

				assert_int_equal(sim_phantom_send(&rig->bus, &cf, 0),
						 0);
			}
			sim_bus_advance(&rig->bus, 2 * MS);
			assert_true(sim_chip_peek(&node->sim, MCP2510_REG_EFLG) &
				    MCP2510_EFLG_RX1OVR);
			ch_corrupt_after(node, at, kinds[k], 2);
			ch_run(rig, 5 * MS);
			assert_int_equal(node->ev.state_count, 0);
			assert_int_equal(node->core.state, CAN_STATE_ERROR_ACTIVE);
			ch_rig_free(rig);
		}
	}
}

static void set_errif(struct ch_node *node)
{
	const u8 tx[4] = { MCP2510_INSTR_BIT_MODIFY, MCP2510_REG_CANINTF,
			   MCP2510_INT_ERR, MCP2510_INT_ERR };

	sim_chip_spi(&node->sim, tx, NULL, sizeof(tx));
}

/*
 * Every state read of a pass disagrees with its TEC/REC: MISO flips bits
 * 0xa5 for all three pairs, so EFLG reads TXBO (with TXWAR and EWARN) and
 * both counters read 165.  No pair is believable, so the state the chip
 * had stays; the last EFLG read must not take the interface bus-off.
 * The pass: READ STATUS (shows nothing), CANINTF/EFLG, the ERRIF clear,
 * then EFLG and TEC/REC three times.
 */
static void test_disagreeing_reads_keep_the_state(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];

	(void)state;
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	set_errif(node);
	assert_true(ch_int_asserted(node));
	sim_chip_faults(&node->sim)->spi_corrupt_xor = 0xa5;
	ch_corrupt_after(node, 3, SIM_CORRUPT_FLIP, 6);
	assert_true(mcp2510_irq_handle(&node->core) >= 0);
	assert_int_equal(sim_chip_faults(&node->sim)->spi_corrupt, 0);
	assert_int_equal(node->ev.state_count, 0);
	assert_int_equal(node->core.counters.bus_offs, 0);
	assert_int_equal(node->core.state, CAN_STATE_ERROR_ACTIVE);
	/* the next pass reads the state again, and it is right */
	set_errif(node);
	ch_service(node, 4, NULL);
	assert_int_equal(node->ev.state_count, 0);
	assert_int_equal(node->core.state, CAN_STATE_ERROR_ACTIVE);
	assert_false(ch_int_asserted(node));
	ch_rig_free(rig);
}

/*
 * A receiver pushed to error-passive by bus errors and brought back by
 * good frames: REC falls to 119 (warning), then below 96 (active).
 * Neither step sets an EFLG bit, so by default (the reading that helps a
 * driver least) no ERRIF comes; the core must still report both.  With
 * errif_on_decrease it gets the flags, and reports the same.
 */
static void run_receiver_recovery(bool errif_on_decrease)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x321, 2, 0);
	unsigned int i;

	sim_chip_faults(&node->sim)->errif_on_decrease = errif_on_decrease;
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	sim_phantom_attach(&rig->bus, 0);
	sim_bus_faults(&rig->bus)->bus_errors = 130;
	assert_int_equal(sim_phantom_send(&rig->bus, &cf, 0), 0);
	ch_run_idle(rig, 100 * MS);
	assert_int_equal(sim_chip_rec(&node->sim), 119);
	assert_int_equal(node->ev.state_count, 3);
	assert_int_equal(node->ev.state[0], CAN_STATE_ERROR_WARNING);
	assert_int_equal(node->ev.state[1], CAN_STATE_ERROR_PASSIVE);
	assert_int_equal(node->ev.state[2], CAN_STATE_ERROR_WARNING);
	assert_int_equal(node->core.state, CAN_STATE_ERROR_WARNING);

	for (i = 0; i < 30; i++) {
		cf = ch_frame(0x300 + i, 1, i);
		assert_int_equal(sim_phantom_send(&rig->bus, &cf, 0), 0);
		ch_run_idle(rig, 10 * MS);
	}
	assert_int_equal(sim_chip_rec(&node->sim), 89);
	assert_int_equal(node->ev.state_count, 4);
	assert_int_equal(node->ev.state[3], CAN_STATE_ERROR_ACTIVE);
	assert_int_equal(node->core.state, CAN_STATE_ERROR_ACTIVE);
	assert_int_equal(node->ev.error[node->ev.error_count - 1].data[1],
			 CAN_ERR_CRTL_ACTIVE);
	assert_int_equal(node->ev.rx_count, 31);
	ch_rig_free(rig);
}

static void test_receiver_recovery_without_errif(void **state)
{
	(void)state;
	run_receiver_recovery(false);
}

static void test_receiver_recovery_with_errif(void **state)
{
	(void)state;
	run_receiver_recovery(true);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_lone_node_goes_passive),
		cmocka_unit_test(test_bus_off_and_the_chips_own_recovery),
		cmocka_unit_test(test_bus_off_found_after_the_recovery),
		cmocka_unit_test(test_slow_recovery_by_sending_is_no_bus_off),
		cmocka_unit_test(test_restart_from_bus_off),
		cmocka_unit_test(test_stop_in_bus_off),
		cmocka_unit_test(test_halt_failing_gives_up_nothing),
		cmocka_unit_test(test_bus_error_reporting),
		cmocka_unit_test(test_bus_error_direction),
		cmocka_unit_test(test_error_counters),
		cmocka_unit_test(test_one_shot_failure_is_reported),
		cmocka_unit_test(test_one_shot_failure_while_warning),
		cmocka_unit_test(test_state_change_during_the_pass),
		cmocka_unit_test(test_corrupted_reads_keep_the_state),
		cmocka_unit_test(test_disagreeing_reads_keep_the_state),
		cmocka_unit_test(test_receiver_recovery_without_errif),
		cmocka_unit_test(test_receiver_recovery_with_errif),
	};

	return cmocka_run_group_tests_name("core_error", tests, NULL, NULL);
}
