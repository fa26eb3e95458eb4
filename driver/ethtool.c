// SPDX-License-Identifier: GPL-2.0
/*
 * ethtool: driver identity and the register dump laid out in the uapi
 * header.  Timestamps are software ones, from the host's clock: the
 * chip has none.  Received frames carry the time INT fired where that is
 * known to be after their end of frame (rx.c), sent frames what can-dev
 * stamps at transmit; so software stamping is what is offered, hardware
 * stamping is not.
 */
#include <linux/ethtool.h>
#include <linux/netdevice.h>
#include <linux/spi/spi.h>
#include <linux/string.h>

#include "mcp2510_priv.h"

static void mcp2510_get_drvinfo(struct net_device *ndev,
				struct ethtool_drvinfo *info)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);

	strscpy(info->driver, MCP2510_DRV_NAME, sizeof(info->driver));
	strscpy(info->bus_info, dev_name(&priv->spi->dev),
		sizeof(info->bus_info));
}

static int mcp2510_get_regs_len(struct net_device *ndev)
{
	return MCP2510_REGDUMP_LEN;
}

static void mcp2510_get_regs(struct net_device *ndev,
			     struct ethtool_regs *regs, void *buf)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);
	int ret;

	regs->version = MCP2510_REGDUMP_VERSION;
	mcp2510_lock(priv);
	ret = mcp2510_regs_dump(&priv->chip, buf);
	mcp2510_unlock(priv);
	/* ethtool cannot be told of a failure here: never hand out junk. */
	if (ret)
		memset(buf, 0, MCP2510_REGDUMP_LEN);
}

const struct ethtool_ops mcp2510_ethtool_ops = {
	.get_drvinfo = mcp2510_get_drvinfo,
	.get_regs_len = mcp2510_get_regs_len,
	.get_regs = mcp2510_get_regs,
	.get_ts_info = ethtool_op_get_ts_info,
	.get_sset_count = mcp2510_get_sset_count,
	.get_strings = mcp2510_get_strings,
	.get_ethtool_stats = mcp2510_get_ethtool_stats,
};
