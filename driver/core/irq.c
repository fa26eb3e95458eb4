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
 * starve error reporting, after both RX buffers were seen full (an
 * overflow may follow), and while the chip is not error-active (so that a
 * recovery from bus-off is seen at the next interrupt of any kind).
 *
 * Flags are cleared with one BIT MODIFY naming only the flags handled, so
 * a flag raised meanwhile survives and asserts INT again.  ERRIF is the
 * exception: it is cleared on its own before EFLG is read again for the
 * state (see handle_errors()).  A buffer whose RXnIF is set is never
 * overwritten by the chip, so reading it before the clear cannot lose a
 * frame.
 *
 * RXB0 is read before RXB1: with rollover a frame only goes to RXB1 while
 * RXB0 is full, so when both are seen full RXB0's frame is usually the
 * older one.  Not always: a pass that saw only RXB0 full keeps it full
 * until its clear, so frame B arriving meanwhile rolls over to RXB1, and
 * frame C arriving after the clear takes RXB0.  The next pass finds both
 * full with the newer frame in RXB0.  It cannot tell that from RXB0 having
 * stayed full all along: no register records the order of arrival
 * (FILHIT and RX STATUS name the filter and the buffer, not the time),
 * and an overflow flag only says a frame was lost.  Another READ STATUS
 * after every clear would narrow the window, not close it (B and C may
 * both arrive before it), at one more transfer per received frame.  So
 * under a flood two adjacent frames may reach the stack swapped; the
 * soak counts them.
 */
#include "mcp2510_core_priv.h"

#define STATUS_RXIF_ALL	(MCP2510_STATUS_RX0IF | MCP2510_STATUS_RX1IF)

struct irq_flags {
	u8 intf;		/* CANINTF bits to handle */
	u8 eflg;
	u8 txreq;		/* slots with TXREQ set ... */
	bool have_txreq;	/* ... when READ STATUS was read */
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

/*
 * Read the flagged RX buffers, oldest first, into @frames; returns how
 * many.  Delivery waits until their flags are cleared: should the clear
 * fail, the next pass reads them again instead of delivering them twice.
 */
static int rx_read(struct mcp2510_chip *chip, u8 intf,
		   struct can_frame frames[MCP2510_RXB_COUNT])
{
	u8 regs[MCP2510_FRAME_REGS];
	unsigned int n;
	int count = 0, err;

	if ((intf & MCP2510_INT_RX_ALL) == MCP2510_INT_RX_ALL)
		chip->irq.full_read_next = true;
	for (n = 0; n < MCP2510_RXB_COUNT; n++) {
		if (!(intf & MCP2510_INT_RX(n)))
			continue;
		err = mcp2510_rxb_read(chip, n, regs);
		if (err)
			return err;
		mcp2510_frame_decode(regs, &frames[count++]);
	}
	return count;
}

/* RXnIF to clear by hand: READ RX BUFFER clears its own. */
static u8 rx_clear_mask(const struct mcp2510_chip *chip, u8 intf)
{
	return chip->variant->has_buffer_instrs ? 0 : intf & MCP2510_INT_RX_ALL;
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
 * Clear ERRIF, then read the EFLG the state is taken from.  A change after
 * the pass read the flags (TEC crossing 128 while it runs) raises ERRIF
 * again: read in the other order, the clear would take that ERRIF with it
 * and the change would go unseen.  RXnOVR goes first: ERRIF must not be
 * cleared while RXnOVR still stands.
 */
static int errif_clear_reread(struct mcp2510_chip *chip, u8 ovr, u8 *eflg)
{
	int err;

	if (ovr) {
		err = mcp2510_reg_modify(chip, MCP2510_REG_EFLG, ovr, 0);
		if (err)
			return err;
	}
	err = mcp2510_reg_modify(chip, MCP2510_REG_CANINTF, MCP2510_INT_ERR, 0);
	if (err)
		return err;
	return mcp2510_reg_read(chip, MCP2510_REG_EFLG, eflg, 1);
}

/* Reads of EFLG and TEC/REC until they agree, at most. */
#define STATE_READ_TRIES	3

/*
 * EFLG and the counters for a state change.  The state decides whether
 * the interface goes bus-off, so a read that may be corrupted is not
 * enough: EFLG must agree with TEC/REC, read just after it.  When they
 * disagree (a corrupted read, or a counter crossing a limit in between)
 * both are read again; a short burst of corrupted transfers spoils at
 * most two pairs.  Returns 1 when a pair agreed, 0 when none did: then
 * nothing read can be trusted, and taking the last EFLG anyway is how a
 * few garbled bytes used to put a healthy interface bus-off.
 */
static int state_read(struct mcp2510_chip *chip, u8 ovr, u8 *eflg,
		      struct can_berr_counter *bec)
{
	unsigned int tries = 0;
	int err;

	err = errif_clear_reread(chip, ovr, eflg);
	for (;;) {
		if (err)
			return err;
		err = mcp2510_berr_counter(chip, bec);
		if (err)
			return err;
		if (mcp2510_error_state_plausible(*eflg, bec))
			return 1;
		if (++tries == STATE_READ_TRIES)
			return 0;
		err = mcp2510_reg_read(chip, MCP2510_REG_EFLG, eflg, 1);
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
	u8 eflg, late = 0;
	int err;

	if (!state_due && !(f->intf & MCP2510_INT_MERR))
		return 0;
	if (state_due)
		err = state_read(chip, ovr, &eflg, &bec);
	else
		err = mcp2510_berr_counter(chip, &bec);
	if (err < 0)
		return err;
	if (state_due && err) {
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
	struct can_frame frames[MCP2510_RXB_COUNT];
	struct irq_flags f;
	int nframes, i, err;
	u8 clear;

	chip->counters.irq_loops++;
	err = flags_read(chip, &f);
	if (err)
		return err;
	nframes = rx_read(chip, f.intf, frames);
	if (nframes < 0)
		return nframes;
	err = handle_errors(chip, &f);
	if (err)
		return err;
	clear = rx_clear_mask(chip, f.intf) | handle_tx(chip, &f) |
		(f.intf & (MCP2510_INT_MERR | MCP2510_INT_WAK));
	if (clear) {
		err = mcp2510_reg_modify(chip, MCP2510_REG_CANINTF, clear, 0);
		if (err)
			return err;
	}
	for (i = 0; i < nframes; i++)
		if (chip->events->rx)
			chip->events->rx(chip->ctx, &frames[i]);
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
	chip->counters.irq_storms++;
	return -EAGAIN;
}
