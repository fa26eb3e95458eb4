// SPDX-License-Identifier: GPL-2.0
/*
 * One chip's receive side: acceptance masks and filters, the two receive
 * buffers with rollover (BUKT), overflow, and frames destroyed by an
 * error as listen-only mode receives them.
 *
 * References: DS21291 section 4 (message reception, registers 4-1..4-17);
 * DS21801 section 4 (4.2 receive buffers, 4.5 masks and filters, table
 * 4-2, 4.5.1 data byte filtering, MCP2515 only) and 10.3 (listen-only
 * mode); AN739.
 */
#include "sim_private.h"

/* ---- Receive ------------------------------------------------------------------ */

static u32 sim_id_bits(const u8 *id)
{
	return (u32)id[MCP2510_ID_SIDH] << 21 |
	       (u32)FIELD_GET(MCP2510_SIDL_SID_MASK, id[MCP2510_ID_SIDL]) << 18 |
	       (u32)(id[MCP2510_ID_SIDL] & MCP2510_SIDL_EID_MASK) << 16 |
	       (u32)id[MCP2510_ID_EID8] << 8 | id[MCP2510_ID_EID0];
}

/*
 * Filter n under mask m (DS21801 4.5, table 4-2): every mask bit set
 * demands equality.  A filter takes only the frame type its EXIDE names.
 * Standard frames compare the 11 id bits; the MCP2515 also compares
 * EID15..0 with data bytes 0 and 1 of standard data frames (DS21801
 * 4.5.1, missing bytes read as 0).  The MCP2510 data sheet has no data
 * byte filtering.
 */
static bool sim_filter_match(const struct sim_chip *chip, unsigned int f,
			     unsigned int m, const struct can_frame *cf)
{
	const u8 *filter = &chip->regs[MCP2510_REG_RXF(f)];
	u32 fbits = sim_id_bits(filter);
	u32 mbits = sim_id_bits(&chip->regs[MCP2510_REG_RXM(m)]);
	bool ext = cf->can_id & CAN_EFF_FLAG;
	u32 frame;

	if (ext != !!(filter[MCP2510_ID_SIDL] & MCP2510_SIDL_EXIDE))
		return false;
	if (ext)
		return !(((cf->can_id & CAN_EFF_MASK) ^ fbits) & mbits);
	frame = (cf->can_id & CAN_SFF_MASK) << MCP2510_EID_BITS;
	if (chip->variant == SIM_MCP2515 && !(cf->can_id & CAN_RTR_FLAG)) {
		frame |= (u32)(cf->len > 0 ? cf->data[0] : 0) << 8;
		frame |= cf->len > 1 ? cf->data[1] : 0;
	} else {
		mbits &= ~0xffffU;
	}
	mbits &= ~(0x3U << 16);		/* EID17..16 mean nothing here */
	return !((frame ^ fbits) & mbits);
}

/*
 * DS21801 4.2: RXM selects which frames a buffer takes; RXM 00..10 only
 * valid ones.  A frame destroyed by an error (!valid) only reaches a
 * buffer with RXM 11.
 */
static int sim_rxb_accept(const struct sim_chip *chip, unsigned int n,
			  const struct can_frame *cf, bool valid)
{
	u8 rxm = FIELD_GET(MCP2510_RXBCTRL_RXM_MASK,
			   chip->regs[MCP2510_REG_RXBCTRL(n)]);
	bool ext = cf->can_id & CAN_EFF_FLAG;
	unsigned int first = n ? 2 : 0, last = n ? 5 : 1, f;

	if (rxm == MCP2510_RXM_ANY)
		return first;
	if (!valid)
		return -1;
	if ((rxm == MCP2510_RXM_STD && ext) || (rxm == MCP2510_RXM_EXT && !ext))
		return -1;
	for (f = first; f <= last; f++)
		if (sim_filter_match(chip, f, n, cf))
			return f;
	return -1;
}

static void sim_rxb_load(struct sim_chip *chip, unsigned int n,
			 const struct can_frame *cf, unsigned int filhit,
			 bool rolled)
{
	u8 *b = sim_reg(chip, MCP2510_REG_RXB(n));
	bool ext = cf->can_id & CAN_EFF_FLAG, rtr = cf->can_id & CAN_RTR_FLAG;
	u32 id = ext ? cf->can_id & CAN_EFF_MASK : cf->can_id & CAN_SFF_MASK;
	u32 sid = ext ? id >> MCP2510_EID_BITS : id;
	u8 ctrl = b[MCP2510_BUF_CTRL] & ~(MCP2510_RXBCTRL_RXRTR |
					  (n ? MCP2510_RXB1CTRL_FILHIT_MASK :
					       MCP2510_RXB0CTRL_FILHIT0));
	u8 dlc = cf->len8_dlc > CAN_MAX_DLEN && cf->len == CAN_MAX_DLEN ?
		 cf->len8_dlc : cf->len;

	b[MCP2510_BUF_SIDH] = sid >> MCP2510_SID_SHIFT_SIDH;
	b[MCP2510_BUF_SIDL] = FIELD_PREP(MCP2510_SIDL_SID_MASK, sid & 7);
	b[MCP2510_BUF_EID8] = 0;
	b[MCP2510_BUF_EID0] = 0;
	if (ext) {
		b[MCP2510_BUF_SIDL] |= MCP2510_SIDL_EXIDE | ((id >> 16) & 3);
		b[MCP2510_BUF_EID8] = id >> 8;
		b[MCP2510_BUF_EID0] = id;
	} else if (rtr) {
		b[MCP2510_BUF_SIDL] |= MCP2510_SIDL_SRR;
	}
	b[MCP2510_BUF_DLC] = dlc | (ext && rtr ? MCP2510_DLC_RTR : 0);
	if (!rtr)
		memcpy(&b[MCP2510_BUF_D0], cf->data, cf->len);
	if (rtr)
		ctrl |= MCP2510_RXBCTRL_RXRTR;
	ctrl |= n ? filhit : (filhit & MCP2510_RXB0CTRL_FILHIT0);
	b[MCP2510_BUF_CTRL] = ctrl;

	chip->rx_status[n] = FIELD_PREP(MCP2515_RXSTATUS_TYPE_MASK,
					(ext ? 2 : 0) | (rtr ? 1 : 0)) |
			     (rolled ? MCP2515_RXSTATUS_FILHIT_RXF0_RB1 + filhit :
				       filhit);
	*sim_reg(chip, MCP2510_REG_CANINTF) |= MCP2510_INT_RX(n);
	chip->counters.frames_rx++;
}

