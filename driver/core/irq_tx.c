// SPDX-License-Identifier: GPL-2.0
/*
 * The TX side of a pass: which pending buffers the flags show sent or,
 * in one-shot mode, dropped, and which TXnIF flags the pass may clear.
 */
#include "mcp2510_core_priv.h"

/* Returns the CANINTF bits to clear. */
u8 handle_tx(struct mcp2510_chip *chip, const struct irq_flags *f)
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
