// SPDX-License-Identifier: GPL-2.0
/*
 * Transmit path.  start_xmit runs in atomic context but loading a frame
 * takes SPI transfers that sleep, so skbs wait in a three-entry FIFO for
 * the TX work.  At most three frames are accepted and not yet finished
 * (queued plus loaded), one per hardware buffer: the queue stops exactly
 * when all three buffers are taken and wakes as soon as one frees.
 *
 * Byte queue limits: every frame start_xmit accepts is reported sent,
 * with its length on the wire (can_skb_get_frame_len()), and every one
 * is reported completed exactly once, however it ends.  A frame in a TX
 * buffer carries its length in its echo skb, and the echo helpers give
 * it back when the frame is sent or aborted; the completions of one hold
 * of the chip lock are reported together when it is released.  The halt
 * at bus-off ends every frame in the chip before can-dev's restart could
 * flush an echo skb, so none is lost that way.  A frame dropped before
 * it reached the chip, or whose echo skb could not be made, is counted
 * with the completions of the hold that dropped it: BQL's completion may
 * not run twice at once, and the chip lock is what keeps every report of
 * one apart from the others.
 */
#include <linux/can/dev.h>
#include <linux/can/skb.h>
#include <linux/netdevice.h>

#include "mcp2510_priv.h"

static unsigned int mcp2510_tx_busy(const struct mcp2510_priv *priv)
{
	return priv->tx_fifo_len + priv->tx_loading +
	       hweight8(priv->tx_inflight);
}

/*
 * Under tx_lock, which start_xmit holds while it takes a buffer.  A
 * detached device (suspend) keeps its queue stopped whatever frees:
 * netif_device_attach() wakes it.
 */
static void mcp2510_tx_wake(struct mcp2510_priv *priv)
{
	if (mcp2510_tx_busy(priv) < MCP2510_TXB_COUNT &&
	    netif_queue_stopped(priv->ndev) &&
	    netif_device_present(priv->ndev))
		netif_wake_queue(priv->ndev);
}

/* After a restart: only if a buffer is free, or start_xmit gets BUSY. */
void mcp2510_tx_wake_queue(struct mcp2510_priv *priv)
{
	spin_lock_bh(&priv->tx_lock);
	mcp2510_tx_wake(priv);
	spin_unlock_bh(&priv->tx_lock);
}

netdev_tx_t mcp2510_start_xmit(struct sk_buff *skb, struct net_device *ndev)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);
	unsigned int bytes, tail;

	if (can_dev_dropped_skb(ndev, skb))
		return NETDEV_TX_OK;
	bytes = can_skb_get_frame_len(skb);

	spin_lock(&priv->tx_lock);
	if (mcp2510_tx_busy(priv) >= MCP2510_TXB_COUNT) {
		/* The queue should have been stopped: ask the stack to retry. */
		netif_stop_queue(ndev);
		spin_unlock(&priv->tx_lock);
		netdev_err_once(ndev, "transmit while all buffers are taken\n");
		return NETDEV_TX_BUSY;
	}
	tail = (priv->tx_fifo_head + priv->tx_fifo_len) % MCP2510_TXB_COUNT;
	priv->tx_fifo[tail] = skb;
	priv->tx_fifo_len++;
	/* Before the work can see the frame, so it is never completed first. */
	netdev_sent_queue(ndev, bytes);
	if (mcp2510_tx_busy(priv) == MCP2510_TXB_COUNT)
		netif_stop_queue(ndev);
	spin_unlock(&priv->tx_lock);

	queue_work(system_highpri_wq, &priv->tx_work);
	return NETDEV_TX_OK;
}

/*
 * Take the oldest queued skb and count it as being loaded in the same
 * critical section, so that start_xmit never sees a free buffer that is
 * in fact being filled.  mcp2510_tx_loaded() ends the loading state.
 */
static struct sk_buff *mcp2510_tx_fifo_pop(struct mcp2510_priv *priv)
{
	struct sk_buff *skb = NULL;

	spin_lock_bh(&priv->tx_lock);
	if (priv->tx_fifo_len) {
		skb = priv->tx_fifo[priv->tx_fifo_head];
		priv->tx_fifo[priv->tx_fifo_head] = NULL;
		priv->tx_fifo_head = (priv->tx_fifo_head + 1) % MCP2510_TXB_COUNT;
		priv->tx_fifo_len--;
		priv->tx_loading = true;
	}
	spin_unlock_bh(&priv->tx_lock);
	return skb;
}

/*
 * Give back the skb mcp2510_tx_fifo_pop() took, at the head again: no
 * buffer is free yet.  It stays counted, so the queue stays as it is.
 */
static void mcp2510_tx_fifo_unpop(struct mcp2510_priv *priv,
				  struct sk_buff *skb)
{
	spin_lock_bh(&priv->tx_lock);
	priv->tx_fifo_head = (priv->tx_fifo_head + MCP2510_TXB_COUNT - 1) %
			     MCP2510_TXB_COUNT;
	priv->tx_fifo[priv->tx_fifo_head] = skb;
	priv->tx_fifo_len++;
	priv->tx_loading = false;
	spin_unlock_bh(&priv->tx_lock);
}

/* Under tx_lock: frames wait for the work, which may have given up. */
static void mcp2510_tx_retry_locked(struct mcp2510_priv *priv)
{
	if (priv->tx_fifo_len)
		queue_work(system_highpri_wq, &priv->tx_work);
}

