// SPDX-License-Identifier: GPL-2.0
/*
 * struct can_frame <-> buffer registers SIDH..D7: standard, extended, RTR,
 * every length, DLC clamping and the raw DLC of CAN_CTRLMODE_CC_LEN8_DLC.  Frames through real chips are the TX
 * and IRQ suites' business.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "mcp2510_core.h"

/* offsets inside SIDH..D7 */
#define SIDH	0
#define SIDL	1
#define EID8	2
#define EID0	3
#define DLC	4
#define D0	5

static void test_standard_frame_layout(void **state)
{
	struct can_frame cf = { .can_id = 0x5a3, .len = 3,
				.data = { 0x11, 0x22, 0x33 } };
	u8 regs[MCP2510_FRAME_REGS];

	(void)state;
	memset(regs, 0xee, sizeof(regs));
	assert_int_equal(mcp2510_frame_encode(&cf, 0, regs), 5 + 3);
	assert_int_equal(regs[SIDH], 0x5a3 >> 3);
	assert_int_equal(regs[SIDL], (0x5a3 & 7) << 5);	/* EXIDE clear */
	assert_int_equal(regs[EID8], 0);
	assert_int_equal(regs[EID0], 0);
	assert_int_equal(regs[DLC], 3);
	assert_memory_equal(regs + D0, cf.data, 3);
	assert_int_equal(regs[D0 + 3], 0xee);	/* nothing past the data */
}

static void test_extended_frame_layout(void **state)
{
	/* 29 bits: 0b10101010101 | 01 | 0x9abc */
	u32 id = 0x155u << 18 | 1u << 16 | 0x9abc;
	struct can_frame cf = { .can_id = id | CAN_EFF_FLAG, .len = 8,
				.data = { 1, 2, 3, 4, 5, 6, 7, 8 } };
	u8 regs[MCP2510_FRAME_REGS];

	(void)state;
	assert_int_equal(mcp2510_frame_encode(&cf, 0, regs), 13);
	assert_int_equal(regs[SIDH], 0x155 >> 3);
	assert_int_equal(regs[SIDL], (0x155 & 7) << 5 | MCP2510_SIDL_EXIDE | 1);
	assert_int_equal(regs[EID8], 0x9a);
	assert_int_equal(regs[EID0], 0xbc);
	assert_int_equal(regs[DLC], 8);
}

static void test_remote_frames(void **state)
{
	struct can_frame std = { .can_id = 0x123 | CAN_RTR_FLAG, .len = 4 };
	struct can_frame ext = { .can_id = 0x1234567 | CAN_RTR_FLAG |
					   CAN_EFF_FLAG, .len = 2 };
	u8 regs[MCP2510_FRAME_REGS];
	struct can_frame back;

	(void)state;
	/* TX: the RTR bit lives in DLC for both formats; no data is sent */
	assert_int_equal(mcp2510_frame_encode(&std, 0, regs), 5);
	assert_int_equal(regs[DLC], MCP2510_DLC_RTR | 4);
	assert_int_equal(mcp2510_frame_encode(&ext, 0, regs), 5);
	assert_int_equal(regs[DLC], MCP2510_DLC_RTR | 2);

	/* RX: a standard remote frame is flagged by SIDL.SRR */
	memset(regs, 0, sizeof(regs));
	regs[SIDH] = 0x123 >> 3;
	regs[SIDL] = (0x123 & 7) << 5 | MCP2510_SIDL_SRR;
	regs[DLC] = 4;
	regs[D0] = 0x55;
	mcp2510_frame_decode(regs, 0, &back);
	assert_int_equal(back.can_id, 0x123 | CAN_RTR_FLAG);
	assert_int_equal(back.len, 4);
	assert_int_equal(back.data[0], 0);	/* a remote frame has no data */

	/* ... an extended one by DLC.RTR */
	regs[SIDL] = MCP2510_SIDL_EXIDE;
	regs[DLC] = MCP2510_DLC_RTR | 2;
	mcp2510_frame_decode(regs, 0, &back);
	assert_true(back.can_id & CAN_RTR_FLAG);
	assert_true(back.can_id & CAN_EFF_FLAG);
	assert_int_equal(back.len, 2);
}

static void test_round_trip_every_length(void **state)
{
	static const canid_t ids[] = {
		0, 0x7ff, 0x555, CAN_EFF_FLAG, CAN_EFF_FLAG | 0x1fffffff,
		CAN_EFF_FLAG | 0x0aaaaaaa, CAN_EFF_FLAG | 0x15555555,
	};
	unsigned int i, len;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(ids); i++) {
		for (len = 0; len <= CAN_MAX_DLEN; len++) {
			struct can_frame cf = { .can_id = ids[i], .len = len };
			u8 regs[MCP2510_FRAME_REGS];
			struct can_frame back;
			unsigned int b;

			for (b = 0; b < len; b++)
				cf.data[b] = 0x30 + 7 * b + i;
			assert_int_equal(mcp2510_frame_encode(&cf, 0, regs),
					 5 + len);
			mcp2510_frame_decode(regs, 0, &back);
			assert_int_equal(back.can_id, cf.can_id);
			assert_int_equal(back.len, len);
			assert_memory_equal(back.data, cf.data, CAN_MAX_DLEN);
		}
	}
}

