// SPDX-License-Identifier: GPL-2.0
/*
 * SocketCAN driver for the Microchip MCP2510, MCP2515 and MCP25625 SPI CAN
 * controllers: device matching, firmware properties, probe and remove.
 */
#include <linux/clk.h>
#include <linux/module.h>
#include <linux/mod_devicetable.h>
#include <linux/netdevice.h>
#include <linux/property.h>
#include <linux/regulator/consumer.h>
#include <linux/slab.h>
#include <linux/spi/spi.h>

#include "mcp2510_priv.h"

static const enum mcp2510_model mcp2510_model_mcp2510 = MCP2510_MODEL_MCP2510;
static const enum mcp2510_model mcp2510_model_mcp2515 = MCP2510_MODEL_MCP2515;
static const enum mcp2510_model mcp2510_model_mcp25625 = MCP2510_MODEL_MCP25625;

static const struct of_device_id mcp2510_of_match[] = {
	{ .compatible = "microchip,mcp2510", .data = &mcp2510_model_mcp2510 },
	{ .compatible = "microchip,mcp2515", .data = &mcp2510_model_mcp2515 },
	{ .compatible = "microchip,mcp25625", .data = &mcp2510_model_mcp25625 },
	{ }
};
MODULE_DEVICE_TABLE(of, mcp2510_of_match);

static const struct spi_device_id mcp2510_spi_id[] = {
	{ "mcp2510", (kernel_ulong_t)&mcp2510_model_mcp2510 },
	{ "mcp2515", (kernel_ulong_t)&mcp2510_model_mcp2515 },
	{ "mcp25625", (kernel_ulong_t)&mcp2510_model_mcp25625 },
	{ }
};
MODULE_DEVICE_TABLE(spi, mcp2510_spi_id);

/*
 * Firmware match data first, then the SPI id table for board-info devices
 * (spi_get_device_match_data() does the same but is missing from older
 * 6.1 stable kernels).
 */
static const struct mcp2510_variant *mcp2510_match_variant(struct spi_device *spi)
{
	const enum mcp2510_model *model = device_get_match_data(&spi->dev);
	const struct spi_device_id *id;

	if (!model) {
		id = spi_get_device_id(spi);
		if (!id)
			return NULL;
		model = (const enum mcp2510_model *)id->driver_data;
	}
	return mcp2510_variant_get(*model);
}

/* The oscillator on OSC1, from a clock or a clock-frequency property. */
static int mcp2510_get_osc(struct mcp2510_priv *priv, u32 *osc_hz)
{
	struct device *dev = &priv->spi->dev;

	priv->clk = devm_clk_get_optional(dev, NULL);
	if (IS_ERR(priv->clk))
		return dev_err_probe(dev, PTR_ERR(priv->clk),
				     "cannot get the oscillator clock\n");

	if (priv->clk) {
		*osc_hz = clk_get_rate(priv->clk);
	} else if (device_property_read_u32(dev, "clock-frequency", osc_hz)) {
		dev_err(dev, "no oscillator: give clocks or clock-frequency\n");
		return -EINVAL;
	}

	if (*osc_hz < MCP2510_OSC_MIN_HZ || *osc_hz > MCP2510_OSC_MAX_HZ) {
		dev_err(dev, "oscillator at %u Hz is outside 1-25 MHz\n",
			*osc_hz);
		return -ERANGE;
	}
	return 0;
}

static struct regulator *mcp2510_get_supply(struct device *dev,
					    const char *name)
{
	struct regulator *reg = devm_regulator_get_optional(dev, name);

	/* Boards without a switchable supply have none: not an error. */
	if (PTR_ERR(reg) == -ENODEV)
		return NULL;
	if (IS_ERR(reg))
		dev_err_probe(dev, PTR_ERR(reg), "cannot get %s-supply\n",
			      name);
	return reg;
}

/*
 * spi-max-frequency is clamped to what the variant supports (5 MHz on the
 * MCP2510, 10 MHz on the MCP2515/MCP25625), which is also the default.
 */
