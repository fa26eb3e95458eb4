// SPDX-License-Identifier: GPL-2.0
/*
 * Bit timing from the command line, its errors told as
 * can-calc-bit-timing and the kernel tell them.
 */
#include <inttypes.h>
#include <stdio.h>

#include "cli.h"

/* Why @bitrate at @sp cannot be made, when without @sp it can. */
static void sample_point_why(struct cli_args *a, uint32_t osc_hz,
			     uint32_t bitrate, uint32_t sp)
{
	struct can_bittiming bt;
	uint8_t cnf[3];
	uint32_t later;
	char earliest[48] = "";

	for (later = sp + 1; later < 1000; later++)
		if (!mcp2510_bittiming_for(osc_hz, bitrate, later, &bt, cnf))
			break;
	if (later < 1000)
		snprintf(earliest, sizeof(earliest), "; the earliest here is %.3f",
			 bt.sample_point / 1000.0);
	cli_error(a->err, a->prog,
		  "sample point %.3f at %" PRIu32 " bit/s breaks the data sheet's PRSEG + PS1 >= PS2 (the sample point must come after the middle of the bit)%s",
		  sp / 1000.0, bitrate, earliest);
}

/*
 * The oscillator tolerance CAN allows a node at best (Bosch CAN 2.0,
 * part B, section 9: 1.58 %), in hundredths of a percent: a node further
 * off than that from the others cannot stay in step with them.
 */
#define CAN_TOLERANCE_CENTI_PCT	158
/* A sample point further off the CiA one than this is told about (in %). */
#define SP_WARN_PCT		5.0

/* The CiA recommendation, as the kernel's calculator takes it. */
static uint32_t cia_sample_point(uint32_t bitrate)
{
	if (bitrate > 800000)
		return 750;
	if (bitrate > 500000)
		return 800;
	return 875;
}

/* @real's distance from @nominal, in % of @nominal. */
static double off_pct(uint32_t real, uint32_t nominal)
{
	double d = (double)real - (double)nominal;

	return 100.0 * (d < 0 ? -d : d) / nominal;
}

/* Refused beyond the tolerance, a warning when not exact; 0 or -1. */
static int rate_error(struct cli_args *a, uint32_t osc_hz, uint32_t bitrate,
		      const struct can_bittiming *bt)
{
	double pct = off_pct(bt->bitrate, bitrate);

	if (bt->bitrate == bitrate)
		return 0;
	if (pct * 100 > CAN_TOLERANCE_CENTI_PCT) {
		cli_error(a->err, a->prog,
			  "bit rate %" PRIu32 ": the nearest a %" PRIu32 " Hz oscillator makes is %u, %.1f%% off, beyond the 1.58%% oscillator tolerance CAN allows",
			  bitrate, osc_hz, bt->bitrate, pct);
		return -1;
	}
	cli_error(a->err, a->prog,
		  "warning: bit rate %u is %.1f%% off the %" PRIu32 " asked for",
		  bt->bitrate, pct, bitrate);
	return 0;
}

static void sample_point_warning(struct cli_args *a, uint32_t osc_hz,
				 uint32_t bitrate, uint32_t sp,
				 const struct can_bittiming *bt)
{
	uint32_t nominal = sp ? sp : cia_sample_point(bitrate);
	double pct = off_pct(bt->sample_point, nominal);

	if (bt->sample_point == nominal || (!sp && pct <= SP_WARN_PCT))
		return;
	cli_error(a->err, a->prog,
		  "warning: %ssample point %.3f cannot be made at %" PRIu32 " bit/s from a %" PRIu32 " Hz oscillator; using %.3f (%.1f%% off)",
		  sp ? "" : "the CiA ", nominal / 1000.0, bitrate, osc_hz,
		  bt->sample_point / 1000.0, pct);
}

int cli_bittiming(struct cli_args *a, uint32_t osc_hz, uint32_t bitrate,
		  uint32_t sp, struct can_bittiming *bt, uint8_t cnf[3])
{
	if (mcp2510_bittiming_for(osc_hz, bitrate, sp, bt, cnf)) {
		if (sp && !mcp2510_bittiming_for(osc_hz, bitrate, 0, bt, cnf)) {
			sample_point_why(a, osc_hz, bitrate, sp);
			return -1;
		}
		cli_error(a->err, a->prog,
			  "bit rate %" PRIu32 " cannot be made from a %" PRIu32 " Hz oscillator (none within 5%% with 6 to 25 quanta of 2 to 128 oscillator periods)",
			  bitrate, osc_hz);
		return -1;
	}
	if (rate_error(a, osc_hz, bitrate, bt))
		return -1;
	sample_point_warning(a, osc_hz, bitrate, sp, bt);
	return 0;
}
