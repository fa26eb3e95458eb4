// SPDX-License-Identifier: GPL-2.0
/*
 * One chip's register file: what each address reads back, which bits the
 * MCU may write in which mode, the side effects of a write (TXBnCTRL,
 * CANCTRL, CANINTF, EFLG, the pin control registers) and what RESET or
 * power-on leave in the registers.
 *
 * References: DS21291 (MCP2510) sections 3, 4, 7 and 10 with the register
 * map of table 10-1 and registers 3-1..3-8, 4-1..4-17, 10-1, 10-2;
 * DS21801 (MCP2515) sections 3, 4, 7 and 11 with table 11-1; AN739.
 */
#include "sim_private.h"

#define SIM_ROW_CANSTAT		0x0e	/* CANSTAT answers at 0xXe of every row */
#define SIM_ROW_CANCTRL		0x0f	/* CANCTRL answers at 0xXf of every row */
#define SIM_FILTER_SIDL_MASK	0xeb	/* SID2..0, EXIDE, EID17..16 */
#define SIM_MASK_SIDL_MASK	0xe3	/* SID2..0, EID17..16 */
#define SIM_TXB_SIDL_MASK	0xeb
#define SIM_TXB_DLC_MASK	(MCP2510_DLC_RTR | MCP2510_DLC_MASK)
#define SIM_RXB_SIDL_MASK	0xfb	/* bit 2 unimplemented */
#define SIM_RXB_DLC_MASK	0x7f	/* bit 7 unimplemented */
#define SIM_TXBCTRL_WMASK	(MCP2510_TXBCTRL_TXREQ | MCP2510_TXBCTRL_TXP_MASK)

/* ---- Register file ------------------------------------------------------ */

u8 *sim_reg(struct sim_chip *chip, unsigned int addr)
{
	return &chip->regs[addr & SIM_ADDR_MASK];
}

static bool sim_chip_config(const struct sim_chip *chip)
{
	return chip->opmode == MCP2510_MODE_CONFIG;
}

/* DS21291 register 10-2: OPMOD and the highest-priority enabled interrupt */
static u8 sim_chip_icod(const struct sim_chip *chip)
{
	static const u8 order[] = {
		MCP2510_INT_ERR, MCP2510_INT_WAK, MCP2510_INT_TX0,
		MCP2510_INT_TX1, MCP2510_INT_TX2, MCP2510_INT_RX0,
		MCP2510_INT_RX1,
	};
	u8 pending = chip->regs[MCP2510_REG_CANINTE] &
		     chip->regs[MCP2510_REG_CANINTF];
	unsigned int i;

	for (i = 0; i < ARRAY_SIZE(order); i++)
		if (pending & order[i])
			return i + 1;
	return MCP2510_ICOD_NONE;
}

static u8 sim_chip_canstat(const struct sim_chip *chip)
{
	return FIELD_PREP(MCP2510_CANSTAT_OPMOD_MASK, chip->opmode) |
	       FIELD_PREP(MCP2510_CANSTAT_ICOD_MASK, sim_chip_icod(chip));
}

/* TXRTSCTRL.BnRTS: the pin level in input mode, 0 in request-to-send mode */
static u8 sim_chip_txrtsctrl(const struct sim_chip *chip)
{
	u8 val = chip->regs[MCP2510_REG_TXRTSCTRL];
	unsigned int n;

	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (!(val & MCP2510_TXRTSCTRL_BRTSM(n)) && chip->rts_level[n])
			val |= MCP2510_TXRTSCTRL_BRTS(n);
	return val;
}

u8 sim_reg_read(const struct sim_chip *chip, unsigned int addr)
{
	addr &= SIM_ADDR_MASK;
	if ((addr & 0x0f) == SIM_ROW_CANSTAT)
		return sim_chip_canstat(chip);
	if ((addr & 0x0f) == SIM_ROW_CANCTRL)
		return chip->regs[MCP2510_REG_CANCTRL];
	switch (addr) {
	case MCP2510_REG_TEC:
		return chip->tec > 255 ? 255 : chip->tec;
	case MCP2510_REG_REC:
		return chip->rec > 255 ? 255 : chip->rec;
	case MCP2510_REG_TXRTSCTRL:
		return sim_chip_txrtsctrl(chip);
	default:
		return chip->regs[addr];
	}
}

