// SPDX-License-Identifier: GPL-2.0
/*
 * The general-purpose pins: RX0BF/RX1BF driven as outputs, TX0RTS..TX2RTS
 * read as inputs (their reset function).
 */
#include "mcp2510_core_priv.h"

int mcp2510_pin_bf_set(struct mcp2510_chip *chip, unsigned int n, bool level)
{
	/* BnBFE set and BnBFM clear make the pin a digital output */
	u8 mask = MCP2510_BFPCTRL_BFS(n) | MCP2510_BFPCTRL_BFE(n) |
		  MCP2510_BFPCTRL_BFM(n);
	u8 val = MCP2510_BFPCTRL_BFE(n) | (level ? MCP2510_BFPCTRL_BFS(n) : 0);

	if (n >= MCP2510_RXB_COUNT)
		return -EINVAL;
	return mcp2510_reg_modify(chip, MCP2510_REG_BFPCTRL, mask, val);
}

int mcp2510_pin_rts_get(struct mcp2510_chip *chip, unsigned int n)
{
	u8 txrtsctrl;
	int err;

	if (n >= MCP2510_TXB_COUNT)
		return -EINVAL;
	err = mcp2510_reg_read(chip, MCP2510_REG_TXRTSCTRL, &txrtsctrl, 1);
	if (err)
		return err;
	return !!(txrtsctrl & MCP2510_TXRTSCTRL_BRTS(n));
}