static void test_dlc_above_8_is_clamped(void **state)
{
	u8 regs[MCP2510_FRAME_REGS];
	struct can_frame back;
	unsigned int dlc;

	(void)state;
	for (dlc = 9; dlc <= 15; dlc++) {
		memset(regs, 0x77, sizeof(regs));
		regs[SIDL] = 0;
		regs[DLC] = dlc | MCP2510_DLC_RB0;	/* reserved bits set */
		mcp2510_frame_decode(regs, 0, &back);
		assert_int_equal(back.len, 8);
		assert_int_equal(back.data[7], 0x77);
	}
}

/* cc-len8-dlc: a DLC of 9..15 is written and read as is, with 8 bytes. */
static void test_len8_dlc_round_trip(void **state)
{
	u8 regs[MCP2510_FRAME_REGS];
	struct can_frame back;
	unsigned int dlc;

	(void)state;
	for (dlc = 9; dlc <= CAN_MAX_RAW_DLC; dlc++) {
		struct can_frame cf = { .can_id = 0x123, .len = 8,
					.len8_dlc = dlc,
					.data = { 1, 2, 3, 4, 5, 6, 7, 8 } };
		struct can_frame ext = cf;

		assert_int_equal(mcp2510_frame_encode(&cf,
						      CAN_CTRLMODE_CC_LEN8_DLC,
						      regs), 13);
		assert_int_equal(regs[DLC], dlc);
		mcp2510_frame_decode(regs, CAN_CTRLMODE_CC_LEN8_DLC, &back);
		assert_int_equal(back.len, 8);
		assert_int_equal(back.len8_dlc, dlc);
		assert_memory_equal(back.data, cf.data, 8);

		/* an extended remote frame keeps RTR beside the raw DLC */
		ext.can_id = CAN_EFF_FLAG | CAN_RTR_FLAG | 0x1234567;
		assert_int_equal(mcp2510_frame_encode(&ext,
						      CAN_CTRLMODE_CC_LEN8_DLC,
						      regs), 5);
		assert_int_equal(regs[DLC], MCP2510_DLC_RTR | dlc);
		mcp2510_frame_decode(regs, CAN_CTRLMODE_CC_LEN8_DLC, &back);
		assert_int_equal(back.can_id, ext.can_id);
		assert_int_equal(back.len, 8);
		assert_int_equal(back.len8_dlc, dlc);
	}
}

/* Without the mode len8_dlc is ignored on TX and never set on RX. */
static void test_len8_dlc_needs_the_mode(void **state)
{
	struct can_frame cf = { .can_id = 0x321, .len = 8, .len8_dlc = 14,
				.data = { 8, 7, 6, 5, 4, 3, 2, 1 } };
	struct can_frame short_cf = { .can_id = 0x321, .len = 3,
				      .len8_dlc = 14 };
	u8 regs[MCP2510_FRAME_REGS];
	struct can_frame back;

	(void)state;
	assert_int_equal(mcp2510_frame_encode(&cf, 0, regs), 13);
	assert_int_equal(regs[DLC], 8);
	/* len8_dlc counts only beside a length of 8 */
	assert_int_equal(mcp2510_frame_encode(&short_cf,
					      CAN_CTRLMODE_CC_LEN8_DLC,
					      regs), 8);
	assert_int_equal(regs[DLC], 3);
	/* a DLC that is no raw DLC is ignored too */
	cf.len8_dlc = 8;
	assert_int_equal(mcp2510_frame_encode(&cf, CAN_CTRLMODE_CC_LEN8_DLC,
					      regs), 13);
	assert_int_equal(regs[DLC], 8);

	regs[DLC] = 14;
	mcp2510_frame_decode(regs, 0, &back);
	assert_int_equal(back.len, 8);
	assert_int_equal(back.len8_dlc, 0);
	assert_memory_equal(back.data, cf.data, 8);
	regs[DLC] = 5;
	mcp2510_frame_decode(regs, CAN_CTRLMODE_CC_LEN8_DLC, &back);
	assert_int_equal(back.len, 5);
	assert_int_equal(back.len8_dlc, 0);
}

static void test_encode_refuses_bad_length(void **state)
{
	struct can_frame cf = { .can_id = 1, .len = 9 };
	u8 regs[MCP2510_FRAME_REGS];

	(void)state;
	assert_int_equal(mcp2510_frame_encode(&cf, 0, regs), -EINVAL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_standard_frame_layout),
		cmocka_unit_test(test_len8_dlc_round_trip),
		cmocka_unit_test(test_len8_dlc_needs_the_mode),
		cmocka_unit_test(test_extended_frame_layout),
		cmocka_unit_test(test_remote_frames),
		cmocka_unit_test(test_round_trip_every_length),
		cmocka_unit_test(test_dlc_above_8_is_clamped),
		cmocka_unit_test(test_encode_refuses_bad_length),
	};

	return cmocka_run_group_tests_name("core_frame", tests, NULL, NULL);
}
