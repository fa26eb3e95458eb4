// SPDX-License-Identifier: GPL-2.0
/*
 * Fault confinement as SocketCAN sees it: EFLG/TEC/REC become
 * CAN_STATE_* changes and error frames, RXnOVR becomes an overflow report,
 * MERRF a bus error.
 */
#include "mcp2510_core_priv.h"

#define EFLG_PASSIVE	(MCP2510_EFLG_TXEP | MCP2510_EFLG_RXEP)
#define EFLG_WARNING	(MCP2510_EFLG_TXWAR | MCP2510_EFLG_RXWAR | \
			 MCP2510_EFLG_EWARN)

enum can_state mcp2510_error_eflg_state(u8 eflg)
{
	if (eflg & MCP2510_EFLG_TXBO)
		return CAN_STATE_BUS_OFF;
	if (eflg & EFLG_PASSIVE)
		return CAN_STATE_ERROR_PASSIVE;
	if (eflg & EFLG_WARNING)
		return CAN_STATE_ERROR_WARNING;
	return CAN_STATE_ERROR_ACTIVE;
}

/*
 * The limits EFLG follows (DS21801 section 6): warning at 96, passive at
 * 128, per counter.  TXBO comes on top of TXEP (bus-off is reached through
 * error-passive, and TEC stays up until the recovery clears it).  Every
 * flag must match, so a corrupted read rarely passes for a real one.
 */
bool mcp2510_error_state_plausible(u8 eflg, const struct can_berr_counter *bec)
{
	u8 want = 0;

	if (bec->txerr >= 96)
		want |= MCP2510_EFLG_TXWAR | MCP2510_EFLG_EWARN;
	if (bec->rxerr >= 96)
		want |= MCP2510_EFLG_RXWAR | MCP2510_EFLG_EWARN;
	if (bec->txerr >= 128)
		want |= MCP2510_EFLG_TXEP;
	if (bec->rxerr >= 128)
		want |= MCP2510_EFLG_RXEP;
	if (eflg & MCP2510_EFLG_TXBO && bec->txerr >= 128)
		want |= MCP2510_EFLG_TXBO;
	return (eflg & (EFLG_PASSIVE | EFLG_WARNING | MCP2510_EFLG_TXBO)) == want;
}

static void error_frame_init(struct can_frame *cf, canid_t class,
			     const struct can_berr_counter *bec)
{
	memset(cf, 0, sizeof(*cf));
	cf->can_id = CAN_ERR_FLAG | CAN_ERR_CNT | class;
	cf->len = CAN_ERR_DLC;
	cf->data[6] = bec->txerr;
	cf->data[7] = bec->rxerr;
}

static void error_frame_send(struct mcp2510_chip *chip,
			     const struct can_frame *cf)
{
	if (chip->events->error)
		chip->events->error(chip->ctx, cf);
}

/* data[1] of a CAN_ERR_CRTL frame: which side is how bad */
static u8 crtl_detail(enum can_state state, u8 eflg)
{
	switch (state) {
	case CAN_STATE_ERROR_PASSIVE:
		return (eflg & MCP2510_EFLG_TXEP ? CAN_ERR_CRTL_TX_PASSIVE : 0) |
		       (eflg & MCP2510_EFLG_RXEP ? CAN_ERR_CRTL_RX_PASSIVE : 0);
	case CAN_STATE_ERROR_WARNING:
		return (eflg & MCP2510_EFLG_TXWAR ? CAN_ERR_CRTL_TX_WARNING : 0) |
		       (eflg & MCP2510_EFLG_RXWAR ? CAN_ERR_CRTL_RX_WARNING : 0);
	default:
		return CAN_ERR_CRTL_ACTIVE;
	}
}

static void count_state(struct mcp2510_chip *chip, enum can_state state)
{
	switch (state) {
	case CAN_STATE_ERROR_WARNING:
		chip->counters.warnings++;
		break;
	case CAN_STATE_ERROR_PASSIVE:
		chip->counters.passives++;
		break;
	case CAN_STATE_BUS_OFF:
		chip->counters.bus_offs++;
		break;
	default:
		break;
	}
}

