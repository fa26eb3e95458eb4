/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The inside of a libmcp2510 handle, shared by the library's files. */
#ifndef MCP2510_HANDLE_H
#define MCP2510_HANDLE_H

#include <stddef.h>

#include "mcp2510_core.h"
#include "mcp2510.h"
#include "transport.h"

struct event_ring {
	struct mcp2510_event ev[MCP2510_EVENT_RING_SIZE];
	unsigned int head;
	unsigned int count;
	uint32_t overflows;
	int fd;				/* eventfd, readable while count > 0 */
	bool signalled;
};

struct mcp2510 {
	struct mcp2510_chip chip;
	struct mcp2510_transport *transport;
	int tx_timeout_ms;
	struct can_bittiming bt;
	bool have_bt;
	uint32_t ctrlmode;
	struct mcp2510_filters filters;
	bool running;
	bool reset_done;		/* this handle reset the chip */
	enum can_state state;
	struct can_frame tx_frames[MCP2510_TXB_COUNT];	/* by TX slot */
	uint64_t rx_frames;
	uint64_t tx_frames_done;
	struct event_ring ring;
	int epoll_fd;
};

/* Set errno from a negative errno and return -1; pass 0 through. */
int mcp2510_fail(int ret);

extern const struct mcp2510_events mcp2510_lib_events;
int mcp2510_ring_init(struct event_ring *r);
void mcp2510_ring_free(struct event_ring *r);
bool mcp2510_ring_pop(struct event_ring *r, struct mcp2510_event *ev);

/* Wait up to @timeout_ms for INT and handle it: 1 handled, 0 timeout. */
int mcp2510_service(struct mcp2510 *h, int timeout_ms);
/* Handle a pending interrupt on behalf of another handle's wait. */
void mcp2510_irq_hook(void *ctx);

/*
 * A public struct's layout is the soname's promise (mcp2510.h): its
 * reserved space stays last, and on LP64 (where it was measured) its size
 * does not change.
 */
#define MCP2510_ABI_LAYOUT(type, lp64_size)					\
	_Static_assert(offsetof(type, reserved) +				\
		       sizeof(((type *)NULL)->reserved) == sizeof(type),	\
		       #type ": the reserved space must stay last");		\
	_Static_assert(sizeof(void *) != 8 || sizeof(type) == (lp64_size),	\
		       #type ": the size must not change")

/* A struct passed in whose reserved space is not zero asks for more than
 * this library knows. */
static inline bool mcp2510_reserved_zero(const void *reserved, size_t len)
{
	const unsigned char *p = reserved;

	while (len--)
		if (*p++)
			return false;
	return true;
}

#endif /* MCP2510_HANDLE_H */
