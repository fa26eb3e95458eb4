// SPDX-License-Identifier: GPL-2.0
/*
 * The interrupt loop: find out what the chip flags, turn it into events
 * and clear exactly what was handled.
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
 * TX, error and wake-up flags are cleared with one BIT MODIFY naming only
 * the flags handled, so a flag raised meanwhile survives and asserts INT
 * again.  ERRIF is cleared on its own before EFLG is read again for the
 * state (see handle_errors()).  A buffer whose RXnIF is set is never
 * overwritten by the chip, so reading it before its release cannot lose
 * a frame; each RX buffer is released right after it is read, and its
 * frame delivered then, so that neither error handling nor a failed
 * transfer later in the pass holds a buffer or loses a frame.
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
 */
#include "mcp2510_core_priv.h"

#define STATUS_RXIF_ALL	(MCP2510_STATUS_RX0IF | MCP2510_STATUS_RX1IF)

struct irq_flags {
	u8 intf;		/* CANINTF bits to handle */
	u8 eflg;
	u8 txreq;		/* slots with TXREQ set ... */
	bool have_txreq;	/* ... when READ STATUS was read */
	u8 status;		/* what it read */
	bool full;		/* CANINTF and EFLG were read */
};

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

static bool full_read_due(const struct mcp2510_chip *chip)
{
	return chip->irq.full_read_next || !chip->irq.passes_to_full_read ||
	       chip->state != CAN_STATE_ERROR_ACTIVE;
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

static int flags_read(struct mcp2510_chip *chip, struct irq_flags *f)
{
	u8 status;
	int err;

	memset(f, 0, sizeof(*f));
	if (full_read_due(chip)) {
		err = flags_read_full(chip, f);
		if (!err && chip->ctrlmode & CAN_CTRLMODE_ONE_SHOT &&
		    f->intf & chip->inte & MCP2510_INT_MERR &&
		    mcp2510_tx_pending(chip))
			err = flags_read_txreq(chip, f);
	} else {
		chip->irq.passes_to_full_read--;
		err = mcp2510_read_status(chip, &status);
		if (err)
			return err;
		status_decode(status, f);
		if (!(f->intf & chip->inte))
			err = flags_read_full(chip, f);
	}
	f->intf &= chip->inte;
	return err;
}

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
 * is released.  The release of RXB0 is followed, in the same message, by
 * a READ STATUS: whether RXB1 was full at that moment tells which buffer
 * holds the older frame from now on (see the top of the file).  The
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
	if (!n)
		x[nx++] = (struct mcp2510_xfer){ status_tx, status_rx,
						 sizeof(status_tx) };
	err = mcp2510_xfer_msg(chip, x, nx);
	if (err) {
		int ret = rxb_recover(chip, n, &cf);

		if (ret > 0 && chip->events->rx)
			chip->events->rx(chip->ctx, &cf);
		return err;
	}
	if (n)
		chip->irq.rx1_first = false;
	else
		chip->irq.rx1_first = status_rx[1] & MCP2510_STATUS_RX1IF;
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
static int rx_take(struct mcp2510_chip *chip, u8 intf)
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
	if ((intf & MCP2510_INT_RX_ALL) == MCP2510_INT_RX_ALL ||
	    (chip->filters.rollover && intf & MCP2510_INT_RX(1)))
		chip->irq.full_read_next = true;
	for (i = 0; i < MCP2510_RXB_COUNT; i++) {
		unsigned int n = i ? !first : first;

		if (!(intf & MCP2510_INT_RX(n)))
			continue;
		err = rxb_take(chip, n);
		if (err)
			return err;
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
 * overflows alone, which no pass can tell from READ STATUS.
 */
static bool rx_first_waited(const struct mcp2510_chip *chip,
			    const struct irq_flags *f)
{
	u8 rx = f->intf & MCP2510_INT_RX_ALL;

	if (!rx || rx != f->intf || chip->irq.flags_cleared ||
	    !chip->filters.rollover)
		return false;
	return rx != MCP2510_INT_RX_ALL || rx_order_known(chip);
}

/* Returns the CANINTF bits to clear. */
static u8 handle_tx(struct mcp2510_chip *chip, const struct irq_flags *f)
{
	u8 pending = mcp2510_tx_pending(chip);
	u8 txif = 0, finished, clear = 0;
	unsigned int n;

	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (f->intf & MCP2510_INT_TX(n))
			txif |= BIT(n);
	/*
	 * With TXREQ known, a pending buffer whose TXREQ went away without
	 * TXnIF was dropped by the chip.  Only a one-shot chip drops frames
	 * by itself.  Otherwise the chip reset (or the read was wrong): the
	 * buffer stays busy, so that no new frame goes into a chip that
	 * cannot send it, until the health check tells which and gives up
	 * the frame, alone or with the others of a reset chip.
	 */
	finished = f->have_txreq ? pending & ~f->txreq : pending & txif;
	mcp2510_tx_complete(chip, finished & txif);
	if (chip->ctrlmode & CAN_CTRLMODE_ONE_SHOT)
		mcp2510_tx_lost(chip, finished & ~txif);
	/*
	 * A TXnIF of a buffer still counted as pending (set after READ
	 * STATUS saw TXREQ) stays set, to be handled by the next pass.
	 */
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (txif & BIT(n) & ~(pending & ~finished))
			clear |= MCP2510_INT_TX(n);
	return clear;
}

#define EFLG_RXOVR_ALL	(MCP2510_EFLG_RX0OVR | MCP2510_EFLG_RX1OVR)

/*
 * Clear ERRIF, then read the EFLG the state is taken from, then TEC/REC to
 * check it against, all in one message: under an RX flood every overflow
 * brings this here, and each message more is time during which both
 * buffers stay full.  A change after the pass read the flags (TEC
 * crossing 128 while it runs) raises ERRIF again: read in the other
 * order, the clear would take that ERRIF with it and the change would go
 * unseen.  RXnOVR goes first: ERRIF must not be cleared while RXnOVR
 * still stands.
 */
static int errif_clear_reread(struct mcp2510_chip *chip, u8 ovr, u8 *eflg,
			      struct can_berr_counter *bec)
{
	const u8 ovr_tx[4] = { MCP2510_INSTR_BIT_MODIFY, MCP2510_REG_EFLG,
			       ovr, 0 };
	const u8 errif_tx[4] = { MCP2510_INSTR_BIT_MODIFY, MCP2510_REG_CANINTF,
				 MCP2510_INT_ERR, 0 };
	const u8 eflg_tx[3] = { MCP2510_INSTR_READ, MCP2510_REG_EFLG };
	const u8 bec_tx[4] = { MCP2510_INSTR_READ, MCP2510_REG_TEC };
	u8 eflg_rx[3] = { 0 }, bec_rx[4] = { 0 };
	struct mcp2510_xfer x[4];
	unsigned int nx = 0;
	int err;

	if (ovr)
		x[nx++] = (struct mcp2510_xfer){ ovr_tx, NULL, sizeof(ovr_tx) };
	x[nx++] = (struct mcp2510_xfer){ errif_tx, NULL, sizeof(errif_tx) };
	x[nx++] = (struct mcp2510_xfer){ eflg_tx, eflg_rx, sizeof(eflg_tx) };
	x[nx++] = (struct mcp2510_xfer){ bec_tx, bec_rx, sizeof(bec_tx) };
	err = mcp2510_xfer_msg(chip, x, nx);
	if (err)
		return err;
	*eflg = eflg_rx[2];
	bec->txerr = bec_rx[2];
	bec->rxerr = bec_rx[3];
	return 0;
}

/* Reads of EFLG and TEC/REC until they agree, at most. */
#define STATE_READ_TRIES	3

/*
 * EFLG and the counters for a state change.  The state decides whether
 * the interface goes bus-off, so a read that may be corrupted is not
 * enough: EFLG must agree with TEC/REC, read just after it.  When they
 * disagree (a corrupted read, or a counter crossing a limit in between)
 * both are read again; a short burst of corrupted transfers spoils at
 * most two pairs.  @agreed tells whether a pair agreed; when none did,
 * nothing read can be trusted, and taking the last EFLG anyway is how a
 * few garbled bytes used to put a healthy interface bus-off.
 */
static int state_read(struct mcp2510_chip *chip, u8 ovr, u8 *eflg,
		      struct can_berr_counter *bec, bool *agreed)
{
	unsigned int tries = 0;
	int err;

	*agreed = false;
	err = errif_clear_reread(chip, ovr, eflg, bec);
	for (;;) {
		if (err)
			return err;
		if (mcp2510_error_state_plausible(*eflg, bec)) {
			*agreed = true;
			return 0;
		}
		if (++tries == STATE_READ_TRIES)
			return 0;
		err = mcp2510_reg_read(chip, MCP2510_REG_EFLG, eflg, 1);
		if (!err)
			err = mcp2510_berr_counter(chip, bec);
	}
}

/*
 * ERRIF reports a worse error state or an overflow; a better state (after
 * bus-off recovery, or as the counters fall) raises no flag, so while the
 * chip is not error-active every full read compares EFLG with the state.
 * Either way ERRIF is cleared here, not with the pass's other flags.
 */
static int handle_errors(struct mcp2510_chip *chip, const struct irq_flags *f)
{
	bool state_due = f->full &&
			 (f->intf & MCP2510_INT_ERR ||
			  mcp2510_error_eflg_state(f->eflg) != chip->state);
	u8 ovr = f->intf & MCP2510_INT_ERR ? f->eflg & EFLG_RXOVR_ALL : 0;
	struct can_berr_counter bec;
	bool agreed = false;
	u8 eflg, late = 0;
	int err;

	if (!state_due && !(f->intf & MCP2510_INT_MERR))
		return 0;
	if (state_due)
		err = state_read(chip, ovr, &eflg, &bec, &agreed);
	else
		err = mcp2510_berr_counter(chip, &bec);
	if (err)
		return err;
	if (agreed) {
		mcp2510_error_state_update(chip, eflg, &bec);
		/* an overflow since the first read: its ERRIF may be gone */
		late = eflg & EFLG_RXOVR_ALL;
	} else if (state_due) {
		/*
		 * Keep the state we had.  ERRIF is cleared, so a real change
		 * would raise no flag again: have the next pass read EFLG.
		 */
		chip->irq.full_read_next = true;
		bec = chip->bec;
	}
	mcp2510_error_overflow(chip, ovr | late, &bec);
	if (f->intf & MCP2510_INT_MERR)
		mcp2510_error_bus(chip, &bec);
	if (late)
		return mcp2510_reg_modify(chip, MCP2510_REG_EFLG, late, 0);
	return 0;
}

static int flags_count(u8 flags)
{
	int n = 0;

	for (; flags; flags &= flags - 1)
		n++;
	return n;
}

/* One pass; returns the number of flags handled, 0 when none were set. */
static int irq_pass(struct mcp2510_chip *chip)
{
	struct irq_flags f;
	int err;
	u8 clear;

	chip->counters.irq_loops++;
	err = flags_read(chip, &f);
	if (err)
		return err;
	if (chip->events->rx_pass)
		chip->events->rx_pass(chip->ctx, rx_first_waited(chip, &f));
	chip->irq.flags_cleared = false;
	err = rx_take(chip, f.intf);
	if (err)
		return err;
	err = handle_errors(chip, &f);
	if (err)
		return err;
	if (f.have_txreq)
		mcp2510_tx_resolve(chip, f.status);
	clear = handle_tx(chip, &f) |
		(f.intf & (MCP2510_INT_MERR | MCP2510_INT_WAK));
	if (clear) {
		err = mcp2510_reg_modify(chip, MCP2510_REG_CANINTF, clear, 0);
		if (err)
			return err;
	}
	err = mcp2510_tx_kick(chip);
	if (err)
		return err;
	return flags_count(f.intf);
}

int mcp2510_irq_handle(struct mcp2510_chip *chip)
{
	unsigned int pass;
	int handled = 0, n;

	for (pass = 0; pass < MCP2510_IRQ_MAX_PASSES; pass++) {
		n = irq_pass(chip);
		if (n < 0)
			return n;
		handled += n;
		/*
		 * A level-triggered line fires again while anything is
		 * pending; an edge-triggered one only after INT went high,
		 * i.e. after a pass found nothing at all.
		 */
		if (!chip->irq_edge || !n)
			return handled;
	}
	chip->counters.irq_loop_bound++;
	return -EAGAIN;
}