bool sim_rxb_full(const struct sim_chip *chip, unsigned int n)
{
	return chip->regs[MCP2510_REG_CANINTF] & MCP2510_INT_RX(n);
}

static void sim_rx_overflow(struct sim_chip *chip, unsigned int n)
{
	*sim_reg(chip, MCP2510_REG_EFLG) |= MCP2510_EFLG_RXOVR(n);
	*sim_reg(chip, MCP2510_REG_CANINTF) |= MCP2510_INT_ERR;
	chip->counters.overflows++;
}

/*
 * The message assembly buffer holds a frame, valid or (listen-only mode)
 * destroyed by an error.  AN739: RXB0's mask and filters first, and a
 * frame RXB0 takes never reaches RXB1's filters; a full RXB0 passes it on
 * only with BUKT (FILHIT 0/1 in RXB1).  A full buffer is never
 * overwritten: RXnIF locks it and RXnOVR records the loss.
 */
static void sim_chip_take(struct sim_chip *chip, const struct can_frame *cf,
			  bool valid)
{
	int f = sim_rxb_accept(chip, 0, cf, valid);

	if (f >= 0) {
		if (!sim_rxb_full(chip, 0))
			sim_rxb_load(chip, 0, cf, f, false);
		else if (!(chip->regs[MCP2510_REG_RXBCTRL(0)] & MCP2510_RXB0CTRL_BUKT))
			sim_rx_overflow(chip, 0);
		else if (!sim_rxb_full(chip, 1))
			sim_rxb_load(chip, 1, cf, f, true);
		else
			sim_rx_overflow(chip, 1);
		return;
	}
	f = sim_rxb_accept(chip, 1, cf, valid);
	if (f < 0)
		return;
	if (sim_rxb_full(chip, 1))
		sim_rx_overflow(chip, 1);
	else
		sim_rxb_load(chip, 1, cf, f, false);
}

void sim_chip_accept(struct sim_chip *chip, const struct can_frame *cf)
{
	struct sim_chip_faults *f = &chip->faults;
	struct can_frame bad;

	if (f->rx_corrupt_every && ++f->rx_taken % f->rx_corrupt_every == 0 &&
	    cf->len) {
		bad = *cf;
		bad.data[bad.len - 1] ^= 0x01;
		cf = &bad;
	}
	sim_chip_take(chip, cf, true);
}

/* A frame arrived without error (CAN 2.0B rule 8 for REC). */
void sim_chip_rx_ok(struct sim_chip *chip, const struct can_frame *cf)
{
	if (chip->opmode == MCP2510_MODE_NORMAL) {
		if (chip->rec >= SIM_PASSIVE_LIMIT)
			chip->rec = SIM_REC_AFTER_PASSIVE;
		else if (chip->rec)
			chip->rec--;
	}
	sim_chip_accept(chip, cf);
	sim_chip_update_eflg(chip);
	sim_chip_update_pins(chip);
}

/*
 * This chip detected an error as a receiver (rule 1: REC + 1).  heard is
 * the frame the error destroyed when this chip could follow it (same bit
 * rate), else NULL.
 *
 * DS21801 10.3 (AN739 "Listen-only Mode" likewise): listen-only mode
 * receives "all messages (including messages with errors)" by setting
 * RXM to 11.  What the buffer then holds is not said; the model takes
 * the reading hardest on a driver: the frame as sent, loaded like a valid
 * one, nothing in the buffer telling it apart (MERRF is the only trace).
 */
void sim_chip_rx_error(struct sim_chip *chip, const struct can_frame *heard)
{
	*sim_reg(chip, MCP2510_REG_CANINTF) |= MCP2510_INT_MERR;
	chip->counters.rx_errors++;
	/* listen-only mode sends no error flags, its counters are inactive */
	if (chip->opmode == MCP2510_MODE_NORMAL && chip->rec < 255)
		chip->rec++;
	if (chip->opmode == MCP2510_MODE_LISTEN_ONLY && heard)
		sim_chip_take(chip, heard, false);
	sim_chip_update_eflg(chip);
	sim_chip_update_pins(chip);
}

bool sim_chip_listening(const struct sim_chip *chip)
{
	return sim_chip_ready(chip) && !chip->bus_off &&
	       (chip->opmode == MCP2510_MODE_NORMAL ||
		chip->opmode == MCP2510_MODE_LISTEN_ONLY);
}
