// SPDX-License-Identifier: GPL-2.0
/*
 * One MCP2510 / MCP2515: register file, SPI instruction decoding, modes,
 * transmit and receive buffers, interrupts, pins and fault confinement.
 * The bus (sim_bus.c) decides what happens on the wire and calls in here.
 *
 * References: DS21291 (MCP2510), DS21801 (MCP2515), AN739.
 */
#include "sim_private.h"

#define SIM_ADDR_MASK		0x7f	/* the address pointer has 7 bits */
#define SIM_MISO_IDLE		0xff	/* SO high impedance, pulled up */
#define SIM_ROW_CANSTAT		0x0e	/* CANSTAT answers at 0xXe of every row */
#define SIM_ROW_CANCTRL		0x0f	/* CANCTRL answers at 0xXf of every row */
#define SIM_DEFAULT_CORRUPT	0xa5
#define SIM_CORRUPT_SEED	0x2545f491u	/* any non-zero xorshift state */
#define SIM_OSC_MIN		1000U
#define SIM_OSC_MAX		100000000U

#define SIM_FILTER_SIDL_MASK	0xeb	/* SID2..0, EXIDE, EID17..16 */
#define SIM_MASK_SIDL_MASK	0xe3	/* SID2..0, EID17..16 */
#define SIM_TXB_SIDL_MASK	0xeb
#define SIM_TXB_DLC_MASK	(MCP2510_DLC_RTR | MCP2510_DLC_MASK)
#define SIM_RXB_SIDL_MASK	0xfb	/* bit 2 unimplemented */
#define SIM_RXB_DLC_MASK	0x7f	/* bit 7 unimplemented */
#define SIM_TXBCTRL_WMASK	(MCP2510_TXBCTRL_TXREQ | MCP2510_TXBCTRL_TXP_MASK)
#define SIM_TXBCTRL_FLAGS	(MCP2510_TXBCTRL_ABTF | MCP2510_TXBCTRL_MLOA | \
				 MCP2510_TXBCTRL_TXERR)
#define SIM_EFLG_STATE		(MCP2510_EFLG_TXBO | MCP2510_EFLG_TXEP | \
				 MCP2510_EFLG_RXEP | MCP2510_EFLG_TXWAR | \
				 MCP2510_EFLG_RXWAR | MCP2510_EFLG_EWARN)
#define SIM_EFLG_OVR		(MCP2510_EFLG_RX1OVR | MCP2510_EFLG_RX0OVR)

static void sim_chip_update_pins(struct sim_chip *chip);

u64 sim_now(const struct sim_chip *chip)
{
	return chip->bus ? chip->bus->now : 0;
}

/* 128 oscillator cycles, rounded up to whole nanoseconds */
u64 sim_chip_startup_ns(const struct sim_chip *chip)
{
	return sim_div_u64((u64)SIM_STARTUP_CYCLES * SIM_NS_PER_SEC +
			   chip->osc_hz - 1, chip->osc_hz);
}

/* ---- Register file ------------------------------------------------------ */

static u8 *sim_reg(struct sim_chip *chip, unsigned int addr)
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

static u8 sim_reg_read(const struct sim_chip *chip, unsigned int addr)
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
static bool sim_reg_bit_modifiable(unsigned int addr)
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

/* ---- Error state ---------------------------------------------------------- */

bool sim_chip_error_active(const struct sim_chip *chip)
{
	return chip->tec < SIM_PASSIVE_LIMIT && chip->rec < SIM_PASSIVE_LIMIT;
}

/*
 * EFLG follows the counters; ERRIF rises when an EFLG bit becomes set,
 * and with faults.errif_on_decrease also when a state bit clears (the
 * data sheets leave that open: DS21801 7.6 lists the conditions as
 * limits reached, not left).
 */
