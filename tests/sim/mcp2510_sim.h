/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Register-accurate model of the Microchip MCP2510 / MCP2515 CAN controller
 * and of the CAN bus that joins several of them.
 *
 * The model is plain C11 with no allocation and no libc beyond memcpy and
 * memset, so the same source runs under cmocka, behind the userspace
 * transport and inside the simulated-SPI kernel module.  Every object is
 * allocated by the caller; the struct members are private by convention
 * (read them only through the functions below).
 *
 * Time: the bus owns a clock in nanoseconds.  SPI transfers happen
 * instantly at the current bus time; sim_bus_advance() runs everything that
 * takes time (start-up after reset, mode changes, frames, error frames,
 * bus-off recovery, wake-up) as discrete events.  Nothing happens between
 * calls, so a harness jumps to sim_bus_next_event() or advances by the time
 * a real driver would have waited.
 *
 * Transmit requests made within the first bit of a start of frame
 * contend in one arbitration: the start of frame goes out at the first
 * sim_bus_advance() after the request (or when the bus goes idle),
 * never inside the SPI call that made it, and the arbitration is decided
 * one bit later.  Callbacks (pins, monitor) run inside
 * sim_bus_advance() and may do SPI transfers; a nested sim_bus_advance()
 * from a callback does nothing.  Nothing here locks: one caller at a time.
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
 *
 * tests/sim/README.md lists every choice the data sheets leave open and
 * what is not modelled.
 */
#ifndef MCP2510_SIM_H
#define MCP2510_SIM_H

#include "mcp2510_compat.h"
#include <linux/can/mcp2510.h>

#define SIM_MAX_NODES			8
#define SIM_PHANTOM_QUEUE		16
#define SIM_STARTUP_CYCLES		128
/* the seed of sim_chip_init(): any value will do */
#define SIM_DEFAULT_SEED		0x6d2b79f5u
/* a bus record's sender when the phantom node sent the frame */
#define SIM_NODE_PHANTOM		(-1)

enum sim_variant { SIM_MCP2510, SIM_MCP2515 };

/* Output pins, active low: a level of true means the pin is high. */
enum sim_pin { SIM_PIN_INT, SIM_PIN_RX0BF, SIM_PIN_RX1BF, SIM_PIN_COUNT };

struct sim_bus;
struct sim_chip;

/* ---- Bus monitor ------------------------------------------------------- */

enum sim_record_kind {
	SIM_REC_FRAME,		/* a frame went through without error */
	SIM_REC_ERROR,		/* a frame was destroyed by an error frame */
};

enum sim_error_cause {
	SIM_ERR_NONE,
	SIM_ERR_ACK,		/* nobody acknowledged (transmitter's ACK error) */
	SIM_ERR_BITRATE,	/* a node at another bit rate flagged the frame */
	SIM_ERR_INJECTED,	/* sim_bus_faults.bus_errors */
	SIM_ERR_SENDER_LOST,	/* the sender was reset or lost power mid-frame */
};

struct sim_bus_record {
	enum sim_record_kind kind;
	enum sim_error_cause cause;
	int sender;		/* node index (sim_bus_attach order) or SIM_NODE_PHANTOM */
	struct can_frame frame;	/* can_id carries CAN_EFF_FLAG / CAN_RTR_FLAG */
	u32 bitrate;		/* the sender's bit rate, bit/s, rounded */
	u32 bits;		/* bit times the bus was busy, incl. intermission */
	u64 start_ns;		/* start of frame */
	u64 end_ns;		/* end of intermission: the bus is free again */
	bool acked;
};

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

/*
 * Per-bus faults (sim_bus_faults()).  bus_errors counts down per frame
 * corrupted; every node then detects an error, as for a CRC error.
 */
struct sim_bus_faults {
	u32 bus_errors;		/* corrupt the next N frames */
	bool no_ack;		/* no node, not even the phantom, drives the ACK slot */
};

/* ---- Objects (members private) ------------------------------------------ */

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

