// SPDX-License-Identifier: LGPL-2.1-or-later
/* What a stopped handle can be told: bit timing, control modes, filters. */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "handle.h"
#include "mcp2510_core_priv.h"	/* mcp2510_filters_write() */

#define NSEC_PER_SEC	1000000000ull

static const uint32_t supported_ctrlmodes =
	CAN_CTRLMODE_LOOPBACK | CAN_CTRLMODE_LISTENONLY |
	CAN_CTRLMODE_3_SAMPLES | CAN_CTRLMODE_BERR_REPORTING |
	CAN_CTRLMODE_CC_LEN8_DLC;

_Static_assert(MCP2510_OSC_HZ_MIN == MCP2510_OSC_MIN_HZ &&
	       MCP2510_OSC_HZ_MAX == MCP2510_OSC_MAX_HZ,
	       "the public oscillator range is the core's");

static int osc_check(uint32_t osc_hz)
{
	if (osc_hz < MCP2510_OSC_MIN_HZ || osc_hz > MCP2510_OSC_MAX_HZ)
		return -EINVAL;
	return 0;
}

int mcp2510_bittiming_for(uint32_t osc_hz, uint32_t bitrate,
			  uint32_t sample_point, struct can_bittiming *bt,
			  uint8_t cnf[3])
{
	int ret = osc_check(osc_hz);

	if (!ret && (!bitrate || sample_point >= 1000))
		ret = -EINVAL;
	if (ret)
		return mcp2510_fail(ret);
	memset(bt, 0, sizeof(*bt));
	bt->bitrate = bitrate;
	bt->sample_point = sample_point;
	ret = mcp2510_bittiming_calc(osc_hz / 2, bt);
	if (!ret)
		ret = mcp2510_bittiming_encode(bt, 0, cnf);
	return mcp2510_fail(ret);
}

static int stopped(const struct mcp2510 *h)
{
	return h->running ? -EBUSY : 0;
}

int mcp2510_set_bitrate(struct mcp2510 *h, uint32_t bitrate,
			uint32_t sample_point)
{
	struct can_bittiming bt;
	uint8_t cnf[3];
	int ret = stopped(h);

	if (ret)
		return mcp2510_fail(ret);
	if (mcp2510_bittiming_for(h->chip.osc_hz, bitrate, sample_point,
				  &bt, cnf))
		return -1;
	h->bt = bt;
	h->have_bt = true;
	return 0;
}

/* Fill what the kernel derives from explicit segments: brp/tq, rate, SP. */
static int bittiming_complete(uint32_t clock_hz, struct can_bittiming *bt)
{
	uint64_t total = 1ull + bt->prop_seg + bt->phase_seg1 + bt->phase_seg2;

	if (!bt->brp && bt->tq)
		bt->brp = (uint32_t)(((uint64_t)bt->tq * clock_hz +
				      NSEC_PER_SEC / 2) / NSEC_PER_SEC);
	if (!bt->brp || !bt->phase_seg2 || !bt->sjw)
		return -EINVAL;
	bt->tq = (uint32_t)((uint64_t)bt->brp * NSEC_PER_SEC / clock_hz);
	bt->bitrate = (uint32_t)(clock_hz / (bt->brp * total));
	bt->sample_point = (uint32_t)(1000 * (total - bt->phase_seg2) / total);
	return 0;
}

int mcp2510_set_bittiming(struct mcp2510 *h, const struct can_bittiming *in)
{
	struct can_bittiming bt = *in;
	uint8_t cnf[3];
	int ret = stopped(h);

	if (!ret)
		ret = bittiming_complete(h->chip.osc_hz / 2, &bt);
	if (!ret)
		ret = mcp2510_bittiming_encode(&bt, h->ctrlmode, cnf);
	if (ret)
		return mcp2510_fail(ret);
	h->bt = bt;
	h->have_bt = true;
	return 0;
}

int mcp2510_get_bittiming(const struct mcp2510 *h, struct can_bittiming *bt)
{
	if (!h->have_bt)
		return mcp2510_fail(-ENODATA);
	*bt = h->bt;
	return 0;
}

int mcp2510_set_ctrlmode(struct mcp2510 *h, uint32_t ctrlmode)
{
	uint32_t supported = supported_ctrlmodes;
	int ret = stopped(h);

	if (ret)
		return mcp2510_fail(ret);
	if (h->chip.variant->has_one_shot)
		supported |= CAN_CTRLMODE_ONE_SHOT;
	if (ctrlmode & ~supported)
		return mcp2510_fail(-EOPNOTSUPP);
	h->ctrlmode = ctrlmode;
	return 0;
}

uint32_t mcp2510_get_ctrlmode(const struct mcp2510 *h)
{
	return h->ctrlmode;
}

/* ---- hardware filters: the public struct mirrors the core's ---------- */

static void id_to_core(const struct mcp2510_hw_id *in,
		       struct mcp2510_filter_id *out)
{
	out->id = in->id;
	out->ext = in->ext;
}

static void id_from_core(const struct mcp2510_filter_id *in,
			 struct mcp2510_hw_id *out)
{
	out->id = in->id;
	out->ext = in->ext;
}

static void filters_to_core(const struct mcp2510_hw_filters *in,
			    struct mcp2510_filters *out)
{
	unsigned int i;

	for (i = 0; i < MCP2510_MASK_COUNT; i++)
		id_to_core(&in->mask[i], &out->mask[i]);
	for (i = 0; i < MCP2510_FILTER_COUNT; i++)
		id_to_core(&in->filter[i], &out->filter[i]);
	for (i = 0; i < MCP2510_RXB_COUNT; i++)
		out->rxm[i] = in->rxm[i];
	out->rollover = in->rollover;
}

