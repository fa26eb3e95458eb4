// SPDX-License-Identifier: GPL-2.0
/*
 * The TX side of a pass: which pending buffers the flags show sent or,
 * in one-shot mode, dropped, and which TXnIF flags the pass may clear;
 * and the polls that end a drain without waiting for the interrupt.
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

/*
 * A drain (tx.c): frames are staged behind the last pending one and go
 * with one RTS once it is sent.  Waiting for its TXnIF to assert INT
 * leaves the bus idle for an interrupt's latency and a flags read before
 * that RTS; polling READ STATUS for its end leaves it idle for one poll
 * at most.  Only with one frame left, already on its way when its
 * predecessor's completion was handled; a frame received meanwhile also
 * ends the polls.  The next pass decodes the status read here.
 */
int tx_drain_poll(struct mcp2510_chip *chip)
{
	u8 pending = mcp2510_tx_pending(chip), txreq = 0, status;
	unsigned int i, n;
	int err;

	/* one frame left */
	if (!chip->tx.staged || !pending || pending & (pending - 1))
		return 0;
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (pending & BIT(n))
			txreq = MCP2510_STATUS_TXREQ(n);
	for (i = 0; i < MCP2510_IRQ_TX_POLLS; i++) {
		err = mcp2510_read_status(chip, &status);
		if (err)
			return err;
		if (!(status & txreq) ||
		    status & (MCP2510_STATUS_RX0IF | MCP2510_STATUS_RX1IF)) {
			chip->irq.tx_polled = true;
			chip->irq.tx_poll_status = status;
			return 1;
		}
	}
	return 0;
}
