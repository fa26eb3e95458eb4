// SPDX-License-Identifier: GPL-2.0
/*
 * Reading the interrupt flags a pass handles: READ STATUS when it tells
 * enough, CANINTF and EFLG when it does not.
 *
 * A pass normally starts with READ STATUS (2 bytes): it shows RXnIF, TXnIF
 * and TXREQ, everything a busy chip raises per frame.  It does not show
 * ERRIF, WAKIF or MERRF, so the pass reads CANINTF and EFLG instead (4
 * bytes, same transfer count) when READ STATUS shows nothing although INT
 * fired, every MCP2510_IRQ_FULL_READ_EVERY passes so an RX flood cannot
 * starve error reporting, after both RX buffers were seen full or, with
 * rollover, RXB1 was taken (an overflow may follow), and while the chip
 * is not error-active (so that a recovery from bus-off is seen at the
 * next interrupt of any kind).
 *
 * Under an RX flood a pass reads nothing at all: the READ STATUS that
 * ended the previous pass's last release (irq_rx.c) showed the next
 * frame, and the pass takes it on that.  Only its receive flags count:
 * the previous pass cleared TXnIF and requested frames after that READ
 * STATUS, so its TX bits may be stale, and they wait for the next pass
 * that reads the flags, at the latest the full read that comes every
 * MCP2510_IRQ_FULL_READ_EVERY passes.  That full read also sees the
 * ERRIF of an overflow a pass may have missed (full_read_next): under a
 * flood an overflow is reported a few frames late rather than every
 * other frame paying for CANINTF.  The first pass of the next interrupt
 * still reads it, so receive timestamps keep their guarantee (see
 * rx_first_waited()).
 */
#include "mcp2510_core_priv.h"

static void status_decode(u8 status, struct irq_flags *f)
{
	unsigned int n;

	f->intf = 0;
	f->txreq = 0;
	for (n = 0; n < MCP2510_RXB_COUNT; n++)
		if (status & (n ? MCP2510_STATUS_RX1IF : MCP2510_STATUS_RX0IF))
			f->intf |= MCP2510_INT_RX(n);
	for (n = 0; n < MCP2510_TXB_COUNT; n++) {
		if (status & MCP2510_STATUS_TXIF(n))
			f->intf |= MCP2510_INT_TX(n);
		if (status & MCP2510_STATUS_TXREQ(n))
			f->txreq |= BIT(n);
	}
	f->have_txreq = true;
	f->status = status;
}

static bool full_read_periodic(const struct mcp2510_chip *chip)
{
	return !chip->irq.passes_to_full_read ||
	       chip->state != CAN_STATE_ERROR_ACTIVE;
}

static bool full_read_due(const struct mcp2510_chip *chip)
{
	return chip->irq.full_read_next || full_read_periodic(chip);
}

static int flags_read_full(struct mcp2510_chip *chip, struct irq_flags *f)
{
	u8 regs[2];
	int err;

	err = mcp2510_reg_read(chip, MCP2510_REG_CANINTF, regs, sizeof(regs));
	if (err)
		return err;
	f->intf = regs[0];
	f->eflg = regs[1];
	f->full = true;
	chip->irq.full_read_next = false;
	chip->irq.passes_to_full_read = MCP2510_IRQ_FULL_READ_EVERY;
	return 0;
}

static bool flags_from_rx_status(struct mcp2510_chip *chip,
				 struct irq_flags *f)
{
	struct irq_flags s;

	if (!rx_status_more(chip) || full_read_periodic(chip))
		return false;
	status_decode(chip->irq.rx_status, &s);
	f->intf = s.intf & MCP2510_INT_RX_ALL & chip->inte;
	if (!f->intf)
		return false;
	f->rx_continued = true;
	chip->irq.passes_to_full_read--;
	return true;
}

/*
 * MERRF in one-shot mode after a full read without READ STATUS: a frame
 * may have been dropped (TXREQ gone without TXnIF) and only TXREQ tells, so read
 * it.  TXnIF comes from the same read, later than CANINTF's: a frame sent
 * in between is seen sent, not taken for lost.
 */
static int flags_read_txreq(struct mcp2510_chip *chip, struct irq_flags *f)
{
	struct irq_flags s;
	u8 status;
	int err;

	err = mcp2510_read_status(chip, &status);
	if (err)
		return err;
	status_decode(status, &s);
	f->intf |= s.intf & MCP2510_INT_TX_ALL & chip->inte;
	f->txreq = s.txreq;
	f->have_txreq = true;
	f->status = status;
	return 0;
}

/*
 * READ STATUS, or what a drain's poll read after the previous pass's
 * clear and RTS: nothing has changed the flags since.  A frame it shows
 * came during this call, after INT fired (see rx_first_waited()).
 */
static int status_get(struct mcp2510_chip *chip, struct irq_flags *f,
		      u8 *status)
{
	if (chip->irq.tx_polled) {
		chip->irq.tx_polled = false;
		f->polled = true;
		*status = chip->irq.tx_poll_status;
		return 0;
	}
	return mcp2510_read_status(chip, status);
}

int flags_read(struct mcp2510_chip *chip, struct irq_flags *f)
{
	u8 status;
	int err;

	memset(f, 0, sizeof(*f));
	if (flags_from_rx_status(chip, f))
		return 0;
	if (full_read_due(chip)) {
		chip->irq.tx_polled = false;
		err = flags_read_full(chip, f);
		if (!err && chip->ctrlmode & CAN_CTRLMODE_ONE_SHOT &&
		    f->intf & chip->inte & MCP2510_INT_MERR &&
		    mcp2510_tx_pending(chip))
			err = flags_read_txreq(chip, f);
	} else {
		chip->irq.passes_to_full_read--;
		err = status_get(chip, f, &status);
		if (err)
			return err;
		status_decode(status, f);
		if (!(f->intf & chip->inte))
			err = flags_read_full(chip, f);
	}
	f->intf &= chip->inte;
	return err;
}
