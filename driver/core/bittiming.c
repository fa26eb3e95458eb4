// SPDX-License-Identifier: GPL-2.0
/*
 * Bit timing: the chip's limits for the kernel's calculator, and CNF1..CNF3
 * from a struct can_bittiming, checked against the rules of the data sheet
 * and AN739 ("Bit Timing Requirements").
 */
#include "mcp2510_core_priv.h"

/* Time quanta of the synchronisation segment, always one. */
#define SYNC_SEG		1
/* Information processing time after the sample point, in quanta. */
#define IPT_TQ			2
#define PRSEG_MAX		8
#define PS1_MAX			8
#define PS2_MAX			8
#define SJW_MAX			4
#define BRP_MAX			64

/*
 * In CAN-clock quanta (oscillator / 2): TSEG1 = PRSEG + PS1 (2..16, but
 * PRSEG + PS1 >= PS2 >= 2 and PS1 >= 1 make 3 the useful minimum, which
 * the encoder holds timing given by hand to as well).
 */
const struct can_bittiming_const mcp2510_bittiming_const = {
	.name = "mcp2510",
	.tseg1_min = 3,
	.tseg1_max = PRSEG_MAX + PS1_MAX,
	.tseg2_min = IPT_TQ,
	.tseg2_max = PS2_MAX,
	.sjw_max = SJW_MAX,
	.brp_min = 1,
	.brp_max = BRP_MAX,
	.brp_inc = 1,
};

static bool within(u32 v, u32 min, u32 max)
{
	return v >= min && v <= max;
}

static int bittiming_check(const struct can_bittiming *bt)
{
	if (!within(bt->prop_seg, 1, PRSEG_MAX) ||
	    !within(bt->phase_seg1, 1, PS1_MAX) ||
	    !within(bt->phase_seg2, IPT_TQ, PS2_MAX) ||
	    !within(bt->sjw, 1, SJW_MAX) ||
	    !within(bt->brp, 1, BRP_MAX))
		return -EINVAL;
	/*
	 * Sample point at or after the middle of the bit, and no shorter a
	 * TSEG1 than the constants tell the stack (which checks only timing
	 * given by hand against them).
	 */
	if (bt->prop_seg + bt->phase_seg1 < bt->phase_seg2 ||
	    bt->prop_seg + bt->phase_seg1 < mcp2510_bittiming_const.tseg1_min)
		return -EINVAL;
	/* a resynchronisation must not move the bit end before the sample */
	if (bt->phase_seg2 <= bt->sjw)
		return -EINVAL;
	return 0;
}

int mcp2510_bittiming_encode(const struct can_bittiming *bt, u32 ctrlmode,
			     u8 cnf[3])
{
	int err;

	err = bittiming_check(bt);
	if (err)
		return err;
	cnf[0] = FIELD_PREP(MCP2510_CNF1_SJW_MASK, bt->sjw - 1) |
		 FIELD_PREP(MCP2510_CNF1_BRP_MASK, bt->brp - 1);
	/* BTLMODE: PS2 comes from CNF3, not from max(PS1, IPT) */
	cnf[1] = MCP2510_CNF2_BTLMODE |
		 (ctrlmode & CAN_CTRLMODE_3_SAMPLES ? MCP2510_CNF2_SAM : 0) |
		 FIELD_PREP(MCP2510_CNF2_PHSEG1_MASK, bt->phase_seg1 - 1) |
		 FIELD_PREP(MCP2510_CNF2_PRSEG_MASK, bt->prop_seg - 1);
	cnf[2] = FIELD_PREP(MCP2510_CNF3_PHSEG2_MASK, bt->phase_seg2 - 1);
	return 0;
}

void mcp2510_bittiming_decode(const u8 cnf[3], u32 osc_hz,
			      struct can_bittiming *bt)
{
	u32 ntq, clock_khz;

	memset(bt, 0, sizeof(*bt));
	bt->brp = FIELD_GET(MCP2510_CNF1_BRP_MASK, cnf[0]) + 1;
	bt->sjw = FIELD_GET(MCP2510_CNF1_SJW_MASK, cnf[0]) + 1;
	bt->prop_seg = FIELD_GET(MCP2510_CNF2_PRSEG_MASK, cnf[1]) + 1;
	bt->phase_seg1 = FIELD_GET(MCP2510_CNF2_PHSEG1_MASK, cnf[1]) + 1;
	if (cnf[1] & MCP2510_CNF2_BTLMODE)
		bt->phase_seg2 = FIELD_GET(MCP2510_CNF3_PHSEG2_MASK, cnf[2]) + 1;
	else
		bt->phase_seg2 = bt->phase_seg1 > IPT_TQ ? bt->phase_seg1 : IPT_TQ;

	ntq = SYNC_SEG + bt->prop_seg + bt->phase_seg1 + bt->phase_seg2;
	bt->sample_point = 1000 * (ntq - bt->phase_seg2) / ntq;
	if (!osc_hz)
		return;
	/* 32-bit arithmetic only: a quantum is 2 * BRP oscillator periods */
	bt->bitrate = osc_hz / (2 * bt->brp * ntq);
	clock_khz = osc_hz / 1000;
	if (clock_khz)
		bt->tq = 2000000 * bt->brp / clock_khz;
}
