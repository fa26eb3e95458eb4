// SPDX-License-Identifier: GPL-2.0
/*
 * Putting frames into the TX buffers and requesting them: the load, the
 * RTS, and what READ STATUS (which shows TXREQ and TXnIF) says when a
 * message carrying either fails.  An RTS whose outcome nothing could
 * tell leaves its buffer "unsure" until a READ STATUS does.  A message
 * stops at the transfer that fails, so a frame is never requested unless
 * its load went through, nor after a clear that did not.  tx.c decides
 * which buffer and priority each frame gets.
 */
#include "mcp2510_core_priv.h"

/* The longest load: WRITE, TXBnCTRL's address and value, the frame. */
#define TX_LOAD_MAX	(3 + MCP2510_FRAME_REGS)

/*
 * The transfer that loads a frame into @slot, in @tx: SIDH..D(len-1)
 * and, unless TXBnCTRL already holds @txp, TXBnCTRL in front.  Without
 * it the MCP2515 uses LOAD TX BUFFER, the MCP2510 a WRITE from SIDH: a
 * lone frame, which always takes the top key, then fits in a transfer
 * spi-bcm2835 polls at 5 MHz (see mcp2510_xfer_first_len()).  Returns
 * its length.
 */
static unsigned int tx_load_prepare(const struct mcp2510_chip *chip,
				    unsigned int slot, u8 txp, const u8 *regs,
				    unsigned int nregs, u8 tx[TX_LOAD_MAX])
{
	bool txp_held = txp == chip->tx.prio[slot] &&
			!(chip->tx.prio_unknown & BIT(slot));
	unsigned int hdr;

	if (txp_held && chip->variant->has_buffer_instrs) {
		tx[0] = MCP2515_INSTR_LOAD_TX_BUFFER |
			MCP2515_LOAD_TXB_SIDH(slot);
		hdr = 1;
	} else if (txp_held) {
		tx[0] = MCP2510_INSTR_WRITE;
		tx[1] = MCP2510_REG_TXBSIDH(slot);
		hdr = 2;
	} else {
		tx[0] = MCP2510_INSTR_WRITE;
		tx[1] = MCP2510_REG_TXBCTRL(slot);
		tx[2] = FIELD_PREP(MCP2510_TXBCTRL_TXP_MASK, txp);
		hdr = 3;
	}
	memcpy(tx + hdr, regs, nregs);
	return hdr + nregs;
}

/* What the load in @tx leaves TXBnCTRL holding, @err its outcome. */
static void tx_load_done(struct mcp2510_chip *chip, unsigned int slot,
			 u8 txp, const u8 *tx, int err)
{
	if (!err) {
		chip->tx.prio[slot] = txp;
		chip->tx.prio_unknown &= ~BIT(slot);
	} else if (tx[0] == MCP2510_INSTR_WRITE &&
		   tx[1] == MCP2510_REG_TXBCTRL(slot)) {
		chip->tx.prio_unknown |= BIT(slot);
	}
}

int mcp2510_tx_load(struct mcp2510_chip *chip, unsigned int slot, u8 txp,
		    const u8 *regs, unsigned int nregs)
{
	u8 tx[TX_LOAD_MAX];
	unsigned int len;
	int err;

	len = tx_load_prepare(chip, slot, txp, regs, nregs, tx);
	err = mcp2510_xfer(chip, tx, NULL, len);
	tx_load_done(chip, slot, txp, tx, err);
	return err;
}

/*
 * What READ STATUS says of the unsure slots: a staged frame whose RTS was
 * latched is pending now; a dropped frame's slot is free once its TXREQ
 * is clear.
 */
void mcp2510_tx_resolve(struct mcp2510_chip *chip, u8 status)
{
	unsigned int n;

	for (n = 0; n < MCP2510_TXB_COUNT; n++) {
		bool txreq = status & MCP2510_STATUS_TXREQ(n);
		bool latched = txreq || status & MCP2510_STATUS_TXIF(n);

		if (!(chip->tx.unsure & BIT(n)))
			continue;
		if (chip->tx.busy & BIT(n)) {
			if (latched)
				chip->tx.staged &= ~BIT(n);
			chip->tx.unsure &= ~BIT(n);
		} else if (!txreq) {
			chip->tx.unsure &= ~BIT(n);
		}
	}
}

