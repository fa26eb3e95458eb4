// SPDX-License-Identifier: GPL-2.0
/*
 * Receive path: the IRQ thread queues frames, error frames and the echoes
 * of sent frames here and a NAPI poll hands them to the stack, so they
 * arrive in exactly the order the chip produced them whichever CPU the
 * thread ran on.  (netif_rx() would use the backlog of the current CPU and
 * could reorder frames read on different CPUs.)  can_rx_offload would do
 * the same, but can-dev only contains it when an in-tree driver selects
 * CONFIG_CAN_RX_OFFLOAD, which an out-of-tree module cannot: many small
 * kernels lack it.
 */
#include <linux/can/dev.h>
#include <linux/if_packet.h>
#include <linux/netdevice.h>
#include <linux/skbuff.h>

#include "mcp2510_priv.h"

/* Bounds memory while the stack lags: about 2 s of frames at 1 Mbit/s. */
#define MCP2510_RX_QUEUE_MAX	16384

void mcp2510_rx_init(struct mcp2510_priv *priv)
{
	skb_queue_head_init(&priv->rx_queue);
	netif_napi_add(priv->ndev, &priv->napi, mcp2510_rx_poll);
}

void mcp2510_rx_queue(struct mcp2510_priv *priv, struct sk_buff *skb)
{
	struct net_device_stats *stats = &priv->ndev->stats;

	if (skb_queue_len(&priv->rx_queue) >= MCP2510_RX_QUEUE_MAX) {
		dev_kfree_skb_any(skb);
		stats->rx_dropped++;
		stats->rx_fifo_errors++;
		return;
	}
	skb_queue_tail(&priv->rx_queue, skb);
}

/*
 * The echo of a sent frame, in completion order.  It is marked as looped
 * back while queued so that mcp2510_rx_poll() does not count it received.
 */
void mcp2510_rx_queue_echo(struct mcp2510_priv *priv, struct sk_buff *skb)
{
	skb->pkt_type = PACKET_LOOPBACK;
	skb_queue_tail(&priv->rx_queue, skb);
}

/* After a pass over the chip: let NAPI deliver what it queued. */
void mcp2510_rx_kick(struct mcp2510_priv *priv)
{
	if (skb_queue_empty_lockless(&priv->rx_queue))
		return;
	/* From a thread: the softirq must run when BHs come back on. */
	local_bh_disable();
	napi_schedule(&priv->napi);
	local_bh_enable();
}

static void mcp2510_rx_count(struct net_device *ndev,
			     const struct sk_buff *skb)
{
	const struct can_frame *cf = (const struct can_frame *)skb->data;

	/* Error frames are not traffic: they are counted by their class. */
	if (cf->can_id & CAN_ERR_FLAG)
		return;
	ndev->stats.rx_packets++;
	if (!(cf->can_id & CAN_RTR_FLAG))
		ndev->stats.rx_bytes += cf->len;
}

int mcp2510_rx_poll(struct napi_struct *napi, int budget)
{
	struct mcp2510_priv *priv = container_of(napi, struct mcp2510_priv,
						 napi);
	struct sk_buff *skb;
	int done = 0;

	while (done < budget && (skb = skb_dequeue(&priv->rx_queue))) {
		if (skb->pkt_type == PACKET_LOOPBACK)
			skb->pkt_type = PACKET_BROADCAST;
		else
			mcp2510_rx_count(priv->ndev, skb);
		netif_receive_skb(skb);
		done++;
	}
	/* A frame queued while the poll was finishing found it scheduled. */
	if (done < budget && napi_complete_done(napi, done) &&
	    !skb_queue_empty_lockless(&priv->rx_queue))
		napi_schedule(napi);
	return done;
}

/* Interface down: deliver nothing more, free what is still queued. */
void mcp2510_rx_disable(struct mcp2510_priv *priv)
{
	napi_disable(&priv->napi);
	skb_queue_purge(&priv->rx_queue);
}
