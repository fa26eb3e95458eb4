/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Portable MCP2510/MCP2515/MCP25625 driver core.
 *
 * Everything about the chip that is not about Linux: SPI framing, bring-up,
 * bit timing, acceptance filters, frame encoding, the ordered three-buffer
 * transmit scheduler, interrupt decoding and the error-state machine.  It is
 * compiled unchanged into the kernel module and into libmcp2510.
 *
 * The core never allocates, sleeps (other than through ops->delay_us),
 * locks or logs.  The caller serialises every call on one chip, performs
 * the SPI transfers through ops and receives what happened through events.
 * Functions return 0 (or a non-negative count) or a negative errno.
 */
#ifndef MCP2510_CORE_H
#define MCP2510_CORE_H

#include "mcp2510_compat.h"
#include <linux/can/mcp2510.h>

enum mcp2510_model {
	MCP2510_MODEL_MCP2510,
	MCP2510_MODEL_MCP2515,
	MCP2510_MODEL_MCP25625,
};

/* What differs between the chips of the family. */
struct mcp2510_variant {
	const char *name;
	enum mcp2510_model model;
	u32 spi_default_hz;		/* 5 MHz MCP2510, 10 MHz MCP2515 */
	bool has_buffer_instrs;		/* READ RX BUFFER, LOAD TX BUFFER, RX STATUS */
	bool has_one_shot;		/* CANCTRL.OSM */
	u8 reset_canctrl;		/* CANCTRL after RESET, for detection */
};

const struct mcp2510_variant *mcp2510_variant_get(enum mcp2510_model model);

/* Oscillator limits accepted by the core, in Hz (the CAN clock is half). */
#define MCP2510_OSC_MIN_HZ	1000000
#define MCP2510_OSC_MAX_HZ	25000000

/* The chip's bit-timing limits, in CAN clock (oscillator / 2) quanta. */
extern const struct can_bittiming_const mcp2510_bittiming_const;

/* One chip-select-low period of a message (see mcp2510_ops.xfer_msg). */
struct mcp2510_xfer {
	const u8 *tx;
	u8 *rx;				/* may be NULL */
	unsigned int len;
};

/*
 * How many bytes of a @len-byte period a transport sends in its first
 * transfer at @speed_hz, chip select held low into a second with the
 * rest: all of them unless two transfers keep a common controller in
 * its polling mode where one does not (spi.c).
 */
unsigned int mcp2510_xfer_first_len(unsigned int len, u32 speed_hz);

/* Most chip-select periods the core puts in one message. */
#define MCP2510_XFER_MSG_MAX	4

struct mcp2510_ops {
	/*
	 * One chip-select-low period: clock out @len bytes of @tx while
	 * storing what the chip returns in @rx (@rx may be NULL).  The core
	 * passes buffers on its stack: a transport that needs DMA-safe memory
	 * copies.  Returns 0 or a negative errno (the core reports -EIO).
	 */
	int (*xfer)(void *ctx, const u8 *tx, u8 *rx, unsigned int len);
	/*
	 * Optional: @n (at most MCP2510_XFER_MSG_MAX) chip-select-low
	 * periods in one go, chip select rising between them only for as
	 * long as the chip needs, with no other traffic and no sleep in
	 * between, so that the chip sees them microseconds apart (one
	 * spi_message).  Stops at the first period that fails.  The receive
	 * order is exact only with it: without it the core calls xfer for
	 * each period and a delay between them can let two frames in.
	 */
	int (*xfer_msg)(void *ctx, const struct mcp2510_xfer *x,
			unsigned int n);
	/* Wait at least @us microseconds; may sleep. */
	void (*delay_us)(void *ctx, unsigned int us);
};