/*
 * The chip leaves bus-off by itself after 128 x 11 recessive bits (1.4 ms
 * at 1 Mbit/s) with TEC, REC and EFLG cleared: an interrupt served later
 * finds it error-active as if it had never been off the bus.  Only that
 * recovery lowers TEC by more than one a frame sent, so a fall greater
 * than the frames seen sent since the last read, plus those sent but not
 * seen yet (one a buffer), gives the bus-off away.
 */
static bool bus_off_missed(const struct mcp2510_chip *chip,
			   const struct can_berr_counter *bec)
{
	return chip->state != CAN_STATE_BUS_OFF &&
	       bec->txerr + chip->sent_since_bec + MCP2510_TXB_COUNT <
	       chip->bec.txerr;
}

void mcp2510_error_state_update(struct mcp2510_chip *chip, u8 eflg,
				const struct can_berr_counter *bec)
{
	enum can_state state = mcp2510_error_eflg_state(eflg);
	struct can_frame cf;

	if (bus_off_missed(chip, bec))
		state = CAN_STATE_BUS_OFF;
	chip->bec = *bec;
	chip->sent_since_bec = 0;
	if (state == chip->state)
		return;
	/* only a worse state is counted, as the kernel's statistics do */
	if (state > chip->state)
		count_state(chip, state);
	chip->state = state;
	if (chip->events->state)
		chip->events->state(chip->ctx, state, bec);

	if (state == CAN_STATE_BUS_OFF) {
		error_frame_init(&cf, CAN_ERR_BUSOFF, bec);
	} else {
		error_frame_init(&cf, CAN_ERR_CRTL, bec);
		cf.data[1] = crtl_detail(state, eflg);
	}
	error_frame_send(chip, &cf);
}

u8 mcp2510_error_overflow(struct mcp2510_chip *chip, u8 eflg,
			  const struct can_berr_counter *bec)
{
	u8 ovr = eflg & (MCP2510_EFLG_RX0OVR | MCP2510_EFLG_RX1OVR);
	struct can_frame cf;
	unsigned int n;

	if (!ovr)
		return 0;
	for (n = 0; n < MCP2510_RXB_COUNT; n++)
		if (ovr & MCP2510_EFLG_RXOVR(n))
			chip->counters.rx_overflows++;
	error_frame_init(&cf, CAN_ERR_CRTL, bec);
	cf.data[1] = CAN_ERR_CRTL_RX_OVERFLOW;
	error_frame_send(chip, &cf);
	return ovr;
}

/*
 * MERRF does not say whether the chip was sending or receiving, but a
 * buffer still waiting to go with TXERR set had its frame destroyed.  A
 * buffer that went out since then is no longer busy, and TXREQ clears
 * TXERR, so an old failure is not taken for a new one.
 */
static bool error_while_sending(struct mcp2510_chip *chip)
{
	unsigned int n;
	u8 ctrl;

	for (n = 0; n < MCP2510_TXB_COUNT; n++) {
		if (!(chip->tx.busy & BIT(n)))
			continue;
		/* A failed read leaves the direction unknown: say receive. */
		if (mcp2510_reg_read(chip, MCP2510_REG_TXBCTRL(n), &ctrl, 1))
			return false;
		if (ctrl & MCP2510_TXBCTRL_TXERR)
			return true;
	}
	return false;
}

void mcp2510_error_bus(struct mcp2510_chip *chip,
		       const struct can_berr_counter *bec)
{
	struct can_frame cf;

	chip->counters.bus_errors++;
	if (!(chip->ctrlmode & CAN_CTRLMODE_BERR_REPORTING))
		return;
	/* the chip does not say which kind of error it saw */
	error_frame_init(&cf, CAN_ERR_PROT | CAN_ERR_BUSERROR, bec);
	if (error_while_sending(chip))
		cf.data[2] = CAN_ERR_PROT_TX;
	error_frame_send(chip, &cf);
}

int mcp2510_berr_counter(struct mcp2510_chip *chip,
			 struct can_berr_counter *bec)
{
	u8 regs[2];
	int err;

	err = mcp2510_reg_read(chip, MCP2510_REG_TEC, regs, sizeof(regs));
	if (err)
		return err;
	bec->txerr = regs[0];
	bec->rxerr = regs[1];
	return 0;
}
