// SPDX-License-Identifier: GPL-2.0
/*
 * One chip's operating modes and pins: mode requests and when they take
 * effect, sleep and wake-up, the INT, RXnBF and TXnRTS pins, power and
 * the RESET pin, and the model's life cycle and inspection calls.
 *
 * References: DS21291 sections 3.5 (TXnRTS), 4.4 (RXnBF), 7 (interrupts),
 * 9 (modes of operation) and 10 (register 10-1 CANCTRL, 10-2 CANSTAT);
 * DS21801 sections 3.5, 4.4, 7, 10 (modes, 10.2 sleep and wake-up) and
 * 11; AN739 "Listen-only Mode" and REQOP.
 */
#include "sim_private.h"

#define SIM_OSC_MIN		1000U
#define SIM_OSC_MAX		100000000U

/* ---- Modes ------------------------------------------------------------------ */

void sim_chip_enter_mode(struct sim_chip *chip, unsigned int mode)
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
bool sim_chip_mode_held(const struct sim_chip *chip)
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
void sim_chip_mode_try(struct sim_chip *chip)
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
void sim_chip_mode_request(struct sim_chip *chip)
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
void sim_chip_wake(struct sim_chip *chip)
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

void sim_chip_update_pins(struct sim_chip *chip)
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
