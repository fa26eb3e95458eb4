// SPDX-License-Identifier: GPL-2.0
/*
 * The core's transport: one chip-select-low period per call on the SPI
 * device, through bounce buffers because the core hands us its stack.
 */
#include <linux/delay.h>
#include <linux/spi/spi.h>
#include <linux/string.h>

#include "mcp2510_priv.h"

void mcp2510_lock(struct mcp2510_priv *priv)
{
	mutex_lock(&priv->lock);
}

/*
 * What was queued for the stack under the lock goes to NAPI before the
 * next holder can queue more: the stack sees the chip's order.
 */
void mcp2510_unlock(struct mcp2510_priv *priv)
{
	mcp2510_rx_flush(priv);
	mutex_unlock(&priv->lock);
}

static int mcp2510_spi_xfer(void *ctx, const u8 *tx, u8 *rx, unsigned int len)
{
	struct mcp2510_priv *priv = ctx;
	struct spi_transfer xfer = {
		.tx_buf = priv->spi_tx,
		.rx_buf = priv->spi_rx,
		.len = len,
	};
	int ret;

	lockdep_assert_held(&priv->lock);
	if (len > MCP2510_SPI_BUF_LEN)
		return -EMSGSIZE;

	memcpy(priv->spi_tx, tx, len);
	ret = spi_sync_transfer(priv->spi, &xfer, 1);
	if (ret)
		return ret;
	if (rx)
		memcpy(rx, priv->spi_rx, len);
	return 0;
}

static void mcp2510_spi_delay_us(void *ctx, unsigned int us)
{
	fsleep(us);
}

const struct mcp2510_ops mcp2510_spi_ops = {
	.xfer = mcp2510_spi_xfer,
	.delay_us = mcp2510_spi_delay_us,
};