int mcp2510_tx_status_resolve(struct mcp2510_chip *chip)
{
	u8 status;
	int err;

	err = mcp2510_read_status(chip, &status);
	if (!err)
		mcp2510_tx_resolve(chip, status);
	return err;
}

/*
 * After a failed RTS: those of @slots whose request the chip latched
 * (TXREQ set, or TXnIF if the frame is gone already), or -EIO when READ
 * STATUS could not tell either (see the top).
 */
static int tx_latched(struct mcp2510_chip *chip, u8 slots)
{
	u8 status, latched = 0;
	unsigned int n;
	int err;

	err = mcp2510_read_status(chip, &status);
	if (err)
		return err;
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (status & (MCP2510_STATUS_TXREQ(n) | MCP2510_STATUS_TXIF(n)))
			latched |= BIT(n);
	return latched & slots;
}

/* The staged frames, once nothing older is pending; 0 or -EIO. */
static int tx_kick_due(struct mcp2510_chip *chip, u8 *slots)
{
	int ret;

	*slots = 0;
	if (!chip->tx.staged || mcp2510_tx_pending(chip))
		return 0;
	if (chip->tx.unsure & chip->tx.busy) {
		/* an RTS of theirs failed: never request a frame twice */
		ret = mcp2510_tx_status_resolve(chip);
		if (ret)
			return ret;
		if (!chip->tx.staged || mcp2510_tx_pending(chip))
			return 0;
	}
	*slots = chip->tx.staged;
	return 0;
}

/*
 * Request the staged frames once nothing older is pending: they hold the
 * top keys, in queue order, and go with one RTS.  @intf_clear, the
 * CANINTF flags an interrupt pass handled, is cleared in the same
 * message, after the RTS: the bus, idle since the last frame, waits for
 * the RTS alone.  The flags cleared are those of buffers no longer
 * pending, none of them requested here.  A failed message stops at the
 * transfer that failed: READ STATUS tells whether the RTS got through,
 * and a flag left set is cleared by the next pass.
 */
int mcp2510_tx_kick(struct mcp2510_chip *chip, u8 intf_clear)
{
	const u8 modify[4] = { MCP2510_INSTR_BIT_MODIFY, MCP2510_REG_CANINTF,
			       intf_clear, 0 };
	struct mcp2510_xfer x[2];
	unsigned int nx = 0;
	int ret, err;
	u8 rts, slots;

	err = tx_kick_due(chip, &slots);
	if (err)
		return err;
	if (slots) {
		rts = MCP2510_INSTR_RTS | slots;
		x[nx++] = (struct mcp2510_xfer){ &rts, NULL, sizeof(rts) };
	}
	if (intf_clear)
		x[nx++] = (struct mcp2510_xfer){ modify, NULL, sizeof(modify) };
	if (!nx)
		return 0;
	err = mcp2510_xfer_msg(chip, x, nx);
	if (!slots)
		return err;
	ret = err ? tx_latched(chip, slots) : slots;
	if (ret < 0) {
		chip->tx.unsure |= chip->tx.staged;
		return ret;
	}
	chip->tx.staged &= ~ret;
	return err;
}

/*
 * Load @cf into a slot with a key below every pending frame and request
 * it, in one message: the RTS follows the load by a chip-select period
 * rather than by a message.  A message that fails stops at the transfer
 * that failed, so a frame is never requested unless loaded; whether the
 * RTS got through is then for READ STATUS to say, as after a failed RTS
 * alone.
 */
int mcp2510_tx_send(struct mcp2510_chip *chip, unsigned int slot, u8 txp,
		    const u8 *regs, unsigned int nregs)
{
	const u8 rts = MCP2510_INSTR_RTS | BIT(slot);
	u8 load[TX_LOAD_MAX];
	struct mcp2510_xfer x[2] = {
		{ load, NULL, 0 },
		{ &rts, NULL, sizeof(rts) },
	};
	int ret;

	x[0].len = tx_load_prepare(chip, slot, txp, regs, nregs, load);
	if (!mcp2510_xfer_msg(chip, x, ARRAY_SIZE(x))) {
		tx_load_done(chip, slot, txp, load, 0);
		return 0;
	}
	/* a request the chip latched had the whole load before it */
	ret = tx_latched(chip, BIT(slot));
	tx_load_done(chip, slot, txp, load,
		     ret == (int)BIT(slot) ? 0 : -EIO);
	if (ret < 0)
		chip->tx.unsure |= BIT(slot);
	return ret == (int)BIT(slot) ? 0 : -EIO;
}
