// SPDX-License-Identifier: GPL-2.0
/*
 * Receive path, on can-dev's rx-offload in manual mode.  Whoever runs
 * the chip under its lock queues received frames, error frames and
 * echoes, and hands the batch to NAPI before releasing the lock: the
 * stack sees the chip's order whichever CPU each pass ran on.  The
 * interface reports the driver's own count of received frames, as
 * rx-offload counts echoes too.  Frames are stamped with the time INT
 * fired or the time their pass read the flags, never before their end
 * and never decreasing in queue order.  The rules:
 * docs/driver-internals.md.
 */
#include <linux/can/dev.h>
#include <linux/can/rx-offload.h>
#include <linux/can/skb.h>
#include <linux/netdevice.h>

#include "mcp2510_priv.h"

/* Before the first use of the chip lock: unlocking hands frames on. */
int mcp2510_rx_init(struct mcp2510_priv *priv)
{
	atomic64_set(&priv->rx_irq_ns, 0);
	return can_rx_offload_add_manual(priv->ndev, &priv->offload,
					 NAPI_POLL_WEIGHT);
}

/* A received frame or an error frame, with the chip lock held. */
void mcp2510_rx_queue(struct mcp2510_priv *priv, struct sk_buff *skb)
{
	const struct can_frame *cf = (const struct can_frame *)skb->data;
	struct net_device_stats *stats = &priv->ndev->stats;
	canid_t id = cf->can_id;
	u8 len = cf->len;

	lockdep_assert_held(&priv->lock);
	/* No length on the wire: it tells the frame from an echo (rx_disable). */
	mcp2510_skb_set_frame_len(skb, 0);
	/* On failure rx-offload has freed the skb: the stack lags too far. */
	if (can_rx_offload_queue_tail(&priv->offload, skb)) {
		stats->rx_dropped++;
		stats->rx_fifo_errors++;
		return;
	}
	/* Error frames are not traffic: they are counted by their class. */
	if (id & CAN_ERR_FLAG)
		return;
	WRITE_ONCE(priv->rx_packets, priv->rx_packets + 1);
	if (!(id & CAN_RTR_FLAG))
		WRITE_ONCE(priv->rx_bytes, priv->rx_bytes + len);
}

/*
 * The echo of the frame sent from @slot, behind everything read before
 * its completion; can-dev drops it instead when the sender wanted no
 * loopback.  Returns the frame's data length for tx_bytes, which the
 * helper does not when it drops the echo, and sets @frame_len to the
 * length on the wire the echo skb carried for BQL.
 */
unsigned int mcp2510_rx_queue_echo(struct mcp2510_priv *priv,
				   unsigned int slot, unsigned int *frame_len)
{
	struct sk_buff *skb = priv->can.echo_skb[slot];
	unsigned int len;

	lockdep_assert_held(&priv->lock);
	if (!skb)
		return 0;
	len = can_skb_get_data_len(skb);
	skb->tstamp = mcp2510_rx_stamp_event(priv);
	can_rx_offload_get_echo_skb_queue_tail(&priv->offload, slot, frame_len);
	return len;
}

/*
 * Hand what this hold of the chip lock queued to the stack, before the
 * next holder can queue more: the stack sees the chip's order.  The
 * finish schedules NAPI with bottom halves off, and enabling them again
 * runs its poll right here, under the chip lock, unless NAPI is already
 * running elsewhere; it delivers the frames in order either way.
 */
void mcp2510_rx_deliver(struct mcp2510_priv *priv)
{
	lockdep_assert_held(&priv->lock);
	priv->rx_in_pass = false;
	can_rx_offload_threaded_irq_finish(&priv->offload);
}

/*
 * Hard IRQ context.  On an edge-triggered line this may run while a pass
 * is under way; the latest time is the one to keep (see rx_pass in
 * mcp2510_core.h: it is about INT being asserted since the last pass).
 */
void mcp2510_rx_stamp_irq(struct mcp2510_priv *priv)
{
	atomic64_set(&priv->rx_irq_ns, ktime_to_ns(ktime_get_real()));
}

/* The core's rx_pass: a pass read the flags (see the top of the file). */
void mcp2510_rx_pass(struct mcp2510_priv *priv, bool first_waited)
{
	ktime_t now = ktime_get_real();
	s64 irq_ns = atomic64_xchg(&priv->rx_irq_ns, 0);

	lockdep_assert_held(&priv->lock);
	priv->rx_pass_ts = now;
	priv->rx_first_ts = now;
	/* a clock set back in between would make the INT time the later */
	if (first_waited && irq_ns && irq_ns <= ktime_to_ns(now))
		priv->rx_first_ts = ns_to_ktime(irq_ns);
	priv->rx_in_pass = true;
}

/* The timestamp of the next received frame. */
ktime_t mcp2510_rx_stamp_frame(struct mcp2510_priv *priv)
{
	ktime_t ts;

	lockdep_assert_held(&priv->lock);
	if (!priv->rx_in_pass)
		return ktime_get_real();
	ts = priv->rx_first_ts;
	priv->rx_first_ts = priv->rx_pass_ts;
	return ts;
}

/* The timestamp of an error frame. */
ktime_t mcp2510_rx_stamp_event(struct mcp2510_priv *priv)
{
	lockdep_assert_held(&priv->lock);
	return priv->rx_in_pass ? priv->rx_pass_ts : ktime_get_real();
}

void mcp2510_get_stats64(struct net_device *ndev,
			 struct rtnl_link_stats64 *stats)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);

	netdev_stats_to_stats64(stats, &ndev->stats);
	stats->rx_packets = READ_ONCE(priv->rx_packets);
	stats->rx_bytes = READ_ONCE(priv->rx_bytes);
}

/*
 * Interface down: deliver nothing more, drop what is still queued.  The
 * frames received among it were counted when queued: they never reached
 * the stack, so they count as dropped instead.  Echoes carry their length
 * on the wire (can_put_echo_skb()), received frames none.
 */
void mcp2510_rx_disable(struct mcp2510_priv *priv)
{
	struct net_device_stats *stats = &priv->ndev->stats;
	const struct can_frame *cf;
	struct sk_buff *skb;

	can_rx_offload_disable(&priv->offload);
	while ((skb = skb_dequeue(&priv->offload.skb_queue))) {
		cf = (const struct can_frame *)skb->data;
		if (!(cf->can_id & CAN_ERR_FLAG) &&
		    !mcp2510_skb_frame_len(skb)) {
			WRITE_ONCE(priv->rx_packets, priv->rx_packets - 1);
			if (!(cf->can_id & CAN_RTR_FLAG))
				WRITE_ONCE(priv->rx_bytes,
					   priv->rx_bytes - cf->len);
			stats->rx_dropped++;
		}
		kfree_skb(skb);
	}
}

void mcp2510_rx_del(struct mcp2510_priv *priv)
{
	can_rx_offload_del(&priv->offload);
}
