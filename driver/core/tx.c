// SPDX-License-Identifier: GPL-2.0
/*
 * The ordered three-buffer transmit scheduler.
 *
 * SocketCAN expects frames to leave in the order they were queued, but the
 * chip does not know that order: among the buffers with TXREQ set it sends
 * the one with the highest TXBnCTRL.TXP first and, on equal TXP, the one
 * with the higher buffer number.  So every buffer holds a key
 *
 *	key = TXP * 3 + buffer number		(0 .. 11, higher goes first)
 *
 * and a new frame must get a key below the key of every frame still
 * pending: then the chip's choice is always the oldest frame.  Each new
 * frame takes the highest such key any free buffer can have, so the keys
 * walk down by about one per frame while all three buffers stay busy.
 *
 * When no free buffer has a key left below the pending ones, waiting for
 * the bus to drain would leave buffers idle.  Instead the pending frames
 * are raised to the top keys, oldest first and each just below the one
 * before it, with a BIT MODIFY of their TXP.  Every raise only increases a
 * key and the oldest frame moves first, so at every instant in between the
 * keys still fall in queue order, whichever frame the chip picks next.
 * With twelve keys this costs two BIT MODIFYs about every nine frames of a
 * continuous stream; an idle chip's first frame needs none.
 *
 * Completions are reported in queue order too: a buffer that finished
 * before an older one (possible only if the older one was lost) waits in
 * tx.done until the older one is accounted for.
 */
#include "mcp2510_core_priv.h"

#define TXP_MAX		3
#define SLOTS_ALL	(BIT(MCP2510_TXB_COUNT) - 1)
#define KEY(txp, slot)	((txp) * MCP2510_TXB_COUNT + (slot))
/* above every key: the ceiling when nothing is pending */
#define KEY_CEILING	KEY(TXP_MAX + 1, 0)

static bool seq_before(u32 a, u32 b)
{
	return (s32)(a - b) < 0;
}

/* Slots of @mask, oldest frame first; returns how many. */
static unsigned int queue_order(const struct mcp2510_chip *chip, u8 mask,
				u8 order[MCP2510_TXB_COUNT])
{
	unsigned int n = 0, slot, i;

	for (slot = 0; slot < MCP2510_TXB_COUNT; slot++) {
		if (!(mask & BIT(slot)))
			continue;
		for (i = n; i > 0 &&
		     seq_before(chip->tx.seq[slot], chip->tx.seq[order[i - 1]]);
		     i--)
			order[i] = order[i - 1];
		order[i] = slot;
		n++;
	}
	return n;
}

u8 mcp2510_tx_pending(const struct mcp2510_chip *chip)
{
	return chip->tx.busy & ~chip->tx.done;
}

static unsigned int tx_key(const struct mcp2510_chip *chip, unsigned int slot)
{
	return KEY(chip->tx.prio[slot], slot);
}

/* Highest TXP that puts @slot below @ceiling, or -1 if none does. */
static int txp_below(unsigned int ceiling, unsigned int slot)
{
	unsigned int txp;

	if (ceiling <= slot)
		return -1;
	txp = (ceiling - 1 - slot) / MCP2510_TXB_COUNT;
	return txp > TXP_MAX ? TXP_MAX : txp;
}

static unsigned int pending_floor(const struct mcp2510_chip *chip)
{
	unsigned int floor = KEY_CEILING, slot;

	for (slot = 0; slot < MCP2510_TXB_COUNT; slot++)
		if (mcp2510_tx_pending(chip) & BIT(slot) &&
		    tx_key(chip, slot) < floor)
			floor = tx_key(chip, slot);
	return floor;
}

/* The free slot and TXP with the highest key below every pending frame. */
static bool tx_pick(const struct mcp2510_chip *chip, unsigned int *slot,
		    u8 *txp)
{
	unsigned int floor = pending_floor(chip);
	int best_key = -1;
	unsigned int s;

	for (s = 0; s < MCP2510_TXB_COUNT; s++) {
		int p;

		if (chip->tx.busy & BIT(s))
			continue;
		p = txp_below(floor, s);
		if (p >= 0 && (int)KEY(p, s) > best_key) {
			best_key = KEY(p, s);
			*slot = s;
			*txp = p;
		}
	}
	return best_key >= 0;
}

static int txp_write(struct mcp2510_chip *chip, unsigned int slot, u8 txp)
{
	int err;

	err = mcp2510_reg_modify(chip, MCP2510_REG_TXBCTRL(slot),
				 MCP2510_TXBCTRL_TXP_MASK, txp);
	if (err) {
		/* the chip may hold either value: rewrite it next time */
		chip->tx.prio_unknown |= BIT(slot);
		return err;
	}
	chip->tx.prio[slot] = txp;
	chip->tx.prio_unknown &= ~BIT(slot);
	chip->tx.prio_raises++;
	return 0;
}

/* Lift the pending frames to the top keys, oldest first (see above). */
static int tx_raise(struct mcp2510_chip *chip)
{
	u8 order[MCP2510_TXB_COUNT];
	unsigned int n, i, ceiling = KEY_CEILING;
	int err;

	n = queue_order(chip, mcp2510_tx_pending(chip), order);
	for (i = 0; i < n; i++) {
		unsigned int slot = order[i];
		u8 txp = txp_below(ceiling, slot);

		if (txp != chip->tx.prio[slot] ||
		    chip->tx.prio_unknown & BIT(slot)) {
			err = txp_write(chip, slot, txp);
			if (err)
				return err;
		}
		ceiling = KEY(txp, slot);
	}
	return 0;
}

