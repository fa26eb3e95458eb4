// SPDX-License-Identifier: GPL-2.0
/*
 * Taking frames out of the receive buffers in a pass, the older frame
 * first, and telling whether the first one waited in the chip.
 *
 * A buffer whose RXnIF is set is never overwritten by the chip, so
 * reading it before its release cannot lose a frame; each RX buffer is
 * released right after it is read, and its frame delivered then, so that
 * neither error handling nor a failed transfer later in the pass holds a
 * buffer or loses a frame.
 *
 * Receive order.  With rollover (the default filters) a frame enters
 * RXB1 only while RXB0 is full.  So RXB1 holds the older frame exactly
 * when it was full at the moment RXB0 was released: every frame that
 * takes RXB0 after that is newer.  No register records the order, but
 * that moment can be watched: the release of RXB0 (the MCP2515's READ RX
 * BUFFER 0 itself, the MCP2510's BIT MODIFY of RX0IF after reading it)
 * is followed, in the same SPI message, by a READ STATUS, and when it
 * shows RX1IF the next pass reads RXB1 first (irq.rx1_first).  The READ
 * STATUS comes a few microseconds after the release, with chip select
 * high only in between; it would be wrong only if two frames completed
 * in that gap (one taking RXB0, the next RXB1), and frames are at least
 * 47 bit times apart.  Without ops->xfer_msg the two periods are
 * separate transfers and a delay between them reopens that window.
 * Frames that go to RXB1 directly (rollover off, or a frame only RXB1's
 * filters accept) make the order between the buffers unknowable.
 *
 * The release of RXB1 is followed by a READ STATUS too, so that every
 * pass that takes a frame ends knowing whether the next one has come:
 * under a flood the next pass takes it on the strength of that status
 * (irq.rx_status, see irq_flags.c), without reading the flags again or
 * waiting for INT.
 */
#include "mcp2510_core_priv.h"

/* Instruction bytes in front of a receive buffer's registers. */
static unsigned int rxb_read_cmd(const struct mcp2510_chip *chip,
				 unsigned int n, bool plain, u8 *tx)
{
	if (chip->variant->has_buffer_instrs && !plain) {
		tx[0] = MCP2515_INSTR_READ_RX_BUFFER | MCP2515_READ_RXB_SIDH(n);
		return 1;
	}
	tx[0] = MCP2510_INSTR_READ;
	tx[1] = MCP2510_REG_RXBSIDH(n);
	return 2;
}

/*
 * The transfer that was to release RXBn failed, and it may or may not
 * have reached the chip.  Read the buffer, then CANINTF, in one message:
 * RXnIF clear means the release happened and no frame has taken the
 * buffer since, so the registers just read still hold the frame, which
 * must be delivered now or never.  RXnIF set means the chip kept it (a
 * frame arriving in between could also set it, but the failed transfer
 * was microseconds ago): the next pass reads it.  Returns 1 with the
 * frame in @cf, 0 when the chip kept it, or -EIO.
 */
static int rxb_recover(struct mcp2510_chip *chip, unsigned int n,
		       struct can_frame *cf)
{
	u8 tx[2 + MCP2510_FRAME_REGS] = { 0 };
	u8 rx[2 + MCP2510_FRAME_REGS];
	const u8 intf_tx[3] = { MCP2510_INSTR_READ, MCP2510_REG_CANINTF };
	u8 intf_rx[3] = { 0 };
	struct mcp2510_xfer x[2] = {
		{ tx, rx, 0 },
		{ intf_tx, intf_rx, sizeof(intf_tx) },
	};
	int err;

	x[0].len = rxb_read_cmd(chip, n, true, tx) + MCP2510_FRAME_REGS;
	err = mcp2510_xfer_msg(chip, x, ARRAY_SIZE(x));
	if (err)
		return err;
	if (intf_rx[2] & MCP2510_INT_RX(n))
		return 0;
	mcp2510_frame_decode(rx + 2, chip->ctrlmode, cf);
	/* later than a READ STATUS in the message would be, but close */
	chip->irq.rx1_first = !n && intf_rx[2] & MCP2510_INT_RX(1);
	return 1;
}

/*
 * Read RXBn and release it in one message, delivering the frame once it
 * is released.  The release is followed, in the same message, by a READ
 * STATUS: after RXB0's, whether RXB1 was full at that moment tells which
 * buffer holds the older frame from now on (see the top of the file).  The
 * MCP2515's READ RX BUFFER releases the buffer itself when chip select
 * rises; the MCP2510 needs a BIT MODIFY of RXnIF after the READ.  When
 * the message fails, rxb_recover() finds out whether the release
 * happened (whatever became of the read before it).
 */