/*
 * A buffer whose RTS failed stays out of use until a READ STATUS shows
 * it free, and nothing reports when one does: the watch calls this.
 */
void mcp2510_tx_retry(struct mcp2510_priv *priv)
{
	spin_lock_bh(&priv->tx_lock);
	mcp2510_tx_retry_locked(priv);
	spin_unlock_bh(&priv->tx_lock);
}

/*
 * A popped skb now sits in @slot, or in none when @slot is negative: then
 * it was dropped, and counted done under the chip lock.
 */
static void mcp2510_tx_loaded(struct mcp2510_priv *priv, int slot)
{
	spin_lock_bh(&priv->tx_lock);
	priv->tx_loading = false;
	if (slot >= 0)
		priv->tx_inflight |= BIT(slot);
	else
		mcp2510_tx_wake(priv);
	spin_unlock_bh(&priv->tx_lock);
}

/* With the chip lock held: a frame of @bytes on the wire has ended. */
static void mcp2510_tx_count_done(struct mcp2510_priv *priv,
				  unsigned int bytes)
{
	lockdep_assert_held(&priv->lock);
	priv->tx_done_frames++;
	priv->tx_done_bytes += bytes;
}

/*
 * Called with the chip lock held, from an event: the frame in @slot has
 * ended, and @bytes is what its echo skb carried (0 without one).
 */
void mcp2510_tx_slot_release(struct mcp2510_priv *priv, unsigned int slot,
			     unsigned int bytes)
{
	mcp2510_tx_count_done(priv, bytes);
	spin_lock_bh(&priv->tx_lock);
	priv->tx_inflight &= ~BIT(slot);
	mcp2510_tx_wake(priv);
	mcp2510_tx_retry_locked(priv);
	spin_unlock_bh(&priv->tx_lock);
}

/* Before the chip lock is released: report what this hold completed. */
void mcp2510_tx_report_done(struct mcp2510_priv *priv)
{
	lockdep_assert_held(&priv->lock);
	if (!priv->tx_done_frames)
		return;
	netdev_completed_queue(priv->ndev, priv->tx_done_frames,
			       priv->tx_done_bytes);
	priv->tx_done_frames = 0;
	priv->tx_done_bytes = 0;
}

static int mcp2510_tx_load(struct mcp2510_priv *priv, struct sk_buff *skb,
			   unsigned int bytes)
{
	const struct can_frame *cf = (const struct can_frame *)skb->data;
	int slot;

	lockdep_assert_held(&priv->lock);
	/* A chip whose bus-off is not halted yet may still send. */
	if (mcp2510_dev_state(priv) != MCP2510_DEV_RUNNING &&
	    mcp2510_dev_state(priv) != MCP2510_DEV_BUS_OFF)
		return -ENETDOWN;

	slot = mcp2510_tx_submit(&priv->chip, cf);
	if (slot < 0)
		return slot;

	mcp2510_tx_loaded(priv, slot);
	/*
	 * The chip lock keeps the IRQ thread out until the echo skb is in
	 * place, so a completion can never find the slot empty.  Without
	 * one (no memory for a clone) nothing carries the length.
	 */
	if (can_put_echo_skb(skb, priv->ndev, slot, bytes))
		mcp2510_tx_count_done(priv, bytes);
	return 0;
}

void mcp2510_tx_work(struct work_struct *work)
{
	struct mcp2510_priv *priv = container_of(work, struct mcp2510_priv,
						 tx_work);
	struct sk_buff *skb;
	unsigned int bytes;
	int ret;

	/*
	 * One frame per lock hold: completions may free buffers meanwhile.
	 * tx_dropped is counted under the lock, as the events count it.
	 * -EBUSY: every buffer the glue counts free is one whose RTS failed
	 * and which the chip may still be sending.  The frame waits for the
	 * next buffer to end (mcp2510_tx_slot_release() or the watch).
	 */
	while ((skb = mcp2510_tx_fifo_pop(priv))) {
		/* Before the load: the echo may be gone once it is in place. */
		bytes = can_skb_get_frame_len(skb);
		mcp2510_lock(priv);
		ret = mcp2510_tx_load(priv, skb, bytes);
		if (ret == -EBUSY) {
			mcp2510_tx_fifo_unpop(priv, skb);
		} else if (ret) {
			priv->ndev->stats.tx_dropped++;
			mcp2510_tx_count_done(priv, bytes);
		}
		mcp2510_unlock(priv);
		if (ret == -EBUSY)
			return;
		if (!ret)
			continue;
		if (ret != -ENETDOWN)
			netdev_err_once(priv->ndev, "loading a frame failed: %pe\n",
					ERR_PTR(ret));
		dev_kfree_skb(skb);
		mcp2510_tx_loaded(priv, ret);
	}
}

/*
 * Drop the frames still waiting for the work; the caller has stopped the
 * queue and the work.  Frames in the chip are the core's to abort.
 */
void mcp2510_tx_flush(struct mcp2510_priv *priv)
{
	struct sk_buff *skb;
	unsigned int bytes;

	while ((skb = mcp2510_tx_fifo_pop(priv))) {
		bytes = can_skb_get_frame_len(skb);
		dev_kfree_skb(skb);
		mcp2510_lock(priv);
		priv->ndev->stats.tx_dropped++;
		mcp2510_tx_count_done(priv, bytes);
		mcp2510_unlock(priv);
		mcp2510_tx_loaded(priv, -ENETDOWN);
	}
}
