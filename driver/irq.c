// SPDX-License-Identifier: GPL-2.0
/*
 * The INT pin.  Every interrupt is handled in a thread because reading
 * the chip takes SPI transfers that sleep; there is no hard handler and
 * the line stays masked (IRQF_ONESHOT) until the thread is done.
 */
#include <linux/interrupt.h>
#include <linux/irq.h>
#include <linux/netdevice.h>
#include <linux/spi/spi.h>

#include "mcp2510_priv.h"

/*
 * The trigger the firmware gave the line, or level-low (INT is active low
 * and stays asserted while anything is pending) when it gave none.  On an
 * edge the core must keep reading until nothing is pending, because an
 * event arriving during the pass produces no new edge.
 */
unsigned long mcp2510_irq_trigger(struct mcp2510_priv *priv)
{
	unsigned int type = irq_get_trigger_type(priv->spi->irq);

	if (type == IRQ_TYPE_NONE)
		type = IRQ_TYPE_LEVEL_LOW;
	priv->chip.irq_edge = !!(type & IRQ_TYPE_EDGE_BOTH);
	return type;
}

irqreturn_t mcp2510_irq_thread(int irq, void *data)
{
	struct mcp2510_priv *priv = data;
	int handled;

	mcp2510_lock(priv);
	handled = mcp2510_irq_handle(&priv->chip);
	/* Stopping the chip from inside the core's pass is not allowed. */
	if (priv->halt_requested)
		mcp2510_halt_locked(priv);
	mcp2510_unlock(priv);
	mcp2510_rx_kick(priv);

	if (handled == -EAGAIN) {
		netdev_warn_once(priv->ndev, "INT keeps asserting: interrupt storm\n");
		return IRQ_HANDLED;
	}
	if (handled < 0) {
		if (net_ratelimit())
			netdev_err(priv->ndev, "interrupt handling failed: %pe\n",
				   ERR_PTR(handled));
		/* Lets the spurious-interrupt detector shut a dead chip up. */
		return IRQ_NONE;
	}
	return handled ? IRQ_HANDLED : IRQ_NONE;
}
