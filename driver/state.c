// SPDX-License-Identifier: GPL-2.0
/*
 * The device's state and the transitions between states, all of them:
 *
 *	OFF <-> POWERED <-> WAKE_ARMED		power, wake-on-CAN
 *	POWERED -> RUNNING			open, resume
 *	RUNNING -> BUS_OFF -> HALTED -> RUNNING	bus-off, halt, restart
 *	BUS_OFF -> RUNNING			the chip recovered by itself
 *	RUNNING, BUS_OFF, HALTED -> POWERED	close, suspend
 *
 * Power and wake-on-CAN change it with nothing else running (no INT
 * handler, no watch); everything else under the chip lock.  hw_down
 * reads it without the lock while the IRQ thread may still move it
 * among the three running states, hence the _ONCE accesses.
 */
#include <linux/bits.h>
#include <linux/bug.h>
#include <linux/compiler.h>

#include "mcp2510_priv.h"

#define RUNNING_STATES	(BIT(MCP2510_DEV_RUNNING) | BIT(MCP2510_DEV_BUS_OFF) | \
			 BIT(MCP2510_DEV_HALTED))

/* For each state, the states it may be entered from. */
static const u8 mcp2510_dev_from[] = {
	[MCP2510_DEV_OFF] = BIT(MCP2510_DEV_POWERED),
	[MCP2510_DEV_POWERED] = BIT(MCP2510_DEV_OFF) |
				BIT(MCP2510_DEV_WAKE_ARMED) | RUNNING_STATES,
	[MCP2510_DEV_WAKE_ARMED] = BIT(MCP2510_DEV_POWERED),
	[MCP2510_DEV_RUNNING] = BIT(MCP2510_DEV_POWERED) |
				BIT(MCP2510_DEV_BUS_OFF) |
				BIT(MCP2510_DEV_HALTED),
	[MCP2510_DEV_BUS_OFF] = BIT(MCP2510_DEV_RUNNING),
	[MCP2510_DEV_HALTED] = BIT(MCP2510_DEV_BUS_OFF),
};

enum mcp2510_dev_state mcp2510_dev_state(const struct mcp2510_priv *priv)
{
	return READ_ONCE(priv->state);
}

/* INT requested and the chip started, on the bus or stopped at bus-off. */
bool mcp2510_dev_running(const struct mcp2510_priv *priv)
{
	return RUNNING_STATES & BIT(mcp2510_dev_state(priv));
}

void mcp2510_dev_enter(struct mcp2510_priv *priv, enum mcp2510_dev_state to)
{
	WARN_ON_ONCE(!(mcp2510_dev_from[to] & BIT(priv->state)));
	WRITE_ONCE(priv->state, to);
}
