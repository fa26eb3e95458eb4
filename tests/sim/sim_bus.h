/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The CAN bus that joins the chips: its clock and events, its record of
 * every frame for a monitor, and its faults.
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
 */
#ifndef MCP2510_SIM_BUS_H
#define MCP2510_SIM_BUS_H

#include "sim_chip.h"
#include "sim_phantom.h"

#define SIM_MAX_NODES			8
/* a bus record's sender when the phantom node sent the frame */
#define SIM_NODE_PHANTOM		(-1)

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

/*
 * Per-bus faults (sim_bus_faults()).  bus_errors counts down per frame
 * corrupted; every node then detects an error, as for a CRC error.
 */
struct sim_bus_faults {
	u32 bus_errors;		/* corrupt the next N frames */
	bool no_ack;		/* no node, not even the phantom, drives the ACK slot */
};

/* ---- Bus state (members private) --------------------------------------- */

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

/* ---- Helpers shared with the tests --------------------------------------- */

/*
 * Bits the frame occupies on the wire without errors: SOF through EOF with
 * the stuff bits its actual bit pattern (incl. CRC) needs, plus the 3-bit
 * intermission.
 */
u32 sim_frame_bits(const struct can_frame *cf);

#endif /* MCP2510_SIM_BUS_H */
