// SPDX-License-Identifier: GPL-2.0
/*
 * What the core reports, turned into skbs and statistics.  Every event
 * arrives with the chip lock held, mostly from the IRQ thread, so frames
 * are queued for the stack in the order the chip received them.
 */
#include <linux/can/skb.h>
#include <linux/netdevice.h>

#include "mcp2510_priv.h"

static void mcp2510_event_rx(void *ctx, const struct can_frame *frame)
{
	struct mcp2510_priv *priv = ctx;
	/* taken even for a frame dropped here: it is that frame's */
	ktime_t ts = mcp2510_rx_stamp_frame(priv);
	struct can_frame *cf;
	struct sk_buff *skb;

	skb = alloc_can_skb(priv->ndev, &cf);
	if (!skb) {
		priv->ndev->stats.rx_dropped++;
		return;
	}
	*cf = *frame;
	skb->tstamp = ts;
	/* rx_packets and rx_bytes are counted once it is queued. */
	mcp2510_rx_queue(priv, skb);
}

static void mcp2510_event_tx_done(void *ctx, unsigned int slot)
{
	struct mcp2510_priv *priv = ctx;
	struct net_device_stats *stats = &priv->ndev->stats;
	unsigned int frame_len = 0;

	stats->tx_bytes += mcp2510_rx_queue_echo(priv, slot, &frame_len);
	stats->tx_packets++;
	mcp2510_tx_slot_release(priv, slot, frame_len);
}

static void mcp2510_event_tx_aborted(void *ctx, unsigned int slot)
{
	struct mcp2510_priv *priv = ctx;
	unsigned int frame_len = 0;

	/* No echo skb: none could be made when the frame was loaded. */
	if (priv->can.echo_skb[slot]) {
		can_free_echo_skb(priv->ndev, slot, &frame_len);
		priv->ndev->stats.tx_dropped++;
		priv->ndev->stats.tx_aborted_errors++;
	}
	mcp2510_tx_slot_release(priv, slot, frame_len);
}

static void mcp2510_event_state(void *ctx, enum can_state state,
				const struct can_berr_counter *bec)
{
	struct mcp2510_priv *priv = ctx;
	enum can_state tx_state, rx_state;

	/* A chip back from bus-off by itself has nothing left to halt. */
	if (state != CAN_STATE_BUS_OFF &&
	    mcp2510_dev_state(priv) == MCP2510_DEV_BUS_OFF)
		mcp2510_dev_enter(priv, MCP2510_DEV_RUNNING);
	if (state == priv->can.state)
		return;

	/*
	 * Left alone the chip would recover by itself after 128 x 11
	 * recessive bits and be back on the bus, sending and completing
	 * frames, while the carrier is off and can_restart() empties the echo
	 * slots without the chip lock.  It is stopped once the interrupt pass
	 * is over, and only then does the interface go bus-off (see
	 * mcp2510_halt_locked()): no restart can find it busy.
	 */
	if (state == CAN_STATE_BUS_OFF) {
		if (mcp2510_dev_state(priv) == MCP2510_DEV_RUNNING)
			mcp2510_dev_enter(priv, MCP2510_DEV_BUS_OFF);
		return;
	}

	/* Blame the direction whose counter is higher, as the stack expects. */
	tx_state = bec->txerr >= bec->rxerr ? state : CAN_STATE_ERROR_ACTIVE;
	rx_state = bec->txerr <= bec->rxerr ? state : CAN_STATE_ERROR_ACTIVE;
	/* The core sends its own error frame; this keeps state and counters. */
	can_change_state(priv->ndev, NULL, tx_state, rx_state);
}

static void mcp2510_count_error(struct mcp2510_priv *priv,
				const struct can_frame *cf)
{
	struct net_device_stats *stats = &priv->ndev->stats;

	if (cf->can_id & CAN_ERR_BUSERROR) {
		priv->can.can_stats.bus_error++;
		if (cf->data[2] & CAN_ERR_PROT_TX)
			stats->tx_errors++;
		else
			stats->rx_errors++;
	}
	if (cf->can_id & CAN_ERR_ACK)
		stats->tx_errors++;
	if ((cf->can_id & CAN_ERR_CRTL) &&
	    (cf->data[1] & CAN_ERR_CRTL_RX_OVERFLOW)) {
		stats->rx_over_errors++;
		stats->rx_errors++;
	}
}

static void mcp2510_event_error(void *ctx, const struct can_frame *frame)
{
	struct mcp2510_priv *priv = ctx;
	struct can_frame *cf;
	struct sk_buff *skb;

	/* Count even when no skb can be had: the statistics must not lie. */
	mcp2510_count_error(priv, frame);

	skb = alloc_can_err_skb(priv->ndev, &cf);
	if (!skb)
		return;
	*cf = *frame;
	skb->tstamp = mcp2510_rx_stamp_event(priv);
	mcp2510_rx_queue(priv, skb);
}

static void mcp2510_event_rx_pass(void *ctx, bool first_waited)
{
	mcp2510_rx_pass(ctx, first_waited);
}

const struct mcp2510_events mcp2510_netdev_events = {
	.rx = mcp2510_event_rx,
	.tx_done = mcp2510_event_tx_done,
	.tx_aborted = mcp2510_event_tx_aborted,
	.state = mcp2510_event_state,
	.error = mcp2510_event_error,
	.rx_pass = mcp2510_event_rx_pass,
};
