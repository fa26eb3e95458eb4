// SPDX-License-Identifier: GPL-2.0
/*
 * The watch: a delayed work that looks after the chip while the interface
 * is up, for what the INT line cannot report.  Each tick checks that the
 * chip still holds what was programmed (a chip that reset itself never
 * raises INT again) and programs it again if not.  Through an interrupt
 * storm the line is disabled and the work polls the chip instead, for a
 * backoff that doubles while the storm goes on.  On an edge-triggered
 * line each tick also runs the interrupt loop: an edge lost while INT
 * was low would leave INT low for good.  docs/driver-internals.md has
 * the figures behind the periods.
 */
#include <linux/can/dev.h>
#include <linux/interrupt.h>
#include <linux/jiffies.h>
#include <linux/minmax.h>
#include <linux/netdevice.h>
#include <linux/spi/spi.h>

#include "mcp2510_priv.h"

/*
 * Measured on 6.1 in the rig (idle SPI cost; a chip reset to back in
 * service, mean of five): 1 s costs 2 transfers a second and takes
 * 0.76 s; 200 ms, 10 a second for 0.18 s; 5 s, 4.4 s.
 */
#define MCP2510_WATCH_MS	1000
/*
 * The frame behind a lost edge waited 20 ms (mean of ten, 38 at most)
 * for 69 transfers a second; 10 ms: 6.5 ms for 245; 200 ms: 101 ms for
 * 20, and a flood with lost edges lost 1987 of 2000 frames.
 */
#define MCP2510_WATCH_EDGE_MS	50
#define MCP2510_POLL_MS		10
#define MCP2510_BACKOFF_MIN_MS	100
#define MCP2510_BACKOFF_MAX_MS	2000
/* A storm within this long of the line coming back is the same storm. */
#define MCP2510_STORM_GAP_MS	1000

static unsigned long mcp2510_watch_delay(const struct mcp2510_priv *priv)
{
	const struct mcp2510_watch *w = &priv->watch;

	if (w->state == MCP2510_WATCH_POLLING)
		return msecs_to_jiffies(MCP2510_POLL_MS);
	return msecs_to_jiffies(priv->chip.irq_edge ? MCP2510_WATCH_EDGE_MS :
				MCP2510_WATCH_MS);
}

/* An error frame that tells listeners the controller was restarted. */
static void mcp2510_watch_report_restart(struct mcp2510_priv *priv)
{
	struct can_frame *cf;
	struct sk_buff *skb;

	skb = alloc_can_err_skb(priv->ndev, &cf);
	if (!skb)
		return;
	cf->can_id |= CAN_ERR_RESTARTED;
	mcp2510_rx_queue(priv, skb);
}

static void mcp2510_watch_health(struct mcp2510_priv *priv)
{
	struct mcp2510_watch *w = &priv->watch;
	int ret;

	ret = mcp2510_health_check(&priv->chip);
	if (ret != -EBADMSG)
		return;
	/* One line per episode, however many ticks the chip stays broken. */
	if (!w->recovering)
		netdev_err(priv->ndev,
			   "chip lost its configuration (reset, or garbage on SPI): re-initialising\n");
	w->recovering = true;
	ret = mcp2510_recover(&priv->chip);
	if (ret)
		return;
	w->recovering = false;
	/*
	 * The chip is programmed again and error-active: the interface must
	 * say so in full.  Its carrier is normally on (a bus-off chip is
	 * stopped and never checked), but state and carrier go together.
	 */
	priv->can.state = CAN_STATE_ERROR_ACTIVE;
	if (!netif_carrier_ok(priv->ndev))
		netif_carrier_on(priv->ndev);
	mcp2510_gpio_restore(priv);
	mcp2510_watch_report_restart(priv);
	netdev_info(priv->ndev, "chip re-initialised\n");
}

/* Run the interrupt loop as the IRQ thread would. */
static void mcp2510_watch_poll(struct mcp2510_priv *priv)
{
	struct mcp2510_watch *w = &priv->watch;
	int handled;

	handled = mcp2510_irq_handle(&priv->chip);
	/*
	 * Work found outside a storm is an interrupt the line never brought,
	 * unless INT fired since the thread last ran: the thread, waiting
	 * for the chip lock, would have found that work itself.
	 */
	if (handled > 0 && w->state != MCP2510_WATCH_POLLING &&
	    atomic_read(&w->irqs_fired) == w->irqs_seen)
		w->missed_interrupts++;
}

