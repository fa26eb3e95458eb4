// SPDX-License-Identifier: GPL-2.0
/*
 * One chip's transmit side: the three transmit buffers, their priority,
 * requests (TXREQ, RTS, TXnRTS), aborts (ABAT, clearing TXREQ), one-shot
 * mode, lost arbitration, the end of a frame, and loopback mode, where a
 * frame goes round inside the chip.
 *
 * References: DS21291 section 3 (message transmission, registers 3-1 and
 * 3-2) and 9.4 (loopback); DS21801 section 3 (3.4 aborting
 * transmission) and 10.5 (loopback mode); AN739 "Buffer priority".
 */
#include "sim_private.h"

#define SIM_TXBCTRL_FLAGS	(MCP2510_TXBCTRL_ABTF | MCP2510_TXBCTRL_MLOA | \
				 MCP2510_TXBCTRL_TXERR)

/* ---- Transmit ----------------------------------------------------------------- */

u8 *sim_txbctrl(struct sim_chip *chip, unsigned int n)
{
	return sim_reg(chip, MCP2510_REG_TXBCTRL(n));
}

/* AN739 "Buffer priority": highest TXP, then the higher buffer number. */
int sim_chip_pick_buffer(const struct sim_chip *chip)
{
	int best = -1, best_prio = -1;
	unsigned int n;

	if (chip->regs[MCP2510_REG_CANCTRL] & MCP2510_CANCTRL_ABAT)
		return -1;	/* AN739: ABAT must be cleared to transmit */
	for (n = 0; n < MCP2510_TXB_COUNT; n++) {
		u8 ctrl = chip->regs[MCP2510_REG_TXBCTRL(n)];
		int prio = FIELD_GET(MCP2510_TXBCTRL_TXP_MASK, ctrl);

		if ((ctrl & MCP2510_TXBCTRL_TXREQ) && prio >= best_prio) {
			best = n;
			best_prio = prio;
		}
	}
	return best;
}

bool sim_chip_ready(const struct sim_chip *chip)
{
	return chip->powered && sim_now(chip) >= chip->ready_at;
}

/* The buffer this chip would send if arbitration started now, or -1. */
int sim_chip_tx_candidate(const struct sim_chip *chip)
{
	if (!sim_chip_ready(chip) || chip->opmode != MCP2510_MODE_NORMAL ||
	    chip->bus_off || chip->tx.active)
		return -1;
	return sim_chip_pick_buffer(chip);
}

/* Decode TXBn into a frame (DLC 9..15 goes out as is, with 8 bytes). */
void sim_chip_tx_frame(const struct sim_chip *chip, unsigned int buf,
		       struct can_frame *cf)
{
	const u8 *b = &chip->regs[MCP2510_REG_TXB(buf)];
	u8 sidl = b[MCP2510_BUF_SIDL], dlc = b[MCP2510_BUF_DLC] & MCP2510_DLC_MASK;
	u32 sid = (u32)b[MCP2510_BUF_SIDH] << MCP2510_SID_SHIFT_SIDH |
		  FIELD_GET(MCP2510_SIDL_SID_MASK, sidl);

	memset(cf, 0, sizeof(*cf));
	if (sidl & MCP2510_SIDL_EXIDE)
		cf->can_id = CAN_EFF_FLAG | sid << MCP2510_EID_BITS |
			     (u32)(sidl & MCP2510_SIDL_EID_MASK) << 16 |
			     (u32)b[MCP2510_BUF_EID8] << 8 | b[MCP2510_BUF_EID0];
	else
		cf->can_id = sid;
	if (b[MCP2510_BUF_DLC] & MCP2510_DLC_RTR)
		cf->can_id |= CAN_RTR_FLAG;
	cf->len = dlc > CAN_MAX_DLEN ? CAN_MAX_DLEN : dlc;
	if (dlc > CAN_MAX_DLEN)
		cf->len8_dlc = dlc;
	if (!(cf->can_id & CAN_RTR_FLAG))
		memcpy(cf->data, &b[MCP2510_BUF_D0], cf->len);
}

void sim_chip_tx_start(struct sim_chip *chip, unsigned int buf)
{
	chip->tx.active = true;
	chip->tx.loopback = false;
	chip->tx.abort = false;
	chip->tx.abort_abat = false;
	chip->tx.buf = buf;
}

static bool sim_chip_one_shot(const struct sim_chip *chip)
{
	return chip->variant == SIM_MCP2515 &&
	       (chip->regs[MCP2510_REG_CANCTRL] & MCP2515_CANCTRL_OSM);
}

/*
 * The buffer gives up its request.  DS21801 3.4: ABTF is set only for an
 * abort requested with ABAT; clearing TXREQ aborts without it.  Whether
 * a failed one-shot attempt sets it 3.4 does not say
 * (faults.abtf_on_one_shot).
 */
