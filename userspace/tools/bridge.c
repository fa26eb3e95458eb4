// SPDX-License-Identifier: GPL-2.0
/*
 * Chip <-> socket forwarding.  While all three transmit buffers are busy
 * the bridge holds one frame and stops reading the socket, so the
 * socket's receive queue, not this process, absorbs a burst.
 */
#include <errno.h>
#include <poll.h>
#include <string.h>
#include <unistd.h>

#include "bridge.h"

void bridge_init(struct bridge *b, struct mcp2510 *h, int sock)
{
	memset(b, 0, sizeof(*b));
	b->h = h;
	b->sock = sock;
}

static int to_socket(struct bridge *b, const struct can_frame *cf)
{
	ssize_t n = write(b->sock, cf, sizeof(*cf));

	if (n == (ssize_t)sizeof(*cf)) {
		b->counts.to_socket++;
		return 0;
	}
	/* a full queue (ENOBUFS) loses the frame, as a real interface would */
	if (n >= 0 || errno == ENOBUFS || errno == EAGAIN) {
		b->counts.socket_drops++;
		return 0;
	}
	return -1;
}

static int from_chip(struct bridge *b)
{
	struct mcp2510_event ev;

	while (!mcp2510_recv(b->h, &ev, 0)) {
		if (ev.type == MCP2510_EVENT_TX_ABORTED)
			b->counts.chip_drops++;
		if (ev.type != MCP2510_EVENT_RX && ev.type != MCP2510_EVENT_ERROR)
			continue;
		if (to_socket(b, &ev.frame))
			return -1;
	}
	return errno == EAGAIN || errno == ETIMEDOUT ? 0 : -1;
}

/* Queue the held frame; still holding it when the chip has no room. */
static int flush_held(struct bridge *b)
{
	if (!b->holding)
		return 0;
	if (mcp2510_send(b->h, &b->held, MCP2510_SEND_NONBLOCK)) {
		if (errno == EAGAIN)
			return 0;
		if (errno != EINVAL)
			return -1;
		b->counts.ignored++;
	} else {
		b->counts.to_chip++;
	}
	b->holding = false;
	return 0;
}

static int from_socket(struct bridge *b)
{
	ssize_t n = read(b->sock, &b->held, sizeof(b->held));

	if (n < 0)
		return errno == EAGAIN || errno == EINTR ? 0 : -1;
	if (n == 0) {
		errno = ECONNRESET;
		return -1;
	}
	if (n != (ssize_t)sizeof(b->held) || b->held.can_id & CAN_ERR_FLAG) {
		b->counts.ignored++;
		return 0;
	}
	b->holding = true;
	return flush_held(b);
}

int bridge_poll(struct bridge *b, int stop_fd, int timeout_ms)
{
	struct pollfd p[3] = {
		{ .fd = mcp2510_fd(b->h), .events = POLLIN },
		{ .fd = b->holding ? -1 : b->sock, .events = POLLIN },
		{ .fd = stop_fd, .events = POLLIN },
	};

	if (poll(p, 3, timeout_ms) < 0)
		return errno == EINTR ? 0 : -1;
	if (p[2].revents & POLLIN)
		return 1;
	if ((p[0].revents & POLLIN) && (from_chip(b) || flush_held(b)))
		return -1;
	if ((p[1].revents & (POLLIN | POLLHUP)) && from_socket(b))
		return -1;
	return 0;
}
