// SPDX-License-Identifier: GPL-2.0
/*
 * The health check against simulated chips: a started chip passes; a chip
 * that reset itself and a MISO line returning garbage both fail; recovery
 * gives up the frames in the TX buffers and programs the same bit timing,
 * filters and interrupt enables again; a chip that keeps reading garbage
 * is not declared recovered; a busy buffer the chip no longer holds is
 * given up; a reset gives up only the frames in the chip; and a stream
 * with corrupted reads always drains.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

#define BITRATE		500000
#define MS		1000000ULL

/* A lone started node: its frames get no ACK, so they stay in the chip. */
static struct ch_rig *started_rig(u32 ctrlmode)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2515);
	struct mcp2510_filters f;

	mcp2510_filters_default(&f);
	f.mask[0].id = 0x7ff;
	f.filter[0].id = 0x123;
	f.rxm[1] = MCP2510_RXM_STD;
	assert_int_equal(mcp2510_filters_apply(&rig->node[0].core, &f), 0);
	assert_int_equal(ch_start(&rig->node[0], BITRATE, ctrlmode), 0);
	return rig;
}

static void peek_all(struct ch_node *node, u8 regs[MCP2510_REG_COUNT])
{
	unsigned int addr;

	for (addr = 0; addr < MCP2510_REG_COUNT; addr++)
		regs[addr] = sim_chip_peek(&node->sim, addr);
}

static void test_started_chip_is_healthy(void **state)
{
	static const u32 modes[] = {
		0, CAN_CTRLMODE_LOOPBACK, CAN_CTRLMODE_LISTENONLY,
		CAN_CTRLMODE_ONE_SHOT | CAN_CTRLMODE_3_SAMPLES,
	};
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(modes); i++) {
		struct ch_rig *rig = started_rig(modes[i]);
		struct ch_node *node = &rig->node[0];

		assert_int_equal(mcp2510_health_check(&node->core), 0);
		ch_run(rig, 10 * MS);
		assert_int_equal(mcp2510_health_check(&node->core), 0);
		/* a stopped chip has nothing to hold */
		assert_int_equal(mcp2510_stop(&node->core), 0);
		assert_int_equal(mcp2510_health_check(&node->core), 0);
		ch_rig_free(rig);
	}
}

static void test_reset_is_detected_and_undone(void **state)
{
	struct ch_rig *rig = started_rig(0);
	struct ch_node *node = &rig->node[0];
	u8 before[MCP2510_REG_COUNT], after[MCP2510_REG_COUNT];
	struct can_frame cf = ch_frame(0x123, 8, 1);

	(void)state;
	peek_all(node, before);
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	ch_run(rig, MS);	/* nobody acknowledges: both stay in the chip */

	sim_chip_reset_pin(&node->sim);
	sim_bus_advance(&rig->bus, sim_chip_startup_ns(&node->sim));
	assert_int_equal(mcp2510_health_check(&node->core), -EBADMSG);

	assert_int_equal(mcp2510_recover(&node->core), 0);
	assert_int_equal(node->core.counters.recoveries, 1);
	assert_int_equal(node->ev.tx_aborted_count, 2);
	assert_int_equal(mcp2510_tx_free(&node->core), MCP2510_TXB_COUNT);
	assert_int_equal(mcp2510_health_check(&node->core), 0);
	assert_int_equal(sim_chip_opmode(&node->sim), MCP2510_MODE_NORMAL);
	/* bit timing, filters, masks, RXM and CANINTE as before the reset */
	peek_all(node, after);
	assert_memory_equal(before + MCP2510_REG_CNF3, after + MCP2510_REG_CNF3, 4);
	assert_memory_equal(before, after, 0x0c);	/* filters 0-2 */
	assert_memory_equal(before + 0x10, after + 0x10, 0x0c);	/* filters 3-5 */
	assert_memory_equal(before + 0x20, after + 0x20, 8);	/* masks */
	assert_int_equal(after[MCP2510_REG_RXBCTRL(1)] & MCP2510_RXBCTRL_RXM_MASK,
			 before[MCP2510_REG_RXBCTRL(1)] & MCP2510_RXBCTRL_RXM_MASK);
	ch_rig_free(rig);
}