static int rxb_take(struct mcp2510_chip *chip, unsigned int n)
{
	const u8 modify[4] = { MCP2510_INSTR_BIT_MODIFY, MCP2510_REG_CANINTF,
			       MCP2510_INT_RX(n), 0 };
	const u8 status_tx[2] = { MCP2510_INSTR_READ_STATUS, 0 };
	u8 tx[2 + MCP2510_FRAME_REGS] = { 0 };
	u8 rx[2 + MCP2510_FRAME_REGS];
	u8 status_rx[2] = { 0 };
	struct mcp2510_xfer x[3];
	struct can_frame cf;
	unsigned int hdr, nx = 0;
	int err;

	hdr = rxb_read_cmd(chip, n, false, tx);
	x[nx++] = (struct mcp2510_xfer){ tx, rx, hdr + MCP2510_FRAME_REGS };
	/* a plain READ releases nothing */
	if (!chip->variant->has_buffer_instrs)
		x[nx++] = (struct mcp2510_xfer){ modify, NULL, sizeof(modify) };
	x[nx++] = (struct mcp2510_xfer){ status_tx, status_rx,
					 sizeof(status_tx) };
	err = mcp2510_xfer_msg(chip, x, nx);
	if (err) {
		int ret = rxb_recover(chip, n, &cf);

		if (ret > 0 && chip->events->rx)
			chip->events->rx(chip->ctx, &cf);
		return err;
	}
	chip->irq.rx1_first = !n && status_rx[1] & MCP2510_STATUS_RX1IF;
	chip->irq.rx_status = status_rx[1];
	mcp2510_frame_decode(rx + hdr, chip->ctrlmode, &cf);
	if (chip->events->rx)
		chip->events->rx(chip->ctx, &cf);
	return 0;
}

/*
 * Take the flagged RX buffers, the older frame first.  Each frame is
 * delivered as soon as its buffer is released, so an error later in the
 * pass neither loses it (the MCP2515's READ RX BUFFER released it
 * already) nor holds a buffer the chip could fill meanwhile.
 */
int rx_take(struct mcp2510_chip *chip, u8 intf)
{
	unsigned int first = chip->irq.rx1_first && intf & MCP2510_INT_RX(1);
	unsigned int i;
	int err;

	/*
	 * Both full: an overflow may follow.  With rollover RXB1 only fills
	 * while RXB0 is full, so taking it says the same even when this
	 * pass saw RXB0 empty: the overflow may have come meanwhile, its
	 * ERRIF unseen by READ STATUS (and rx_first_waited() relies on that).
	 */
	chip->irq.rx_status = 0;
	if ((intf & MCP2510_INT_RX_ALL) == MCP2510_INT_RX_ALL ||
	    (chip->filters.rollover && intf & MCP2510_INT_RX(1)))
		chip->irq.full_read_next = true;
	for (i = 0; i < MCP2510_RXB_COUNT; i++) {
		unsigned int n = i ? !first : first;

		if (!(intf & MCP2510_INT_RX(n)))
			continue;
		err = rxb_take(chip, n);
		if (err) {
			chip->irq.rx_status = 0;
			return err;
		}
	}
	return 0;
}

/*
 * A flood whose backlog the loop has just taken: the next frame is still
 * on the bus, and leaving now costs the interrupt latency, whose tail can
 * outlast both receive buffers.  A few READ STATUS polls wait for it
 * instead; each costs 2 bytes in its own chip-select period.
 */
int rx_poll(struct mcp2510_chip *chip)
{
	unsigned int i;
	u8 status;
	int err;

	for (i = 0; i < MCP2510_IRQ_RX_POLLS; i++) {
		err = mcp2510_read_status(chip, &status);
		if (err)
			return err;
		chip->irq.rx_status = status;
		if (rx_status_more(chip))
			return 1;
	}
	return 0;
}

/*
 * With rollover on: whether RXB1 can only hold a frame that came after
 * the one in RXB0 or the one released from it: RXB0 taking every frame,
 * so that no frame goes to RXB1 while RXB0 is free.  RXB0 takes every frame
 * when it ignores its filters, or when its mask is 0 and its two filters
 * name both formats (a filter matches only its own format).
 */
static bool rx_order_known(const struct mcp2510_chip *chip)
{
	const struct mcp2510_filters *f = &chip->filters;

	if (f->rxm[0] == MCP2510_RXM_ANY)
		return true;
	return f->rxm[0] == MCP2510_RXM_FILTERED && !f->mask[0].id &&
	       f->filter[0].ext != f->filter[1].ext;
}

/*
 * Whether the first frame this pass delivers was in the chip at every
 * moment INT was asserted since the previous pass (see rx_pass in
 * mcp2510_core.h).  Only passes clear flags, so a flag that asserted INT
 * then is among @f.  When every flag in @f is a receive flag, a full
 * buffer asserted it, and the oldest frame held now was held then.  The
 * ERRIF of an overflow is no receive flag: it outlives the full buffers.
 * A pass that released both, not seeing the overflow's ERRIF (READ
 * STATUS does not show it), leaves INT asserted with both buffers free,
 * and the frames the next pass finds came after INT fired.  So the pass
 * after one that may have missed an overflow reads CANINTF (rx_take()):
 * with rollover every overflow happens while RXB1 is full, and the pass
 * that takes RXB1 has the next one read CANINTF.  Without rollover RXB0
 * overflows alone, which no pass can tell from READ STATUS.  A pass that
 * goes on from the previous one's READ STATUS, or from a drain's poll,
 * takes a frame that came during that pass or poll, after INT fired.
 */
bool rx_first_waited(const struct mcp2510_chip *chip,
		     const struct irq_flags *f)
{
	u8 rx = f->intf & MCP2510_INT_RX_ALL;

	if (!rx || rx != f->intf || f->rx_continued || f->polled ||
	    chip->irq.flags_cleared || !chip->filters.rollover)
		return false;
	return rx != MCP2510_INT_RX_ALL || rx_order_known(chip);
}
