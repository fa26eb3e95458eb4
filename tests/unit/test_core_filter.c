// SPDX-License-Identifier: GPL-2.0
/*
 * Acceptance filters: the sysfs/CLI text forms, register encoding, and
 * what a simulated chip programmed by the core lets through (the default,
 * AN739's example configuration, receive modes).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

#define MS	1000000ULL

static int parse(const char *s, struct mcp2510_filter_id *id)
{
	return mcp2510_filter_id_parse(s, strlen(s), id);
}

static void test_parse_ids(void **state)
{
	struct mcp2510_filter_id id;

	(void)state;
	assert_int_equal(parse("7ff", &id), 0);
	assert_int_equal(id.id, 0x7ff);
	assert_false(id.ext);
	assert_int_equal(parse("1fffffffx", &id), 0);
	assert_int_equal(id.id, 0x1fffffff);
	assert_true(id.ext);
	assert_int_equal(parse("0", &id), 0);
	assert_int_equal(id.id, 0);
	assert_int_equal(parse("ABCx\n", &id), 0);	/* as echo writes it */
	assert_int_equal(id.id, 0xabc);
	assert_true(id.ext);
	assert_int_equal(parse("000007ff", &id), 0);
	assert_int_equal(id.id, 0x7ff);
}

static void test_parse_refuses_and_keeps_the_old_value(void **state)
{
	static const char *const bad[] = {
		"", "\n", "x", "800", "20000000x", "0x7ff", "7fg", "-1",
		" 7ff", "7ff ", "7ffxx", "123456789x", "7f\nf",
	};
	struct mcp2510_filter_id id = { .id = 0x42, .ext = true };
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(bad); i++) {
		if (parse(bad[i], &id) != -EINVAL)
			fail_msg("accepted \"%s\"", bad[i]);
		assert_int_equal(id.id, 0x42);
		assert_true(id.ext);
	}
	/* only @len characters count */
	assert_int_equal(mcp2510_filter_id_parse("7ff", 2, &id), 0);
	assert_int_equal(id.id, 0x7f);
}

static void test_format_round_trips(void **state)
{
	static const struct mcp2510_filter_id ids[] = {
		{ 0, false }, { 0x7ff, false }, { 0x10, false },
		{ 0, true }, { 0x1fffffff, true }, { 0x12345, true },
	};
	static const char *const text[] = {
		"0", "7ff", "10", "0x", "1fffffffx", "12345x",
	};
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(ids); i++) {
		char buf[12];
		struct mcp2510_filter_id back;
		int len = mcp2510_filter_id_format(&ids[i], buf);

		assert_string_equal(buf, text[i]);
		assert_int_equal(len, strlen(text[i]));
		assert_int_equal(parse(buf, &back), 0);
		assert_int_equal(back.id, ids[i].id);
		assert_int_equal(back.ext, ids[i].ext);
	}
}

static void test_rxm_names(void **state)
{
	static const char *const names[] = { "filtered", "std", "ext", "any" };
	unsigned int i;
	u8 rxm = 9;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(names); i++) {
		assert_int_equal(mcp2510_rxm_parse(names[i], strlen(names[i]),
						   &rxm), 0);
		assert_int_equal(rxm, i);
		assert_string_equal(mcp2510_rxm_name(i), names[i]);
	}
	assert_int_equal(mcp2510_rxm_parse("any\n", 4, &rxm), 0);
	assert_int_equal(rxm, MCP2510_RXM_ANY);
	assert_int_equal(mcp2510_rxm_parse("an", 2, &rxm), -EINVAL);
	assert_int_equal(mcp2510_rxm_parse("anyx", 4, &rxm), -EINVAL);
	assert_int_equal(mcp2510_rxm_parse("", 0, &rxm), -EINVAL);
	assert_int_equal(mcp2510_rxm_parse("ANY", 3, &rxm), -EINVAL);
	assert_null(mcp2510_rxm_name(4));
}

static void test_register_encoding(void **state)
{
	const struct mcp2510_filter_id std = { 0x5a3, false };
	const struct mcp2510_filter_id ext = { 0x155u << 18 | 2u << 16 | 0x1234,
					       true };
	u8 regs[MCP2510_ID_LEN];

	(void)state;
	mcp2510_filter_id_encode(&std, false, regs);
	assert_int_equal(regs[0], 0x5a3 >> 3);
	assert_int_equal(regs[1], (0x5a3 & 7) << 5);
	assert_int_equal(regs[2], 0);
	assert_int_equal(regs[3], 0);

	mcp2510_filter_id_encode(&ext, false, regs);
	assert_int_equal(regs[0], 0x155 >> 3);
	assert_int_equal(regs[1], (0x155 & 7) << 5 | MCP2510_SIDL_EXIDE | 2);
	assert_int_equal(regs[2], 0x12);
	assert_int_equal(regs[3], 0x34);

	/* a mask has no EXIDE */
	mcp2510_filter_id_encode(&ext, true, regs);
	assert_int_equal(regs[1], (0x155 & 7) << 5 | 2);
}

