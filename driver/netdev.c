// SPDX-License-Identifier: GPL-2.0
/*
 * Network interface: bringing the chip up and down with the interface,
 * restarts after bus-off, and the error counters.  The chip sleeps while
 * the interface is down.
 */
#include <linux/interrupt.h>
#include <linux/minmax.h>
#include <linux/netdevice.h>
#include <linux/regulator/consumer.h>
#include <linux/rtnetlink.h>
#include <linux/spi/spi.h>

#include "mcp2510_priv.h"

/* The shortest wait before an automatic restart that failed is tried again. */
#define MCP2510_RESTART_RETRY_MS	1000

/* Reset the chip, check that it answers, and leave it asleep until open. */
int mcp2510_chip_reset_sleep(struct mcp2510_priv *priv)
{
	int ret;

	mcp2510_lock(priv);
	ret = mcp2510_hw_reset(&priv->chip);
	if (!ret) {
		mcp2510_gpio_restore(priv);
		ret = mcp2510_sleep(&priv->chip);
	}
	mcp2510_unlock(priv);
	return ret;
}

/* Program everything the user configured and enter the operating mode. */
static int mcp2510_chip_start_locked(struct mcp2510_priv *priv)
{
	int ret;

	lockdep_assert_held(&priv->lock);
	ret = mcp2510_filters_apply(&priv->chip, &priv->filters);
	if (ret)
		return ret;

	/*
	 * The state changes only once the chip runs: a restart that failed
	 * leaves the interface bus-off, where a later restart is allowed.
	 * Start reports no state, so nothing is lost by setting it after.
	 */
	ret = mcp2510_start(&priv->chip, &priv->can.bittiming,
			    priv->can.ctrlmode);
	if (ret)
		return ret;

	priv->can.state = CAN_STATE_ERROR_ACTIVE;
	mcp2510_dev_enter(priv, MCP2510_DEV_RUNNING);
	/* The reset inside start returned the RXnBF pins to their defaults. */
	mcp2510_gpio_restore(priv);
	return 0;
}

static int mcp2510_xceiver_enable(struct mcp2510_priv *priv)
{
	return priv->xceiver ? regulator_enable(priv->xceiver) : 0;
}

static void mcp2510_xceiver_disable(struct mcp2510_priv *priv)
{
	if (priv->xceiver)
		regulator_disable(priv->xceiver);
}

/*
 * A resume that could not power the chip left it off (with the interface
 * up but off the bus): bringing the interface up again powers it.  The
 * chip lost its registers, so it is reset as at probe.
 */
static int mcp2510_power_again(struct mcp2510_priv *priv)
{
	int ret;

	if (mcp2510_dev_state(priv) != MCP2510_DEV_OFF)
		return 0;
	ret = mcp2510_power_on(priv);
	if (ret) {
		netdev_err(priv->ndev, "cannot power the chip: %pe\n",
			   ERR_PTR(ret));
		return ret;
	}
	return mcp2510_chip_reset_sleep(priv);
}

int mcp2510_hw_up(struct mcp2510_priv *priv)
{
	int ret;

	ret = mcp2510_power_again(priv);
	if (ret)
		return ret;
	ret = mcp2510_xceiver_enable(priv);
	if (ret)
		return ret;

	can_rx_offload_enable(&priv->offload);
	/*
	 * The handler is in place before the chip starts: on an edge
	 * triggered line an INT asserted during start would otherwise never
	 * be seen again.  It waits for the chip lock until start is done.
	 */
	ret = request_threaded_irq(priv->spi->irq, mcp2510_irq_hard,
				   mcp2510_irq_thread,
				   priv->irq_flags | IRQF_ONESHOT,
				   dev_name(&priv->spi->dev), priv);
	if (ret)
		goto out_disable_rx;

	mcp2510_lock(priv);
	ret = mcp2510_chip_start_locked(priv);
	if (ret)
		mcp2510_stop(&priv->chip);
	mcp2510_rx_deliver(priv);
	mcp2510_unlock(priv);
	if (ret)
		goto out_free_irq;
	mcp2510_watch_start(priv);
	return 0;

out_free_irq:
	free_irq(priv->spi->irq, priv);
out_disable_rx:
	mcp2510_rx_disable(priv);
	mcp2510_xceiver_disable(priv);
	priv->can.state = CAN_STATE_STOPPED;
	return ret;
}

/*
 * Also after a failed hw_up (on resume: the interface stays up), when
 * only the TX work may still hold frames start_xmit queued meanwhile.
 */
void mcp2510_hw_down(struct mcp2510_priv *priv)
{
	bool running = mcp2510_dev_running(priv);

	/* No more interrupts or loads: the chip is ours alone from here. */
	if (running) {
		mcp2510_watch_stop(priv);
		free_irq(priv->spi->irq, priv);
	}
	cancel_work_sync(&priv->tx_work);
	mcp2510_tx_flush(priv);
	if (!running)
		return;

	mcp2510_lock(priv);
	if (mcp2510_dev_state(priv) != MCP2510_DEV_HALTED)
		mcp2510_stop(&priv->chip);
	mcp2510_dev_enter(priv, MCP2510_DEV_POWERED);
	mcp2510_rx_deliver(priv);
	mcp2510_unlock(priv);

	mcp2510_rx_disable(priv);
	mcp2510_xceiver_disable(priv);
	priv->can.state = CAN_STATE_STOPPED;
}