static void test_garbage_is_detected(void **state)
{
	static const enum sim_corrupt_kind kinds[] = {
		SIM_CORRUPT_FIXED, SIM_CORRUPT_RANDOM, SIM_CORRUPT_FLIP,
	};
	static const u8 bytes[] = { 0x00, 0xff };
	unsigned int k, b;

	(void)state;
	for (k = 0; k < ARRAY_SIZE(kinds); k++) {
		for (b = 0; b < ARRAY_SIZE(bytes); b++) {
			struct ch_rig *rig = started_rig(0);
			struct ch_node *node = &rig->node[0];
			struct sim_chip_faults *f = sim_chip_faults(&node->sim);

			f->spi_corrupt_kind = kinds[k];
			f->spi_corrupt_byte = bytes[b];
			f->spi_corrupt = 2;	/* the check's two transfers */
			assert_int_equal(mcp2510_health_check(&node->core),
					 -EBADMSG);
			assert_int_equal(mcp2510_health_check(&node->core), 0);
			ch_rig_free(rig);
		}
	}
}

static void test_no_recovery_while_garbage_lasts(void **state)
{
	struct ch_rig *rig = started_rig(0);
	struct ch_node *node = &rig->node[0];
	struct sim_chip_faults *f = sim_chip_faults(&node->sim);

	(void)state;
	f->spi_corrupt_kind = SIM_CORRUPT_RANDOM;
	f->spi_corrupt = SIM_CORRUPT_FOREVER;
	assert_int_equal(mcp2510_health_check(&node->core), -EBADMSG);
	assert_int_equal(mcp2510_recover(&node->core), -ENODEV);
	assert_int_equal(node->core.counters.recoveries, 0);

	f->spi_corrupt = 0;
	assert_int_equal(mcp2510_recover(&node->core), 0);
	assert_int_equal(node->core.counters.recoveries, 1);
	assert_int_equal(mcp2510_health_check(&node->core), 0);
	ch_rig_free(rig);
}

/*
 * A frame the chip dropped behind the driver's back (ABAT, as a misjudged
 * buffer can leave it): TXREQ and TXnIF are clear, nothing interrupts,
 * and only the check sees that the buffer is no longer busy.
 */
static void test_check_gives_up_a_silent_buffer(void **state)
{
	static const u8 abat[4] = { MCP2510_INSTR_BIT_MODIFY,
				    MCP2510_REG_CANCTRL, MCP2510_CANCTRL_ABAT,
				    MCP2510_CANCTRL_ABAT };
	struct ch_rig *rig = started_rig(0);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x123, 8, 1);
	struct ch_spi_mark m;

	(void)state;
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	ch_run(rig, MS);	/* no ACK: it stays in the chip */
	ch_spi_mark(node, &m);
	assert_int_equal(mcp2510_health_check(&node->core), 0);
	/* a pending frame costs the check one READ STATUS */
	assert_int_equal(ch_spi_since(node, &m).transfers, 3);
	assert_int_equal(mcp2510_tx_free(&node->core), 2);

	sim_chip_spi(&node->sim, abat, NULL, sizeof(abat));
	ch_run(rig, 10 * MS);
	assert_false(ch_int_asserted(node));
	assert_int_equal(mcp2510_tx_free(&node->core), 2);
	assert_int_equal(mcp2510_health_check(&node->core), 0);
	assert_int_equal(node->ev.tx_aborted_count, 1);
	assert_int_equal(node->core.counters.tx_errors, 1);
	assert_int_equal(mcp2510_tx_free(&node->core), MCP2510_TXB_COUNT);
	ch_rig_free(rig);
}

/*
 * A chip that resets with three frames in its buffers: a pass that runs
 * before the check (an edge-triggered line's poll, an interrupt already
 * pending) finds TXREQ gone without TXnIF.  The buffers must stay busy:
 * freed, they would take frames still queued in the stack into a chip
 * that cannot send them, and the recovery would give those up too.
 */