static void sim_chip_update_eflg(struct sim_chip *chip)
{
	u8 *eflg = sim_reg(chip, MCP2510_REG_EFLG);
	u8 old = *eflg, state = 0;

	if (chip->tec >= SIM_WARNING_LIMIT)
		state |= MCP2510_EFLG_TXWAR;
	if (chip->rec >= SIM_WARNING_LIMIT)
		state |= MCP2510_EFLG_RXWAR;
	if (state)
		state |= MCP2510_EFLG_EWARN;
	if (chip->tec >= SIM_PASSIVE_LIMIT)
		state |= MCP2510_EFLG_TXEP;
	if (chip->rec >= SIM_PASSIVE_LIMIT)
		state |= MCP2510_EFLG_RXEP;
	if (chip->bus_off)
		state |= MCP2510_EFLG_TXBO;
	*eflg = (old & SIM_EFLG_OVR) | state;
	if ((*eflg & ~old) ||
	    (chip->faults.errif_on_decrease && (old & ~*eflg & SIM_EFLG_STATE)))
		*sim_reg(chip, MCP2510_REG_CANINTF) |= MCP2510_INT_ERR;
}

static void sim_chip_clear_counters(struct sim_chip *chip)
{
	chip->tec = 0;
	chip->rec = 0;
	chip->bus_off = false;
	chip->recovery_count = 0;
	sim_chip_update_eflg(chip);
}

/* ---- Modes ------------------------------------------------------------------ */

static void sim_chip_enter_mode(struct sim_chip *chip, unsigned int mode)
{
	chip->opmode = mode;
	chip->mode_pending = false;
	/*
	 * DS21801 10.1: entering configuration mode clears the error
	 * counters.  DS21801 10.3: in listen-only mode they are reset and
	 * deactivated (rx_ok and rx_error count nothing there).
	 */
	if (mode == MCP2510_MODE_CONFIG || mode == MCP2510_MODE_LISTEN_ONLY)
		sim_chip_clear_counters(chip);
}

static bool sim_chip_tx_pending(const struct sim_chip *chip)
{
	unsigned int n;

	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (chip->regs[MCP2510_REG_TXBCTRL(n)] & MCP2510_TXBCTRL_TXREQ)
			return true;
	return false;
}

/*
 * DS21801 10.0: "the mode will not change until all pending message
 * transmissions are complete" (the model holds the MCP2510 to it too).
 * Pending is a frame on the bus or any buffer with TXREQ set, in the
 * modes that transmit (normal, loopback); listen-only, sleep and
 * configuration mode send nothing, so nothing there can hold a request.
 * A bus-off chip's buffers wait for the recovery:
 * faults.mode_change_in_bus_off says whether they hold the request
 * meanwhile (the data sheets do not say).  ABAT or clearing TXREQ is how
 * the MCU ends the wait.
 */
static bool sim_chip_mode_held(const struct sim_chip *chip)
{
	if (chip->tx.active)
		return true;
	if (chip->opmode != MCP2510_MODE_NORMAL &&
	    chip->opmode != MCP2510_MODE_LOOPBACK)
		return false;
	if (chip->bus_off && chip->faults.mode_change_in_bus_off)
		return false;
	return sim_chip_tx_pending(chip);
}

/* A requested mode whose time has come and that nothing holds: now. */
static void sim_chip_mode_try(struct sim_chip *chip)
{
	unsigned int req = FIELD_GET(MCP2510_CANCTRL_REQOP_MASK,
				     chip->regs[MCP2510_REG_CANCTRL]);

	if (!chip->mode_pending || sim_now(chip) < chip->mode_at ||
	    sim_chip_mode_held(chip))
		return;
	chip->mode_pending = false;
	if (req <= MCP2510_MODE_CONFIG)
		sim_chip_enter_mode(chip, req);
}

/*
 * REQOP changed.  The mode follows after faults.mode_delay_ns, once no
 * transmission is pending (sim_chip_mode_held()).  From sleep the
 * oscillator must start again first.  REQOP 5..7 is no mode (AN739: 111
 * is only valid after power-up): nothing happens.
 */