/*
 * Bus-off: keep the chip off the bus until can-dev restarts it, by hand or
 * after restart-ms.  The interface becomes bus-off only once the chip is
 * stopped and its frames aborted: a restart must find a quiet device.  A
 * halt the SPI did not let through stays requested, and the next pass of
 * the IRQ thread or of the watch tries again; meanwhile the frames stay
 * in flight, as the chip may still send them.
 */
void mcp2510_halt_locked(struct mcp2510_priv *priv)
{
	int ret;

	lockdep_assert_held(&priv->lock);
	ret = mcp2510_halt(&priv->chip);
	if (ret) {
		netdev_warn_once(priv->ndev, "cannot halt the chip at bus-off: %pe\n",
				 ERR_PTR(ret));
		return;
	}
	mcp2510_dev_enter(priv, MCP2510_DEV_HALTED);
	/* Bus-off is the controller's as a whole: no direction to blame. */
	can_change_state(priv->ndev, NULL, CAN_STATE_BUS_OFF, CAN_STATE_BUS_OFF);
	can_bus_off(priv->ndev);
}

/*
 * An automatic restart that failed: can-dev schedules nothing more, and a
 * manual restart is refused while restart-ms is set.  Try again later, at
 * most once a second, so that a chip without power does not flood the log.
 */
static void mcp2510_restart_retry(struct mcp2510_priv *priv)
{
	int ms = max(priv->can.restart_ms, MCP2510_RESTART_RETRY_MS);

	if (priv->can.restart_ms)
		schedule_delayed_work(&priv->can.restart_work,
				      msecs_to_jiffies(ms));
}

/*
 * A restart failed: the interface stays bus-off with its carrier off.
 * can-dev before the end of 2023 (6.1.21, say) turns the carrier on after
 * do_set_mode() whatever it returned, and its next restart then hits
 * BUG_ON(netif_carrier_ok()); so this runs once can_restart() has
 * returned: the automatic one as can.restart_work, the manual one under
 * RTNL.  Not cancelled by ndo_stop, which holds RTNL: it checks that the
 * interface is still up and the chip still halted.
 */
static void mcp2510_restart_failed_work(struct work_struct *work)
{
	struct mcp2510_priv *priv = container_of(work, struct mcp2510_priv,
						 restart_failed_work);

	cancel_delayed_work_sync(&priv->can.restart_work);
	rtnl_lock();
	mcp2510_lock(priv);
	if (netif_running(priv->ndev) &&
	    mcp2510_dev_state(priv) == MCP2510_DEV_HALTED) {
		netif_carrier_off(priv->ndev);
		mcp2510_restart_retry(priv);
	}
	mcp2510_unlock(priv);
	rtnl_unlock();
}

void mcp2510_restart_init(struct mcp2510_priv *priv)
{
	INIT_WORK(&priv->restart_failed_work, mcp2510_restart_failed_work);
}

/* At remove, without RTNL: the interface is gone, nothing queues it again. */
void mcp2510_restart_cancel(struct mcp2510_priv *priv)
{
	cancel_work_sync(&priv->restart_failed_work);
}

/* Restart a chip stopped at bus-off; on failure it stays stopped. */
static int mcp2510_restart_halted_locked(struct mcp2510_priv *priv)
{
	int ret;

	ret = mcp2510_chip_start_locked(priv);
	if (ret)
		mcp2510_stop(&priv->chip);
	return ret;
}

int mcp2510_do_set_mode(struct net_device *ndev, enum can_mode mode)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);
	int ret;

	if (mode != CAN_MODE_START)
		return -EOPNOTSUPP;

	/*
	 * can-dev restarts only a bus-off interface, and the interface is
	 * bus-off only once the chip is halted: a chip that sleeps and needs
	 * everything programmed again.
	 */
	mcp2510_lock(priv);
	if (mcp2510_dev_state(priv) == MCP2510_DEV_HALTED)
		ret = mcp2510_restart_halted_locked(priv);
	else
		ret = -ENETDOWN;
	mcp2510_rx_deliver(priv);
	mcp2510_unlock(priv);
	if (ret) {
		schedule_work(&priv->restart_failed_work);
		return ret;
	}

	mcp2510_tx_wake_queue(priv);
	return 0;
}

int mcp2510_do_get_berr_counter(const struct net_device *ndev,
				struct can_berr_counter *bec)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);
	int ret;

	mcp2510_lock(priv);
	ret = mcp2510_berr_counter(&priv->chip, bec);
	mcp2510_unlock(priv);
	return ret;
}

static int mcp2510_open(struct net_device *ndev)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);
	int ret;

	ret = open_candev(ndev);
	if (ret)
		return ret;

	ret = mcp2510_hw_up(priv);
	if (ret) {
		netdev_err(ndev, "cannot start the chip: %pe\n", ERR_PTR(ret));
		close_candev(ndev);
		return ret;
	}

	/* Every frame of the last time up was completed; start afresh. */
	netdev_reset_queue(ndev);
	netif_start_queue(ndev);
	return 0;
}

static int mcp2510_stop_netdev(struct net_device *ndev)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);

	netif_stop_queue(ndev);
	mcp2510_hw_down(priv);
	close_candev(ndev);
	return 0;
}

const struct net_device_ops mcp2510_netdev_ops = {
	.ndo_open = mcp2510_open,
	.ndo_stop = mcp2510_stop_netdev,
	.ndo_start_xmit = mcp2510_start_xmit,
	.ndo_change_mtu = mcp2510_change_mtu,
	.ndo_get_stats64 = mcp2510_get_stats64,
};