/* Decoding gives back what was encoded, filters and masks of both widths. */
static void test_register_decoding(void **state)
{
	static const struct mcp2510_filter_id ids[] = {
		{ 0x5a3, false }, { 0x7ff, false },
		{ 0x155u << 18 | 2u << 16 | 0x1234, true },
		{ 0x1fffffff, true }, { 1, true },
	};
	struct mcp2510_filter_id back;
	u8 regs[MCP2510_ID_LEN];
	unsigned int i, is_mask;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(ids); i++) {
		for (is_mask = 0; is_mask <= 1; is_mask++) {
			mcp2510_filter_id_encode(&ids[i], is_mask, regs);
			mcp2510_filter_id_decode(regs, is_mask, &back);
			assert_int_equal(back.ext, ids[i].ext);
			assert_int_equal(back.id, ids[i].id);
		}
	}
}

static void test_check_and_apply(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct mcp2510_chip *chip = &rig->node[0].core;
	struct mcp2510_filters f;

	(void)state;
	mcp2510_filters_default(&f);
	f.filter[2].id = 0x800;		/* too wide for a standard id */
	assert_int_equal(mcp2510_filters_apply(chip, &f), -EINVAL);
	f.filter[2].id = 0x20000000;
	f.filter[2].ext = true;		/* ... and for an extended one */
	assert_int_equal(mcp2510_filters_apply(chip, &f), -EINVAL);
	f.filter[2].id = 0x7ff;
	f.filter[2].ext = false;
	f.rxm[1] = 4;
	assert_int_equal(mcp2510_filters_apply(chip, &f), -EINVAL);
	f.rxm[1] = MCP2510_RXM_ANY;
	assert_int_equal(mcp2510_filters_apply(chip, &f), 0);
	assert_int_equal(chip->filters.rxm[1], MCP2510_RXM_ANY);

	assert_int_equal(ch_start(&rig->node[0], 500000, 0), 0);
	assert_int_equal(mcp2510_filters_apply(chip, &f), -EBUSY);
	/* programmed at start */
	assert_int_equal(sim_chip_peek(&rig->node[0].sim, MCP2510_REG_RXFSIDH(2)),
			 0xff);
	assert_int_equal(sim_chip_peek(&rig->node[0].sim, MCP2510_REG_RXFSIDL(2)),
			 0xe0);
	ch_rig_free(rig);
}

/* Send @ids from node 1 (started with default filters), count what node 0 got. */
static unsigned int deliver(struct ch_rig *rig, const canid_t *ids,
			    unsigned int n, bool *got)
{
	unsigned int i, before = rig->node[0].ev.rx_count;

	for (i = 0; i < n; i++) {
		struct can_frame cf = ch_frame(ids[i], 2, i);
		unsigned int count = rig->node[0].ev.rx_count;

		assert_true(mcp2510_tx_submit(&rig->node[1].core, &cf) >= 0);
		ch_run_idle(rig, 10 * MS);
		got[i] = rig->node[0].ev.rx_count > count;
		if (got[i])
			assert_true(ch_frame_equal(&rig->node[0].ev.rx[count %
							CH_LOG_MAX], &cf));
	}
	return rig->node[0].ev.rx_count - before;
}

static struct ch_rig *filter_rig(const struct mcp2510_filters *f)
{
	struct ch_rig *rig = ch_rig_new(2, MCP2510_MODEL_MCP2510);

	if (f)
		assert_int_equal(mcp2510_filters_apply(&rig->node[0].core, f),
				 0);
	assert_int_equal(ch_start(&rig->node[0], 500000, 0), 0);
	assert_int_equal(ch_start(&rig->node[1], 500000, 0), 0);
	return rig;
}

static const canid_t mixed_ids[] = {
	0x000, 0x7ff, 0x500, 0x123, CAN_EFF_FLAG | 0x1fffffff,
	CAN_EFF_FLAG | 0x0, CAN_EFF_FLAG | 0x1400000, 0x123 | CAN_RTR_FLAG,
};

static void test_default_accepts_everything(void **state)
{
	struct ch_rig *rig = filter_rig(NULL);
	bool got[ARRAY_SIZE(mixed_ids)];

	(void)state;
	assert_int_equal(deliver(rig, mixed_ids, ARRAY_SIZE(mixed_ids), got),
			 ARRAY_SIZE(mixed_ids));
	ch_rig_free(rig);
}

