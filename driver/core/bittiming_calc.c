// SPDX-License-Identifier: GPL-2.0
/*
 * Userspace bit-timing calculator.  Where a kernel runs the chip, its
 * can_calc_bittiming() turns "bitrate 500000" into quanta; libmcp2510 and
 * mcp2510ctl have no kernel to ask, so this makes the same choices (Linux
 * 6.1) to give a bus the same timing whichever driver runs the node:
 *
 *  - nominal sample point: the one asked for, else CiA's 75.0 % above
 *    800 kbit/s, 80.0 % above 500 kbit/s and 87.5 % otherwise;
 *  - quanta per bit are tried from the most to the fewest, each with the
 *    prescaler rounded up and then rounded down; a candidate wins on a
 *    smaller bit-rate error, or on an equal one with a sample point
 *    closer to (and not after) the nominal one; the search ends at the
 *    first exact match;
 *  - the winner's TSEG1 is split evenly, the odd quantum to PS1; SJW is
 *    1 unless asked for, then capped at 4 and at PS2;
 *  - more than 5.0 % bit-rate error is refused;
 *  - unlike the kernel, a split leaving TSEG1 below the chip's minimum or
 *    shorter than TSEG2 is no candidate: it could not be programmed.
 *
 * Not built into the kernel module: it divides 64-bit numbers.
 */
#include "mcp2510_core_priv.h"

#define SYNC_SEG		1
#define MAX_ERROR_PERMILLE	50

struct split {
	u32 tseg1, tseg2;
	u32 sample_point;	/* permille */
	u32 error;		/* distance to the nominal one; U32_MAX: none */
};

static u32 distance(u32 a, u32 b)
{
	return a > b ? a - b : b - a;
}

static u32 clamp_u32(u32 v, u32 lo, u32 hi)
{
	return v < lo ? lo : v > hi ? hi : v;
}

static u32 nominal_sample_point(const struct can_bittiming *bt)
{
	if (bt->sample_point)
		return bt->sample_point;
	if (bt->bitrate > 800000)
		return 750;
	if (bt->bitrate > 500000)
		return 800;
	return 875;
}

/*
 * Split @tseg quanta (all but the sync segment) into TSEG1 and TSEG2 with
 * the sample point nearest to @nominal without passing it, trying the
 * TSEG2 the nominal point asks for and one quantum less.  No split at all
 * can come out when TSEG2's limits push the point past @nominal, or when
 * the TSEG1 left over is too short (the kernel's calculator would hand
 * such a split on; the encoder refuses it).
 */
static struct split split_tseg(const struct can_bittiming_const *btc,
			       u32 nominal, u32 tseg)
{
	u32 ntq = tseg + SYNC_SEG;
	struct split best = { .error = U32_MAX };
	u32 shorter;

	for (shorter = 0; shorter <= 1; shorter++) {
		struct split s;

		s.tseg2 = clamp_u32(ntq - nominal * ntq / 1000 - shorter,
				    btc->tseg2_min, btc->tseg2_max);
		s.tseg1 = tseg - s.tseg2;
		if (s.tseg1 > btc->tseg1_max) {
			s.tseg1 = btc->tseg1_max;
			s.tseg2 = tseg - s.tseg1;
		}
		/*
		 * An early nominal point leaves TSEG1 shorter than the chip
		 * counts, or than TSEG2 (AN739: PRSEG + PS1 >= PS2).
		 */
		if (s.tseg1 < btc->tseg1_min || s.tseg1 < s.tseg2)
			continue;
		s.sample_point = 1000 * (ntq - s.tseg2) / ntq;
		s.error = distance(nominal, s.sample_point);
		if (s.sample_point <= nominal && s.error < best.error)
			best = s;
	}
	return best;
}

/*
 * The search state.  sp_error is forgotten whenever a better bit rate
 * turns up, even when that candidate then fails on its sample point: a
 * later candidate at the old bit-rate error then wins on any valid sample
 * point.  The kernel's calculator behaves this way, so this one does too.
 */
struct search {
	u32 brp, tseg;
	u32 rate_error, sp_error;
};

static bool consider(const struct can_bittiming_const *btc, u32 clock_hz,
		     u32 bitrate, u32 nominal, u32 ntq, u32 brp,
		     struct search *best)
{
	u32 rate_error, sp_error;

	if (brp < btc->brp_min || brp > btc->brp_max)
		return false;
	rate_error = distance(bitrate, clock_hz / (brp * ntq));
	if (rate_error > best->rate_error)
		return false;
	if (rate_error < best->rate_error)
		best->sp_error = U32_MAX;
	sp_error = split_tseg(btc, nominal, ntq - SYNC_SEG).error;
	if (sp_error >= best->sp_error)
		return false;
	best->brp = brp;
	best->tseg = ntq - SYNC_SEG;
	best->rate_error = rate_error;
	best->sp_error = sp_error;
	return !rate_error && !sp_error;
}

static struct search search(const struct can_bittiming_const *btc,
			    u32 clock_hz, u32 bitrate, u32 nominal)
{
	struct search best = { .rate_error = U32_MAX, .sp_error = U32_MAX };
	u32 ntq_max = SYNC_SEG + btc->tseg1_max + btc->tseg2_max;
	u32 ntq_min = SYNC_SEG + btc->tseg1_min + btc->tseg2_min;
	u32 ntq;

	for (ntq = ntq_max; ntq >= ntq_min; ntq--) {
		u32 brp = (u32)(clock_hz / ((u64)ntq * bitrate));
		u32 brp_up = (brp + 1) / btc->brp_inc * btc->brp_inc;
		u32 brp_down = brp / btc->brp_inc * btc->brp_inc;

		if (consider(btc, clock_hz, bitrate, nominal, ntq, brp_up,
			     &best) ||
		    consider(btc, clock_hz, bitrate, nominal, ntq, brp_down,
			     &best))
			break;
	}
	return best;
}

int mcp2510_bittiming_calc(u32 clock_hz, struct can_bittiming *bt)
{
	const struct can_bittiming_const *btc = &mcp2510_bittiming_const;
	u32 nominal, ntq;
	struct search best;
	struct split s;

	if (!clock_hz || !bt->bitrate || bt->sample_point >= 1000)
		return -EINVAL;
	nominal = nominal_sample_point(bt);
	best = search(btc, clock_hz, bt->bitrate, nominal);
	if (best.rate_error == U32_MAX ||
	    (u64)best.rate_error * 1000 / bt->bitrate > MAX_ERROR_PERMILLE)
		return -EDOM;

	s = split_tseg(btc, nominal, best.tseg);
	ntq = SYNC_SEG + best.tseg;
	bt->sample_point = s.sample_point;
	bt->tq = (u32)((u64)best.brp * 1000000000 / clock_hz);
	bt->prop_seg = s.tseg1 / 2;
	bt->phase_seg1 = s.tseg1 - bt->prop_seg;
	bt->phase_seg2 = s.tseg2;
	if (!bt->sjw)
		bt->sjw = 1;
	if (bt->sjw > btc->sjw_max)
		bt->sjw = btc->sjw_max;
	if (bt->sjw > s.tseg2)
		bt->sjw = s.tseg2;
	bt->brp = best.brp;
	bt->bitrate = clock_hz / (best.brp * ntq);
	return 0;
}