static void sim_chip_mode_request(struct sim_chip *chip)
{
	unsigned int req = FIELD_GET(MCP2510_CANCTRL_REQOP_MASK,
				     chip->regs[MCP2510_REG_CANCTRL]);
	u64 delay = chip->faults.mode_delay_ns;

	chip->mode_pending = false;
	if (req > MCP2510_MODE_CONFIG || req == chip->opmode)
		return;
	if (chip->opmode == MCP2510_MODE_SLEEP)
		delay += sim_chip_startup_ns(chip);
	chip->mode_pending = true;
	chip->mode_at = sim_now(chip) + delay;
	sim_chip_mode_try(chip);
}

/*
 * Wake-up (DS21801 10.2): bus activity or the MCU setting CANINTF.WAKIF
 * while asleep.  The oscillator restarts (128 cycles, plus the "slow
 * wake" fault), then the chip is in listen-only mode.
 */
static void sim_chip_wake(struct sim_chip *chip)
{
	if (chip->wake_pending)
		return;
	chip->wake_pending = true;
	chip->mode_pending = false;
	chip->wake_at = sim_now(chip) + sim_chip_startup_ns(chip) +
			chip->faults.wake_delay_ns;
}

/* The bus saw a start of frame. AN739: with WAKIE clear a sleeping chip sleeps on. */
void sim_chip_bus_activity(struct sim_chip *chip)
{
	if (!chip->powered || chip->opmode != MCP2510_MODE_SLEEP ||
	    !(chip->regs[MCP2510_REG_CANINTE] & MCP2510_INT_WAK))
		return;
	chip->regs[MCP2510_REG_CANINTF] |= MCP2510_INT_WAK;
	sim_chip_wake(chip);
	sim_chip_update_pins(chip);
}

/* ---- Bit timing ------------------------------------------------------------- */

/* IPT: the information processing time after the sample point, in quanta */
#define SIM_IPT_TQ	2

/*
 * DS21291 section 5: TQ = 2 (BRP + 1) / Fosc; a bit is SyncSeg (1 TQ) +
 * PropSeg + PS1 + PS2; with BTLMODE clear PS2 is the greater of PS1 and
 * the information processing time (2 TQ).
 *
 * The rules (DS21291 5.8, DS21801 5.3 "Programming Time Segments":
 * "Prop Seg + Phase Seg 1 >= Phase Seg 2", "Phase Seg 2 > Sync Jump
 * Width"; AN739 "Rules for setting the bit time": "PS2 >= IPT ... The
 * IPT = 2 TQ so PS2(min) = 2 TQ", and CNF3's PHSEG2 "from 2 - 8 TQ").
 * The data sheets' third rule, PropSeg + PS1 >= TDELAY, always holds on
 * the model's bus, which has no propagation delay.  SAM (three samples,
 * "should only be used at slower bus rates", AN739 CNF2) and the BRP are
 * not restricted by any rule the data sheets state.
 */
void sim_chip_timing(const struct sim_chip *chip, struct sim_timing *t)
{
	u8 cnf1 = chip->regs[MCP2510_REG_CNF1];
	u8 cnf2 = chip->regs[MCP2510_REG_CNF2];
	u8 cnf3 = chip->regs[MCP2510_REG_CNF3];
	u32 brp = FIELD_GET(MCP2510_CNF1_BRP_MASK, cnf1) + 1;
	u32 prseg = FIELD_GET(MCP2510_CNF2_PRSEG_MASK, cnf2) + 1;
	u32 ps1 = FIELD_GET(MCP2510_CNF2_PHSEG1_MASK, cnf2) + 1;
	u32 sjw = FIELD_GET(MCP2510_CNF1_SJW_MASK, cnf1) + 1;
	u32 ps2, cycles;

	if (cnf2 & MCP2510_CNF2_BTLMODE)
		ps2 = FIELD_GET(MCP2510_CNF3_PHSEG2_MASK, cnf3) + 1;
	else
		ps2 = ps1 > SIM_IPT_TQ ? ps1 : SIM_IPT_TQ;
	t->nbt = 1 + prseg + ps1 + ps2;
	t->ps1 = ps1;
	t->ps2 = ps2;
	t->sjw = sjw;
	t->valid = ps2 >= SIM_IPT_TQ && prseg + ps1 >= ps2 && ps2 > sjw;
	cycles = 2 * brp * t->nbt;
	t->ns = sim_div_u64((u64)cycles * SIM_NS_PER_SEC + chip->osc_hz / 2,
			    chip->osc_hz);
}