/* Give the line another chance once the backoff is over. */
static void mcp2510_watch_end_polling(struct mcp2510_priv *priv)
{
	struct mcp2510_watch *w = &priv->watch;

	if (w->state != MCP2510_WATCH_POLLING ||
	    time_before(jiffies, w->poll_until))
		return;
	w->state = MCP2510_WATCH_IRQ_BACK;
	w->irq_back_at = jiffies;
	enable_irq(priv->spi->irq);
}

/* A storm is over when the line stayed quiet for a while after coming back. */
static void mcp2510_watch_end_storm(struct mcp2510_priv *priv)
{
	struct mcp2510_watch *w = &priv->watch;

	if (w->state != MCP2510_WATCH_IRQ_BACK ||
	    time_before(jiffies, w->irq_back_at +
			msecs_to_jiffies(MCP2510_STORM_GAP_MS)))
		return;
	w->state = MCP2510_WATCH_IRQ;
	netdev_info(priv->ndev, "INT quiet again: back to interrupts\n");
}

static void mcp2510_watch_work(struct work_struct *work)
{
	struct mcp2510_priv *priv = container_of(to_delayed_work(work),
						 struct mcp2510_priv,
						 watch.work);
	struct mcp2510_watch *w = &priv->watch;
	unsigned long delay;

	mcp2510_lock(priv);
	if (w->state == MCP2510_WATCH_STOPPED) {
		mcp2510_unlock(priv);
		return;
	}
	mcp2510_watch_health(priv);
	if (w->state == MCP2510_WATCH_POLLING || priv->chip.irq_edge)
		mcp2510_watch_poll(priv);
	if (mcp2510_dev_state(priv) == MCP2510_DEV_BUS_OFF)
		mcp2510_halt_locked(priv);
	mcp2510_watch_end_polling(priv);
	mcp2510_watch_end_storm(priv);
	delay = mcp2510_watch_delay(priv);
	mcp2510_rx_deliver(priv);
	mcp2510_unlock(priv);
	mcp2510_tx_retry(priv);

	queue_delayed_work(system_percpu_wq, &w->work, delay);
}

/*
 * From the IRQ thread, with the chip lock held: INT keeps firing for
 * nothing.  The thread cannot wait for itself, hence the nosync disable.
 */
void mcp2510_watch_storm(struct mcp2510_priv *priv)
{
	struct mcp2510_watch *w = &priv->watch;
	bool same;

	lockdep_assert_held(&priv->lock);
	if (w->state == MCP2510_WATCH_STOPPED ||
	    w->state == MCP2510_WATCH_POLLING)
		return;
	disable_irq_nosync(priv->spi->irq);

	same = w->state == MCP2510_WATCH_IRQ_BACK &&
	       time_before(jiffies, w->irq_back_at +
			   msecs_to_jiffies(MCP2510_STORM_GAP_MS));
	w->state = MCP2510_WATCH_POLLING;
	if (same) {
		w->backoff_ms = min(2 * w->backoff_ms, MCP2510_BACKOFF_MAX_MS);
	} else {
		w->backoff_ms = MCP2510_BACKOFF_MIN_MS;
		w->irq_storms++;
		if (net_ratelimit())
			netdev_warn(priv->ndev,
				    "interrupt storm on INT: polling the chip instead\n");
	}
	w->poll_until = jiffies + msecs_to_jiffies(w->backoff_ms);
	mod_delayed_work(system_percpu_wq, &w->work, 0);
}

void mcp2510_watch_init(struct mcp2510_priv *priv)
{
	atomic_set(&priv->watch.irqs_fired, 0);
	INIT_DELAYED_WORK(&priv->watch.work, mcp2510_watch_work);
}

void mcp2510_watch_start(struct mcp2510_priv *priv)
{
	struct mcp2510_watch *w = &priv->watch;

	mcp2510_lock(priv);
	w->state = MCP2510_WATCH_IRQ;
	w->recovering = false;
	w->irqs_seen = atomic_read(&w->irqs_fired);
	mcp2510_unlock(priv);
	queue_delayed_work(system_percpu_wq, &w->work,
			   mcp2510_watch_delay(priv));
}

/* Before free_irq(): leaves the line enabled, as request_irq() found it. */
void mcp2510_watch_stop(struct mcp2510_priv *priv)
{
	struct mcp2510_watch *w = &priv->watch;
	bool polling;

	mcp2510_lock(priv);
	polling = w->state == MCP2510_WATCH_POLLING;
	w->state = MCP2510_WATCH_STOPPED;
	mcp2510_unlock(priv);

	cancel_delayed_work_sync(&w->work);
	if (polling)
		enable_irq(priv->spi->irq);
}
