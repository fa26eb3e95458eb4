// SPDX-License-Identifier: GPL-2.0
/*
 * The health check against simulated chips: a started chip passes; a chip
 * that reset itself and a MISO line returning garbage both fail; recovery
 * gives up the frames in the TX buffers and programs the same bit timing,
 * filters and interrupt enables again; a chip that keeps reading garbage
 * is not declared recovered.
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

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_started_chip_is_healthy),
		cmocka_unit_test(test_reset_is_detected_and_undone),
		cmocka_unit_test(test_garbage_is_detected),
		cmocka_unit_test(test_no_recovery_while_garbage_lasts),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
