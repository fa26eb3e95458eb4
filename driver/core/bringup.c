// SPDX-License-Identifier: GPL-2.0
/*
 * Bring-up and operating modes: RESET and the start-up wait, telling a
 * live chip from a missing one, mode requests, sleep and wake-up.
 */
#include "mcp2510_core_priv.h"

/* Oscillator start-up timer after RESET (DS21291, AN739). */
#define OST_CYCLES		128
#define OST_MARGIN_US		5
/*
 * A chip still not answering after this much waiting is absent.  The
 * start-up timer only begins once the oscillator runs, and a crystal
 * whose supply was only just switched on takes milliseconds to get there.
 */
#define RESET_TIMEOUT_US	50000
/*
 * A mode change waits for the bus to go idle: allow a few frames with
 * error frames at the configured bit rate, and never less than 10 ms.
 */
#define MODE_TIMEOUT_MIN_US	10000
#define MODE_TIMEOUT_BITS	600
#define POLL_FIRST_US		10
#define POLL_MAX_US		1000

void mcp2510_delay_us(struct mcp2510_chip *chip, unsigned int us)
{
	if (us)
		chip->ops->delay_us(chip->ctx, us);
}

static unsigned int ost_us(const struct mcp2510_chip *chip)
{
	return DIV_ROUND_UP(OST_CYCLES * 1000000U, chip->osc_hz) +
	       OST_MARGIN_US;
}

/*
 * After RESET CANSTAT reads exactly configuration mode with no interrupt
 * code, and CANCTRL has REQOP configuration (power-up on the MCP2510),
 * no abort, and CLKOUT enabled at /8.  A MISO line stuck at 0x00 or
 * 0xff, or a chip still in start-up, fails both.
 */
static bool reset_values_ok(const struct mcp2510_chip *chip, const u8 regs[2])
{
	u8 canctrl_fixed = chip->variant->reset_canctrl &
			   ~MCP2510_CANCTRL_REQOP_MASK;
	u8 reqop = FIELD_GET(MCP2510_CANCTRL_REQOP_MASK, regs[1]);

	return regs[0] == MCP2510_RESET_CANSTAT &&
	       (regs[1] & ~MCP2510_CANCTRL_REQOP_MASK) == canctrl_fixed &&
	       (reqop == MCP2510_MODE_CONFIG || reqop == MCP2510_MODE_POWERUP);
}

/* The next wait of a poll: twice the last one, at most POLL_MAX_US. */
static unsigned int poll_backoff(unsigned int wait)
{
	return wait * 2 > POLL_MAX_US ? POLL_MAX_US : wait * 2;
}

int mcp2510_hw_reset(struct mcp2510_chip *chip)
{
	const u8 reset = MCP2510_INSTR_RESET;
	unsigned int wait = ost_us(chip), waited = 0;
	u8 regs[2];	/* CANSTAT, CANCTRL */
	int err;

	err = mcp2510_xfer(chip, &reset, NULL, 1);
	if (err)
		return err;
	for (;;) {
		mcp2510_delay_us(chip, wait);
		waited += wait;
		err = mcp2510_reg_read(chip, MCP2510_REG_CANSTAT, regs,
				       sizeof(regs));
		if (err)
			return err;
		if (reset_values_ok(chip, regs)) {
			mcp2510_tx_reset(chip);
			chip->irq.flags_cleared = true;
			return 0;
		}
		if (waited >= RESET_TIMEOUT_US)
			return -ENODEV;
		wait = poll_backoff(wait);
	}
}

static unsigned int mode_timeout_us(const struct mcp2510_chip *chip)
{
	unsigned int us = MODE_TIMEOUT_BITS * chip->bit_us;

	return us > MODE_TIMEOUT_MIN_US ? us : MODE_TIMEOUT_MIN_US;
}

/* Poll CANSTAT.OPMOD until it reads @mode, backing off up to 1 ms. */
static int opmode_wait(struct mcp2510_chip *chip, u8 mode)
{
	unsigned int budget = mode_timeout_us(chip), waited = 0;
	unsigned int wait = POLL_FIRST_US;
	u8 canstat;
	int err;

	for (;;) {
		err = mcp2510_reg_read(chip, MCP2510_REG_CANSTAT, &canstat, 1);
		if (err)
			return err;
		if (FIELD_GET(MCP2510_CANSTAT_OPMOD_MASK, canstat) == mode)
			return 0;
		if (waited >= budget)
			return -ETIMEDOUT;
		mcp2510_delay_us(chip, wait);
		waited += wait;
		wait = poll_backoff(wait);
	}
}

int mcp2510_set_mode(struct mcp2510_chip *chip, u8 mode)
{
	int err;

	if (mode > MCP2510_MODE_CONFIG)
		return -EINVAL;
	err = mcp2510_reg_modify(chip, MCP2510_REG_CANCTRL,
				 MCP2510_CANCTRL_REQOP_MASK,
				 FIELD_PREP(MCP2510_CANCTRL_REQOP_MASK, mode));
	if (err)
		return err;
	return opmode_wait(chip, mode);
}

int mcp2510_sleep(struct mcp2510_chip *chip)
{
	return mcp2510_set_mode(chip, MCP2510_MODE_SLEEP);
}

void mcp2510_wake_filter_set(struct mcp2510_chip *chip, bool on)
{
	chip->wake_filter = on;
}

/*
 * A WAKIF left from before would assert INT at once and read as a
 * wake-up that never happened: clear it before enabling it.
 */
int mcp2510_wake_arm(struct mcp2510_chip *chip)
{
	const u8 inte = MCP2510_INT_WAK;
	int err;

	err = mcp2510_reg_modify(chip, MCP2510_REG_CANINTF, MCP2510_INT_WAK, 0);
	if (err)
		return err;
	err = mcp2510_reg_write(chip, MCP2510_REG_CANINTE, &inte, 1);
	if (err)
		return err;
	return mcp2510_sleep(chip);
}

int mcp2510_wake_ack(struct mcp2510_chip *chip)
{
	u8 intf;
	int err;

	err = mcp2510_reg_read(chip, MCP2510_REG_CANINTF, &intf, 1);
	if (err)
		return err;
	if (!(intf & MCP2510_INT_WAK))
		return 0;
	err = mcp2510_reg_modify(chip, MCP2510_REG_CANINTF, MCP2510_INT_WAK, 0);
	return err ? err : 1;
}
