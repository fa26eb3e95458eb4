/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The phantom node: a bus participant with no chip behind it, which
 * acknowledges, sends queued frames and floods the bus (sim_phantom.c).
 */
#ifndef MCP2510_SIM_PHANTOM_H
#define MCP2510_SIM_PHANTOM_H

#include "mcp2510_compat.h"

#define SIM_PHANTOM_QUEUE		16

struct sim_bus;

/* state inside struct sim_bus (members private) */
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

#endif /* MCP2510_SIM_PHANTOM_H */
