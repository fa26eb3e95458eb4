// SPDX-License-Identifier: GPL-2.0
/*
 * The INT pin.  Every interrupt is handled in a thread because reading
 * the chip takes SPI transfers that sleep; the hard handler only notes
 * the time, for receive timestamps, and the line stays masked
 * (IRQF_ONESHOT) until the thread is done.
 */
#include <linux/interrupt.h>
#include <linux/irq.h>
#include <linux/jiffies.h>
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

/*
 * A level-triggered INT only fires while the chip flags something, and the
 * thread clears what it handles, so a call that finds nothing is rare: it
 * takes a flag cleared by another path in between.  Many in a short time
 * mean INT is asserted for no reason (a stuck line, a short), and an
 * edge-triggered loop that hits its bound means the chip never lets go.
 * A call whose SPI transfers fail clears nothing either: while the fault
 * lasts, a level-triggered INT fires again as soon as it is unmasked.
 * Either way the line only keeps the CPU busy: hand the chip to the watch,
 * which polls it and gives the line back after a backoff.
 */
static bool mcp2510_irq_storm(struct mcp2510_priv *priv, int handled)
{
	struct mcp2510_watch *w = &priv->watch;

	if (handled > 0)
		return false;
	if (time_after(jiffies, w->unhandled_since + HZ)) {
		w->unhandled_since = jiffies;
		w->unhandled_irqs = 0;
	}
	if (handled != -EAGAIN &&
	    ++w->unhandled_irqs < MCP2510_STORM_UNHANDLED_IRQS)
		return false;
	w->unhandled_irqs = 0;
	mcp2510_watch_storm(priv);
	return true;
}

/*
 * INT fired: the frame that asserted it has ended on the bus.  The
 * thread may run much later (scheduling, and SPI reads before the frame
 * is queued), so the time is taken here; rx.c decides which frame may
 * carry it.
 */
irqreturn_t mcp2510_irq_hard(int irq, void *data)
{
	struct mcp2510_priv *priv = data;

	mcp2510_rx_stamp_irq(priv);
	atomic_inc(&priv->watch.irqs_fired);
	return IRQ_WAKE_THREAD;
}

irqreturn_t mcp2510_irq_thread(int irq, void *data)
{
	struct mcp2510_priv *priv = data;
	bool storm;
	int handled;

	mcp2510_lock(priv);
	priv->watch.irqs_seen = atomic_read(&priv->watch.irqs_fired);
	handled = mcp2510_irq_handle(&priv->chip);
	/* Stopping the chip from inside the core's pass is not allowed. */
	if (mcp2510_dev_state(priv) == MCP2510_DEV_BUS_OFF)
		mcp2510_halt_locked(priv);
	storm = mcp2510_irq_storm(priv, handled);
	mcp2510_rx_deliver(priv);
	mcp2510_unlock(priv);

	/* Handled by disabling the line: not for the spurious detector. */
	if (storm || handled == -EAGAIN)
		return IRQ_HANDLED;
	if (handled < 0) {
		if (net_ratelimit())
			netdev_err(priv->ndev, "interrupt handling failed: %pe\n",
				   ERR_PTR(handled));
		/*
		 * The interrupt was the chip's; that it could not be read is
		 * the storm accounting's business.  IRQ_NONE would feed
		 * genirq's spurious detector, which disables the line for
		 * good: nothing enables it again while the interface is up.
		 */
		return IRQ_HANDLED;
	}
	return handled ? IRQ_HANDLED : IRQ_NONE;
}