struct mcp2510_events {
	/* A frame arrived; called in the order the chip received them. */
	void (*rx)(void *ctx, const struct can_frame *cf);
	/* The frame loaded into TX buffer @slot was sent: in queue order. */
	void (*tx_done)(void *ctx, unsigned int slot);
	/* The frame in @slot was dropped (abort, one-shot failure, restart). */
	void (*tx_aborted)(void *ctx, unsigned int slot);
	/* The error state changed, with the counters at that moment. */
	void (*state)(void *ctx, enum can_state state,
		      const struct can_berr_counter *bec);
	/*
	 * A SocketCAN error frame to deliver (CAN_ERR_FLAG set, class bits in
	 * can_id, details in data[] as <linux/can/error.h> lays out, TEC/REC
	 * in data[6..7] with CAN_ERR_CNT).  The class bits tell the caller
	 * which statistics to count.
	 */
	void (*error)(void *ctx, const struct can_frame *cf);
	/*
	 * Optional, for receive timestamps: a pass of mcp2510_irq_handle()
	 * has read the interrupt flags, and the frames it found follow,
	 * oldest first; each of them ended on the bus before this call.
	 * @first_waited: the first of them was already in the chip at every
	 * moment INT was asserted since the previous pass, so the time INT
	 * fired is after its end of frame too.  False when a flag other than
	 * a receive flag was set (an overflow's ERRIF included), without
	 * rollover, when the order of two full buffers cannot be known (see
	 * irq_rx.c), and in the first pass after a reset or a wake-up cleared
	 * flags outside the loop.  A pass that reads READ STATUS alone cannot
	 * see ERRIF, MERRF or WAKIF; after a possible overflow the next pass
	 * reads them, but an error state change or a bus error raised since
	 * the last full read may have asserted INT before the frame came
	 * (irq_flags.c reads them every few passes).
	 */
	void (*rx_pass)(void *ctx, bool first_waited);
};

/* The two masks, six filters and receive modes (see the uapi header). */
struct mcp2510_filter_id {
	u32 id;				/* 11 or 29 bit identifier */
	bool ext;			/* extended (29 bit) */
};

struct mcp2510_filters {
	struct mcp2510_filter_id mask[MCP2510_MASK_COUNT];
	struct mcp2510_filter_id filter[MCP2510_FILTER_COUNT];
	u8 rxm[MCP2510_RXB_COUNT];	/* MCP2510_RXM_* */
	bool rollover;			/* RXB0CTRL.BUKT */
};

/* Accept every frame: masks 0, both buffers filtered, rollover on. */
void mcp2510_filters_default(struct mcp2510_filters *f);
/*
 * Value of one hex digit, either case, or -1.  Inline so that text
 * parsers outside the core need not link it, and free of <ctype.h> for
 * the kernel build.
 */
static inline int mcp2510_hex_digit(char c)
{
	if (c >= '0' && c <= '9')
		return c - '0';
	if (c >= 'a' && c <= 'f')
		return c - 'a' + 10;
	if (c >= 'A' && c <= 'F')
		return c - 'A' + 10;
	return -1;
}

/* Parse "7ff" or "1fffffffx" (sysfs and CLI syntax); -EINVAL if bad. */
int mcp2510_filter_id_parse(const char *s, size_t len,
			    struct mcp2510_filter_id *out);
/* Format as above into @buf (at least 12 bytes); returns the length. */
int mcp2510_filter_id_format(const struct mcp2510_filter_id *id, char *buf);
/* Parse/format a receive mode name: filtered, std, ext, any. */
int mcp2510_rxm_parse(const char *s, size_t len, u8 *rxm);
const char *mcp2510_rxm_name(u8 rxm);

struct mcp2510_counters {
	u32 rx_overflows;		/* frames lost to a full RX buffer */
	u32 bus_errors;			/* MERRF events */
	u32 arbitration_lost;
	u32 tx_errors;			/* TXERR / aborted frames */
	u32 warnings, passives, bus_offs, restarts;
	u32 irq_loops;			/* passes through the interrupt loop */
	u32 irq_loop_bound;		/* loops stopped by the bound */
	u32 recoveries;			/* re-initialised after a health check */
};

/*
 * One chip.  The caller owns the memory (embedded in its private data),
 * fills it with mcp2510_init() and treats the fields as private.
 */
struct mcp2510_chip {
	const struct mcp2510_variant *variant;
	const struct mcp2510_ops *ops;
	const struct mcp2510_events *events;
	void *ctx;
	u32 osc_hz;
	u32 ctrlmode;			/* CAN_CTRLMODE_* in force */
	bool irq_edge;			/* INT wired to an edge-triggered input */
	enum can_state state;
	struct can_berr_counter bec;
	u32 sent_since_bec;		/* frames seen sent since bec was read */
	struct mcp2510_filters filters;
	struct mcp2510_counters counters;