static void sim_chip_abort_buffer(struct sim_chip *chip, unsigned int n,
				  bool abtf)
{
	u8 *ctrl = sim_txbctrl(chip, n);

	*ctrl &= ~MCP2510_TXBCTRL_TXREQ;
	if (abtf)
		*ctrl |= MCP2510_TXBCTRL_ABTF;
}

/* Lost arbitration: MLOA, and with one-shot mode no second attempt. */
void sim_chip_tx_lost(struct sim_chip *chip)
{
	int buf = sim_chip_pick_buffer(chip);

	if (buf < 0)
		return;
	*sim_txbctrl(chip, buf) |= MCP2510_TXBCTRL_MLOA;
	chip->counters.arbitration_lost++;
	if (sim_chip_one_shot(chip))
		sim_chip_abort_buffer(chip, buf, chip->faults.abtf_on_one_shot);
	sim_chip_update_pins(chip);
}

/* Still driving the frame it started: a reset or power loss ends that. */
bool sim_chip_sending(const struct sim_chip *chip)
{
	return chip->tx.active;
}

/*
 * The chip's frame is over.  ok: sent and acknowledged.  Otherwise
 * count_error says whether TEC grows by 8 (CAN 2.0B rule 3; not for an
 * error-passive sender's ACK error without dominant bits, exception 1).
 */
void sim_chip_tx_end(struct sim_chip *chip, bool ok, bool count_error)
{
	unsigned int buf = chip->tx.buf;
	u8 *ctrl = sim_txbctrl(chip, buf);

	if (!chip->tx.active)
		return;		/* reset or power loss while on the bus */
	chip->tx.active = false;
	if (ok) {
		*ctrl &= ~MCP2510_TXBCTRL_TXREQ;
		*sim_reg(chip, MCP2510_REG_CANINTF) |= MCP2510_INT_TX(buf);
		chip->counters.frames_tx++;
		if (!chip->tx.loopback && chip->tec && !chip->bus_off)
			chip->tec--;
	} else {
		*ctrl |= MCP2510_TXBCTRL_TXERR;
		*sim_reg(chip, MCP2510_REG_CANINTF) |= MCP2510_INT_MERR;
		chip->counters.tx_errors++;
		if (count_error)
			sim_chip_tec_add(chip, 8);
		if (chip->tx.abort_abat)
			sim_chip_abort_buffer(chip, buf, true);
		else if (sim_chip_one_shot(chip))
			sim_chip_abort_buffer(chip, buf,
					      chip->faults.abtf_on_one_shot);
		else if (chip->tx.abort || !(*ctrl & MCP2510_TXBCTRL_TXREQ))
			sim_chip_abort_buffer(chip, buf, false);
	}
	sim_chip_update_eflg(chip);
	sim_chip_update_pins(chip);
}

/* TXREQ written or requested by RTS / TXnRTS. */
void sim_chip_request(struct sim_chip *chip, unsigned int n)
{
	u8 *ctrl = sim_txbctrl(chip, n);

	if (*ctrl & MCP2510_TXBCTRL_TXREQ)
		return;
	/* setting TXREQ starts a new attempt: old outcome flags go */
	*ctrl = (*ctrl & ~SIM_TXBCTRL_FLAGS) | MCP2510_TXBCTRL_TXREQ;
}

/* ABAT set: every pending buffer not on the bus now is aborted. */
void sim_chip_abort_all(struct sim_chip *chip)
{
	unsigned int n;

	for (n = 0; n < MCP2510_TXB_COUNT; n++) {
		if (chip->tx.active && chip->tx.buf == n) {
			chip->tx.abort = true;
			chip->tx.abort_abat = true;
			continue;
		}
		if (*sim_txbctrl(chip, n) & MCP2510_TXBCTRL_TXREQ)
			sim_chip_abort_buffer(chip, n, true);
	}
}

/* ---- Loopback: frames go round inside the chip ----------------------------- */

void sim_chip_loopback_start(struct sim_chip *chip, unsigned int buf)
{
	struct can_frame cf;

	sim_chip_tx_frame(chip, buf, &cf);
	sim_chip_tx_start(chip, buf);
	chip->tx.loopback = true;
	chip->tx.end_at = sim_now(chip) +
			  (u64)sim_frame_bits(&cf) * sim_chip_bit_ns(chip);
}

void sim_chip_loopback_end(struct sim_chip *chip)
{
	struct can_frame cf;

	sim_chip_tx_frame(chip, chip->tx.buf, &cf);
	sim_chip_tx_end(chip, true, false);
	sim_chip_accept(chip, &cf);
	sim_chip_update_pins(chip);
}
