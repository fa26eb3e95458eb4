/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * libmcp2510: the MCP2510 / MCP2515 / MCP25625 driver core in userspace.
 *
 * A handle drives one chip through a transport named by a string:
 *
 *   "spidev:/dev/spidevB.C"  the chip on a Linux spidev device; its INT
 *                            pin on a GPIO line ("gpiochipN:LINE" in the
 *                            options) or, without one, polled.
 *   "sim"                    a simulated chip in this process, on a bus
 *                            of its own with an always-acknowledging
 *                            phantom node, so a lone node's frames go out.
 *   "sim:NAME"               a simulated chip on the in-process bus NAME,
 *                            shared with every other handle opened on
 *                            "sim:NAME" and without a phantom: the chips
 *                            acknowledge each other.  Simulated time runs
 *                            only while a handle on the bus waits.
 *
 * Errors: functions return -1 (or NULL) and set errno.  The handle is not
 * thread-safe: serialise every call on one handle.  Only the functions
 * below are exported; the driver core inside the library is not.
 *
 * Events (received frames, completed transmissions, state changes, error
 * frames) queue in a fixed ring inside the handle; mcp2510_recv() takes
 * them out, handling the chip's interrupts while it waits.  When the ring
 * is full new events are dropped and counted in
 * mcp2510_stats.ring_overflows.
 *
 * Compatibility: the structs below keep their size and the places of
 * their fields for as long as the soname stays libmcp2510.so.0.  A later
 * version adds fields by taking them from the reserved space at the end
 * of a struct.  What a program passes in must have that space zeroed (the
 * _init and _default functions do; designated initialisers do), else the
 * call fails with EINVAL: an older library refuses a setting it does not
 * know rather than ignore it.  What the library fills in has it zeroed.
 */
#ifndef LIBMCP2510_H
#define LIBMCP2510_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <time.h>
/*
 * struct timespec comes with C11's or POSIX's <time.h>; a strict C99
 * program (-std=c99, no _POSIX_C_SOURCE) gets it from glibc's own header
 * (glibc 2.26 and later; <time.h> has defined __GLIBC__ by here).
 */
#if (!defined(__STDC_VERSION__) || __STDC_VERSION__ < 201112L) && \
	defined(__GLIBC__)
#include <bits/types/struct_timespec.h>
#endif
#include <linux/can.h>
#include <linux/can/netlink.h>

