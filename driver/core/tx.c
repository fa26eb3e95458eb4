// SPDX-License-Identifier: GPL-2.0
/*
 * The ordered three-buffer transmit scheduler.  The chip sends the
 * pending buffer with the highest key (TXP * 3 + buffer number), so each
 * new frame gets a key below every pending frame's; when none is left it
 * is staged and requested with the others once the pending ones are gone.
 * A buffer is written only while its TXREQ is clear; loading and
 * requesting are tx_request.c's.  Completions are reported in queue
 * order.  Why, and what it is worth against one buffer (measured):
 * docs/driver-internals.md.
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
	return chip->tx.busy & ~chip->tx.done & ~chip->tx.staged;
}

/* Slots that can take a new frame. */
static u8 tx_unused(const struct mcp2510_chip *chip)
{
	return SLOTS_ALL & ~chip->tx.busy & ~chip->tx.unsure;
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

/* The lowest key of the slots in @mask, KEY_CEILING when none. */
static unsigned int key_floor(const struct mcp2510_chip *chip, u8 mask)
{
	unsigned int floor = KEY_CEILING, slot;

	for (slot = 0; slot < MCP2510_TXB_COUNT; slot++)
		if (mask & BIT(slot) && tx_key(chip, slot) < floor)
			floor = tx_key(chip, slot);
	return floor;
}

/* The unused slot and TXP with the highest key below @floor. */
static bool tx_pick(const struct mcp2510_chip *chip, unsigned int floor,
		    unsigned int *slot, u8 *txp)
{
	int best_key = -1;
	unsigned int s;

	for (s = 0; s < MCP2510_TXB_COUNT; s++) {
		int p;

		if (!(tx_unused(chip) & BIT(s)))
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

unsigned int mcp2510_tx_free(const struct mcp2510_chip *chip)
{
	unsigned int slot, n = 0;

	for (slot = 0; slot < MCP2510_TXB_COUNT; slot++)
		if (!(chip->tx.busy & BIT(slot)))
			n++;
	return n;
}

/* Load @cf below the staged frames, to be requested by mcp2510_tx_kick(). */
static int tx_stage(struct mcp2510_chip *chip, const u8 *regs,
		    unsigned int nregs, unsigned int *slot)
{
	u8 txp = 0;
	int ret;

	if (!tx_pick(chip, key_floor(chip, chip->tx.staged), slot, &txp))
		return -EBUSY;	/* unreachable: 12 keys for 3 slots */
	ret = mcp2510_tx_load(chip, *slot, txp, regs, nregs);
	if (ret)
		return ret;
	chip->tx.staged |= BIT(*slot);
	chip->tx.stages++;
	return 0;
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
	nregs = mcp2510_frame_encode(cf, chip->ctrlmode, regs);
	if (nregs < 0)
		return nregs;
	if (!tx_unused(chip)) {
		err = mcp2510_tx_status_resolve(chip);
		if (err)
			return err;
		if (!tx_unused(chip))
			return -EBUSY;
	}

	if (!chip->tx.staged &&
	    tx_pick(chip, key_floor(chip, mcp2510_tx_pending(chip)), &slot,
		    &txp))
		err = mcp2510_tx_send(chip, slot, txp, regs, nregs);
	else
		err = tx_stage(chip, regs, nregs, &slot);
	if (err)
		return err;

	chip->tx.busy |= BIT(slot);
	chip->tx.seq[slot] = chip->tx.next_seq++;
	/*
	 * Staged with nothing pending (an earlier kick failed): go now.  The
	 * frame is the core's either way; a failed kick is retried by the
	 * next interrupt or health check.
	 */
	mcp2510_tx_kick(chip, 0);
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
	u8 sent = slots & chip->tx.busy & ~chip->tx.done;

	for (; sent; sent &= sent - 1)
		chip->sent_since_bec++;
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
		chip->tx.staged &= ~BIT(slot);
		chip->tx.unsure &= ~BIT(slot);
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