	/* What mcp2510_start() programmed, for mcp2510_restart(). */
	bool started;
	u8 cnf[3];			/* CNF1, CNF2, CNF3 */
	u8 inte;			/* CANINTE in force */
	u8 opmode;			/* MCP2510_MODE_* while started */
	u32 bit_us;			/* one bit time, rounded up; 0: unknown */
	bool wake_filter;		/* CNF3.WAKFIL at start */

	/* Ordered transmit scheduler state (see tx.c). */
	struct {
		u32 seq[MCP2510_TXB_COUNT];	/* queue position per slot */
		u8 prio[MCP2510_TXB_COUNT];	/* TXP in each TXBnCTRL */
		u8 busy;			/* bit n: slot n holds a frame */
		u8 done;			/* sent, tx_done not yet raised */
		u8 prio_unknown;		/* TXBnCTRL.TXP unsure after -EIO */
		u8 staged;			/* loaded, waiting for its RTS */
		u8 unsure;			/* RTS failed, TXREQ unknown */
		u32 next_seq;
		u32 stages;			/* frames that had to be staged */
	} tx;

	/* Interrupt loop state (see irq.c). */
	struct {
		u8 passes_to_full_read;	/* countdown to reading CANINTF/EFLG */
		bool full_read_next;	/* both RX buffers were full */
		bool rx1_first;		/* RXB1 holds the older frame */
		bool flags_cleared;	/* by a reset or wake-up: see rx_pass */
		/* READ STATUS after the pass's last release, 0: none */
		u8 rx_status;
		/* a drain's poll (irq_tx.c) read this, for the next pass */
		bool tx_polled;
		u8 tx_poll_status;
	} irq;
};

int mcp2510_init(struct mcp2510_chip *chip, const struct mcp2510_variant *v,
		 u32 osc_hz, const struct mcp2510_ops *ops,
		 const struct mcp2510_events *events, void *ctx);

/* ---- frame and identifier encoding (pure, no SPI) ---- */
/* Buffer registers SIDH..D7, as READ RX BUFFER and LOAD TX BUFFER see them. */
#define MCP2510_FRAME_REGS	(MCP2510_BUF_LEN - 1)
/*
 * Encode @cf into SIDH..D7 (@regs holds MCP2510_FRAME_REGS bytes); returns
 * how many of them carry the frame (5 + data bytes): the rest need not be
 * sent.  -EINVAL for a length above 8.  With CAN_CTRLMODE_CC_LEN8_DLC in
 * @ctrlmode a length of 8 goes out with len8_dlc (9..15) as its DLC.
 */
int mcp2510_frame_encode(const struct can_frame *cf, u32 ctrlmode, u8 *regs);
/*
 * Decode SIDH..D7; a DLC above 8 gives length 8, and with
 * CAN_CTRLMODE_CC_LEN8_DLC in @ctrlmode also len8_dlc.  RTR frames carry
 * no data.
 */
void mcp2510_frame_decode(const u8 *regs, u32 ctrlmode, struct can_frame *cf);
/* SIDH, SIDL, EID8, EID0 of a filter (EXIDE for extended) or of a mask. */
void mcp2510_filter_id_encode(const struct mcp2510_filter_id *id,
			      bool is_mask, u8 regs[MCP2510_ID_LEN]);
/* Back from those four registers (a mask with EID bits is extended). */
void mcp2510_filter_id_decode(const u8 regs[MCP2510_ID_LEN], bool is_mask,
			      struct mcp2510_filter_id *id);
/* -EINVAL unless every identifier fits its width and RXM is known. */
int mcp2510_filters_check(const struct mcp2510_filters *f);

/* ---- register access (one SPI transfer each) ---- */
int mcp2510_reg_read(struct mcp2510_chip *chip, u8 addr, u8 *buf,
		     unsigned int len);
int mcp2510_reg_write(struct mcp2510_chip *chip, u8 addr, const u8 *buf,
		      unsigned int len);
