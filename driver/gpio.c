// SPDX-License-Identifier: GPL-2.0
/*
 * The chip's spare pins as a gpiochip, when the firmware marks the device
 * as a gpio-controller: lines 0-1 are the RX0BF/RX1BF outputs, lines 2-4
 * the TX0RTS..TX2RTS inputs.  Their directions are fixed by the silicon.
 */
#include <linux/property.h>
#include <linux/spi/spi.h>

#include "mcp2510_priv.h"

static const char * const mcp2510_gpio_names[MCP2510_GPIO_COUNT] = {
	"RX0BF", "RX1BF", "TX0RTS", "TX1RTS", "TX2RTS",
};

static bool mcp2510_gpio_is_output(unsigned int offset)
{
	return offset < MCP2510_GPIO_BF_COUNT;
}

static int mcp2510_gpio_get_direction(struct gpio_chip *gc,
				      unsigned int offset)
{
	return mcp2510_gpio_is_output(offset) ? GPIO_LINE_DIRECTION_OUT :
						GPIO_LINE_DIRECTION_IN;
}

static int mcp2510_gpio_write(struct mcp2510_priv *priv, unsigned int n,
			      int value)
{
	int ret;

	mcp2510_lock(priv);
	ret = mcp2510_pin_bf_set(&priv->chip, n, value);
	if (!ret) {
		priv->bf_set |= BIT(n);
		if (value)
			priv->bf_level |= BIT(n);
		else
			priv->bf_level &= ~BIT(n);
	}
	mcp2510_unlock(priv);
	return ret;
}

static int mcp2510_gpio_direction_input(struct gpio_chip *gc,
					unsigned int offset)
{
	return mcp2510_gpio_is_output(offset) ? -EINVAL : 0;
}

static int mcp2510_gpio_direction_output(struct gpio_chip *gc,
					 unsigned int offset, int value)
{
	if (!mcp2510_gpio_is_output(offset))
		return -EINVAL;
	return mcp2510_gpio_write(gpiochip_get_data(gc), offset, value);
}

static int mcp2510_gpio_get(struct gpio_chip *gc, unsigned int offset)
{
	struct mcp2510_priv *priv = gpiochip_get_data(gc);
	int ret;

	/* The chip cannot read an RXnBF level back: report what was set. */
	if (mcp2510_gpio_is_output(offset))
		return !!(priv->bf_level & BIT(offset));

	mcp2510_lock(priv);
	ret = mcp2510_pin_rts_get(&priv->chip,
				  offset - MCP2510_GPIO_BF_COUNT);
	mcp2510_unlock(priv);
	return ret;
}

/* A failed SPI transfer is the caller's to know, not only the log's. */
static int mcp2510_gpio_set(struct gpio_chip *gc, unsigned int offset,
			    int value)
{
	if (!mcp2510_gpio_is_output(offset))
		return -EINVAL;
	return mcp2510_gpio_write(gpiochip_get_data(gc), offset, value);
}

#ifndef MCP2510_HAVE_GPIO_SET_INT
/*
 * Kernels from before the end of gpiolib's set_rv() transition (begun in
 * 6.15) take no error from .set: logging it is all that is left to do.
 * The name then stands for this function, the one gpiolib calls.
 */
static void mcp2510_gpio_set_void(struct gpio_chip *gc, unsigned int offset,
				  int value)
{
	int ret = mcp2510_gpio_set(gc, offset, value);

	if (ret)
		dev_err_ratelimited(gc->parent, "setting %s failed: %pe\n",
				    mcp2510_gpio_names[offset], ERR_PTR(ret));
}

#define mcp2510_gpio_set	mcp2510_gpio_set_void
#endif

/* After a chip reset, with the chip lock held. */
void mcp2510_gpio_restore(struct mcp2510_priv *priv)
{
	unsigned int n;

	lockdep_assert_held(&priv->lock);
	for (n = 0; n < MCP2510_GPIO_BF_COUNT; n++)
		if (priv->bf_set & BIT(n))
			mcp2510_pin_bf_set(&priv->chip, n,
					   priv->bf_level & BIT(n));
}

int mcp2510_gpio_register(struct mcp2510_priv *priv)
{
	struct device *dev = &priv->spi->dev;
	struct gpio_chip *gc = &priv->gpio;

	if (!device_property_read_bool(dev, "gpio-controller"))
		return 0;

	gc->label = dev_name(dev);
	gc->parent = dev;
	gc->owner = THIS_MODULE;
	gc->base = -1;
	gc->ngpio = MCP2510_GPIO_COUNT;
	gc->names = mcp2510_gpio_names;
	gc->can_sleep = true;	/* every access is an SPI transfer */
	gc->get_direction = mcp2510_gpio_get_direction;
	gc->direction_input = mcp2510_gpio_direction_input;
	gc->direction_output = mcp2510_gpio_direction_output;
	gc->get = mcp2510_gpio_get;
	gc->set = mcp2510_gpio_set;

	return gpiochip_add_data(gc, priv);
}

void mcp2510_gpio_unregister(struct mcp2510_priv *priv)
{
	/* ngpio is only set once the chip is registered. */
	if (priv->gpio.ngpio)
		gpiochip_remove(&priv->gpio);
}