u8 sim_chip_peek(const struct sim_chip *chip, u8 addr)
{
	return sim_reg_read(chip, addr);
}

/* Bits of the first 0x30 addresses the MCU may write now. */
static u8 sim_ctrl_write_mask(const struct sim_chip *chip, unsigned int addr)
{
	bool config = sim_chip_config(chip);

	switch (addr) {
	case MCP2510_REG_BFPCTRL:
		return 0x3f;
	case MCP2510_REG_TXRTSCTRL:	/* DS21801 10.1: configuration mode only */
		return config ? 0x07 : 0;
	case MCP2510_REG_TEC:
	case MCP2510_REG_REC:
		return 0;
	case MCP2510_REG_CNF3:
		if (!config)
			return 0;
		return chip->variant == SIM_MCP2515 ?
		       MCP2515_CNF3_SOF | MCP2510_CNF3_WAKFIL | MCP2510_CNF3_PHSEG2_MASK :
		       MCP2510_CNF3_WAKFIL | MCP2510_CNF3_PHSEG2_MASK;
	case MCP2510_REG_CNF2:
	case MCP2510_REG_CNF1:
		return config ? 0xff : 0;
	case MCP2510_REG_CANINTE:
	case MCP2510_REG_CANINTF:
		return 0xff;
	case MCP2510_REG_EFLG:		/* only the overflow flags are R/W */
		return SIM_EFLG_OVR;
	}
	/* filters and masks, configuration mode only (AN739 "Set Bit Timing") */
	if (!config)
		return 0;
	if ((addr & 3) != MCP2510_ID_SIDL)
		return 0xff;
	return addr >= MCP2510_REG_RXM(0) ? SIM_MASK_SIDL_MASK : SIM_FILTER_SIDL_MASK;
}

static u8 sim_reg_write_mask(const struct sim_chip *chip, unsigned int addr)
{
	unsigned int off = addr & 0x0f;

	if (off == SIM_ROW_CANSTAT)
		return 0;
	if (off == SIM_ROW_CANCTRL)
		return chip->variant == SIM_MCP2515 ? 0xff :
		       (u8)~MCP2515_CANCTRL_OSM;
	if (addr < MCP2510_REG_TXB(0))
		return sim_ctrl_write_mask(chip, addr);
	if (addr < MCP2510_REG_RXB(0)) {
		unsigned int n = (addr - MCP2510_REG_TXB(0)) >> 4;

		bool pending = chip->regs[MCP2510_REG_TXBCTRL(n)] &
			       MCP2510_TXBCTRL_TXREQ;

		/* the reading of TXBnCTRL: sim_chip_faults */
		if (off == MCP2510_BUF_CTRL)
			return pending && !chip->faults.txp_writable_while_pending ?
			       MCP2510_TXBCTRL_TXREQ : SIM_TXBCTRL_WMASK;
		/* AN739: a buffer cannot be modified while TXREQ is set */
		if (pending)
			return 0;
		if (off == MCP2510_BUF_SIDL)
			return SIM_TXB_SIDL_MASK;
		if (off == MCP2510_BUF_DLC)
			return SIM_TXB_DLC_MASK;
		return 0xff;
	}
	if (off != MCP2510_BUF_CTRL)
		return 0;		/* received data is read only */
	if (addr == MCP2510_REG_RXBCTRL(0))
		return MCP2510_RXBCTRL_RXM_MASK | MCP2510_RXB0CTRL_BUKT;
	return MCP2510_RXBCTRL_RXM_MASK;
}

/* DS21801 table 12-1 / register map: registers BIT MODIFY works on */
bool sim_reg_bit_modifiable(unsigned int addr)
{
	if ((addr & 0x0f) == SIM_ROW_CANCTRL)
		return true;
	switch (addr) {
	case MCP2510_REG_BFPCTRL:
	case MCP2510_REG_TXRTSCTRL:
	case MCP2510_REG_CNF3:
	case MCP2510_REG_CNF2:
	case MCP2510_REG_CNF1:
	case MCP2510_REG_CANINTE:
	case MCP2510_REG_CANINTF:
	case MCP2510_REG_EFLG:
		return true;
	}
	/* TXBnCTRL and RXBnCTRL sit at the start of their rows */
	return addr >= MCP2510_REG_TXB(0) && (addr & 0x0f) == MCP2510_BUF_CTRL;
}