int mcp2510_reg_modify(struct mcp2510_chip *chip, u8 addr, u8 mask, u8 val);
int mcp2510_read_status(struct mcp2510_chip *chip, u8 *status);

/* ---- bring-up and modes ---- */
/* RESET, start-up wait, check the chip answers: -ENODEV when it does not. */
int mcp2510_hw_reset(struct mcp2510_chip *chip);
/* Request MCP2510_MODE_*, poll CANSTAT.OPMOD: -ETIMEDOUT if it never comes. */
int mcp2510_set_mode(struct mcp2510_chip *chip, u8 mode);
int mcp2510_sleep(struct mcp2510_chip *chip);
/*
 * Wake-on-CAN.  mcp2510_wake_filter_set() chooses whether the next start
 * sets CNF3.WAKFIL (glitches on RXCAN do not wake the chip).  After
 * mcp2510_stop(), mcp2510_wake_arm() enables the wake-up interrupt alone
 * and leaves the chip asleep: the next start of frame on the bus wakes
 * it into listen-only mode (that frame is lost) and asserts INT.
 * mcp2510_wake_ack() returns 1 and clears WAKIF when the chip woke, 0
 * when it did not.  A start or restart programs the chip from scratch.
 */
void mcp2510_wake_filter_set(struct mcp2510_chip *chip, bool on);
int mcp2510_wake_arm(struct mcp2510_chip *chip);
int mcp2510_wake_ack(struct mcp2510_chip *chip);

/* ---- bit timing ---- */
/* Check @bt against the chip and AN739's rules and encode CNF1..CNF3. */
int mcp2510_bittiming_encode(const struct can_bittiming *bt, u32 ctrlmode,
			     u8 cnf[3]);
/*
 * Choose the timing the Linux kernel's calculator would choose for
 * @bt->bitrate and @bt->sample_point (tenths of a percent, 0 for the CiA
 * default) at @clock_hz (the CAN clock: oscillator / 2).  For userspace,
 * where no kernel calculator runs; the kernel module does not use it.
 * -EINVAL for a zero clock or bit rate or a sample point of 100 % or
 * more, -EDOM when the chip cannot come within 5 % of the bit rate with
 * a sample point no later than the one asked for.
 */
int mcp2510_bittiming_calc(u32 clock_hz, struct can_bittiming *bt);
/* Inverse of mcp2510_bittiming_encode(), for dumps and tests. */
void mcp2510_bittiming_decode(const u8 cnf[3], u32 osc_hz,
			      struct can_bittiming *bt);

/* ---- start/stop ---- */
/*
 * Reset, program bit timing (@bt in CAN-clock quanta as the kernel's
 * calculator fills it), filters, interrupt enables and @ctrlmode
 * (CAN_CTRLMODE_LOOPBACK, _LISTENONLY, _3_SAMPLES, _ONE_SHOT,
 * _BERR_REPORTING) and enter the operating mode.
 */
int mcp2510_start(struct mcp2510_chip *chip, const struct can_bittiming *bt,
		  u32 ctrlmode);
/* Abort pending frames (tx_aborted for each), mask interrupts, sleep. */
int mcp2510_stop(struct mcp2510_chip *chip);
/*
 * mcp2510_stop() at bus-off, where the chip would recover and send its
 * frames: when ABAT cannot be set, nothing is given up or changed and the
 * error is returned, for the caller to try again.
 */
int mcp2510_halt(struct mcp2510_chip *chip);
/*
 * Bus-off recovery or a manual restart: drop queued frames (tx_aborted),
 * reset the chip (clearing TEC/REC), program what mcp2510_start() was
 * given and enter the operating mode; a state event reports error-active.
 */
int mcp2510_restart(struct mcp2510_chip *chip);
/*
 * Check and keep masks and filters; mcp2510_start() programs them in
 * configuration mode.  -EBUSY while started, -EINVAL if @f is invalid.
 */
int mcp2510_filters_apply(struct mcp2510_chip *chip,
			  const struct mcp2510_filters *f);

/* ---- transmit ---- */
/* Free TX buffers; the caller stops its queue at 0. */
unsigned int mcp2510_tx_free(const struct mcp2510_chip *chip);
/*
 * Load @cf into a free buffer and request it; returns the slot used.
 * -EBUSY when no buffer is free, -ENETDOWN when not started, -EIO when the
 * transport failed and the frame was not sent (a buffer whose request
 * may have reached the chip is kept out of use until READ STATUS shows
 * its TXREQ clear).
 */
