// SPDX-License-Identifier: GPL-2.0
/*
 * The interrupt loop: find out what the chip flags, turn it into events
 * and clear exactly what was handled.  Each pass reads the flags
 * (irq_flags.c), takes the received frames (irq_rx.c), handles errors
 * (irq_error.c) and sent frames (irq_tx.c), then clears the flags.  A
 * pass that took a frame and saw the next arrive is followed by one that
 * takes it, whatever the trigger of the line, and a run of such passes
 * polls for the next frame before it ends (irq_rx.c, rx_poll()); a pass
 * that left a drain waiting for its last frame polls for that frame's
 * end (irq_tx.c, tx_drain_poll()).
 *
 * TX, error and wake-up flags are cleared with one BIT MODIFY naming only
 * the flags handled, so a flag raised meanwhile survives and asserts INT
 * again.  ERRIF is cleared on its own before EFLG is read again for the
 * state (see handle_errors()).
 */
#include "mcp2510_core_priv.h"

static int flags_count(u8 flags)
{
	int n = 0;

	for (; flags; flags &= flags - 1)
		n++;
	return n;
}

/*
 * One pass; returns the number of flags handled, 0 when none were set.
 * *@chained: the pass took a frame on the previous one's READ STATUS.
 */
static int irq_pass(struct mcp2510_chip *chip, bool *chained)
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
	*chained = f.rx_continued;
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
	err = mcp2510_tx_kick(chip, clear);
	if (err)
		return err;
	return flags_count(f.intf);
}

/*
 * Whether a next pass has a frame to take, from the status that ended
 * this one, or, when this pass went on from the previous one's (a
 * flood), from a few polls.  Returns 1, 0 or a transfer error.
 */
static int rx_more(struct mcp2510_chip *chip, bool chained)
{
	if (rx_status_more(chip))
		return 1;
	if (!chained)
		return 0;
	return rx_poll(chip);
}

int mcp2510_irq_handle(struct mcp2510_chip *chip)
{
	unsigned int pass;
	int handled = 0, n, more;
	bool chained = false;

	/* the first pass reads the flags: anything may have come meanwhile */
	chip->irq.rx_status = 0;
	chip->irq.tx_polled = false;
	for (pass = 0; pass < MCP2510_IRQ_MAX_PASSES; pass++) {
		n = irq_pass(chip, &chained);
		if (n < 0)
			return n;
		handled += n;
		/*
		 * The next frame is there: taking it now saves the flags
		 * read and the wait for INT.  Bounded, for the TX work and
		 * other users of the chip that wait for the handler.
		 */
		if (pass + 1 < MCP2510_IRQ_RX_PASSES) {
			more = rx_more(chip, chained);
			if (!more)
				more = tx_drain_poll(chip);
			if (more < 0)
				return more;
			if (more)
				continue;
		}
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
