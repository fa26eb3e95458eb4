/* SPDX-License-Identifier: GPL-2.0 */
/*
 * mcp2510d's forwarding between a chip and a socket that carries one
 * struct can_frame per datagram (a CAN_RAW socket in the daemon): frames
 * and error frames the chip receives go to the socket, data and remote
 * frames read from the socket go to the chip.
 */
#ifndef MCP2510_BRIDGE_H
#define MCP2510_BRIDGE_H

#include <stdbool.h>
#include <stdint.h>
#include <linux/can.h>

#include "mcp2510.h"

struct bridge_counts {
	uint64_t to_socket;		/* frames and error frames written */
	uint64_t to_chip;		/* frames queued on the chip */
	uint64_t socket_drops;		/* the socket refused a frame */
	uint64_t chip_drops;		/* the chip aborted a frame */
	uint64_t ignored;		/* error frames and bad sizes read */
};

struct bridge {
	struct mcp2510 *h;
	int sock;
	struct can_frame held;		/* read, waiting for a TX buffer */
	bool holding;
	struct bridge_counts counts;
};

void bridge_init(struct bridge *b, struct mcp2510 *h, int sock);
/*
 * Wait up to @timeout_ms for the chip, the socket or @stop_fd (-1: none)
 * and move what is ready.  1 when @stop_fd became readable, 0 to go on,
 * -1 with errno on a failure that ends the bridge.
 */
int bridge_poll(struct bridge *b, int stop_fd, int timeout_ms);

#endif /* MCP2510_BRIDGE_H */