int mcp2510_tx_submit(struct mcp2510_chip *chip, const struct can_frame *cf);

/* ---- interrupt ---- */
#define MCP2510_IRQ_MAX_PASSES	64	/* bound of the edge-triggered loop */
/*
 * Passes one call may make while the frames keep coming (level INT): a
 * bound for the TX work and the other users of the chip lock, about
 * 3.5 ms of back-to-back frames at 1 Mbit/s.  Measured in
 * test_core_spi_gap and test_core_spi_time: 16 ends more runs in the
 * interrupt latency (pi 2x: 1954 of 2000 frames against 1975), 64 more
 * in a flags read that comes too late (the slow board: 1993 against all).
 */
#define MCP2510_IRQ_RX_PASSES	32
/*
 * READ STATUS polls for the next frame once a flood's backlog is taken:
 * enough to bridge one frame at 1 Mbit/s on a Raspberry Pi's SPI.
 */
#define MCP2510_IRQ_RX_POLLS	4
/*
 * READ STATUS polls for the end of the last frame before a drain's RTS
 * (irq_tx.c): the rest of a frame at 1 Mbit/s once its predecessor's
 * completion is handled, on a Raspberry Pi's SPI.
 */
#define MCP2510_IRQ_TX_POLLS	8
/* Read CANINTF/EFLG at least every this many passes, even under RX load. */
#define MCP2510_IRQ_FULL_READ_EVERY	8
/*
 * Handle what the chip flags, raising events.  With a level-triggered INT
 * one pass is enough (the line fires again while anything is pending),
 * but a pass that took a frame and saw the next one arrive goes on, up to
 * MCP2510_IRQ_RX_PASSES passes; the last pass of such a run polls READ
 * STATUS up to MCP2510_IRQ_RX_POLLS times for one more frame before the
 * call returns, and one that left a drain waiting for the last frame
 * polls up to MCP2510_IRQ_TX_POLLS times for its end; with chip->irq_edge
 * set it loops until
 * nothing is pending.  The loop is
 * bounded: a chip that never stops asserting returns -EAGAIN and counts an
 * irq storm.  Returns the number of flags handled.  A received frame is
 * delivered as soon as its buffer is released, oldest first; after a
 * transfer error (-EIO) the chip is asked whether the release happened,
 * so the frame is delivered either now or by a later call, not twice.
 */
int mcp2510_irq_handle(struct mcp2510_chip *chip);

/* ---- health (see health.c) ---- */
/*
 * Read back the mode, CNF1-3 and CANINTE (two transfers) and compare them
 * with what mcp2510_start() programmed: 0 when they agree (or the chip is
 * not started), -EBADMSG when the chip reset itself or reads garbage.
 * When they agree and frames are pending (or staged, or a buffer's RTS
 * had an unknown outcome), one READ STATUS more: a busy
 * buffer with neither TXREQ nor TXnIF set is given up (tx_aborted), so
 * a frame no interrupt will ever report cannot hold the queue.
 */
int mcp2510_health_check(struct mcp2510_chip *chip);
/*
 * mcp2510_restart() after a failed health check, counted in
 * counters.recoveries: frames in the TX buffers are given up (tx_aborted),
 * the chip is reset and programmed again with the same settings.
 */
int mcp2510_recover(struct mcp2510_chip *chip);

/* ---- state, dump, pins ---- */
int mcp2510_berr_counter(struct mcp2510_chip *chip,
			 struct can_berr_counter *bec);
/* Whole register file, MCP2510_REGDUMP_LEN bytes, one sequential READ. */
int mcp2510_regs_dump(struct mcp2510_chip *chip, u8 *buf);
/* RX0BF/RX1BF as outputs, TX0RTS..TX2RTS as inputs. */
int mcp2510_pin_bf_set(struct mcp2510_chip *chip, unsigned int n, bool level);
int mcp2510_pin_rts_get(struct mcp2510_chip *chip, unsigned int n);

#endif /* MCP2510_CORE_H */