static void filters_from_core(const struct mcp2510_filters *in,
			      struct mcp2510_hw_filters *out)
{
	unsigned int i;

	memset(out, 0, sizeof(*out));
	for (i = 0; i < MCP2510_MASK_COUNT; i++)
		id_from_core(&in->mask[i], &out->mask[i]);
	for (i = 0; i < MCP2510_FILTER_COUNT; i++)
		id_from_core(&in->filter[i], &out->filter[i]);
	for (i = 0; i < MCP2510_RXB_COUNT; i++)
		out->rxm[i] = in->rxm[i];
	out->rollover = in->rollover;
}

void mcp2510_hw_filters_default(struct mcp2510_hw_filters *f)
{
	struct mcp2510_filters core;

	mcp2510_filters_default(&core);
	filters_from_core(&core, f);
}

MCP2510_ABI_LAYOUT(struct mcp2510_hw_filters, 84);

int mcp2510_set_filters(struct mcp2510 *h, const struct mcp2510_hw_filters *f)
{
	struct mcp2510_filters core;
	int ret = stopped(h);

	if (ret)
		return mcp2510_fail(ret);
	if (!mcp2510_reserved_zero(f->reserved, sizeof(f->reserved)))
		return mcp2510_fail(-EINVAL);
	filters_to_core(f, &core);
	ret = mcp2510_filters_apply(&h->chip, &core);
	if (ret)
		return mcp2510_fail(ret);
	h->filters = core;
	/*
	 * A chip this handle reset waits in configuration mode: write them
	 * now, so they stay for whoever opens it next (see mcp2510_open()).
	 */
	if (h->reset_done)
		ret = mcp2510_filters_write(&h->chip);
	return mcp2510_fail(ret);
}

int mcp2510_get_filters(const struct mcp2510 *h, struct mcp2510_hw_filters *f)
{
	filters_from_core(&h->filters, f);
	return 0;
}

/* "mask1", "filter5", ...: the index after @prefix, below @count. */
static int setting_index(const char *name, const char *prefix,
			 unsigned int count)
{
	size_t n = strlen(prefix);

	if (strncmp(name, prefix, n) || !name[n] || name[n + 1])
		return -1;
	if (name[n] < '0' || (unsigned int)(name[n] - '0') >= count)
		return -1;
	return name[n] - '0';
}

static int set_id(struct mcp2510_hw_id *dst, const char *value)
{
	struct mcp2510_filter_id id;
	int ret = mcp2510_filter_id_parse(value, strlen(value), &id);

	if (ret)
		return ret;
	id_from_core(&id, dst);
	return 0;
}

static int set_rollover(bool *dst, const char *value)
{
	if (strcmp(value, "0") && strcmp(value, "1"))
		return -EINVAL;
	*dst = value[0] == '1';
	return 0;
}

static int hw_filters_set(struct mcp2510_hw_filters *f, const char *name,
			  const char *value)
{
	int i;

	i = setting_index(name, "mask", MCP2510_MASK_COUNT);
	if (i >= 0)
		return set_id(&f->mask[i], value);
	i = setting_index(name, "filter", MCP2510_FILTER_COUNT);
	if (i >= 0)
		return set_id(&f->filter[i], value);
	i = setting_index(name, "rxm", MCP2510_RXB_COUNT);
	if (i >= 0)
		return mcp2510_rxm_parse(value, strlen(value), &f->rxm[i]);
	if (!strcmp(name, "rollover"))
		return set_rollover(&f->rollover, value);
	return -EINVAL;
}

int mcp2510_hw_filters_set(struct mcp2510_hw_filters *f, const char *name,
			   const char *value)
{
	return mcp2510_fail(hw_filters_set(f, name, value));
}

/*
 * As sysfs writes them, except that a 29-bit id has all eight digits:
 * an extended 0 reads "00000000x", where sysfs's "0x" looks like the
 * start of a hexadecimal number.  Both forms parse the same.
 */
static int format_id(const char *name, unsigned int i,
		     const struct mcp2510_hw_id *id, char *buf, size_t len)
{
	if (id->ext)
		return snprintf(buf, len, "%s%u %08" PRIx32 "x", name, i,
				id->id);
	return snprintf(buf, len, "%s%u %" PRIx32, name, i, id->id);
}

static const char *rxm_name(uint8_t rxm)
{
	const char *name = mcp2510_rxm_name(rxm);

	return name ? name : "invalid";
}

int mcp2510_hw_filters_format(const struct mcp2510_hw_filters *f,
			      unsigned int i, char *buf, size_t len)
{
	const unsigned int nmask = MCP2510_MASK_COUNT;
	const unsigned int nfilt = MCP2510_FILTER_COUNT;
	int n;

	if (i < nmask)
		n = format_id("mask", i, &f->mask[i], buf, len);
	else if (i < nmask + nfilt)
		n = format_id("filter", i - nmask, &f->filter[i - nmask],
			      buf, len);
	else if (i < nmask + nfilt + MCP2510_RXB_COUNT)
		n = snprintf(buf, len, "rxm%u %s", i - nmask - nfilt,
			     rxm_name(f->rxm[i - nmask - nfilt]));
	else if (i == MCP2510_HW_FILTER_SETTINGS - 1)
		n = snprintf(buf, len, "rollover %d", f->rollover ? 1 : 0);
	else
		return mcp2510_fail(-EINVAL);
	return n < 0 || (size_t)n >= len ? mcp2510_fail(-ENOSPC) : n;
}
