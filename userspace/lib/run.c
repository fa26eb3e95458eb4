// SPDX-License-Identifier: LGPL-2.1-or-later
/* A running chip: up and down, sending, and the interrupt-driven receive. */
#define _GNU_SOURCE
#include <limits.h>
#include <time.h>

#include "handle.h"

int mcp2510_up(struct mcp2510 *h)
{
	int ret;

	if (h->running)
		return mcp2510_fail(-EBUSY);
	if (!h->have_bt)
		return mcp2510_fail(-ENODATA);
	ret = mcp2510_start(&h->chip, &h->bt, h->ctrlmode);
	if (ret)
		return mcp2510_fail(ret);
	h->running = true;
	h->state = CAN_STATE_ERROR_ACTIVE;
	return 0;
}

int mcp2510_down(struct mcp2510 *h)
{
	int ret;

	if (!h->running)
		return 0;
	ret = mcp2510_stop(&h->chip);
	h->running = false;
	h->state = CAN_STATE_STOPPED;
	return mcp2510_fail(ret);
}

int mcp2510_bus_restart(struct mcp2510 *h)
{
	int ret;

	if (!h->running)
		return mcp2510_fail(-ENETDOWN);
	ret = mcp2510_restart(&h->chip);
	if (ret)
		return mcp2510_fail(ret);
	h->state = CAN_STATE_ERROR_ACTIVE;
	return 0;
}

bool mcp2510_is_up(const struct mcp2510 *h)
{
	return h->running;
}

unsigned int mcp2510_tx_room(const struct mcp2510 *h)
{
	return h->running ? mcp2510_tx_free(&h->chip) : 0;
}

int mcp2510_service(struct mcp2510 *h, int timeout_ms)
{
	struct mcp2510_transport *t = h->transport;
	int ret;

	ret = t->ops->wait_irq(t, timeout_ms);
	if (ret <= 0)
		return ret;
	ret = mcp2510_irq_handle(&h->chip);
	/* a storming chip was counted by the core; keep servicing it */
	if (ret < 0 && ret != -EAGAIN)
		return ret;
	return 1;
}

void mcp2510_irq_hook(void *ctx)
{
	struct mcp2510 *h = ctx;

	if (h->running)
		mcp2510_irq_handle(&h->chip);
}

/* Milliseconds to wait; the deadline is in CLOCK_MONOTONIC time. */
struct deadline {
	bool forever;
	struct timespec at;
};

static void deadline_set(struct deadline *d, int timeout_ms)
{
	d->forever = timeout_ms < 0;
	clock_gettime(CLOCK_MONOTONIC, &d->at);
	if (d->forever)
		return;
	d->at.tv_sec += timeout_ms / 1000;
	d->at.tv_nsec += (long)(timeout_ms % 1000) * 1000000L;
	if (d->at.tv_nsec >= 1000000000L) {
		d->at.tv_sec++;
		d->at.tv_nsec -= 1000000000L;
	}
}

static int deadline_left_ms(const struct deadline *d)
{
	struct timespec now;
	long long ms;

	if (d->forever)
		return -1;
	clock_gettime(CLOCK_MONOTONIC, &now);
	ms = (long long)(d->at.tv_sec - now.tv_sec) * 1000 +
	     (d->at.tv_nsec - now.tv_nsec) / 1000000L;
	if (ms <= 0)
		return 0;
	return ms > INT_MAX ? INT_MAX : (int)ms;
}

static int frame_check(const struct can_frame *cf)
{
	canid_t id = cf->can_id;

	if (id & CAN_ERR_FLAG || cf->len > CAN_MAX_DLEN)
		return -EINVAL;
	if (id & CAN_EFF_FLAG)
		return (id & ~(CAN_EFF_FLAG | CAN_RTR_FLAG)) > CAN_EFF_MASK ?
			-EINVAL : 0;
	return (id & ~CAN_RTR_FLAG) > CAN_SFF_MASK ? -EINVAL : 0;
}

/* Service the chip until a transmit buffer is free. */
static int wait_tx_room(struct mcp2510 *h, unsigned int flags)
{
	struct deadline d;
	int ret;

	deadline_set(&d, h->tx_timeout_ms);
	while (!mcp2510_tx_free(&h->chip)) {
		int left = deadline_left_ms(&d);

		if (flags & MCP2510_SEND_NONBLOCK)
			return -EAGAIN;
		ret = mcp2510_service(h, left);
		if (ret < 0)
			return ret;
		if (!ret)
			return -ETIMEDOUT;
		if (!h->running)
			return -ENETDOWN;
	}
	return 0;
}

int mcp2510_send(struct mcp2510 *h, const struct can_frame *cf,
		 unsigned int flags)
{
	int ret;

	if (!h->running)
		return mcp2510_fail(-ENETDOWN);
	ret = frame_check(cf);
	if (!ret)
		ret = wait_tx_room(h, flags);
	if (!ret)
		ret = mcp2510_tx_submit(&h->chip, cf);
	if (ret < 0)
		return mcp2510_fail(ret);
	h->tx_frames[ret] = *cf;
	return 0;
}

int mcp2510_recv(struct mcp2510 *h, struct mcp2510_event *ev, int timeout_ms)
{
	struct deadline d;
	int ret;

	deadline_set(&d, timeout_ms);
	while (!mcp2510_ring_pop(&h->ring, ev)) {
		int left = deadline_left_ms(&d);

		if (!h->running)
			return mcp2510_fail(-ENETDOWN);
		ret = mcp2510_service(h, left);
		if (ret < 0)
			return mcp2510_fail(ret);
		if (!ret)
			return mcp2510_fail(timeout_ms ? -ETIMEDOUT : -EAGAIN);
	}
	return 0;
}

int mcp2510_fd(const struct mcp2510 *h)
{
	return h->epoll_fd;
}