#ifdef __cplusplus
extern "C" {
#endif

struct mcp2510;

#define MCP2510_EXPORT __attribute__((visibility("default")))

#define MCP2510_DEFAULT_OSC_HZ		16000000u
#define MCP2510_DEFAULT_POLL_MS		2u
#define MCP2510_DEFAULT_TX_TIMEOUT_MS	1000
#define MCP2510_EVENT_RING_SIZE		64u
#define MCP2510_REGS_LEN		128u
/* The version of this header; mcp2510_version() is the library's. */
#define MCP2510_VERSION			"0.1.0"
/* The oscillators the library accepts (EINVAL otherwise). */
#define MCP2510_OSC_HZ_MIN		1000000u
#define MCP2510_OSC_HZ_MAX		25000000u

struct mcp2510_options {
	const char *variant;		/* "mcp2510" (NULL), "mcp2515", "mcp25625" */
	uint32_t osc_hz;		/* oscillator; the CAN clock is half */
	uint32_t spi_hz;		/* 0: 5 MHz MCP2510, 10 MHz MCP2515/25625 */
	uint8_t spi_mode;		/* 0 or 3 */
	const char *int_line;		/* "gpiochipN:LINE" or NULL: poll */
	unsigned int poll_ms;		/* polling interval without INT line */
	int tx_timeout_ms;		/* blocking send; -1 waits forever */
	bool no_reset;			/* spidev: leave a running chip alone */
	uint64_t reserved[8];		/* zero */
};

/* Fill @o with the defaults above. */
MCP2510_EXPORT
void mcp2510_options_init(struct mcp2510_options *o);

/*
 * Open the transport and check that a chip answers (ENODEV if not: a
 * MISO line stuck low or high, no power, no oscillator).  The chip is
 * reset into configuration mode, its reset values checked and a
 * configuration register written and read back, so a handle starts from
 * a known state; unless no_reset asks to look at a chip that another
 * program drives (register dump, state) without disturbing it: then the
 * mode registers must make sense and a transmit buffer's data byte must
 * read back what is written (its value is restored).  A "sim" chip is
 * new at every open.  ENOTTY: the device is not a spidev device.
 * An open that resets keeps the acceptance filters the chip held if they
 * were programmed since its last reset (RXM or BUKT set: a chip set to
 * filtered receive modes without rollover cannot be told from a fresh
 * one and gets the default).  @o may be NULL for the defaults.
 */
MCP2510_EXPORT
struct mcp2510 *mcp2510_open(const char *transport,
			     const struct mcp2510_options *o);
MCP2510_EXPORT
void mcp2510_close(struct mcp2510 *h);

/* Hardware reset; the handle forgets nothing it was told (bit rate...). */
MCP2510_EXPORT
int mcp2510_reset(struct mcp2510 *h);

/* ---- configuration: only while stopped (EBUSY otherwise) ------------- */

/*
 * Bit rate in bit/s, sample point in tenths of a percent (0: the CiA
 * recommendation), chosen as the Linux kernel's calculator would.
 * ERANGE/EINVAL when the oscillator cannot make it.
 */
MCP2510_EXPORT
int mcp2510_set_bitrate(struct mcp2510 *h, uint32_t bitrate,
			uint32_t sample_point);
/* Explicit timing: prop_seg, phase_seg1, phase_seg2, sjw and brp or tq. */
MCP2510_EXPORT
int mcp2510_set_bittiming(struct mcp2510 *h, const struct can_bittiming *bt);
/* The timing in force, all fields filled; ENODATA before any was set. */
MCP2510_EXPORT
int mcp2510_get_bittiming(const struct mcp2510 *h, struct can_bittiming *bt);

/*
 * CAN_CTRLMODE_LOOPBACK, _LISTENONLY, _3_SAMPLES, _BERR_REPORTING and,
 * where the chip has it (not the MCP2510), _ONE_SHOT.  EOPNOTSUPP for
 * anything else.
 */
MCP2510_EXPORT
int mcp2510_set_ctrlmode(struct mcp2510 *h, uint32_t ctrlmode);
MCP2510_EXPORT
uint32_t mcp2510_get_ctrlmode(const struct mcp2510 *h);

/* Hardware acceptance filters, as the sysfs interface describes them. */
struct mcp2510_hw_id {
	uint32_t id;			/* 11 or 29 bit identifier */
	bool ext;			/* 29 bit */
};

struct mcp2510_hw_filters {
	struct mcp2510_hw_id mask[2];	/* RXB0, RXB1 */
	struct mcp2510_hw_id filter[6];	/* 0-1 for RXB0, 2-5 for RXB1 */
	uint8_t rxm[2];			/* MCP2510_RXM_* of <mcp2510/registers.h> */
	bool rollover;
	uint32_t reserved[4];		/* zero */
};

/* The default: every frame accepted. */
MCP2510_EXPORT
void mcp2510_hw_filters_default(struct mcp2510_hw_filters *f);
/*
 * Stopped only.  On a handle that reset the chip they are written to it
 * at once, so they stay for the next program that opens it.
 */
MCP2510_EXPORT
int mcp2510_set_filters(struct mcp2510 *h, const struct mcp2510_hw_filters *f);
MCP2510_EXPORT
int mcp2510_get_filters(const struct mcp2510 *h, struct mcp2510_hw_filters *f);
/*
 * Change one setting by its sysfs name and value ("mask0" "7ff",
 * "filter3" "1234x", "rxm1" "std", "rollover" "0"); EINVAL if either is
 * bad.  Only @f changes.
 */
MCP2510_EXPORT
int mcp2510_hw_filters_set(struct mcp2510_hw_filters *f, const char *name,
			   const char *value);
/* Format setting @i (0 .. MCP2510_HW_FILTER_SETTINGS-1) as "name value". */
#define MCP2510_HW_FILTER_SETTINGS	11
MCP2510_EXPORT
int mcp2510_hw_filters_format(const struct mcp2510_hw_filters *f,
			      unsigned int i, char *buf, size_t len);

/* ---- running ---------------------------------------------------------- */

/* Program everything and join the bus (like "ip link set up"); ENODATA
 * without a bit rate. */
MCP2510_EXPORT
int mcp2510_up(struct mcp2510 *h);
/* Leave the bus; pending frames are aborted (MCP2510_EVENT_TX_ABORTED). */
MCP2510_EXPORT
int mcp2510_down(struct mcp2510 *h);
/* Bus-off recovery by hand. */
MCP2510_EXPORT
int mcp2510_bus_restart(struct mcp2510 *h);
MCP2510_EXPORT
bool mcp2510_is_up(const struct mcp2510 *h);

#define MCP2510_SEND_NONBLOCK	0x1u

/*
 * Queue @cf on one of the three transmit buffers; frames leave in the
 * order they were sent.  With all three busy: EAGAIN under
 * MCP2510_SEND_NONBLOCK, else wait up to tx_timeout_ms (ETIMEDOUT).
 * ENETDOWN when not started.
 */
MCP2510_EXPORT
int mcp2510_send(struct mcp2510 *h, const struct can_frame *cf,
		 unsigned int flags);
/* Free transmit buffers (0..3). */
MCP2510_EXPORT
unsigned int mcp2510_tx_room(const struct mcp2510 *h);

enum mcp2510_event_type {
	MCP2510_EVENT_RX,		/* frame: the received frame */
	MCP2510_EVENT_TX_DONE,		/* frame: the frame that was sent */
	MCP2510_EVENT_TX_ABORTED,	/* frame: the frame that was dropped */
	MCP2510_EVENT_STATE,		/* state, bec */
	MCP2510_EVENT_ERROR		/* frame: a SocketCAN error frame */
};

struct mcp2510_event {
	enum mcp2510_event_type type;
	struct timespec ts;		/* CLOCK_REALTIME when it was queued */
	struct can_frame frame;
	enum can_state state;
	struct can_berr_counter bec;
	uint64_t reserved[4];		/* zero */
};

/*
 * Take the oldest event, handling interrupts for up to @timeout_ms
 * (0: only what is pending now, -1: forever) while none is queued.
 * Returns 0, or -1 with ETIMEDOUT (EAGAIN for timeout 0).
 */
MCP2510_EXPORT
int mcp2510_recv(struct mcp2510 *h, struct mcp2510_event *ev, int timeout_ms);
/*
 * A descriptor that polls readable (POLLIN) while mcp2510_recv() has
 * something to do: an event queued or the chip's interrupt asserted.
 */
MCP2510_EXPORT
int mcp2510_fd(const struct mcp2510 *h);

/* ---- inspection ------------------------------------------------------- */

/*
 * Error state and counters.  For a chip this handle did not bring up
 * (opened with no_reset), the state its registers show.
 */
MCP2510_EXPORT
int mcp2510_state(struct mcp2510 *h, enum can_state *state,
		  struct can_berr_counter *bec);
MCP2510_EXPORT
const char *mcp2510_state_name(enum can_state state);

/* The whole register file, MCP2510_REGS_LEN bytes, index = address. */
MCP2510_EXPORT
int mcp2510_read_regs(struct mcp2510 *h, uint8_t *regs);
/* "CNF1", "TXB0D3", ... for every address below MCP2510_REGS_LEN. */
#define MCP2510_REG_NAME_MAX	12
MCP2510_EXPORT
int mcp2510_reg_name(unsigned int addr, char *buf, size_t len);

struct mcp2510_stats {
	uint64_t spi_transfers;		/* chip-select-low periods */
	uint64_t spi_bytes;
	uint64_t interrupts;		/* INT assertions serviced */
	uint64_t rx_frames;
	uint64_t tx_frames;
	uint32_t ring_overflows;	/* events lost to a full ring */
	uint32_t rx_overflows;		/* frames lost inside the chip */
	uint32_t bus_errors;
	uint32_t arbitration_lost;
	uint32_t tx_errors;
	uint32_t warnings, passives, bus_offs, restarts;
	uint64_t reserved[8];		/* zero */
};

MCP2510_EXPORT
int mcp2510_stats(const struct mcp2510 *h, struct mcp2510_stats *s);
/* The library's version ("0.1.0"), which may be newer than its header's. */
MCP2510_EXPORT
const char *mcp2510_version(void);
/* "mcp2510", "mcp2515" or "mcp25625". */
MCP2510_EXPORT
const char *mcp2510_variant_name(const struct mcp2510 *h);
MCP2510_EXPORT
uint32_t mcp2510_osc_hz(const struct mcp2510 *h);

/*
 * Timing for @bitrate (and @sample_point, 0 for the default) at the
 * oscillator @osc_hz, with the chip's CNF1..CNF3 encoding; needs no chip.
 */
MCP2510_EXPORT
int mcp2510_bittiming_for(uint32_t osc_hz, uint32_t bitrate,
			  uint32_t sample_point, struct can_bittiming *bt,
			  uint8_t cnf[3]);

#ifdef __cplusplus
}
#endif

#endif /* LIBMCP2510_H */