/* ---- Register writes with their side effects ---------------------------------- */

static void sim_write_txbctrl(struct sim_chip *chip, unsigned int n, u8 old)
{
	u8 *ctrl = sim_txbctrl(chip, n);
	bool was = old & MCP2510_TXBCTRL_TXREQ;
	bool now = *ctrl & MCP2510_TXBCTRL_TXREQ;

	if (!was && now) {
		*ctrl &= ~MCP2510_TXBCTRL_TXREQ;
		sim_chip_request(chip, n);
	} else if (was && !now) {
		/*
		 * DS21801 register 3-1: clearing TXREQ requests an abort; 3.4:
		 * without ABTF.  A waiting buffer is done with; the frame on
		 * the bus finishes and, failed, is not repeated.
		 */
		if (chip->tx.active && chip->tx.buf == n)
			chip->tx.abort = true;
	}
}

/*
 * DS21801 7.7: once the chip has set an interrupt flag the MCU cannot
 * clear it until the interrupt condition is removed.  The one condition
 * the data sheets name as the MCU's to remove is an overflow's RXnOVR
 * (7.6.1: "This bit must be cleared by the MCU"), so ERRIF stays while
 * an RXnOVR bit does (faults.errif_clearable_with_overflow: it does not).
 * The EFLG state bits are not such a condition: they are read only and
 * may last for ever (a lone error-passive node), and an ERRIF held by
 * them could never be acknowledged.
 */
static void sim_errif_hold(struct sim_chip *chip, u8 old)
{
	u8 *intf = sim_reg(chip, MCP2510_REG_CANINTF);

	if ((old & ~*intf & MCP2510_INT_ERR) &&
	    (chip->regs[MCP2510_REG_EFLG] & SIM_EFLG_OVR) &&
	    !chip->faults.errif_clearable_with_overflow)
		*intf |= MCP2510_INT_ERR;
}

/*
 * A write into a transmit buffer whose TXREQ is set that touches more
 * than TXREQ (clearing TXREQ is the documented abort).
 */
static bool sim_tx_pending_write(const struct sim_chip *chip,
				 unsigned int addr, u8 mask)
{
	unsigned int n;

	if (addr < MCP2510_REG_TXB(0) || addr >= MCP2510_REG_RXB(0) ||
	    (addr & 0x0f) >= MCP2510_BUF_LEN)
		return false;
	n = (addr - MCP2510_REG_TXB(0)) >> 4;
	if (!(chip->regs[MCP2510_REG_TXBCTRL(n)] & MCP2510_TXBCTRL_TXREQ))
		return false;
	if ((addr & 0x0f) == MCP2510_BUF_CTRL)
		return mask & MCP2510_TXBCTRL_TXP_MASK;
	return true;
}

void sim_reg_write(struct sim_chip *chip, unsigned int addr, u8 val,
			  u8 mask)
{
	u8 wmask, old, *reg;

	addr &= SIM_ADDR_MASK;
	if (sim_tx_pending_write(chip, addr, mask))
		chip->counters.tx_pending_writes++;
	wmask = sim_reg_write_mask(chip, addr) & mask;
	if ((addr & 0x0f) == SIM_ROW_CANCTRL)
		addr = MCP2510_REG_CANCTRL;
	reg = sim_reg(chip, addr);
	old = *reg;
	*reg = (old & ~wmask) | (val & wmask);

	if (addr == MCP2510_REG_CANCTRL) {
		if ((*reg ^ old) & MCP2510_CANCTRL_REQOP_MASK)
			sim_chip_mode_request(chip);
		if ((*reg & ~old) & MCP2510_CANCTRL_ABAT)
			sim_chip_abort_all(chip);
	} else if (addr == MCP2510_REG_CANINTF) {
		sim_errif_hold(chip, old);
		if ((*reg & ~old & MCP2510_INT_WAK) &&
		    chip->opmode == MCP2510_MODE_SLEEP)
			sim_chip_wake(chip);
	} else if (addr == MCP2510_REG_RXBCTRL(0)) {
		*reg &= ~MCP2510_RXB0CTRL_BUKT1;
		if (*reg & MCP2510_RXB0CTRL_BUKT)
			*reg |= MCP2510_RXB0CTRL_BUKT1;
	} else if (addr >= MCP2510_REG_TXB(0) && addr < MCP2510_REG_RXB(0) &&
		   (addr & 0x0f) == MCP2510_BUF_CTRL) {
		sim_write_txbctrl(chip, (addr - MCP2510_REG_TXB(0)) >> 4, old);
	}
	/* an abort may have ended what held a mode request */
	sim_chip_mode_try(chip);
}

