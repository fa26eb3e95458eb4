/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * A simulated bus shared by processes ("sim:NAME@BUS"): a broker process
 * owns the bus model of tests/sim and runs it at wall-clock pace; each
 * handle reaches its chip there over a unix socket (SOCK_SEQPACKET, one
 * struct simbus_msg per packet).
 *
 *   client                         broker
 *   HELLO name, variant, osc  ->   REPLY status, INT level
 *   XFER tx[len]              ->   REPLY status, INT level, rx[len]
 *                             <-   INT level, whenever it changes
 *
 * A chip keeps its registers when its client goes, for the next HELLO
 * of its name; the broker exits, unlinking the socket, when the last
 * client has gone.
 */
#ifndef MCP2510_SIMBUS_H
#define MCP2510_SIMBUS_H

#include <stdint.h>

#define SIMBUS_NAME_MAX		32	/* chip and bus names, with the NUL */
#define SIMBUS_XFER_MAX		256	/* bytes of one CS-low period */

enum simbus_op {
	SIMBUS_HELLO = 1,
	SIMBUS_XFER,
	SIMBUS_REPLY,
	SIMBUS_INT,
};

enum simbus_miso {
	SIMBUS_MISO_OK,
	SIMBUS_MISO_LOW,
	SIMBUS_MISO_HIGH,
};

struct simbus_msg {
	uint8_t op;			/* enum simbus_op */
	uint8_t int_low;		/* REPLY, INT: the chip's INT pin is low */
	uint8_t mcp2515;		/* HELLO: the variant */
	uint8_t miso;			/* HELLO: enum simbus_miso */
	int32_t status;			/* REPLY: 0 or -errno */
	uint32_t osc_hz;		/* HELLO */
	uint32_t len;			/* XFER, REPLY: bytes in data */
	char name[SIMBUS_NAME_MAX];	/* HELLO: the chip's name */
	uint8_t data[SIMBUS_XFER_MAX];
};

/* One packet; 0 or -errno (-EPIPE when the peer has gone). */
int simbus_send(int fd, const struct simbus_msg *m);
int simbus_recv(int fd, struct simbus_msg *m);

/* A chip or bus name: 1..31 of [A-Za-z0-9._-], not starting with '.'. */
int simbus_check_name(const char *name);
/*
 * Connect to bus @bus's broker, starting one (or replacing one that
 * crashed) under a lock so two first users start only one.  The socket
 * is $XDG_RUNTIME_DIR/mcp2510-sim/BUS, or without XDG_RUNTIME_DIR
 * /tmp/mcp2510-sim-UID/BUS in a directory of mode 0700 that must be
 * the user's own.  The connected socket or -errno.
 */
int simbus_connect(const char *bus);
/* Take the lock of the bus whose socket is @sock_path: its fd or -errno. */
int simbus_lock(const char *sock_path);
/* The broker on @listen_fd, bound at @path: never returns. */
_Noreturn void simbus_broker_run(int listen_fd, const char *path);

#endif /* MCP2510_SIMBUS_H */
