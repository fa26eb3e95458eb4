// SPDX-License-Identifier: GPL-2.0
/*
 * The error side of a pass: ERRIF and MERRF become an error state read
 * from EFLG and TEC/REC that agree, overflow reports and bus errors.
 */
#include "mcp2510_core_priv.h"

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
int handle_errors(struct mcp2510_chip *chip, const struct irq_flags *f)
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