/*
 * Bits the register legends mark "x", unknown at power-on (DS21801 and
 * DS21291 registers 3-3..3-8, 4-4..4-9 and the filter and mask registers
 * 4-10..4-17): SIDH..D7 of the transmit and receive buffers, the filters
 * and the masks.  Their unimplemented bits read 0.  Everything else
 * powers up as a number ("R/W-0" and the like).
 */
static u8 sim_unknown_mask(unsigned int addr)
{
	unsigned int off = addr & 0x0f;
	bool rx = addr >= MCP2510_REG_RXB(0);

	if (addr < MCP2510_REG_RXM(0) + 2 * MCP2510_ID_LEN) {
		if (off >= 3 * MCP2510_ID_LEN)
			return 0;	/* control registers at 0xXc..0xXf */
		if ((addr & 3) != MCP2510_ID_SIDL)
			return 0xff;
		return addr >= MCP2510_REG_RXM(0) ? SIM_MASK_SIDL_MASK :
		       SIM_FILTER_SIDL_MASK;
	}
	if (addr < MCP2510_REG_TXB(0) || off < MCP2510_BUF_SIDH ||
	    off >= MCP2510_BUF_LEN)
		return 0;
	if (off == MCP2510_BUF_SIDL)
		return rx ? SIM_RXB_SIDL_MASK : SIM_TXB_SIDL_MASK;
	if (off == MCP2510_BUF_DLC)
		return rx ? SIM_RXB_DLC_MASK : SIM_TXB_DLC_MASK;
	return 0xff;
}

/* A Weyl sequence through a 32-bit finaliser: every seed, even 0, is fine. */
static u8 sim_unknown_byte(struct sim_chip *chip)
{
	u32 z;

	chip->unknown_state += 0x9e3779b9u;
	z = chip->unknown_state;
	z = (z ^ (z >> 16)) * 0x85ebca6bu;
	z = (z ^ (z >> 13)) * 0xc2b2ae35u;
	return (z ^ (z >> 16)) >> 24;
}

/*
 * Power-on (power_on) or RESET.  The "x" registers get new garbage, or
 * with faults.reset_keeps_unknown keep theirs through a RESET; all other
 * registers take their reset values.
 */
void sim_chip_reset(struct sim_chip *chip, bool power_on)
{
	bool keep = !power_on && chip->faults.reset_keeps_unknown;
	unsigned int n, addr;

	for (addr = 0; addr < MCP2510_REG_COUNT; addr++) {
		u8 mask = sim_unknown_mask(addr);

		if (mask && !keep)
			chip->regs[addr] = sim_unknown_byte(chip) & mask;
		else
			chip->regs[addr] &= mask;
	}
	chip->regs[MCP2510_REG_CANCTRL] = chip->variant == SIM_MCP2515 ?
					  MCP2515_RESET_CANCTRL :
					  MCP2510_RESET_CANCTRL;
	chip->opmode = MCP2510_MODE_CONFIG;
	chip->mode_pending = false;
	chip->wake_pending = false;
	memset(&chip->tx, 0, sizeof(chip->tx));
	for (n = 0; n < MCP2510_RXB_COUNT; n++)
		chip->rx_status[n] = 0;
	sim_chip_clear_counters(chip);
	chip->regs[MCP2510_REG_CANINTF] = 0;	/* no ERRIF out of reset */
	chip->ready_at = chip->bus ? sim_now(chip) + sim_chip_startup_ns(chip) : 0;
}
