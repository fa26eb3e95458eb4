// SPDX-License-Identifier: GPL-2.0
/*
 * Power: the chip's supply and oscillator, and system sleep.  Across a
 * suspend the chip may lose power, so resume re-initialises it from
 * scratch instead of trusting any register to have survived.
 */
#include <linux/clk.h>
#include <linux/netdevice.h>
#include <linux/pm.h>
#include <linux/regulator/consumer.h>
#include <linux/spi/spi.h>

#include "mcp2510_priv.h"

/* Idempotent: remove powers off whatever state a failed resume left. */
int mcp2510_power_on(struct mcp2510_priv *priv)
{
	int ret;

	if (priv->powered)
		return 0;
	if (priv->vdd) {
		ret = regulator_enable(priv->vdd);
		if (ret)
			return ret;
	}
	ret = clk_prepare_enable(priv->clk);
	if (ret)
		goto out_vdd_off;
	priv->powered = true;
	return 0;

out_vdd_off:
	if (priv->vdd)
		regulator_disable(priv->vdd);
	return ret;
}

void mcp2510_power_off(struct mcp2510_priv *priv)
{
	if (!priv->powered)
		return;
	clk_disable_unprepare(priv->clk);
	if (priv->vdd)
		regulator_disable(priv->vdd);
	priv->powered = false;
}

static int mcp2510_suspend(struct device *dev)
{
	struct mcp2510_priv *priv = dev_get_drvdata(dev);

	priv->suspended_running = netif_running(priv->ndev);
	if (priv->suspended_running) {
		/*
		 * Detached, the queue stays stopped until resume attaches it
		 * (mcp2510_tx_wake() checks); netif_tx_disable() waits for a
		 * start_xmit running on another CPU, and no bus-off restart
		 * may wake the queue or start the chip meanwhile.
		 */
		netif_device_detach(priv->ndev);
		netif_tx_disable(priv->ndev);
		cancel_delayed_work_sync(&priv->can.restart_work);
		mcp2510_hw_down(priv);
	}
	mcp2510_power_off(priv);
	return 0;
}

static int mcp2510_resume(struct device *dev)
{
	struct mcp2510_priv *priv = dev_get_drvdata(dev);
	int ret;

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
