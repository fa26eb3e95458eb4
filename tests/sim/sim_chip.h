/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The simulated chip: its registers and state, its faults and counters,
 * and what a harness does with it (SPI transfers, pins, power, reset,
 * inspection without side effects).
 *
 * Start-up: after power-on or a RESET instruction (taking effect when chip
 * select rises) the chip is not ready for 128 oscillator cycles
 * (SIM_STARTUP_CYCLES, DS21291 "oscillator start-up timer", AN739
 * "wait the required oscillator startup time").  During that time a
 * transfer is ignored: it has no effect and MISO reads 0xff (the pin is
 * high impedance and the board's pull-up wins).  Advance the bus by
 * sim_chip_startup_ns() before talking to a freshly reset chip.
 *
 * Unknown instructions (including the MCP2515-only ones on an MCP2510) and
 * unpowered chips behave the same way: no effect, MISO reads 0xff.
 */
#ifndef MCP2510_SIM_CHIP_H
#define MCP2510_SIM_CHIP_H

#include "mcp2510_compat.h"
#include <linux/can/mcp2510.h>

#define SIM_STARTUP_CYCLES		128
/* the seed of sim_chip_init(): any value will do */
#define SIM_DEFAULT_SEED		0x6d2b79f5u

enum sim_variant { SIM_MCP2510, SIM_MCP2515 };

/* Output pins, active low: a level of true means the pin is high. */
enum sim_pin { SIM_PIN_INT, SIM_PIN_RX0BF, SIM_PIN_RX1BF, SIM_PIN_COUNT };

struct sim_bus;

/* ---- Counters and faults ------------------------------------------------ */

struct sim_counters {
	u64 spi_transfers;	/* chip-select-low periods */
	u64 spi_bytes;
	u64 spi_ignored;	/* transfers with no effect: start-up, unpowered, unknown */
	u64 frames_tx;		/* frames sent without error */
	u64 frames_rx;		/* frames stored in a receive buffer */
	u64 interrupts;		/* falling edges of INT */
	u64 overflows;		/* frames lost because both candidate buffers were full */
	u64 tx_errors;		/* error frames suffered as transmitter */
	u64 rx_errors;		/* errors detected as receiver */
	u64 arbitration_lost;
	u64 bus_off;		/* entries into bus-off */
	u64 spi_busy_ns;	/* SPI bus time taken by this chip's messages (SPI time on) */
	u64 tx_pending_writes;	/* writes to a TX buffer with TXREQ set, other than of TXREQ alone */
};

/* What a corrupted transfer returns on MISO. */
enum sim_corrupt_kind {
	SIM_CORRUPT_FLIP,	/* the chip's answer with spi_corrupt_xor's bits flipped */
	SIM_CORRUPT_FIXED,	/* spi_corrupt_byte in every byte: a shorted line */
	SIM_CORRUPT_RANDOM,	/* pseudo-random bytes: a floating or noisy line */
};

/* spi_corrupt value that never counts down: garbage until set to 0 */
#define SIM_CORRUPT_FOREVER	U32_MAX

/*
 * Per-chip faults.  Write the fields directly (sim_chip_faults()); the
 * model decrements spi_corrupt as it uses it up.  After changing int_stuck
 * call sim_chip_refresh_pins(), so the pin follows at once.
 */
struct sim_chip_faults {
	u32 spi_corrupt;	/* the next N transfers return garbage on MISO */
	enum sim_corrupt_kind spi_corrupt_kind;
	u8 spi_corrupt_xor;	/* which bits flip in every MISO byte; 0 means 0xa5 */
	u8 spi_corrupt_byte;	/* SIM_CORRUPT_FIXED's byte */
	u32 spi_corrupt_seed;	/* SIM_CORRUPT_RANDOM's state; 0 starts a fixed sequence */
	bool int_stuck;		/* INT held low whatever CANINTE and CANINTF say */
	u64 wake_delay_ns;	/* "slow wake": extra time from wake-up cause to listen-only */
	u64 mode_delay_ns;	/* "slow mode change": REQOP write to CANSTAT.OPMOD */
	/*
	 * Not a fault but a reading of the data sheets, which want TXREQ
	 * clear before a transmit buffer is written and count TXBnCTRL as
	 * part of the buffer, yet abort by clearing TXREQ.  false (the
	 * default, the harsher reading): while TXREQ is set only TXREQ
	 * itself can be written, a TXP write changes nothing.  true: TXP
	 * stays writable.  Either way SIDH..D7 are locked, and every
	 * attempt counts in sim_counters.tx_pending_writes.
	 */
	bool txp_writable_while_pending;
	/*
	 * More readings the data sheets leave open; false (the default) is
	 * the one that helps a driver least.
	 *
	 * mode_change_in_bus_off: a mode request waits while any TXREQ is
	 * set (DS21801 10.0).  A bus-off chip cannot send its pending
	 * buffers until it has recovered: false, the request still waits
	 * for them (sent after the recovery, or aborted); true, a bus-off
	 * chip changes mode at once and the buffers stay pending.
	 */
	bool mode_change_in_bus_off;
	/*
	 * abtf_on_one_shot: whether a failed or lost one-shot attempt sets
	 * ABTF (DS21801 3.4 only says the attempt is not repeated).  false:
	 * TXREQ clears with TXERR or MLOA alone; true: ABTF as well.
	 */
	bool abtf_on_one_shot;
	/*
	 * errif_on_decrease: whether ERRIF fires when an EFLG state bit
	 * clears (warning gone, error-passive to error-active, recovery from
	 * bus-off).  false: only a bit being set raises it, so a driver
	 * that reads EFLG only on ERRIF never sees the way back; true: any
	 * change of the state bits raises it.
	 */
	bool errif_on_decrease;
	/*
	 * errif_clearable_with_overflow: DS21801 7.7 lets the MCU clear a
	 * flag the chip set only once its condition is removed.  An
	 * overflow's condition is RXnOVR, which the MCU must clear
	 * (7.6.1).  false: ERRIF cannot be cleared while an RXnOVR bit is
	 * set; true: it can, in any order.
	 */
	bool errif_clearable_with_overflow;
	/*
	 * Another reading: the register legends give only the value at
	 * power-on, where the buffers, filters and masks are "x"
	 * (unknown), and say of RESET no more than that it restores "the
	 * default state".  false (the default, the harsher reading): RESET
	 * leaves new garbage in them, as power-on does.  true: RESET
	 * leaves them as they were.
	 */
	bool reset_keeps_unknown;
	/*
	 * A broken receive path, for proving that a test notices one: every
	 * Nth frame the chip takes into a receive buffer has the lowest bit
	 * of its last data byte flipped (0: never).  rx_taken counts them.
	 */
	u32 rx_corrupt_every;
	u32 rx_taken;
};

/* ---- Chip state (members private) -------------------------------------- */

struct sim_tx_state {
	bool active;		/* a frame of this chip is on the bus or in the loop */
	bool loopback;		/* ... inside the chip (loopback mode) */
	bool abort;		/* aborted while in flight: do not retry */
	bool abort_abat;	/* ... and by ABAT, which sets ABTF */
	u8 buf;			/* which TX buffer */
	u64 end_at;		/* loopback: when the frame is complete */
};

struct sim_chip {
	struct sim_bus *bus;
	int node;			/* index on the bus, -1 when not attached */
	enum sim_variant variant;
	u32 osc_hz;
	bool powered;
	u8 regs[MCP2510_REG_COUNT];
	u64 ready_at;			/* end of start-up */
	/* operating mode */
	u8 opmode;			/* what CANSTAT.OPMOD shows */
	bool mode_pending;
	u64 mode_at;			/* when a requested mode takes effect */
	bool wake_pending;
	u64 wake_at;
	/* fault confinement */
	u16 tec;			/* reaches 256 internally: bus-off */
	u16 rec;
	bool bus_off;
	u32 recovery_count;		/* sequences of 11 recessive bits seen in bus-off */
	u64 recovery_idle_since;	/* start of idle time not yet counted */
	/* transmit and receive */
	struct sim_tx_state tx;
	u8 rx_status[MCP2510_RXB_COUNT];	/* RX STATUS bits 4:0 per buffer */
	/* pins */
	bool rts_level[MCP2510_TXB_COUNT];
	bool pin_level[SIM_PIN_COUNT];
	void (*pin_cb)(void *ctx, struct sim_chip *chip, enum sim_pin pin, bool level);
	void *pin_ctx;
	struct sim_chip_faults faults;
	struct sim_counters counters;
	u32 unknown_state;		/* generator of the power-up garbage */
};

/* ---- Chip --------------------------------------------------------------- */

/*
 * Power-on state, powered.  The start-up time runs from sim_bus_attach()
 * (a chip on no bus has no clock and is ready at once).  osc_hz must be
 * 1 kHz..100 MHz, else -EINVAL.  Call it once per chip, before
 * sim_bus_attach(): it forgets the bus (use sim_chip_power() or the RESET
 * instruction to reset an attached chip).
 */
int sim_chip_init(struct sim_chip *chip, enum sim_variant variant, u32 osc_hz);
/*
 * The same with the seed of the garbage the registers marked "x" (transmit
 * and receive buffers, filters, masks) hold after power-on and RESET.
 * Every seed gives its own fixed garbage, so runs repeat; give every chip
 * of a bus its own.  sim_chip_init() uses SIM_DEFAULT_SEED.
 */
int sim_chip_init_seeded(struct sim_chip *chip, enum sim_variant variant,
			 u32 osc_hz, u32 seed);
/* One chip-select-low period: len bytes out on MOSI (tx), in on MISO (rx, may be NULL). */
void sim_chip_spi(struct sim_chip *chip, const u8 *tx, u8 *rx, size_t len);
bool sim_chip_pin(const struct sim_chip *chip, enum sim_pin pin);
void sim_chip_set_pin_cb(struct sim_chip *chip,
			 void (*cb)(void *ctx, struct sim_chip *chip,
				    enum sim_pin pin, bool level),
			 void *ctx);
/* Drive the TXnRTS input n (0..2); the pins have pull-ups, so true is idle. */
void sim_chip_set_rts(struct sim_chip *chip, unsigned int n, bool level);
/* Power loss: MISO reads 0xff, pins float high.  Power on: reset state and start-up. */
void sim_chip_power(struct sim_chip *chip, bool on);
/*
 * A pulse on the RESET pin (a brown-out, a glitch): the same as the RESET
 * instruction, registers to their defaults, configuration mode, start-up.
 */
void sim_chip_reset_pin(struct sim_chip *chip);
/* Bring the pins up to date after a change of faults that drive them. */
void sim_chip_refresh_pins(struct sim_chip *chip);
const struct sim_counters *sim_chip_counters(const struct sim_chip *chip);
struct sim_chip_faults *sim_chip_faults(struct sim_chip *chip);

/* Read-only inspection, no side effects (not an SPI transfer). */
u8 sim_chip_peek(const struct sim_chip *chip, u8 addr);
unsigned int sim_chip_opmode(const struct sim_chip *chip);	/* MCP2510_MODE_* */
unsigned int sim_chip_tec(const struct sim_chip *chip);		/* 0..256+ */
unsigned int sim_chip_rec(const struct sim_chip *chip);
bool sim_chip_bus_off(const struct sim_chip *chip);
bool sim_chip_ready(const struct sim_chip *chip);		/* start-up over, powered */
u64 sim_chip_startup_ns(const struct sim_chip *chip);		/* 128 osc cycles */
/*
 * Bit rate from CNF1-3 and the oscillator, bit/s rounded; 0 when CNF1-3
 * break the data sheets' bit timing rules (sim_chip_timing_valid()): the
 * chip still clocks its bits, but cannot communicate.
 */
u32 sim_chip_bitrate(const struct sim_chip *chip);
/*
 * CNF1-3 obey DS21291 5.8 / DS21801 5.3 "Programming Time Segments" and
 * AN739's rules: PS2 >= 2 TQ (the information processing time),
 * PRSEG + PS1 >= PS2, PS2 > SJW.
 */
bool sim_chip_timing_valid(const struct sim_chip *chip);

#endif /* MCP2510_SIM_CHIP_H */