static void test_reset_gives_up_only_the_chips_frames(void **state)
{
	struct ch_rig *rig = started_rig(0);
	struct ch_node *node = &rig->node[0];
	unsigned int i;

	(void)state;
	for (i = 0; i < MCP2510_TXB_COUNT; i++) {
		struct can_frame cf = ch_frame(0x123, 8, i);

		assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	}
	ch_run(rig, MS);	/* no ACK: all three stay in the chip */
	sim_chip_reset_pin(&node->sim);
	sim_bus_advance(&rig->bus, sim_chip_startup_ns(&node->sim));
	assert_false(sim_chip_peek(&node->sim, MCP2510_REG_TXBCTRL(0)) &
		     MCP2510_TXBCTRL_TXREQ);

	assert_true(mcp2510_irq_handle(&node->core) >= 0);
	assert_int_equal(node->ev.tx_aborted_count, 0);
	assert_int_equal(mcp2510_tx_free(&node->core), 0);

	assert_int_equal(mcp2510_health_check(&node->core), -EBADMSG);
	assert_int_equal(mcp2510_recover(&node->core), 0);
	assert_int_equal(node->ev.tx_aborted_count, MCP2510_TXB_COUNT);
	assert_int_equal(mcp2510_tx_free(&node->core), MCP2510_TXB_COUNT);
	ch_rig_free(rig);
}

/* ---- transmit bookkeeping after corrupted reads ---------------------- */

#define STREAM_FRAMES	24
#define WATCH_MS	1000	/* the driver runs the check once a second */

/*
 * A stream that keeps all three buffers busy, against a phantom that
 * acknowledges it and floods the node at the same time, with two periods
 * corrupted (@kind) after @at transfers, and the driver's check once a
 * second.  Returns the millisecond by which every frame was sent or given
 * up (0: never within three checks).
 */
static unsigned int corrupted_stream(enum mcp2510_model model,
				     enum sim_corrupt_kind kind, u64 at)
{
	struct ch_rig *rig = ch_rig_new(1, model);
	struct ch_node *node = &rig->node[0];
	struct can_frame flood = ch_frame(0x050, 8, 0);
	unsigned int submitted = 0, ms, settled = 0;

	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	assert_int_equal(sim_phantom_flood(&rig->bus, &flood, 12, 0), 0);
	ch_corrupt_after(node, at, kind, 2);	/* as the soak does */
	for (ms = 1; ms <= 3 * WATCH_MS && !settled; ms++) {
		while (submitted < STREAM_FRAMES &&
		       mcp2510_tx_free(&node->core)) {
			struct can_frame cf = ch_frame(0x100, 8, submitted);

			assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
			submitted++;
		}
		ch_run(rig, MS);
		if (ms % WATCH_MS == 0 &&
		    mcp2510_health_check(&node->core) == -EBADMSG)
			assert_int_equal(mcp2510_recover(&node->core), 0);
		if (node->ev.tx_done_count + node->ev.tx_aborted_count ==
		    STREAM_FRAMES)
			settled = ms;
	}
	assert_int_equal(mcp2510_tx_free(&node->core), MCP2510_TXB_COUNT);
	/* the chip never left error-active: no read may say otherwise */
	assert_int_equal(node->ev.state_count, 0);
	assert_int_equal(node->core.counters.recoveries, 0);
	ch_rig_free(rig);
	return settled;
}

/*
 * The soak's fault: two corrupted SPI periods in the middle of a stream,
 * at every point of it in turn.  A corrupted read may misjudge a frame,
 * but the queue must drain and the error state must not change.
 */
static void test_corrupted_reads_never_stall_tx(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	static const enum sim_corrupt_kind kinds[] = {
		SIM_CORRUPT_FLIP, SIM_CORRUPT_RANDOM, SIM_CORRUPT_FIXED,
	};
	unsigned int i, k, ms;
	u64 at;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		for (k = 0; k < ARRAY_SIZE(kinds); k++) {
			for (at = 0; at < 150; at++) {
				ms = corrupted_stream(models[i], kinds[k], at);
				if (!ms || ms > WATCH_MS)
					fail_msg("%s, kind %u after %llu: %u ms",
						 models[i] ? "MCP2515" :
							     "MCP2510",
						 k, (unsigned long long)at,
						 ms);
			}
		}
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_started_chip_is_healthy),
		cmocka_unit_test(test_reset_is_detected_and_undone),
		cmocka_unit_test(test_garbage_is_detected),
		cmocka_unit_test(test_no_recovery_while_garbage_lasts),
		cmocka_unit_test(test_check_gives_up_a_silent_buffer),
		cmocka_unit_test(test_reset_gives_up_only_the_chips_frames),
		cmocka_unit_test(test_corrupted_reads_never_stall_tx),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
