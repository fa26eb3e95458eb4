// SPDX-License-Identifier: GPL-2.0
/*
 * ethtool -S: what the driver did about a chip or an INT line that
 * misbehaved, which no netdev or CAN statistic has a place for.
 */
#include <linux/ethtool.h>
#include <linux/netdevice.h>
#include <linux/string.h>

#include "mcp2510_priv.h"

enum mcp2510_stat {
	MCP2510_STAT_IRQ_STORMS,
	MCP2510_STAT_IRQ_LOOP_BOUND,
	MCP2510_STAT_MISSED_IRQS,
	MCP2510_STAT_RECOVERIES,
	MCP2510_STAT_COUNT
};

static const char mcp2510_stat_names[MCP2510_STAT_COUNT][ETH_GSTRING_LEN] = {
	/* INT disabled and the chip polled for a while */
	[MCP2510_STAT_IRQ_STORMS] = "irq_storms",
	/* edge-triggered loops stopped by MCP2510_IRQ_MAX_PASSES */
	[MCP2510_STAT_IRQ_LOOP_BOUND] = "irq_loop_bound",
	/* chip events found by polling an edge line whose edge was lost */
	[MCP2510_STAT_MISSED_IRQS] = "missed_interrupts",
	/* re-initialised after a reset or garbage on SPI */
	[MCP2510_STAT_RECOVERIES] = "chip_recoveries",
};

int mcp2510_get_sset_count(struct net_device *ndev, int sset)
{
	return sset == ETH_SS_STATS ? MCP2510_STAT_COUNT : -EOPNOTSUPP;
}

void mcp2510_get_strings(struct net_device *ndev, u32 sset, u8 *data)
{
	if (sset == ETH_SS_STATS)
		memcpy(data, mcp2510_stat_names, sizeof(mcp2510_stat_names));
}

void mcp2510_get_ethtool_stats(struct net_device *ndev,
			       struct ethtool_stats *stats, u64 *data)
{
	struct mcp2510_priv *priv = netdev_priv(ndev);

	mcp2510_lock(priv);
	data[MCP2510_STAT_IRQ_STORMS] = priv->watch.irq_storms;
	data[MCP2510_STAT_IRQ_LOOP_BOUND] = priv->chip.counters.irq_loop_bound;
	data[MCP2510_STAT_MISSED_IRQS] = priv->watch.missed_interrupts;
	data[MCP2510_STAT_RECOVERIES] = priv->chip.counters.recoveries;
	mcp2510_unlock(priv);
}
