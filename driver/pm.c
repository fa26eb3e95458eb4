// SPDX-License-Identifier: GPL-2.0
/*
 * Power: the chip's supply and oscillator, and system sleep.  Across a
 * suspend the chip may lose power, so resume re-initialises it from
 * scratch instead of trusting any register to have survived.
 *
 * Wake-on-CAN: when the device may wake the system (firmware property
 * wakeup-source, power/wakeup enabled) and the interface is up, suspend
 * leaves the chip powered and asleep with only its wake-up interrupt
 * enabled, and INT becomes a wakeup interrupt.  The first frame on the
 * bus wakes the chip (into listen-only mode: that frame is lost) and INT
 * wakes the system; resume then starts the chip afresh as always.
 */
#include <linux/clk.h>
#include <linux/interrupt.h>
#include <linux/netdevice.h>
#include <linux/pm.h>
#include <linux/pm_wakeup.h>
#include <linux/regulator/consumer.h>
#include <linux/spi/spi.h>

#include "mcp2510_priv.h"

/* Idempotent: remove powers off whatever state a failed resume left. */
int mcp2510_power_on(struct mcp2510_priv *priv)
{
	int ret;

	if (mcp2510_dev_state(priv) != MCP2510_DEV_OFF)
		return 0;
	if (priv->vdd) {
		ret = regulator_enable(priv->vdd);
		if (ret)
			return ret;
	}
	ret = clk_prepare_enable(priv->clk);
	if (ret)
		goto out_vdd_off;
	mcp2510_dev_enter(priv, MCP2510_DEV_POWERED);
	return 0;

out_vdd_off:
	if (priv->vdd)
		regulator_disable(priv->vdd);
	return ret;
}

void mcp2510_power_off(struct mcp2510_priv *priv)
{
	if (mcp2510_dev_state(priv) == MCP2510_DEV_OFF)
		return;
	clk_disable_unprepare(priv->clk);
	if (priv->vdd)
		regulator_disable(priv->vdd);
	mcp2510_dev_enter(priv, MCP2510_DEV_OFF);
}

/*
 * INT while armed: the chip woke.  In the noirq phase genirq reports the
 * wakeup itself and runs this thread after resume; before it (the frame
 * came while other devices were still suspending) the event reported
 * here aborts the suspend, which would otherwise sleep with a chip that
 * no longer can wake it.  Either way the device's wakeup source counts it.
 * WAKIF is the only interrupt enabled, so a chip that cannot be read (its
 * SPI controller may be suspended already) woke all the same.
 */
static irqreturn_t mcp2510_wake_irq_thread(int irq, void *data)
{
	struct mcp2510_priv *priv = data;
	struct device *dev = &priv->spi->dev;
	int woke;

	mcp2510_lock(priv);
	woke = mcp2510_wake_ack(&priv->chip);
	mcp2510_unlock(priv);
	if (woke < 0) {
		/* Unacknowledged, a level-triggered INT would fire again and again. */
		dev_err_ratelimited(dev, "cannot read the wake-up: %pe\n",
				    ERR_PTR(woke));
		disable_irq_nosync(irq);
	} else if (!woke) {
		return IRQ_NONE;
	}
	pm_wakeup_dev_event(dev, 0, true);
	return IRQ_HANDLED;
}

/*
 * After mcp2510_hw_down(): the chip is stopped and asleep, and powered
 * unless the last resume could not power it (then there is nothing to arm).
 */
static int mcp2510_wake_enable(struct mcp2510_priv *priv)
{
	struct spi_device *spi = priv->spi;
	int ret;

	if (mcp2510_dev_state(priv) != MCP2510_DEV_POWERED)
		return -ENODEV;
	/* The transceiver must pass bus activity on to RXCAN. */
	if (priv->xceiver) {
		ret = regulator_enable(priv->xceiver);
		if (ret)
			return ret;
	}
	ret = request_threaded_irq(spi->irq, NULL, mcp2510_wake_irq_thread,
				   priv->irq_flags | IRQF_ONESHOT,
				   dev_name(&spi->dev), priv);
	if (ret)
		goto out_xceiver_off;

	mcp2510_lock(priv);
	ret = mcp2510_wake_arm(&priv->chip);
	mcp2510_unlock(priv);
	if (ret)
		goto out_free_irq;
	ret = enable_irq_wake(spi->irq);
	if (ret)
		goto out_free_irq;
	mcp2510_dev_enter(priv, MCP2510_DEV_WAKE_ARMED);
	return 0;

out_free_irq:
	free_irq(spi->irq, priv);
out_xceiver_off:
	if (priv->xceiver)
		regulator_disable(priv->xceiver);
	return ret;
}

static void mcp2510_wake_disable(struct mcp2510_priv *priv)
{
	if (mcp2510_dev_state(priv) != MCP2510_DEV_WAKE_ARMED)
		return;
	disable_irq_wake(priv->spi->irq);
	free_irq(priv->spi->irq, priv);
	if (priv->xceiver)
		regulator_disable(priv->xceiver);
	mcp2510_dev_enter(priv, MCP2510_DEV_POWERED);
}

static int mcp2510_suspend(struct device *dev)
{
	struct mcp2510_priv *priv = dev_get_drvdata(dev);
	int ret;

	priv->suspended_running = netif_running(priv->ndev);
	if (priv->suspended_running) {
		/*
		 * Detached, the queue stays stopped until resume attaches it
		 * (mcp2510_tx_wake() checks); netif_tx_disable() waits for a
		 * start_xmit running on another CPU, and no bus-off restart
		 * may wake the queue or start the chip meanwhile.  A bus-off
		 * the IRQ thread reports while hw_down waits for it schedules
		 * the restart again: it is cancelled once more after.
		 */
		netif_device_detach(priv->ndev);
		netif_tx_disable(priv->ndev);
		cancel_delayed_work_sync(&priv->can.restart_work);
		mcp2510_hw_down(priv);
		cancel_delayed_work_sync(&priv->can.restart_work);
		if (device_may_wakeup(dev)) {
			ret = mcp2510_wake_enable(priv);
			if (!ret)
				return 0;
			dev_warn(dev, "no wake-up from the bus: %pe\n",
				 ERR_PTR(ret));
		}
	}
	mcp2510_power_off(priv);
	return 0;
}

static int mcp2510_resume(struct device *dev)
{
	struct mcp2510_priv *priv = dev_get_drvdata(dev);
	int ret;

	mcp2510_wake_disable(priv);
	ret = mcp2510_power_on(priv);
	if (!ret)
		ret = mcp2510_chip_reset_sleep(priv);
	if (!ret && priv->suspended_running)
		ret = mcp2510_hw_up(priv);

	if (priv->suspended_running) {
		/*
		 * A fresh start is never bus-off.  After a failure the
		 * interface stays up but off the bus: down and up retries.
		 */
		if (ret)
			netif_carrier_off(priv->ndev);
		else
			netif_carrier_on(priv->ndev);
		netif_device_attach(priv->ndev);
	}
	if (ret)
		dev_err(dev, "cannot bring the chip back: %pe\n", ERR_PTR(ret));
	return ret;
}

const struct dev_pm_ops mcp2510_pm_ops = {
	SYSTEM_SLEEP_PM_OPS(mcp2510_suspend, mcp2510_resume)
};
