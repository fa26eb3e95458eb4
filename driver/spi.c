// SPDX-License-Identifier: GPL-2.0
/*
 * The core's transport: one chip-select-low period per call on the SPI
 * device, or a few in one message, through bounce buffers because the
 * core hands us its stack.
 */
#include <linux/bug.h>
#include <linux/delay.h>
#include <linux/spi/spi.h>
#include <linux/string.h>

#include "mcp2510_priv.h"

void mcp2510_lock(struct mcp2510_priv *priv)
{
	mutex_lock(&priv->lock);
}

/*
 * The frames sent in this hold are reported to BQL as one completion.
 * Whoever ran the core in a way that queues frames for the stack has
 * handed them on (mcp2510_rx_deliver()); frames left here would wait
 * for the next holder.
 */
void mcp2510_unlock(struct mcp2510_priv *priv)
{
	mcp2510_tx_report_done(priv);
	WARN_ON_ONCE(!skb_queue_empty_lockless(&priv->offload.skb_irq_queue));
	mutex_unlock(&priv->lock);
}

/*
 * Chip select high between two periods of one message: the data sheets
 * ask for 50 ns (MCP2515) and 100 ns (MCP2510) at least.  Without an
 * explicit delay the SPI core would wait 10 us, widening the gap the
 * receive-order check relies on being short.
 */
#define MCP2510_CS_HIGH_NS	100

/*
 * The transfers of one period at @off in the bounce buffers: 1, or 2
 * with chip select held low between them (mcp2510_xfer_first_len()).
 */
static unsigned int mcp2510_spi_period(struct mcp2510_priv *priv,
				       struct spi_transfer *t,
				       unsigned int off, unsigned int len)
{
	unsigned int first = mcp2510_xfer_first_len(len,
						    priv->spi->max_speed_hz);

	t[0].tx_buf = priv->spi_tx + off;
	t[0].rx_buf = priv->spi_rx + off;
	t[0].len = first;
	if (first == len)
		return 1;
	t[1].tx_buf = priv->spi_tx + off + first;
	t[1].rx_buf = priv->spi_rx + off + first;
	t[1].len = len - first;
	return 2;
}

/*
 * Several CS-low periods in one spi_message: the controller raises chip
 * select between them (cs_change) and runs them back to back, with no
 * scheduling point in between.  The periods share the bounce buffers.
 */
static int mcp2510_spi_xfer_msg(void *ctx, const struct mcp2510_xfer *x,
				unsigned int n)
{
	struct mcp2510_priv *priv = ctx;
	struct spi_transfer *t = priv->spi_xfers;
	unsigned int i, nt = 0, off = 0;
	int ret;

	lockdep_assert_held(&priv->lock);
	if (!n || n > MCP2510_XFER_MSG_MAX)
		return -EINVAL;
	memset(priv->spi_xfers, 0, sizeof(priv->spi_xfers));
	for (i = 0; i < n; i++) {
		if (x[i].len > MCP2510_SPI_BUF_LEN - off)
			return -EMSGSIZE;
		memcpy(priv->spi_tx + off, x[i].tx, x[i].len);
		nt += mcp2510_spi_period(priv, t + nt, off, x[i].len);
		if (i + 1 < n) {
			t[nt - 1].cs_change = 1;
			t[nt - 1].cs_change_delay.value = MCP2510_CS_HIGH_NS;
			t[nt - 1].cs_change_delay.unit = SPI_DELAY_UNIT_NSECS;
		}
		off += x[i].len;
	}
	ret = spi_sync_transfer(priv->spi, t, nt);
	if (ret)
		return ret;
	for (i = 0, off = 0; i < n; off += x[i].len, i++)
		if (x[i].rx)
			memcpy(x[i].rx, priv->spi_rx + off, x[i].len);
	return 0;
}

static int mcp2510_spi_xfer(void *ctx, const u8 *tx, u8 *rx, unsigned int len)
{
	const struct mcp2510_xfer x = { .tx = tx, .rx = rx, .len = len };

	return mcp2510_spi_xfer_msg(ctx, &x, 1);
}

static void mcp2510_spi_delay_us(void *ctx, unsigned int us)
{
	fsleep(us);
}

const struct mcp2510_ops mcp2510_spi_ops = {
	.xfer = mcp2510_spi_xfer,
	.xfer_msg = mcp2510_spi_xfer_msg,
	.delay_us = mcp2510_spi_delay_us,
};