/*
 * AN739 example 3: RXB0 shut out (mask and filters all ones, extended
 * filters), RXB1 takes exactly 0x500, 0x508, 0x510 and 0x518 through
 * filters 2-5 under an all-ones standard mask.
 */
static void test_an739_example(void **state)
{
	static const canid_t ids[] = {
		0x500, 0x508, 0x510, 0x518, 0x501, 0x520, 0x123, 0x7ff,
		CAN_EFF_FLAG | 0x500, CAN_EFF_FLAG | 0x1fffffff,
	};
	/* AN739: only an all-ones extended frame still gets into RXB0 */
	static const bool want[] = {
		true, true, true, true, false, false, false, false,
		false, true,
	};
	struct mcp2510_filters f;
	struct ch_rig *rig;
	bool got[ARRAY_SIZE(ids)];
	unsigned int i;

	(void)state;
	mcp2510_filters_default(&f);
	f.mask[0] = (struct mcp2510_filter_id){ 0x1fffffff, true };
	f.filter[0] = (struct mcp2510_filter_id){ 0x1fffffff, true };
	f.filter[1] = (struct mcp2510_filter_id){ 0x1fffffff, true };
	f.mask[1] = (struct mcp2510_filter_id){ 0x7ff, false };
	f.filter[2] = (struct mcp2510_filter_id){ 0x500, false };
	f.filter[3] = (struct mcp2510_filter_id){ 0x508, false };
	f.filter[4] = (struct mcp2510_filter_id){ 0x510, false };
	f.filter[5] = (struct mcp2510_filter_id){ 0x518, false };
	rig = filter_rig(&f);

	deliver(rig, ids, ARRAY_SIZE(ids), got);
	for (i = 0; i < ARRAY_SIZE(ids); i++)
		if (got[i] != want[i])
			fail_msg("id %x: got %d, want %d", ids[i], got[i],
				 want[i]);
	/* the last standard one went to RXB1 through filter 5 */
	assert_int_equal(sim_chip_peek(&rig->node[0].sim,
				       MCP2510_REG_RXBCTRL(1)) &
			 MCP2510_RXB1CTRL_FILHIT_MASK, 5);
	ch_rig_free(rig);
}

static void test_receive_modes(void **state)
{
	static const canid_t ids[] = {
		0x123, CAN_EFF_FLAG | 0x123, 0x7ff, CAN_EFF_FLAG | 0x1fffffff,
	};
	struct mcp2510_filters f;
	struct ch_rig *rig;
	bool got[ARRAY_SIZE(ids)];

	(void)state;
	/* RXB0 takes only standard frames, RXB1 nothing but extended 0 */
	mcp2510_filters_default(&f);
	f.rxm[0] = MCP2510_RXM_STD;
	f.mask[1] = (struct mcp2510_filter_id){ 0x1fffffff, true };
	f.rxm[1] = MCP2510_RXM_EXT;
	f.rollover = false;
	rig = filter_rig(&f);
	deliver(rig, ids, ARRAY_SIZE(ids), got);
	assert_true(got[0]);
	assert_false(got[1]);
	assert_true(got[2]);
	assert_false(got[3]);
	ch_rig_free(rig);

	/* "any" on RXB1 takes what RXB0 refuses */
	f.rxm[1] = MCP2510_RXM_ANY;
	rig = filter_rig(&f);
	deliver(rig, ids, ARRAY_SIZE(ids), got);
	assert_true(got[0] && got[1] && got[2] && got[3]);
	ch_rig_free(rig);
}

/* Every filter and mask byte holds what the core's filters encode to. */
static void assert_filters_programmed(struct ch_node *node)
{
	const struct mcp2510_filters *f = &node->core.filters;
	u8 want[MCP2510_ID_LEN];
	unsigned int i, k;

	for (i = 0; i < MCP2510_FILTER_COUNT; i++) {
		mcp2510_filter_id_encode(&f->filter[i], false, want);
		for (k = 0; k < MCP2510_ID_LEN; k++)
			assert_int_equal(sim_chip_peek(&node->sim,
						       MCP2510_REG_RXF(i) + k),
					 want[k]);
	}
	for (i = 0; i < MCP2510_MASK_COUNT; i++) {
		mcp2510_filter_id_encode(&f->mask[i], true, want);
		for (k = 0; k < MCP2510_ID_LEN; k++)
			assert_int_equal(sim_chip_peek(&node->sim,
						       MCP2510_REG_RXM(i) + k),
					 want[k]);
	}
}

/*
 * The filters and masks power up unknown (DS21801 registers 4-10..4-17,
 * "x") and the model fills them with garbage, new at every power-up and,
 * by default, at every RESET.  The core writes every byte of them, so
 * whatever they held, the default configuration takes every frame; also
 * under the reading where RESET keeps what power-up left.
 */
