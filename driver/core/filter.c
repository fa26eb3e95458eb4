// SPDX-License-Identifier: GPL-2.0
/*
 * Acceptance masks, filters and receive modes: their text form (sysfs and
 * mcp2510ctl, see the uapi header) and their registers.  No libc here
 * beyond memcpy/memset: the kernel module compiles this file too.
 */
#include "mcp2510_core_priv.h"

#define EXT_SUFFIX	'x'
#define HEX_DIGITS_MAX	8

static const char *const rxm_names[] = {
	[MCP2510_RXM_FILTERED] = "filtered",
	[MCP2510_RXM_STD] = "std",
	[MCP2510_RXM_EXT] = "ext",
	[MCP2510_RXM_ANY] = "any",
};

void mcp2510_filters_default(struct mcp2510_filters *f)
{
	unsigned int i;

	memset(f, 0, sizeof(*f));
	/*
	 * A filter matches only its own frame format (EXIDE) even where the
	 * mask ignores every identifier bit, so each buffer needs a standard
	 * and an extended filter to take every frame.
	 */
	for (i = 0; i < MCP2510_FILTER_COUNT; i++)
		f->filter[i].ext = i & 1;
	f->rxm[0] = MCP2510_RXM_FILTERED;
	f->rxm[1] = MCP2510_RXM_FILTERED;
	f->rollover = true;
}

/* sysfs hands over what echo wrote, newline included */
static size_t strip_newline(const char *s, size_t len)
{
	if (len && s[len - 1] == '\n')
		len--;
	return len;
}

int mcp2510_filter_id_parse(const char *s, size_t len,
			    struct mcp2510_filter_id *out)
{
	struct mcp2510_filter_id id = { 0 };
	size_t i;

	len = strip_newline(s, len);
	if (len && s[len - 1] == EXT_SUFFIX) {
		id.ext = true;
		len--;
	}
	if (!len || len > HEX_DIGITS_MAX)
		return -EINVAL;
	for (i = 0; i < len; i++) {
		int digit = mcp2510_hex_digit(s[i]);

		if (digit < 0)
			return -EINVAL;
		id.id = id.id << 4 | digit;
	}
	if (id.id > (id.ext ? CAN_EFF_MASK : CAN_SFF_MASK))
		return -EINVAL;
	*out = id;
	return 0;
}

int mcp2510_filter_id_format(const struct mcp2510_filter_id *id, char *buf)
{
	static const char digits[] = "0123456789abcdef";
	unsigned int ndigits = 1;
	unsigned int i, len;

	while (ndigits < HEX_DIGITS_MAX && id->id >> (4 * ndigits))
		ndigits++;
	for (i = 0; i < ndigits; i++)
		buf[i] = digits[(id->id >> (4 * (ndigits - 1 - i))) & 0xf];
	len = ndigits;
	if (id->ext)
		buf[len++] = EXT_SUFFIX;
	buf[len] = '\0';
	return len;
}

static bool name_equal(const char *name, const char *s, size_t len)
{
	size_t i;

	for (i = 0; i < len; i++)
		if (name[i] != s[i] || !name[i])
			return false;
	return !name[len];
}

int mcp2510_rxm_parse(const char *s, size_t len, u8 *rxm)
{
	unsigned int i;

	len = strip_newline(s, len);
	for (i = 0; i < ARRAY_SIZE(rxm_names); i++) {
		if (name_equal(rxm_names[i], s, len)) {
			*rxm = i;
			return 0;
		}
	}
	return -EINVAL;
}

const char *mcp2510_rxm_name(u8 rxm)
{
	return rxm < ARRAY_SIZE(rxm_names) ? rxm_names[rxm] : NULL;
}

static bool filter_id_valid(const struct mcp2510_filter_id *id)
{
	return id->id <= (id->ext ? CAN_EFF_MASK : CAN_SFF_MASK);
}

int mcp2510_filters_check(const struct mcp2510_filters *f)
{
	unsigned int i;

	for (i = 0; i < MCP2510_MASK_COUNT; i++)
		if (!filter_id_valid(&f->mask[i]))
			return -EINVAL;
	for (i = 0; i < MCP2510_FILTER_COUNT; i++)
		if (!filter_id_valid(&f->filter[i]))
			return -EINVAL;
	for (i = 0; i < MCP2510_RXB_COUNT; i++)
		if (f->rxm[i] >= ARRAY_SIZE(rxm_names))
			return -EINVAL;
	return 0;
}

/*
 * A standard mask leaves the EID bits 0: an extended frame is then judged
 * by its top 11 bits, and the MCP2515 does not compare the first data
 * bytes of standard frames (it uses those bits for that).
 */
void mcp2510_filter_id_encode(const struct mcp2510_filter_id *id,
			      bool is_mask, u8 regs[MCP2510_ID_LEN])
{
	u32 sid = id->ext ? id->id >> MCP2510_EID_BITS : id->id;

	regs[MCP2510_ID_SIDH] = sid >> MCP2510_SID_SHIFT_SIDH;
	regs[MCP2510_ID_SIDL] = sid << MCP2510_SID_SHIFT_SIDL &
				MCP2510_SIDL_SID_MASK;
	regs[MCP2510_ID_EID8] = 0;
	regs[MCP2510_ID_EID0] = 0;
	if (!id->ext)
		return;
	regs[MCP2510_ID_SIDL] |= (id->id >> 16) & MCP2510_SIDL_EID_MASK;
	if (!is_mask)
		regs[MCP2510_ID_SIDL] |= MCP2510_SIDL_EXIDE;
	regs[MCP2510_ID_EID8] = id->id >> 8;
	regs[MCP2510_ID_EID0] = id->id;
}

