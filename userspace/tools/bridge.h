/* SPDX-License-Identifier: GPL-2.0 */
/*
 * mcp2510d's forwarding between a chip and a socket that carries one
 * struct can_frame per datagram (a CAN_RAW socket in the daemon): frames
 * and error frames the chip receives go to the socket, data and remote
 * frames read from the socket go to the chip (or are dropped and counted
 * as ignored, when the chip was brought up listen-only).
 *
 * Bus-off follows the kernel's can-dev: the chip is taken off the bus
 * (it would otherwise recover by itself after 128 x 11 recessive bits)
 * and stays off until bridge_restart(), or until restart_ms have passed
 * when restart_ms is not 0.  A restart is reported on the socket with a
 * CAN_ERR_RESTARTED error frame, as can-dev's restart does.
 */
#ifndef MCP2510_BRIDGE_H
#define MCP2510_BRIDGE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>
#include <sys/socket.h>
#include <linux/can.h>

#include "mcp2510.h"

/* Frames waiting for a socket that refused them (ENOBUFS, EAGAIN). */
#define BRIDGE_OUT_QUEUE	64u
/* The waits between tries of a refused write, doubling from the first. */
#define BRIDGE_RETRY_MIN_MS	1
#define BRIDGE_RETRY_MAX_MS	64

struct bridge_counts {
	uint64_t to_socket;		/* data and remote frames written */
	uint64_t error_frames;		/* error frames written */
	uint64_t to_chip;		/* frames queued on the chip */
	uint64_t ignored;		/* error frames, bad sizes, and all
					 * frames of a listen-only chip */
	uint64_t rxq_drops;		/* lost in the socket's receive queue */
	uint64_t enobufs;		/* writes refused and tried again */
	uint64_t socket_drops;		/* lost with the write queue full */
	uint64_t chip_drops;		/* aborted by the chip, or given up
					 * at bridge_stop() */
	uint64_t bus_off_drops;		/* read from the socket while bus-off */
	uint64_t bus_offs;
	uint64_t restarts;
	uint64_t restart_failures;	/* automatic restarts that failed */
};

struct bridge {
	struct mcp2510 *h;
	int sock;
	int restart_ms;			/* 0: restart only by bridge_restart() */
	struct can_frame held;		/* read, waiting for a TX buffer */
	bool holding;
	bool bus_off;			/* the chip is off the bus */
	bool listen_only;		/* the chip never transmits */
	bool stopped;			/* by bridge_stop(): the state below */
	enum can_state last_state;	/* on the bus, before bridge_stop() */
	struct can_berr_counter last_bec;
	struct timespec restart_at;	/* CLOCK_MONOTONIC, with restart_ms */
	/* toward the socket, while it refuses frames */
	struct can_frame out[BRIDGE_OUT_QUEUE];
	unsigned int out_head, out_count;
	int retry_ms;
	struct timespec retry_at;
	uint32_t rxq_seen;		/* the socket's drop count last seen */
	struct bridge_counts counts;
};

void bridge_init(struct bridge *b, struct mcp2510 *h, int sock);
/*
 * Wait up to @timeout_ms for the chip, the socket or @stop_fd (-1: none)
 * and move what is ready; a due restart or retry is made on the way.
 * 1 when @stop_fd became readable, 0 to go on, -1 with errno on a failure
 * that ends the bridge.
 */
int bridge_poll(struct bridge *b, int stop_fd, int timeout_ms);
/*
 * Put a bus-off chip back on the bus.  -1 with EBUSY when it is not
 * bus-off, or errno from the chip (it stays bus-off; with restart_ms the
 * restart is tried again later).
 */
int bridge_restart(struct bridge *b);
/*
 * Take the chip off the bus at shutdown, counting in chip_drops every
 * frame that never went out: those the chip still held (aborted), the
 * one held for a transmit buffer and those left unread in the socket.
 * The statistics stay readable until mcp2510_close(), with the error
 * state the chip had on the bus, not the stopped chip's.
 */
void bridge_stop(struct bridge *b);
/*
 * Take a new total of frames the socket's receive queue dropped (the
 * SO_RXQ_OVFL or SO_MEMINFO value, which wraps at 2^32) into
 * counts.rxq_drops; a total older than the last one adds nothing.
 */
void bridge_rxq_total(struct bridge *b, uint32_t total);
/* The SO_RXQ_OVFL total that came with a datagram read into @msg, if any. */
void bridge_take_cmsgs(struct bridge *b, struct msghdr *msg);
/*
 * The counters as "PREFIX: stats SET: name value ..." lines, one a set,
 * with the socket's drop count brought up to date first.
 */
void bridge_print_stats(struct bridge *b, FILE *out, const char *prefix);

#endif /* MCP2510_BRIDGE_H */