static void test_filters_do_not_rely_on_reset_values(void **state)
{
	unsigned int round;

	(void)state;
	for (round = 0; round < 8; round++) {
		struct ch_rig *rig = ch_rig_new(2, MCP2510_MODEL_MCP2515);
		bool got[ARRAY_SIZE(mixed_ids)];
		unsigned int k;

		/* other garbage each round: power-cycle node 0 a few times */
		for (k = 0; k < round; k++) {
			sim_chip_power(&rig->node[0].sim, false);
			sim_chip_power(&rig->node[0].sim, true);
		}
		sim_chip_faults(&rig->node[0].sim)->reset_keeps_unknown = round & 1;
		assert_int_equal(ch_start(&rig->node[0], 500000, 0), 0);
		assert_int_equal(ch_start(&rig->node[1], 500000, 0), 0);
		assert_filters_programmed(&rig->node[0]);
		assert_int_equal(deliver(rig, mixed_ids, ARRAY_SIZE(mixed_ids),
					 got), ARRAY_SIZE(mixed_ids));
		/* a restart resets the chip: everything is written again */
		assert_int_equal(mcp2510_restart(&rig->node[0].core), 0);
		assert_filters_programmed(&rig->node[0]);
		assert_int_equal(deliver(rig, mixed_ids, ARRAY_SIZE(mixed_ids),
					 got), ARRAY_SIZE(mixed_ids));
		ch_rig_free(rig);
	}
}

/*
 * Listen-only mode (DS21801 10.3): a buffer with RXM 11 also takes frames
 * that an error destroyed, loaded like valid ones.  Node 1's first frame
 * is destroyed (an injected CRC error) and sent again: a listen-only node
 * must report it once, whatever receive modes were chosen.  With the
 * default filters (RXM 00) the chip never takes the destroyed copy; with
 * "any" the core must not let it either.
 */
static void check_listen_only_takes_valid_frames_only(u8 rxm0, u8 rxm1)
{
	struct ch_rig *rig = ch_rig_new(3, MCP2510_MODEL_MCP2515);
	struct ch_node *lom = &rig->node[0];
	struct can_frame cf = ch_frame(0x2a5, 4, 1);
	struct mcp2510_filters f;

	mcp2510_filters_default(&f);
	f.rxm[0] = rxm0;
	f.rxm[1] = rxm1;
	assert_int_equal(mcp2510_filters_apply(&lom->core, &f), 0);
	assert_int_equal(ch_start(lom, 500000, CAN_CTRLMODE_LISTENONLY), 0);
	/* node 2 acknowledges, node 1 sends */
	assert_int_equal(ch_start(&rig->node[1], 500000, 0), 0);
	assert_int_equal(ch_start(&rig->node[2], 500000, 0), 0);
	sim_bus_faults(&rig->bus)->bus_errors = 1;
	assert_true(mcp2510_tx_submit(&rig->node[1].core, &cf) >= 0);
	ch_run_idle(rig, 10 * MS);
	assert_int_equal(rig->node[2].ev.rx_count, 1);
	assert_int_equal(lom->ev.rx_count, 1);
	assert_true(ch_frame_equal(&lom->ev.rx[0], &cf));
	/* and every frame still arrives, standard or extended */
	assert_int_equal(deliver(rig, mixed_ids, ARRAY_SIZE(mixed_ids),
				 (bool[ARRAY_SIZE(mixed_ids)]){ 0 }),
			 ARRAY_SIZE(mixed_ids));
	ch_rig_free(rig);
}

static void test_listen_only_takes_valid_frames_only(void **state)
{
	(void)state;
	check_listen_only_takes_valid_frames_only(MCP2510_RXM_FILTERED,
						  MCP2510_RXM_FILTERED);
	check_listen_only_takes_valid_frames_only(MCP2510_RXM_ANY,
						  MCP2510_RXM_ANY);
	check_listen_only_takes_valid_frames_only(MCP2510_RXM_STD,
						  MCP2510_RXM_ANY);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_parse_ids),
		cmocka_unit_test(test_parse_refuses_and_keeps_the_old_value),
		cmocka_unit_test(test_format_round_trips),
		cmocka_unit_test(test_rxm_names),
		cmocka_unit_test(test_register_encoding),
		cmocka_unit_test(test_register_decoding),
		cmocka_unit_test(test_check_and_apply),
		cmocka_unit_test(test_default_accepts_everything),
		cmocka_unit_test(test_an739_example),
		cmocka_unit_test(test_receive_modes),
		cmocka_unit_test(test_filters_do_not_rely_on_reset_values),
		cmocka_unit_test(test_listen_only_takes_valid_frames_only),
	};

	return cmocka_run_group_tests_name("core_filter", tests, NULL, NULL);
}
