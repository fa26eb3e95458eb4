// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * The core reports what the chip did through callbacks while the library
 * handles an interrupt; they land here, in a fixed ring the caller
 * empties with mcp2510_recv().  A full ring drops the new event and counts
 * it: the chip must be serviced whether or not the caller keeps up.
 */
#define _GNU_SOURCE
#include <unistd.h>
#include <sys/eventfd.h>

#include "handle.h"

int mcp2510_ring_init(struct event_ring *r)
{
	r->head = 0;
	r->count = 0;
	r->overflows = 0;
	r->signalled = false;
	r->fd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
	return r->fd < 0 ? -errno : 0;
}

void mcp2510_ring_free(struct event_ring *r)
{
	if (r->fd >= 0)
		close(r->fd);
	r->fd = -1;
}

static void ring_signal(struct event_ring *r, bool want)
{
	uint64_t v = 1;

	if (want && !r->signalled)
		r->signalled = write(r->fd, &v, sizeof(v)) == sizeof(v);
	else if (!want && r->signalled)
		r->signalled = read(r->fd, &v, sizeof(v)) != sizeof(v);
}

MCP2510_ABI_LAYOUT(struct mcp2510_event, 80);

static struct mcp2510_event *ring_push(struct event_ring *r,
				       enum mcp2510_event_type type)
{
	struct mcp2510_event *ev;

	if (r->count == MCP2510_EVENT_RING_SIZE) {
		r->overflows++;
		return NULL;
	}
	ev = &r->ev[(r->head + r->count) % MCP2510_EVENT_RING_SIZE];
	r->count++;
	memset(ev, 0, sizeof(*ev));
	ev->type = type;
	clock_gettime(CLOCK_REALTIME, &ev->ts);
	ring_signal(r, true);
	return ev;
}

bool mcp2510_ring_pop(struct event_ring *r, struct mcp2510_event *ev)
{
	if (!r->count)
		return false;
	*ev = r->ev[r->head];
	r->head = (r->head + 1) % MCP2510_EVENT_RING_SIZE;
	r->count--;
	ring_signal(r, r->count > 0);
	return true;
}

static void push_frame(struct mcp2510 *h, enum mcp2510_event_type type,
		       const struct can_frame *cf)
{
	struct mcp2510_event *ev = ring_push(&h->ring, type);

	if (ev)
		ev->frame = *cf;
}

static void on_rx(void *ctx, const struct can_frame *cf)
{
	struct mcp2510 *h = ctx;

	h->rx_frames++;
	push_frame(h, MCP2510_EVENT_RX, cf);
}

static void on_tx_done(void *ctx, unsigned int slot)
{
	struct mcp2510 *h = ctx;

	h->tx_frames_done++;
	push_frame(h, MCP2510_EVENT_TX_DONE, &h->tx_frames[slot]);
}

static void on_tx_aborted(void *ctx, unsigned int slot)
{
	struct mcp2510 *h = ctx;

	push_frame(h, MCP2510_EVENT_TX_ABORTED, &h->tx_frames[slot]);
}

static void on_state(void *ctx, enum can_state state,
		     const struct can_berr_counter *bec)
{
	struct mcp2510 *h = ctx;
	struct mcp2510_event *ev;

	h->state = state;
	ev = ring_push(&h->ring, MCP2510_EVENT_STATE);
	if (!ev)
		return;
	ev->state = state;
	ev->bec = *bec;
}

static void on_error(void *ctx, const struct can_frame *cf)
{
	push_frame(ctx, MCP2510_EVENT_ERROR, cf);
}

const struct mcp2510_events mcp2510_lib_events = {
	.rx = on_rx,
	.tx_done = on_tx_done,
	.tx_aborted = on_tx_aborted,
	.state = on_state,
	.error = on_error,
};
