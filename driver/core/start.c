// SPDX-License-Identifier: GPL-2.0
/*
 * The life cycle of a chip: init, start (reset and program everything in
 * configuration mode, then enter the operating mode), stop and restart.
 */
#include "mcp2510_core_priv.h"

#define CTRLMODE_SUPPORTED	(CAN_CTRLMODE_LOOPBACK | \
				 CAN_CTRLMODE_LISTENONLY | \
				 CAN_CTRLMODE_3_SAMPLES | \
				 CAN_CTRLMODE_ONE_SHOT | \
				 CAN_CTRLMODE_BERR_REPORTING | \
				 CAN_CTRLMODE_CC_LEN8_DLC)

int mcp2510_init(struct mcp2510_chip *chip, const struct mcp2510_variant *v,
		 u32 osc_hz, const struct mcp2510_ops *ops,
		 const struct mcp2510_events *events, void *ctx)
{
	if (!v || !ops || !ops->xfer || !ops->delay_us || !events)
		return -EINVAL;
	if (osc_hz < MCP2510_OSC_MIN_HZ || osc_hz > MCP2510_OSC_MAX_HZ)
		return -EINVAL;
	memset(chip, 0, sizeof(*chip));
	chip->variant = v;
	chip->ops = ops;
	chip->events = events;
	chip->ctx = ctx;
	chip->osc_hz = osc_hz;
	chip->state = CAN_STATE_STOPPED;
	mcp2510_filters_default(&chip->filters);
	return 0;
}

static u8 operating_mode(u32 ctrlmode)
{
	if (ctrlmode & CAN_CTRLMODE_LOOPBACK)
		return MCP2510_MODE_LOOPBACK;
	if (ctrlmode & CAN_CTRLMODE_LISTENONLY)
		return MCP2510_MODE_LISTEN_ONLY;
	return MCP2510_MODE_NORMAL;
}

/*
 * MERRF only when someone wants bus errors, or to notice a failed
 * one-shot frame (its TXREQ goes away without TXnIF): on a broken bus it
 * fires for every frame.
 */
static u8 interrupt_enables(u32 ctrlmode)
{
	u8 inte = MCP2510_INT_RX_ALL | MCP2510_INT_TX_ALL | MCP2510_INT_ERR;

	if (ctrlmode & (CAN_CTRLMODE_BERR_REPORTING | CAN_CTRLMODE_ONE_SHOT))
		inte |= MCP2510_INT_MERR;
	return inte;
}

/* One bit in microseconds, rounded up: 2 * BRP * quanta oscillator cycles. */
static u32 bit_time_us(const u8 cnf[3], u32 osc_hz)
{
	struct can_bittiming bt;
	u32 ntq;

	mcp2510_bittiming_decode(cnf, 0, &bt);
	ntq = 1 + bt.prop_seg + bt.phase_seg1 + bt.phase_seg2;
	return DIV_ROUND_UP(2 * bt.brp * ntq * 1000000U, osc_hz);
}

/* Reset the chip and program it as mcp2510_start() recorded. */
static int chip_program(struct mcp2510_chip *chip)
{
	/* CNF3, CNF2, CNF1 and CANINTE are adjacent: one WRITE */
	const u8 regs[4] = {
		chip->cnf[2] | (chip->wake_filter ? MCP2510_CNF3_WAKFIL : 0),
		chip->cnf[1], chip->cnf[0], chip->inte
	};
	u8 osm = chip->ctrlmode & CAN_CTRLMODE_ONE_SHOT ?
		 MCP2515_CANCTRL_OSM : 0;
	int err;

	err = mcp2510_hw_reset(chip);
	if (err)
		return err;
	err = mcp2510_reg_write(chip, MCP2510_REG_CNF3, regs, sizeof(regs));
	if (err)
		return err;
	err = mcp2510_filters_write(chip);
	if (err)
		return err;
	if (osm) {
		err = mcp2510_reg_modify(chip, MCP2510_REG_CANCTRL,
					 MCP2515_CANCTRL_OSM, osm);
		if (err)
			return err;
	}
	chip->irq.full_read_next = false;
	chip->irq.rx1_first = false;
	chip->irq.rx_status = 0;
	chip->irq.passes_to_full_read = MCP2510_IRQ_FULL_READ_EVERY;
	chip->bec.txerr = 0;
	chip->bec.rxerr = 0;
	chip->sent_since_bec = 0;
	return mcp2510_set_mode(chip, chip->opmode);
}