/*
 * A node's bit timing as far as the bus needs it: bit time, the lengths
 * the CAN oscillator-tolerance conditions use, and whether CNF1-3 obey
 * the data sheets' rules.  nbt 0: an ideal node (the phantom), which
 * tolerates whatever the node it talks to tolerates.
 */
struct sim_timing {
	u32 ns;				/* bit time */
	u8 nbt, ps1, ps2, sjw;		/* time quanta */
	bool valid;
};

struct sim_phantom {
	bool attached;
	u32 bitrate;			/* 0: the first chip's */
	struct can_frame queue[SIM_PHANTOM_QUEUE];
	u32 queue_rate[SIM_PHANTOM_QUEUE];	/* bit time, ns */
	unsigned int head, count;
	struct can_frame flood;		/* template of the flood in progress */
	u32 flood_rate;			/* bit time, ns */
	u32 flood_left, flood_sent;
	bool flood_checked;		/* bytes 4-7 carry a CRC-32 */
};

struct sim_bus {
	u64 now;
	struct sim_chip *chips[SIM_MAX_NODES];
	unsigned int nchips;
	/* the frame on the bus */
	bool busy;
	u64 busy_until;
	struct sim_bus_record cur;
	int cur_sender;
	struct sim_timing cur_tm;	/* the sender's bit timing */
	u32 cur_listeners;		/* nodes listening at start of frame (bit per node) */
	/* a start of frame on the bus, its arbitration still open */
	bool sof;
	u64 sof_at;
	u32 sof_ns;			/* bit time of the node that sent it */
	struct sim_phantom phantom;
	struct sim_bus_faults faults;
	void (*monitor)(void *ctx, const struct sim_bus_record *rec);
	void *monitor_ctx;
	bool advancing;			/* inside sim_bus_advance*() */
};

/* ---- Bus ---------------------------------------------------------------- */

void sim_bus_init(struct sim_bus *bus);
/* Returns 0, -ENOSPC when SIM_MAX_NODES chips are attached, -EBUSY if attached. */
int sim_bus_attach(struct sim_bus *bus, struct sim_chip *chip);
/*
 * Run bus time forward by ns, processing every event on the way (work is
 * proportional to the events, not to the time: an idle bus jumps).
 */
void sim_bus_advance(struct sim_bus *bus, u64 ns);
/* Run bus time forward to an absolute time (no-op if in the past). */
void sim_bus_advance_to(struct sim_bus *bus, u64 when);
u64 sim_bus_now(const struct sim_bus *bus);
/* Absolute time of the next scheduled change, U64_MAX when nothing is pending. */
u64 sim_bus_next_event(const struct sim_bus *bus);
bool sim_bus_idle(const struct sim_bus *bus);
/* fn runs at the end of every frame or error frame on the bus (not loopback). */
void sim_bus_set_monitor(struct sim_bus *bus,
			 void (*fn)(void *ctx, const struct sim_bus_record *rec),
			 void *ctx);
struct sim_bus_faults *sim_bus_faults(struct sim_bus *bus);

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

/* ---- Phantom node: a bus participant with no chip ---------------------- */

/*
 * The phantom acknowledges every frame sent at its bit rate (bitrate 0:
 * whatever the first attached chip uses at the time), transmits with
 * normal arbitration, retries after errors and never leaves error-active.
 * A node at another bit rate makes it send error frames, like any node.
 */
void sim_phantom_attach(struct sim_bus *bus, u32 bitrate);
void sim_phantom_detach(struct sim_bus *bus);
/* Queue one frame (attaches the phantom).  0, -ENOSPC, -EINVAL. */
int sim_phantom_send(struct sim_bus *bus, const struct can_frame *cf, u32 bitrate);
/*
 * Send count frames back to back at bus speed.  Frame k (from 0) is cf
 * with its first min(len, 4) data bytes, read as a little-endian number,
 * increased by k, so the frames are distinguishable; identifier and length
 * stay.  Queued frames go first.  0, -EBUSY (a flood runs), -EINVAL.
 */