static int mcp2510_setup_spi(struct spi_device *spi,
			     const struct mcp2510_variant *variant)
{
	if (!spi->max_speed_hz || spi->max_speed_hz > variant->spi_default_hz)
		spi->max_speed_hz = variant->spi_default_hz;
	spi->bits_per_word = 8;
	return spi_setup(spi);
}

static int mcp2510_get_resources(struct mcp2510_priv *priv,
				 const struct mcp2510_variant *variant,
				 u32 *osc_hz)
{
	struct device *dev = &priv->spi->dev;
	int ret;

	ret = mcp2510_get_osc(priv, osc_hz);
	if (ret)
		return ret;

	priv->vdd = mcp2510_get_supply(dev, "vdd");
	if (IS_ERR(priv->vdd))
		return PTR_ERR(priv->vdd);
	priv->xceiver = mcp2510_get_supply(dev, "xceiver");
	if (IS_ERR(priv->xceiver))
		return PTR_ERR(priv->xceiver);

	/* kmalloc memory, unlike the netdev's private area, is DMA-safe. */
	priv->spi_tx = devm_kzalloc(dev, MCP2510_SPI_BUF_LEN, GFP_KERNEL);
	priv->spi_rx = devm_kzalloc(dev, MCP2510_SPI_BUF_LEN, GFP_KERNEL);
	if (!priv->spi_tx || !priv->spi_rx)
		return -ENOMEM;

	ret = mcp2510_setup_spi(priv->spi, variant);
	if (ret)
		dev_err(dev, "SPI setup failed: %pe\n", ERR_PTR(ret));
	return ret;
}

static u32 mcp2510_ctrlmodes(const struct mcp2510_variant *variant)
{
	u32 modes = CAN_CTRLMODE_LOOPBACK | CAN_CTRLMODE_LISTENONLY |
		    CAN_CTRLMODE_3_SAMPLES | CAN_CTRLMODE_BERR_REPORTING |
		    CAN_CTRLMODE_CC_LEN8_DLC;

	if (variant->has_one_shot)
		modes |= CAN_CTRLMODE_ONE_SHOT;
	return modes;
}

static int mcp2510_setup_netdev(struct mcp2510_priv *priv,
				const struct mcp2510_variant *variant,
				u32 osc_hz)
{
	struct net_device *ndev = priv->ndev;
	int ret;

	ret = mcp2510_init(&priv->chip, variant, osc_hz, &mcp2510_spi_ops,
			   &mcp2510_netdev_events, priv);
	if (ret)
		return ret;
	priv->irq_flags = mcp2510_irq_trigger(priv);
	mcp2510_filters_default(&priv->filters);

	mutex_init(&priv->lock);
	spin_lock_init(&priv->tx_lock);
	INIT_WORK(&priv->tx_work, mcp2510_tx_work);
	mcp2510_restart_init(priv);
	mcp2510_watch_init(priv);

	priv->can.clock.freq = osc_hz / 2;
	priv->can.bittiming_const = &mcp2510_bittiming_const;
	priv->can.do_set_mode = mcp2510_do_set_mode;
	priv->can.do_get_berr_counter = mcp2510_do_get_berr_counter;
	priv->can.ctrlmode_supported = mcp2510_ctrlmodes(variant);
	priv->can.state = CAN_STATE_STOPPED;

	ndev->netdev_ops = &mcp2510_netdev_ops;
	ndev->ethtool_ops = &mcp2510_ethtool_ops;
	ndev->sysfs_groups[0] = &mcp2510_filter_group;
	/* Echo sent frames on TX completion, not when queued. */
	ndev->flags |= IFF_ECHO;
	return 0;
}

/*
 * Wake-on-CAN: wakeup-source makes INT a wakeup interrupt (enabled by
 * default, power/wakeup in sysfs turns it off); microchip,wakeup-filter
 * sets CNF3.WAKFIL, which keeps short glitches on RXCAN (below about
 * 50 ns, AN739) from waking the sleeping chip.
 */