u32 sim_chip_bit_ns(const struct sim_chip *chip)
{
	struct sim_timing t;

	sim_chip_timing(chip, &t);
	return t.ns;
}

bool sim_chip_timing_valid(const struct sim_chip *chip)
{
	struct sim_timing t;

	sim_chip_timing(chip, &t);
	return t.valid;
}

u32 sim_chip_bitrate(const struct sim_chip *chip)
{
	struct sim_timing t;

	sim_chip_timing(chip, &t);
	if (!t.valid || !t.ns)
		return 0;
	return (SIM_NS_PER_SEC + t.ns / 2) / t.ns;
}

/* ---- Transmit ----------------------------------------------------------------- */

static u8 *sim_txbctrl(struct sim_chip *chip, unsigned int n)
{
	return sim_reg(chip, MCP2510_REG_TXBCTRL(n));
}

/* AN739 "Buffer priority": highest TXP, then the higher buffer number. */
static int sim_chip_pick_buffer(const struct sim_chip *chip)
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

static void sim_chip_tec_add(struct sim_chip *chip, unsigned int n)
{
	chip->tec += n;
	if (chip->tec >= SIM_BUS_OFF_LIMIT && !chip->bus_off) {
		chip->bus_off = true;
		chip->recovery_count = 0;
		chip->recovery_idle_since = sim_now(chip);
		chip->counters.bus_off++;
	}
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
static void sim_chip_request(struct sim_chip *chip, unsigned int n)
{
	u8 *ctrl = sim_txbctrl(chip, n);

	if (*ctrl & MCP2510_TXBCTRL_TXREQ)
		return;
	/* setting TXREQ starts a new attempt: old outcome flags go */
	*ctrl = (*ctrl & ~SIM_TXBCTRL_FLAGS) | MCP2510_TXBCTRL_TXREQ;
}

/* ABAT set: every pending buffer not on the bus now is aborted. */
static void sim_chip_abort_all(struct sim_chip *chip)
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

static bool sim_rxb_full(const struct sim_chip *chip, unsigned int n)
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

static void sim_chip_accept(struct sim_chip *chip, const struct can_frame *cf)
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

/* ---- Loopback: frames go round inside the chip ----------------------------- */

static void sim_chip_loopback_start(struct sim_chip *chip, unsigned int buf)
{
	struct can_frame cf;

	sim_chip_tx_frame(chip, buf, &cf);
	sim_chip_tx_start(chip, buf);
	chip->tx.loopback = true;
	chip->tx.end_at = sim_now(chip) +
			  (u64)sim_frame_bits(&cf) * sim_chip_bit_ns(chip);
}

static void sim_chip_loopback_end(struct sim_chip *chip)
{
	struct can_frame cf;

	sim_chip_tx_frame(chip, chip->tx.buf, &cf);
	sim_chip_tx_end(chip, true, false);
	sim_chip_accept(chip, &cf);
	sim_chip_update_pins(chip);
}

/* ---- Bus-off recovery (CAN 2.0B: 128 x 11 recessive bits) ------------------ */

static u64 sim_chip_recovery_at(const struct sim_chip *chip)
{
	u64 seq_ns = (u64)SIM_RECOVERY_BITS * sim_chip_bit_ns(chip);

	return chip->recovery_idle_since +
	       (u64)(SIM_RECOVERY_SEQUENCES - chip->recovery_count) * seq_ns;
}

static void sim_chip_recover(struct sim_chip *chip)
{
	sim_chip_clear_counters(chip);
	sim_chip_update_pins(chip);
}

/* The bus was idle from recovery_idle_since to until. */
void sim_chip_recovery_account(struct sim_chip *chip, u64 until)
{
	u32 seq_ns = SIM_RECOVERY_BITS * sim_chip_bit_ns(chip);

	if (!chip->bus_off || until <= chip->recovery_idle_since)
		return;
	chip->recovery_count += sim_div_u64(until - chip->recovery_idle_since,
					    seq_ns);
	chip->recovery_idle_since = until;
}

/* A frame ended: its tail (ACK delimiter, EOF, intermission) is 11 recessive bits. */
void sim_chip_recovery_frame(struct sim_chip *chip, u64 end)
{
	if (!chip->bus_off)
		return;
	chip->recovery_count++;
	chip->recovery_idle_since = end;
	if (chip->recovery_count >= SIM_RECOVERY_SEQUENCES)
		sim_chip_recover(chip);
}

/* ---- Events ------------------------------------------------------------------- */

u64 sim_chip_next_event(const struct sim_chip *chip)
{
	u64 now = sim_now(chip), t = U64_MAX;

	if (!chip->powered)
		return t;
	if (now < chip->ready_at)
		return chip->ready_at;
	if (chip->mode_pending && !sim_chip_mode_held(chip))
		t = sim_min_u64(t, chip->mode_at);
	if (chip->wake_pending)
		t = sim_min_u64(t, chip->wake_at);
	if (chip->tx.active && chip->tx.loopback)
		t = sim_min_u64(t, chip->tx.end_at);
	else if (!chip->tx.active && chip->opmode == MCP2510_MODE_LOOPBACK &&
		 sim_chip_pick_buffer(chip) >= 0)
		t = now;
	if (chip->bus_off && chip->bus && !sim_bus_busy(chip->bus))
		t = sim_min_u64(t, sim_chip_recovery_at(chip));
	return t < now ? now : t;
}

void sim_chip_run_events(struct sim_chip *chip)
{
	u64 now = sim_now(chip);
	int buf;

	if (!sim_chip_ready(chip))
		return;
	if (chip->wake_pending && now >= chip->wake_at) {
		chip->wake_pending = false;
		chip->regs[MCP2510_REG_CANCTRL] &= ~MCP2510_CANCTRL_REQOP_MASK;
		chip->regs[MCP2510_REG_CANCTRL] |=
			FIELD_PREP(MCP2510_CANCTRL_REQOP_MASK, MCP2510_MODE_LISTEN_ONLY);
		sim_chip_enter_mode(chip, MCP2510_MODE_LISTEN_ONLY);
	}
	if (chip->tx.active && chip->tx.loopback && now >= chip->tx.end_at)
		sim_chip_loopback_end(chip);
	sim_chip_mode_try(chip);
	if (!chip->tx.active && chip->opmode == MCP2510_MODE_LOOPBACK) {
		buf = sim_chip_pick_buffer(chip);
		if (buf >= 0)
			sim_chip_loopback_start(chip, buf);
	}
	if (chip->bus_off && chip->bus && !sim_bus_busy(chip->bus) &&
	    now >= sim_chip_recovery_at(chip))
		sim_chip_recover(chip);
	sim_chip_update_pins(chip);
}

/* ---- Pins ---------------------------------------------------------------------- */

static bool sim_chip_pin_level(const struct sim_chip *chip, enum sim_pin pin)
{
	u8 bfp = chip->regs[MCP2510_REG_BFPCTRL];
	unsigned int n;

	if (pin == SIM_PIN_INT && chip->faults.int_stuck)
		return false;	/* shorted to ground: not even power loss helps */
	if (!chip->powered)
		return true;	/* nothing drives the pins; pull-ups win */
	if (pin == SIM_PIN_INT)
		return !(chip->regs[MCP2510_REG_CANINTE] &
			 chip->regs[MCP2510_REG_CANINTF]);
	n = pin == SIM_PIN_RX0BF ? 0 : 1;
	if (!(bfp & MCP2510_BFPCTRL_BFE(n)))
		return true;	/* disabled: high impedance */
	if (bfp & MCP2510_BFPCTRL_BFM(n))
		return !sim_rxb_full(chip, n);
	return bfp & MCP2510_BFPCTRL_BFS(n);
}

static void sim_chip_update_pins(struct sim_chip *chip)
{
	unsigned int pin;

	for (pin = 0; pin < SIM_PIN_COUNT; pin++) {
		bool level = sim_chip_pin_level(chip, pin);

		if (level == chip->pin_level[pin])
			continue;
		chip->pin_level[pin] = level;
		if (pin == SIM_PIN_INT && !level)
			chip->counters.interrupts++;
		if (chip->pin_cb)
			chip->pin_cb(chip->pin_ctx, chip, pin, level);
	}
}

bool sim_chip_pin(const struct sim_chip *chip, enum sim_pin pin)
{
	return pin < SIM_PIN_COUNT ? chip->pin_level[pin] : true;
}

void sim_chip_set_pin_cb(struct sim_chip *chip,
			 void (*cb)(void *ctx, struct sim_chip *chip,
				    enum sim_pin pin, bool level),
			 void *ctx)
{
	chip->pin_cb = cb;
	chip->pin_ctx = ctx;
}

/* DS21291 register 3-2: a falling edge requests TXBn in RTS mode. */
void sim_chip_set_rts(struct sim_chip *chip, unsigned int n, bool level)
{
	bool fall;

	if (n >= MCP2510_TXB_COUNT)
		return;
	fall = chip->rts_level[n] && !level;
	chip->rts_level[n] = level;
	if (fall && sim_chip_ready(chip) &&
	    (chip->regs[MCP2510_REG_TXRTSCTRL] & MCP2510_TXRTSCTRL_BRTSM(n)))
		sim_chip_request(chip, n);
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

static void sim_reg_write(struct sim_chip *chip, unsigned int addr, u8 val,
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

/* ---- SPI ------------------------------------------------------------------------ */

static u8 sim_read_status(const struct sim_chip *chip)
{
	u8 intf = chip->regs[MCP2510_REG_CANINTF], s = 0;
	unsigned int n;

	if (intf & MCP2510_INT_RX0)
		s |= MCP2510_STATUS_RX0IF;
	if (intf & MCP2510_INT_RX1)
		s |= MCP2510_STATUS_RX1IF;
	for (n = 0; n < MCP2510_TXB_COUNT; n++) {
		if (chip->regs[MCP2510_REG_TXBCTRL(n)] & MCP2510_TXBCTRL_TXREQ)
			s |= MCP2510_STATUS_TXREQ(n);
		if (intf & MCP2510_INT_TX(n))
			s |= MCP2510_STATUS_TXIF(n);
	}
	return s;
}

/* DS21801 figure 12-9 */
static u8 sim_rx_status(const struct sim_chip *chip)
{
	u8 rxif = chip->regs[MCP2510_REG_CANINTF] & MCP2510_INT_RX_ALL;
	u8 s = rxif << 6;

	if (rxif & MCP2510_INT_RX0)
		s |= chip->rx_status[0];
	else if (rxif & MCP2510_INT_RX1)
		s |= chip->rx_status[1];
	return s;
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
static void sim_chip_reset(struct sim_chip *chip, bool power_on)
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

/* Sequential READ / WRITE through the 7-bit address pointer (wraps 7f -> 00). */
static void sim_spi_read_seq(struct sim_chip *chip, unsigned int addr,
			     u8 *rx, size_t from, size_t len)
{
	size_t i;

	for (i = from; i < len; i++, addr++)
		if (rx)
			rx[i] = sim_reg_read(chip, addr);
}

static void sim_spi_write_seq(struct sim_chip *chip, unsigned int addr,
			      const u8 *tx, size_t from, size_t len)
{
	size_t i;

	for (i = from; i < len; i++, addr++)
		sim_reg_write(chip, addr, tx[i], 0xff);
}

static void sim_spi_repeat(u8 *rx, size_t len, u8 val)
{
	size_t i;

	for (i = 1; rx && i < len; i++)
		rx[i] = val;
}

/* One instruction; returns false when the chip does not know it. */
static bool sim_spi_execute(struct sim_chip *chip, const u8 *tx, u8 *rx,
			    size_t len)
{
	bool mcp2515 = chip->variant == SIM_MCP2515;
	u8 instr = tx[0];
	unsigned int n;

	switch (instr) {
	case MCP2510_INSTR_RESET:
		sim_chip_reset(chip, false);
		return true;
	case MCP2510_INSTR_READ:
		if (len > 2)
			sim_spi_read_seq(chip, tx[1], rx, 2, len);
		return true;
	case MCP2510_INSTR_WRITE:
		if (len > 2)
			sim_spi_write_seq(chip, tx[1], tx, 2, len);
		return true;
	case MCP2510_INSTR_BIT_MODIFY:
		/* CS raised before the data byte is complete: nothing changes */
		if (len >= 4)
			sim_reg_write(chip, tx[1] & SIM_ADDR_MASK, tx[3],
				      sim_reg_bit_modifiable(tx[1] & SIM_ADDR_MASK) ?
				      tx[2] : 0xff);
		return true;
	case MCP2510_INSTR_READ_STATUS:
		sim_spi_repeat(rx, len, sim_read_status(chip));
		return true;
	case MCP2515_INSTR_RX_STATUS:
		if (!mcp2515)
			return false;
		sim_spi_repeat(rx, len, sim_rx_status(chip));
		return true;
	}
	if ((instr & ~MCP2510_RTS_ALL) == MCP2510_INSTR_RTS) {
		for (n = 0; n < MCP2510_TXB_COUNT; n++)
			if (instr & MCP2510_RTS_TXB(n))
				sim_chip_request(chip, n);
		return true;
	}
	if (mcp2515 && (instr & ~0x06) == MCP2515_INSTR_READ_RX_BUFFER) {
		n = (instr >> 2) & 1;
		sim_spi_read_seq(chip, MCP2510_REG_RXB(n) +
				 ((instr & 0x02) ? MCP2510_BUF_D0 : MCP2510_BUF_SIDH),
				 rx, 1, len);
		/* RXnIF clears when CS goes high */
		*sim_reg(chip, MCP2510_REG_CANINTF) &= ~MCP2510_INT_RX(n);
		return true;
	}
	if (mcp2515 && (instr & ~0x07) == MCP2515_INSTR_LOAD_TX_BUFFER &&
	    (instr & 0x07) < 6) {
		n = (instr & 0x07) >> 1;
		sim_spi_write_seq(chip, MCP2510_REG_TXB(n) +
				  ((instr & 1) ? MCP2510_BUF_D0 : MCP2510_BUF_SIDH),
				  tx, 1, len);
		return true;
	}
	return false;
}

/* xorshift32 (Marsaglia): cheap, and the same bytes on every run */
static u8 sim_corrupt_random(struct sim_chip_faults *f)
{
	u32 x = f->spi_corrupt_seed ? f->spi_corrupt_seed : SIM_CORRUPT_SEED;

	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	f->spi_corrupt_seed = x;
	return x >> 24;
}

static u8 sim_corrupt_byte(struct sim_chip_faults *f, u8 answer)
{
	switch (f->spi_corrupt_kind) {
	case SIM_CORRUPT_FIXED:
		return f->spi_corrupt_byte;
	case SIM_CORRUPT_RANDOM:
		return sim_corrupt_random(f);
	default:
		return answer ^ (f->spi_corrupt_xor ? f->spi_corrupt_xor :
				 SIM_DEFAULT_CORRUPT);
	}
}

static void sim_spi_corrupt(struct sim_chip *chip, u8 *rx, size_t len)
{
	struct sim_chip_faults *f = &chip->faults;
	size_t i;

	if (!f->spi_corrupt)
		return;
	if (f->spi_corrupt != SIM_CORRUPT_FOREVER)
		f->spi_corrupt--;
	for (i = 0; rx && i < len; i++)
		rx[i] = sim_corrupt_byte(f, rx[i]);
}

void sim_chip_spi(struct sim_chip *chip, const u8 *tx, u8 *rx, size_t len)
{
	chip->counters.spi_transfers++;
	chip->counters.spi_bytes += len;
	if (rx)
		memset(rx, SIM_MISO_IDLE, len);
	if (!len || !tx || !sim_chip_ready(chip) ||
	    !sim_spi_execute(chip, tx, rx, len))
		chip->counters.spi_ignored++;
	if (len && chip->powered)
		sim_spi_corrupt(chip, rx, len);
	sim_chip_update_pins(chip);
}

/* ---- Life cycle and inspection ----------------------------------------------------- */

int sim_chip_init(struct sim_chip *chip, enum sim_variant variant, u32 osc_hz)
{
	return sim_chip_init_seeded(chip, variant, osc_hz, SIM_DEFAULT_SEED);
}

int sim_chip_init_seeded(struct sim_chip *chip, enum sim_variant variant,
			 u32 osc_hz, u32 seed)
{
	unsigned int i;

	if ((variant != SIM_MCP2510 && variant != SIM_MCP2515) ||
	    osc_hz < SIM_OSC_MIN || osc_hz > SIM_OSC_MAX)
		return -EINVAL;
	memset(chip, 0, sizeof(*chip));
	chip->node = -1;
	chip->variant = variant;
	chip->osc_hz = osc_hz;
	chip->powered = true;
	for (i = 0; i < MCP2510_TXB_COUNT; i++)
		chip->rts_level[i] = true;
	for (i = 0; i < SIM_PIN_COUNT; i++)
		chip->pin_level[i] = true;
	chip->unknown_state = seed;
	sim_chip_reset(chip, true);
	return 0;
}

void sim_chip_power(struct sim_chip *chip, bool on)
{
	if (on == chip->powered)
		return;
	chip->powered = on;
	if (on)
		sim_chip_reset(chip, true);
	else
		memset(&chip->tx, 0, sizeof(chip->tx));
	sim_chip_update_pins(chip);
}

void sim_chip_reset_pin(struct sim_chip *chip)
{
	if (!chip->powered)
		return;
	sim_chip_reset(chip, false);
	sim_chip_update_pins(chip);
}

void sim_chip_refresh_pins(struct sim_chip *chip)
{
	sim_chip_update_pins(chip);
}

const struct sim_counters *sim_chip_counters(const struct sim_chip *chip)
{
	return &chip->counters;
}

struct sim_chip_faults *sim_chip_faults(struct sim_chip *chip)
{
	return &chip->faults;
}

unsigned int sim_chip_opmode(const struct sim_chip *chip)
{
	return chip->opmode;
}

unsigned int sim_chip_tec(const struct sim_chip *chip)
{
	return chip->tec;
}

unsigned int sim_chip_rec(const struct sim_chip *chip)
{
	return chip->rec;
}

bool sim_chip_bus_off(const struct sim_chip *chip)
{
	return chip->bus_off;
}