/*
 * One transfer: SIDH..D(len-1) and, unless the MCP2515's LOAD TX BUFFER
 * can be used because TXBnCTRL already holds @txp, TXBnCTRL in front.
 */
static int tx_load(struct mcp2510_chip *chip, unsigned int slot, u8 txp,
		   const u8 *regs, unsigned int nregs)
{
	u8 tx[3 + MCP2510_FRAME_REGS];
	unsigned int hdr;
	int err;

	if (chip->variant->has_buffer_instrs && txp == chip->tx.prio[slot] &&
	    !(chip->tx.prio_unknown & BIT(slot))) {
		tx[0] = MCP2515_INSTR_LOAD_TX_BUFFER |
			MCP2515_LOAD_TXB_SIDH(slot);
		hdr = 1;
	} else {
		tx[0] = MCP2510_INSTR_WRITE;
		tx[1] = MCP2510_REG_TXBCTRL(slot);
		tx[2] = FIELD_PREP(MCP2510_TXBCTRL_TXP_MASK, txp);
		hdr = 3;
	}
	memcpy(tx + hdr, regs, nregs);
	err = mcp2510_xfer(chip, tx, NULL, hdr + nregs);
	if (err) {
		if (hdr == 3)
			chip->tx.prio_unknown |= BIT(slot);
		return err;
	}
	chip->tx.prio[slot] = txp;
	chip->tx.prio_unknown &= ~BIT(slot);
	return 0;
}

unsigned int mcp2510_tx_free(const struct mcp2510_chip *chip)
{
	unsigned int slot, n = 0;

	for (slot = 0; slot < MCP2510_TXB_COUNT; slot++)
		if (!(chip->tx.busy & BIT(slot)))
			n++;
	return n;
}

int mcp2510_tx_submit(struct mcp2510_chip *chip, const struct can_frame *cf)
{
	u8 regs[MCP2510_FRAME_REGS];
	unsigned int slot = 0;
	u8 txp = 0;
	int nregs, err;

	if (!chip->started)
		return -ENETDOWN;
	if (chip->tx.busy == SLOTS_ALL)
		return -EBUSY;
	nregs = mcp2510_frame_encode(cf, regs);
	if (nregs < 0)
		return nregs;

	if (!tx_pick(chip, &slot, &txp)) {
		err = tx_raise(chip);
		if (err)
			return err;
		if (!tx_pick(chip, &slot, &txp))
			return -EBUSY;	/* unreachable: a raise frees keys */
	}
	err = tx_load(chip, slot, txp, regs, nregs);
	if (err)
		return err;
	err = mcp2510_rts(chip, BIT(slot));
	if (err)
		return err;

	chip->tx.busy |= BIT(slot);
	chip->tx.seq[slot] = chip->tx.next_seq++;
	return slot;
}

/* Raise events for the finished frames at the head of the queue. */
static void tx_report(struct mcp2510_chip *chip)
{
	u8 order[MCP2510_TXB_COUNT];
	unsigned int n, i;

	n = queue_order(chip, chip->tx.busy, order);
	for (i = 0; i < n && chip->tx.done & BIT(order[i]); i++) {
		chip->tx.busy &= ~BIT(order[i]);
		chip->tx.done &= ~BIT(order[i]);
		if (chip->events->tx_done)
			chip->events->tx_done(chip->ctx, order[i]);
	}
}

void mcp2510_tx_complete(struct mcp2510_chip *chip, u8 slots)
{
	chip->tx.done |= slots & chip->tx.busy;
	tx_report(chip);
}

void mcp2510_tx_lost(struct mcp2510_chip *chip, u8 slots)
{
	u8 order[MCP2510_TXB_COUNT];
	unsigned int n, i;

	n = queue_order(chip, slots & mcp2510_tx_pending(chip), order);
	for (i = 0; i < n; i++) {
		chip->tx.busy &= ~BIT(order[i]);
		chip->counters.tx_errors++;
		if (chip->events->tx_aborted)
			chip->events->tx_aborted(chip->ctx, order[i]);
	}
	tx_report(chip);
}

void mcp2510_tx_abort_all(struct mcp2510_chip *chip)
{
	u8 order[MCP2510_TXB_COUNT];
	unsigned int n, i;

	n = queue_order(chip, chip->tx.busy, order);
	for (i = 0; i < n; i++) {
		unsigned int slot = order[i];
		bool sent = chip->tx.done & BIT(slot);

		chip->tx.busy &= ~BIT(slot);
		chip->tx.done &= ~BIT(slot);
		if (sent && chip->events->tx_done)
			chip->events->tx_done(chip->ctx, slot);
		else if (!sent && chip->events->tx_aborted)
			chip->events->tx_aborted(chip->ctx, slot);
	}
}

/* After a RESET every TXBnCTRL is 0. */
void mcp2510_tx_reset(struct mcp2510_chip *chip)
{
	memset(&chip->tx, 0, sizeof(chip->tx));
}
