// SPDX-License-Identifier: GPL-2.0
/*
 * Bit timing: mcp2510_bittiming_encode() with any struct can_bittiming,
 * and mcp2510_bittiming_calc() with any clock, bit rate, sample point
 * and SJW (fuzz_input.h decisions; the first picks the function).
 *
 * The encoder must refuse what the chip cannot do and encode the rest so
 * that decoding gives the same segments back.  The calculator must end
 * (libFuzzer's -timeout catches a loop), refuse exactly the documented
 * inputs, and otherwise return timing inside mcp2510_bittiming_const
 * with the sample point not before the middle of the bit (AN739), at a
 * bit rate no more than 5 % off, with the fields consistent with each
 * other.
 */
#include <stdint.h>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "mcp2510_core.h"

#define SYNC_SEG		1
#define MAX_ERROR_PERMILLE	50
/* quanta of a bit the chip can count: 1 + 8 + 8 + 8 */
#define NTQ_MAX			25

static bool within(u32 v, u32 min, u32 max)
{
	return v >= min && v <= max;
}

static void check_limits(const struct can_bittiming *bt)
{
	const struct can_bittiming_const *c = &mcp2510_bittiming_const;

	FUZZ_CHECK(within(bt->prop_seg + bt->phase_seg1, c->tseg1_min,
			  c->tseg1_max));
	FUZZ_CHECK(bt->prop_seg >= 1 && bt->phase_seg1 >= 1);
	FUZZ_CHECK(within(bt->phase_seg2, c->tseg2_min, c->tseg2_max));
	FUZZ_CHECK(within(bt->sjw, 1, c->sjw_max));
	FUZZ_CHECK(within(bt->brp, c->brp_min, c->brp_max));
}

static void check_encode(struct fuzz_input *in)
{
	struct can_bittiming bt = { 0 }, back;
	u32 ctrlmode;
	u8 cnf[3] = { 0 };
	bool sam;

	bt.prop_seg = fuzz_back_u32(in);
	bt.phase_seg1 = fuzz_back_u32(in);
	bt.phase_seg2 = fuzz_back_u32(in);
	bt.sjw = fuzz_back_u32(in);
	bt.brp = fuzz_back_u32(in);
	ctrlmode = fuzz_back_u32(in);
	if (mcp2510_bittiming_encode(&bt, ctrlmode, cnf)) {
		FUZZ_CHECK(!cnf[0] && !cnf[1] && !cnf[2]);
		return;
	}
	check_limits(&bt);
	/* AN739: PS2 longer than SJW, sample point not before PS2 */
	FUZZ_CHECK(bt.phase_seg2 > bt.sjw);
	FUZZ_CHECK(bt.prop_seg + bt.phase_seg1 >= bt.phase_seg2);
	mcp2510_bittiming_decode(cnf, 0, &back);
	FUZZ_CHECK(back.prop_seg == bt.prop_seg &&
		   back.phase_seg1 == bt.phase_seg1 &&
		   back.phase_seg2 == bt.phase_seg2 && back.sjw == bt.sjw &&
		   back.brp == bt.brp);
	sam = cnf[1] & MCP2510_CNF2_SAM;
	FUZZ_CHECK(sam == !!(ctrlmode & CAN_CTRLMODE_3_SAMPLES));
}

static void check_calc(struct fuzz_input *in)
{
	struct can_bittiming bt = { 0 };
	u32 clock_hz = fuzz_back_u32(in);
	u32 bitrate, asked_sp, asked_sjw, ntq, error;
	int ret;

	bt.bitrate = fuzz_back_u32(in);
	bt.sample_point = fuzz_back_u32(in);
	bt.sjw = fuzz_back_u8(in);
	bitrate = bt.bitrate;
	asked_sp = bt.sample_point;
	asked_sjw = bt.sjw;
	ret = mcp2510_bittiming_calc(clock_hz, &bt);
	if (!clock_hz || !bitrate || asked_sp >= 1000) {
		FUZZ_CHECK(ret == -EINVAL);
		return;
	}
	FUZZ_CHECK(ret == 0 || ret == -EDOM);
	if (ret)
		return;
	check_limits(&bt);
	FUZZ_CHECK(bt.prop_seg + bt.phase_seg1 >= bt.phase_seg2);
	ntq = SYNC_SEG + bt.prop_seg + bt.phase_seg1 + bt.phase_seg2;
	FUZZ_CHECK(ntq <= NTQ_MAX);
	FUZZ_CHECK(bt.bitrate == clock_hz / (bt.brp * ntq));
	error = bt.bitrate > bitrate ? bt.bitrate - bitrate :
		bitrate - bt.bitrate;
	FUZZ_CHECK((u64)error * 1000 / bitrate <= MAX_ERROR_PERMILLE);
	FUZZ_CHECK(bt.sample_point == 1000 * (ntq - bt.phase_seg2) / ntq);
	FUZZ_CHECK(!asked_sp || bt.sample_point <= asked_sp);
	FUZZ_CHECK(bt.sjw <= bt.phase_seg2);
	FUZZ_CHECK(!asked_sjw || bt.sjw <= asked_sjw);
	FUZZ_CHECK(bt.tq == (u32)((u64)bt.brp * 1000000000 / clock_hz));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct fuzz_input in;

	fuzz_input_init(&in, data, size);
	if (fuzz_back_bool(&in))
		check_calc(&in);
	else
		check_encode(&in);
	return 0;
}