/*
 * The inverse, for filters someone else programmed.  A mask has no EXIDE:
 * one with EID bits set masks extended identifiers.
 */
void mcp2510_filter_id_decode(const u8 regs[MCP2510_ID_LEN], bool is_mask,
			      struct mcp2510_filter_id *id)
{
	u32 sid = (u32)regs[MCP2510_ID_SIDH] << MCP2510_SID_SHIFT_SIDH |
		  (regs[MCP2510_ID_SIDL] & MCP2510_SIDL_SID_MASK) >>
		  MCP2510_SID_SHIFT_SIDL;
	u32 eid = (u32)(regs[MCP2510_ID_SIDL] & MCP2510_SIDL_EID_MASK) << 16 |
		  (u32)regs[MCP2510_ID_EID8] << 8 | regs[MCP2510_ID_EID0];

	id->ext = is_mask ? eid != 0 :
		  !!(regs[MCP2510_ID_SIDL] & MCP2510_SIDL_EXIDE);
	id->id = id->ext ? sid << MCP2510_EID_BITS | eid : sid;
}

/*
 * What goes into the chip.  In listen-only mode a buffer with RXM 11
 * also takes frames an error destroyed (DS21801 10.3: the mode receives
 * "all messages (including messages with errors)" through RXM), loaded
 * like valid ones with nothing to tell them apart, and the sender's
 * retry then arrives as a second copy.  So there "any" becomes what takes
 * every valid frame: RXM 00, the buffer's mask 0 and, as a filter only
 * takes the format its EXIDE names, standard and extended filters.  The
 * buffer's own filters did not count under "any" anyway.
 */
static void filters_for_chip(const struct mcp2510_chip *chip,
			     struct mcp2510_filters *f)
{
	static const u8 first[MCP2510_RXB_COUNT] = { 0, 2 };
	static const u8 last[MCP2510_RXB_COUNT] = { 1, 5 };
	unsigned int n, i;

	*f = chip->filters;
	if (chip->opmode != MCP2510_MODE_LISTEN_ONLY)
		return;
	for (n = 0; n < MCP2510_RXB_COUNT; n++) {
		if (f->rxm[n] != MCP2510_RXM_ANY)
			continue;
		f->rxm[n] = MCP2510_RXM_FILTERED;
		f->mask[n].id = 0;
		f->mask[n].ext = false;
		for (i = first[n]; i <= last[n]; i++) {
			f->filter[i].id = 0;
			f->filter[i].ext = i & 1;
		}
	}
}

/*
 * Filters 0-2 sit at 0x00-0x0b and 3-5 at 0x10-0x1b, the masks at
 * 0x20-0x27: three sequential WRITEs, plus one BIT MODIFY per RXBnCTRL.
 * Configuration mode only: the chip ignores these writes otherwise.
 */
int mcp2510_filters_write(struct mcp2510_chip *chip)
{
	struct mcp2510_filters chip_filters;
	const struct mcp2510_filters *f = &chip_filters;
	u8 regs[3 * MCP2510_ID_LEN];
	unsigned int bank, i;
	u8 ctrl0;
	int err;

	filters_for_chip(chip, &chip_filters);

	for (bank = 0; bank < 2; bank++) {
		for (i = 0; i < 3; i++)
			mcp2510_filter_id_encode(&f->filter[3 * bank + i], false,
						 regs + i * MCP2510_ID_LEN);
		err = mcp2510_reg_write(chip, MCP2510_REG_RXF(3 * bank), regs,
					sizeof(regs));
		if (err)
			return err;
	}
	for (i = 0; i < MCP2510_MASK_COUNT; i++)
		mcp2510_filter_id_encode(&f->mask[i], true,
					 regs + i * MCP2510_ID_LEN);
	err = mcp2510_reg_write(chip, MCP2510_REG_RXM(0), regs,
				MCP2510_MASK_COUNT * MCP2510_ID_LEN);
	if (err)
		return err;

	ctrl0 = FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, f->rxm[0]) |
		(f->rollover ? MCP2510_RXB0CTRL_BUKT : 0);
	err = mcp2510_reg_modify(chip, MCP2510_REG_RXBCTRL(0),
				 MCP2510_RXBCTRL_RXM_MASK |
				 MCP2510_RXB0CTRL_BUKT, ctrl0);
	if (err)
		return err;
	return mcp2510_reg_modify(chip, MCP2510_REG_RXBCTRL(1),
				  MCP2510_RXBCTRL_RXM_MASK,
				  FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK,
					     f->rxm[1]));
}

int mcp2510_filters_apply(struct mcp2510_chip *chip,
			  const struct mcp2510_filters *f)
{
	int err;

	if (chip->started)
		return -EBUSY;
	err = mcp2510_filters_check(f);
	if (err)
		return err;
	chip->filters = *f;
	return 0;
}
