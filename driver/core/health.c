// SPDX-License-Identifier: GPL-2.0
/*
 * Telling whether the chip still holds what mcp2510_start() programmed,
 * and putting it back when it does not.
 *
 * A chip that reset itself (a brown-out, a glitch on the RESET pin) sits
 * in configuration mode with CNF1-3 and CANINTE at zero: it neither sends
 * nor raises INT, so nothing in the interrupt path ever notices.  A broken
 * MISO line reads values no programmed chip can hold, such as an OPMOD of
 * 5 to 7.  Both look the same from here: registers that disagree with
 * what was written, and neither leaves anything the chip says trustworthy.
 *
 * The check also holds the transmit bookkeeping against the chip.  A
 * corrupted read, or a pass that could not see TXREQ, can leave a buffer
 * counted busy whose frame is long gone: TXREQ and TXnIF both clear, so
 * no interrupt will ever report it, and the ordered queue waits on it for
 * good.  Such a frame was dropped as far as anyone can tell; giving it up
 * lets the queue move again within a check period.
 */
#include "mcp2510_core_priv.h"

/* CNF3 bits every variant implements; SOF and WAKFIL may read back 0. */
#define HEALTH_CNF3_MASK	MCP2510_CNF3_PHSEG2_MASK

/* Busy buffers the chip neither sends nor has flagged as sent. */
static int health_tx_check(struct mcp2510_chip *chip)
{
	u8 status, gone = 0;
	unsigned int n;
	int err;

	if (!mcp2510_tx_pending(chip) && !chip->tx.unsure && !chip->tx.staged)
		return 0;
	err = mcp2510_read_status(chip, &status);
	if (err)
		return err;
	mcp2510_tx_resolve(chip, status);
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (!(status & (MCP2510_STATUS_TXREQ(n) |
				MCP2510_STATUS_TXIF(n))))
			gone |= BIT(n);
	mcp2510_tx_lost(chip, gone);
	/* staged frames whose turn came while an RTS failed */
	return mcp2510_tx_kick(chip, 0);
}

int mcp2510_health_check(struct mcp2510_chip *chip)
{
	u8 mode[2], conf[4];	/* CANSTAT, CANCTRL; CNF3, CNF2, CNF1, CANINTE */
	int err;

	if (!chip->started)
		return 0;
	err = mcp2510_reg_read(chip, MCP2510_REG_CANSTAT, mode, sizeof(mode));
	if (err)
		return err;
	err = mcp2510_reg_read(chip, MCP2510_REG_CNF3, conf, sizeof(conf));
	if (err)
		return err;

	if (FIELD_GET(MCP2510_CANSTAT_OPMOD_MASK, mode[0]) != chip->opmode ||
	    FIELD_GET(MCP2510_CANCTRL_REQOP_MASK, mode[1]) != chip->opmode)
		return -EBADMSG;
	if ((conf[0] ^ chip->cnf[2]) & HEALTH_CNF3_MASK ||
	    conf[1] != chip->cnf[1] || conf[2] != chip->cnf[0] ||
	    conf[3] != chip->inte)
		return -EBADMSG;
	return health_tx_check(chip);
}

int mcp2510_recover(struct mcp2510_chip *chip)
{
	int err;

	err = mcp2510_restart(chip);
	if (err)
		return err;
	chip->counters.recoveries++;
	return 0;
}