int mcp2510_start(struct mcp2510_chip *chip, const struct can_bittiming *bt,
		  u32 ctrlmode)
{
	u8 cnf[3];
	int err;

	if (chip->started)
		return -EBUSY;
	if (ctrlmode & ~CTRLMODE_SUPPORTED ||
	    (ctrlmode & CAN_CTRLMODE_ONE_SHOT && !chip->variant->has_one_shot))
		return -EOPNOTSUPP;
	err = mcp2510_bittiming_encode(bt, ctrlmode, cnf);
	if (err)
		return err;

	memcpy(chip->cnf, cnf, sizeof(cnf));
	chip->ctrlmode = ctrlmode;
	chip->opmode = operating_mode(ctrlmode);
	chip->inte = interrupt_enables(ctrlmode);
	chip->bit_us = bit_time_us(cnf, chip->osc_hz);
	err = chip_program(chip);
	if (err)
		return err;
	chip->started = true;
	chip->state = CAN_STATE_ERROR_ACTIVE;
	return 0;
}

/*
 * Frames still queued are given up before the first transfer, so the
 * caller's bookkeeping is right even when the chip no longer answers.
 */
int mcp2510_stop(struct mcp2510_chip *chip)
{
	const u8 none = 0;
	int err;

	mcp2510_tx_abort_all(chip);
	chip->started = false;
	chip->state = CAN_STATE_STOPPED;
	chip->inte = 0;
	err = mcp2510_reg_write(chip, MCP2510_REG_CANINTE, &none, 1);
	if (err)
		return err;
	err = mcp2510_reg_modify(chip, MCP2510_REG_CANCTRL,
				 MCP2510_CANCTRL_ABAT, MCP2510_CANCTRL_ABAT);
	if (err)
		return err;
	return mcp2510_sleep(chip);
}

/*
 * A bus-off chip recovers by itself after 128 x 11 recessive bits and
 * sends what it holds, so its frames are given up only once ABAT went
 * through.  After that nothing more can go out: the rest of the stop is
 * done as well as the SPI allows, and a restart resets the chip anyway.
 */
int mcp2510_halt(struct mcp2510_chip *chip)
{
	int err;

	err = mcp2510_reg_modify(chip, MCP2510_REG_CANCTRL,
				 MCP2510_CANCTRL_ABAT, MCP2510_CANCTRL_ABAT);
	if (err)
		return err;
	mcp2510_stop(chip);
	return 0;
}

/*
 * A full reset clears TEC and REC, which is what a restart from bus-off
 * is for; the chip's own recovery (128 x 11 recessive bits) needs no call.
 * The state event tells the caller the chip is error-active again; the
 * restart error frame is the caller's (the kernel's can_restart() sends
 * one).
 */
int mcp2510_restart(struct mcp2510_chip *chip)
{
	int err;

	if (!chip->started)
		return -ENETDOWN;
	chip->counters.restarts++;
	mcp2510_tx_abort_all(chip);
	err = chip_program(chip);
	if (err)
		return err;
	if (chip->state != CAN_STATE_ERROR_ACTIVE) {
		chip->state = CAN_STATE_ERROR_ACTIVE;
		if (chip->events->state)
			chip->events->state(chip->ctx, chip->state, &chip->bec);
	}
	return 0;
}