static void mcp2510_setup_wakeup(struct mcp2510_priv *priv)
{
	struct device *dev = &priv->spi->dev;

	mcp2510_wake_filter_set(&priv->chip,
				device_property_read_bool(dev,
							  "microchip,wakeup-filter"));
	if (device_property_read_bool(dev, "wakeup-source"))
		device_init_wakeup(dev, true);
}

static int mcp2510_probe(struct spi_device *spi)
{
	struct device *dev = &spi->dev;
	const struct mcp2510_variant *variant;
	struct mcp2510_priv *priv;
	struct net_device *ndev;
	u32 osc_hz;
	int ret;

	variant = mcp2510_match_variant(spi);
	if (!variant)
		return dev_err_probe(dev, -ENODEV, "unknown chip variant\n");
	if (spi->irq <= 0)
		return dev_err_probe(dev, -EINVAL, "no interrupt for INT\n");

	ndev = alloc_candev(sizeof(*priv), MCP2510_TXB_COUNT);
	if (!ndev)
		return -ENOMEM;
	SET_NETDEV_DEV(ndev, dev);
	priv = netdev_priv(ndev);
	priv->ndev = ndev;
	priv->spi = spi;
	spi_set_drvdata(spi, priv);

	ret = mcp2510_get_resources(priv, variant, &osc_hz);
	if (ret)
		goto out_free_candev;
	ret = mcp2510_setup_netdev(priv, variant, osc_hz);
	if (ret)
		goto out_free_candev;

	ret = mcp2510_rx_init(priv);
	if (ret)
		goto out_free_candev;
	ret = mcp2510_power_on(priv);
	if (ret) {
		dev_err(dev, "cannot power the chip: %pe\n", ERR_PTR(ret));
		goto out_del_rx;
	}
	ret = mcp2510_chip_reset_sleep(priv);
	if (ret) {
		dev_err(dev, "no %s answers on SPI: %pe\n", variant->name,
			ERR_PTR(ret));
		goto out_power_off;
	}

	ret = mcp2510_gpio_register(priv);
	if (ret) {
		dev_err(dev, "cannot add the gpiochip: %pe\n", ERR_PTR(ret));
		goto out_power_off;
	}
	mcp2510_setup_wakeup(priv);
	ret = register_candev(ndev);
	if (ret) {
		dev_err(dev, "cannot register the netdev: %pe\n", ERR_PTR(ret));
		goto out_no_wakeup;
	}

	netdev_info(ndev, "%s, oscillator %u Hz, SPI %u Hz, irq %d\n",
		    variant->name, osc_hz, spi->max_speed_hz, spi->irq);
	return 0;

out_no_wakeup:
	device_init_wakeup(dev, false);
	mcp2510_gpio_unregister(priv);
out_power_off:
	mcp2510_power_off(priv);
out_del_rx:
	mcp2510_rx_del(priv);
out_free_candev:
	mutex_destroy(&priv->lock);
	free_candev(ndev);
	return ret;
}

static void mcp2510_remove(struct spi_device *spi)
{
	struct mcp2510_priv *priv = spi_get_drvdata(spi);
	struct net_device *ndev = priv->ndev;

	unregister_candev(ndev);
	mcp2510_restart_cancel(priv);
	device_init_wakeup(&spi->dev, false);
	mcp2510_gpio_unregister(priv);
	mcp2510_power_off(priv);
	mcp2510_rx_del(priv);
	mutex_destroy(&priv->lock);
	free_candev(ndev);
}

static struct spi_driver mcp2510_driver = {
	.driver = {
		.name = MCP2510_DRV_NAME,
		.of_match_table = mcp2510_of_match,
		.pm = pm_sleep_ptr(&mcp2510_pm_ops),
	},
	.id_table = mcp2510_spi_id,
	.probe = mcp2510_probe,
	.remove = mcp2510_remove,
};
module_spi_driver(mcp2510_driver);

MODULE_DESCRIPTION("Microchip MCP2510/MCP2515/MCP25625 SPI CAN controller driver");
MODULE_LICENSE("GPL");