int sim_phantom_flood(struct sim_bus *bus, const struct can_frame *cf,
		      u32 count, u32 bitrate);
/*
 * The same with every frame checkable end to end: bytes 4-7 of frame k
 * are the CRC-32 (reflected, polynomial 0xEDB88320) of the identifier and
 * of bytes 0-3, each as four bytes little-endian, as can-flood
 * (tests/vm/guest) checks them.  @cf must have eight data bytes.
 */
int sim_phantom_flood_checked(struct sim_bus *bus, const struct can_frame *cf,
			      u32 count, u32 bitrate);
/* Frames the phantom still has to send, queue and flood together. */
u32 sim_phantom_pending(const struct sim_bus *bus);

/* ---- SPI time ------------------------------------------------------------ */

/*
 * The model's transfers take no time of their own; a harness that wants
 * SPI to cost what it costs on a board keeps one struct sim_spi_bus per
 * SPI controller and asks it when each chip-select-low period ends.  The
 * chip then acts (sim_chip_spi()) at that time, when CS rises.  A message
 * is one or more periods: its host overhead comes first, then per period
 * CS setup, each transfer's cost (sim_spi_xfer_ns()), CS hold.  Messages
 * to any chip on the controller queue behind each other.  With enabled
 * false everything happens at the time asked for, as without this.
 *
 * The costs follow a controller driver like spi-bcm2835 under the SPI
 * core (docs/performance.md gives each profile's figures and sources):
 * every transfer pays the driver's set-up; bytes take 8 clocks plus
 * idle_clocks; a transfer of at least speed / poll_hz_per_byte bytes runs
 * interrupt-driven and pays a thread wake-up, one of at least dma_min_len
 * bytes runs by DMA (no idle clock) and pays dma_ns.  Wake-ups and
 * interrupt latency are drawn from a distribution with the given median
 * and 99th percentile and a tail beyond (sim_spi_draw()), from the bus's
 * seeded generator, so a run repeats for a seed.
 */
struct sim_spi_timing {
	bool enabled;
	u32 msg_ns;		/* host cost of one message: queueing, set-up, completion */
	u32 cs_setup_ns;	/* CS falling edge to the first SCK edge */
	u32 cs_hold_ns;		/* last SCK edge to CS rising, plus CS high time */
	u32 ctlr_max_hz;	/* the controller's fastest SCK; 0: no limit of its own */
	u32 irq_latency_ns;	/* INT falling to the hard interrupt handler: median */
	u32 irq_latency_p99_ns;	/* its 99th percentile; <= median: constant */
	u32 wake_ns;		/* a handler thread waking after its interrupt: median */
	u32 wake_p99_ns;	/* its 99th percentile; <= median: constant */
	u32 xfer_ns;		/* the controller driver's set-up of one transfer */
	u32 idle_clocks;	/* idle SCK cycles after each byte (not by DMA) */
	u32 poll_hz_per_byte;	/* interrupt-driven from speed / this bytes; 0: never */
	u32 dma_min_len;	/* DMA from this many bytes; 0: never */
	u32 dma_ns;		/* DMA set-up and completion of one transfer */
};

struct sim_spi_bus {
	struct sim_spi_timing timing;
	u64 free_at;		/* the last message handed to the bus ends here */
	u32 rng;		/* the draws' generator state; see sim_spi_seed() */
};

/* One message under way on a struct sim_spi_bus. */
struct sim_spi_msg {
	u64 start;		/* when it got the bus */
	u64 at;			/* end of its last period so far */
};

/* Timing off, bus free, generator at seed 0. */
void sim_spi_bus_init(struct sim_spi_bus *sb);
/* Restart the draws: the same seed gives the same sequence. */
void sim_spi_seed(struct sim_spi_bus *sb, u32 seed);
/* The fastest SCK the chip's data sheet allows: 5 MHz MCP2510, 10 MHz MCP2515. */
u32 sim_chip_sck_max_hz(const struct sim_chip *chip);
/*
 * The clock a transfer asking for speed_hz runs at: no faster than the
 * controller and the chip allow (speed_hz 0: as fast as they allow).
 */
u32 sim_spi_speed_hz(const struct sim_spi_timing *t, u32 speed_hz,
		     u32 chip_max_hz);
/*
 * SCK time of len bytes at that clock, 8 + idle_clocks cycles a byte,
 * rounded up to whole ns; 0 when off.
 */
u64 sim_spi_clock_ns(const struct sim_spi_timing *t, u32 len, u32 speed_hz,
		     u32 chip_max_hz);
/* How the controller runs a transfer of len bytes at speed_hz. */
enum sim_spi_xfer_mode {
	SIM_SPI_POLL,
	SIM_SPI_IRQ,
	SIM_SPI_DMA,
};
enum sim_spi_xfer_mode sim_spi_xfer_mode(const struct sim_spi_timing *t,
					 u32 len, u32 speed_hz,
					 u32 chip_max_hz);
/*
 * One transfer inside a CS-low period: set-up, SCK time and, by its
 * mode, a drawn wake-up or the DMA cost; 0 when off.
 */
u64 sim_spi_xfer_ns(struct sim_spi_bus *sb, u32 len, u32 speed_hz,
		    u32 chip_max_hz);
/* A message wants the bus at now: it starts when the bus is free, after its overhead. */
void sim_spi_msg_begin(struct sim_spi_bus *sb, struct sim_spi_msg *m, u64 now);
/* The next CS-low period, xfer_ns of transfers: returns when CS rises. */
u64 sim_spi_msg_period(const struct sim_spi_bus *sb, struct sim_spi_msg *m,
		       u64 xfer_ns);
/* The message is done: the bus is free at m->at; the chip is charged for it. */
void sim_spi_msg_end(struct sim_spi_bus *sb, struct sim_spi_msg *m,
		     struct sim_chip *chip);
/*
 * One draw from a distribution with this median and 99th percentile:
 * piecewise uniform, half from median / 2 to the median, 49 % up to the
 * 99th percentile, 1 % on to 4 times that (the tail).  p99 <= median:
 * always the median.  *rng advances.
 */
u32 sim_spi_draw(u32 *rng, u32 median, u32 p99);
/* INT falling to the handler thread running: a drawn latency plus wake-up. */
u64 sim_spi_irq_latency_ns(const struct sim_spi_timing *t, u32 *rng);
/* When an interrupt whose line was asserted at asserted_at reaches its handler. */
u64 sim_spi_irq_due(struct sim_spi_bus *sb, u64 asserted_at);

/*
 * Board profiles (sim_spi_profile.c, docs/performance.md): every time
 * constant multiplied by scale_pct / 100 (clock rates and thresholds
 * stay).  SIM_SPI_PROFILE_NONE turns SPI time off.
 */
enum sim_spi_profile {
	SIM_SPI_PROFILE_NONE,
	SIM_SPI_PROFILE_PI,
	SIM_SPI_PROFILE_PI_RT,
	SIM_SPI_PROFILE_SLOW,
	SIM_SPI_PROFILE_COUNT
};

#define SIM_SPI_SCALE_MIN_PCT	10
#define SIM_SPI_SCALE_MAX_PCT	1000
/* 0, or -EINVAL for an unknown profile or a scale out of range. */
int sim_spi_profile_timing(unsigned int profile, u32 scale_pct,
			   struct sim_spi_timing *t);
/* "none", "pi", "pi-rt", "slow"; NULL past the end. */
const char *sim_spi_profile_name(unsigned int profile);
/* The profile called name (len bytes, no NUL needed), or -EINVAL. */
int sim_spi_profile_find(const char *name, size_t len);

/* ---- Helpers shared with the tests --------------------------------------- */

/*
 * Bits the frame occupies on the wire without errors: SOF through EOF with
 * the stuff bits its actual bit pattern (incl. CRC) needs, plus the 3-bit
 * intermission.
 */
u32 sim_frame_bits(const struct can_frame *cf);

#endif /* MCP2510_SIM_H */
