// SPDX-License-Identifier: GPL-2.0
/*
 * Chip <-> socket forwarding.  While all three transmit buffers are busy
 * the bridge holds one frame and stops reading the socket, so the
 * socket's receive queue, not this process, absorbs a burst; what that
 * queue drops is counted from SO_RXQ_OVFL.  A socket that refuses a frame
 * (ENOBUFS from a full queue) gets it again later from a small queue,
 * with a growing wait, while the chip is still serviced.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <limits.h>
#include <poll.h>
#include <string.h>
#include <unistd.h>
#include <sys/socket.h>
#include <linux/can/error.h>
#include <linux/sock_diag.h>

#include "bridge.h"

/* The kernel's restart-ms floor for a restart that failed. */
#define BRIDGE_RESTART_RETRY_MS	1000

void bridge_init(struct bridge *b, struct mcp2510 *h, int sock)
{
	memset(b, 0, sizeof(*b));
	b->h = h;
	b->sock = sock;
	b->retry_ms = BRIDGE_RETRY_MIN_MS;
	b->listen_only = h && mcp2510_get_ctrlmode(h) & CAN_CTRLMODE_LISTENONLY;
}

/* ---- time ---------------------------------------------------------------- */

static void after_ms(struct timespec *t, int ms)
{
	clock_gettime(CLOCK_MONOTONIC, t);
	t->tv_sec += ms / 1000;
	t->tv_nsec += (long)(ms % 1000) * 1000000L;
	if (t->tv_nsec >= 1000000000L) {
		t->tv_sec++;
		t->tv_nsec -= 1000000000L;
	}
}

/* Milliseconds until @t, rounded up; 0 when it has passed. */
static int ms_until(const struct timespec *t)
{
	struct timespec now;
	long long ns;

	clock_gettime(CLOCK_MONOTONIC, &now);
	ns = (long long)(t->tv_sec - now.tv_sec) * 1000000000LL +
	     (t->tv_nsec - now.tv_nsec);
	if (ns <= 0)
		return 0;
	ns = (ns + 999999) / 1000000;
	return ns > INT_MAX ? INT_MAX : (int)ns;
}

static int earlier(int timeout_ms, int ms)
{
	return timeout_ms < 0 || ms < timeout_ms ? ms : timeout_ms;
}

/* ---- toward the socket ----------------------------------------------------- */

static void count_written(struct bridge *b, const struct can_frame *cf)
{
	if (cf->can_id & CAN_ERR_FLAG)
		b->counts.error_frames++;
	else
		b->counts.to_socket++;
}

/* 1 written, 0 refused for now, -1 failed. */
static int write_one(struct bridge *b, const struct can_frame *cf)
{
	ssize_t n = write(b->sock, cf, sizeof(*cf));

	if (n == (ssize_t)sizeof(*cf)) {
		count_written(b, cf);
		return 1;
	}
	if (n >= 0) {
		errno = EMSGSIZE;
		return -1;
	}
	if (errno != ENOBUFS && errno != EAGAIN)
		return -1;
	b->counts.enobufs++;
	after_ms(&b->retry_at, b->retry_ms);
	if (b->retry_ms < BRIDGE_RETRY_MAX_MS)
		b->retry_ms *= 2;
	return 0;
}

/* Write what waits, oldest first, once its retry is due. */
static int flush_out(struct bridge *b)
{
	int ret;

	if (!b->out_count || ms_until(&b->retry_at))
		return 0;
	while (b->out_count) {
		ret = write_one(b, &b->out[b->out_head]);
		if (ret <= 0)
			return ret;
		b->out_head = (b->out_head + 1) % BRIDGE_OUT_QUEUE;
		b->out_count--;
	}
	b->retry_ms = BRIDGE_RETRY_MIN_MS;
	return 0;
}

static int to_socket(struct bridge *b, const struct can_frame *cf)
{
	if (!b->out_count) {
		int ret = write_one(b, cf);

		if (ret)
			return ret < 0 ? -1 : 0;
	}
	if (b->out_count == BRIDGE_OUT_QUEUE) {
		b->counts.socket_drops++;
		return 0;
	}
	b->out[(b->out_head + b->out_count) % BRIDGE_OUT_QUEUE] = *cf;
	b->out_count++;
	return 0;
}

void bridge_rxq_total(struct bridge *b, uint32_t total)
{
	/*
	 * Modular arithmetic takes a wrap of the kernel's counter in stride.
	 * A frame queued before the last SO_MEMINFO look carries an older,
	 * smaller total: it adds nothing.
	 */
	int32_t more = (int32_t)(total - b->rxq_seen);

	if (more <= 0)
		return;
	b->counts.rxq_drops += (uint32_t)more;
	b->rxq_seen = total;
}

/*
 * The SO_RXQ_OVFL total comes with the next frame queued after a drop, so
 * the drops of a burst that nothing followed would stay unseen: the
 * socket's drop count now, as SO_MEMINFO gives it, before a report.
 */
static void rxq_refresh(struct bridge *b)
{
	uint32_t mem[SK_MEMINFO_VARS];
	socklen_t len = sizeof(mem);

	if (!getsockopt(b->sock, SOL_SOCKET, SO_MEMINFO, mem, &len) &&
	    len > SK_MEMINFO_DROPS * sizeof(mem[0]))
		bridge_rxq_total(b, mem[SK_MEMINFO_DROPS]);
}

/* ---- bus-off --------------------------------------------------------------- */

/*
 * Take the chip off the bus as soon as it reports bus-off, before the
 * library services it again: the next interrupt may already be its own
 * recovery.  What the ring still holds (the bus-off error frame) is read
 * afterwards without touching the chip, followed by the frames the chip
 * still held, aborted.
 */
static int halt(struct bridge *b)
{
	b->bus_off = true;
	b->counts.bus_offs++;
	if (mcp2510_down(b->h))
		return -1;
	if (b->holding) {
		b->holding = false;
		b->counts.bus_off_drops++;
	}
	if (b->restart_ms)
		after_ms(&b->restart_at, b->restart_ms);
	return 0;
}

int bridge_restart(struct bridge *b)
{
	struct can_frame cf = { .can_id = CAN_ERR_FLAG | CAN_ERR_RESTARTED,
				.len = CAN_ERR_DLC };

	if (!b->bus_off) {
		errno = EBUSY;
		return -1;
	}
	if (mcp2510_up(b->h)) {
		int err = errno;

		/* as the kernel driver does: try again, at most once a second */
		if (b->restart_ms)
			after_ms(&b->restart_at,
				 b->restart_ms > BRIDGE_RESTART_RETRY_MS ?
				 b->restart_ms : BRIDGE_RESTART_RETRY_MS);
		errno = err;
		return -1;
	}
	b->bus_off = false;
	b->counts.restarts++;
	return to_socket(b, &cf);
}

/* ---- from the chip --------------------------------------------------------- */

static int from_chip(struct bridge *b)
{
	struct mcp2510_event ev;

	while (!mcp2510_recv(b->h, &ev, 0)) {
		switch (ev.type) {
		case MCP2510_EVENT_TX_ABORTED:
			b->counts.chip_drops++;
			break;
		case MCP2510_EVENT_STATE:
			if (ev.state == CAN_STATE_BUS_OFF && !b->bus_off &&
			    halt(b))
				return -1;
			break;
		case MCP2510_EVENT_RX:
		case MCP2510_EVENT_ERROR:
			if (to_socket(b, &ev.frame))
				return -1;
			break;
		default:
			break;
		}
	}
	if (errno == ENETDOWN && b->bus_off)
		return 0;
	return errno == EAGAIN || errno == ETIMEDOUT ? 0 : -1;
}

/* ---- toward the chip ------------------------------------------------------- */

/* Queue the held frame; still holding it when the chip has no room. */
static int flush_held(struct bridge *b)
{
	if (!b->holding || b->bus_off)
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

void bridge_take_cmsgs(struct bridge *b, struct msghdr *msg)
{
	struct cmsghdr *c;
	uint32_t total;

	for (c = CMSG_FIRSTHDR(msg); c; c = CMSG_NXTHDR(msg, c)) {
		if (c->cmsg_level != SOL_SOCKET || c->cmsg_type != SO_RXQ_OVFL ||
		    c->cmsg_len < CMSG_LEN(sizeof(total)))
			continue;
		memcpy(&total, CMSG_DATA(c), sizeof(total));
		bridge_rxq_total(b, total);
	}
}

static int from_socket(struct bridge *b)
{
	union {
		char buf[CMSG_SPACE(sizeof(uint32_t))];
		struct cmsghdr align;
	} control;
	struct iovec iov = { &b->held, sizeof(b->held) };
	struct msghdr msg = { .msg_iov = &iov, .msg_iovlen = 1,
			      .msg_control = control.buf,
			      .msg_controllen = sizeof(control.buf) };
	ssize_t n = recvmsg(b->sock, &msg, 0);

	if (n < 0)
		return errno == EAGAIN || errno == EINTR ? 0 : -1;
	if (n == 0) {
		errno = ECONNRESET;
		return -1;
	}
	bridge_take_cmsgs(b, &msg);
	if (n != (ssize_t)sizeof(b->held) || b->held.can_id & CAN_ERR_FLAG) {
		b->counts.ignored++;
		return 0;
	}
	/* as a bus-off interface, which drops what it is given */
	if (b->bus_off) {
		b->counts.bus_off_drops++;
		return 0;
	}
	/*
	 * As a listen-only CAN interface drops what it is given: the chip
	 * would hold it in a transmit buffer for ever, and with all three
	 * taken the bridge would stop reading the socket.
	 */
	if (b->listen_only) {
		b->counts.ignored++;
		return 0;
	}
	b->holding = true;
	return flush_held(b);
}

/* ---- the loop --------------------------------------------------------------- */

static void due_restart(struct bridge *b)
{
	if (!b->bus_off || !b->restart_ms || ms_until(&b->restart_at))
		return;
	/* a failed restart leaves the chip bus-off: the bridge goes on */
	if (bridge_restart(b))
		b->counts.restart_failures++;
}

/* What @timeout_ms becomes with a retry or a restart due earlier. */
static int wait_ms(const struct bridge *b, int timeout_ms)
{
	if (b->out_count)
		timeout_ms = earlier(timeout_ms, ms_until(&b->retry_at));
	if (b->bus_off && b->restart_ms)
		timeout_ms = earlier(timeout_ms, ms_until(&b->restart_at));
	return timeout_ms;
}

int bridge_poll(struct bridge *b, int stop_fd, int timeout_ms)
{
	struct pollfd p[3] = {
		{ .fd = b->bus_off ? -1 : mcp2510_fd(b->h), .events = POLLIN },
		{ .fd = b->holding ? -1 : b->sock, .events = POLLIN },
		{ .fd = stop_fd, .events = POLLIN },
	};

	if (poll(p, 3, wait_ms(b, timeout_ms)) < 0)
		return errno == EINTR ? 0 : -1;
	if (p[2].revents & POLLIN)
		return 1;
	if ((p[0].revents & POLLIN) && (from_chip(b) || flush_held(b)))
		return -1;
	if ((p[1].revents & (POLLIN | POLLHUP)) && from_socket(b))
		return -1;
	due_restart(b);
	return flush_out(b);
}

/* The error state and counters; bus-off as the bridge took it. */
static void bus_state(struct bridge *b, enum can_state *state,
		      struct can_berr_counter *bec)
{
	if (b->stopped) {
		*state = b->last_state;
		*bec = b->last_bec;
		return;
	}
	*state = CAN_STATE_STOPPED;
	bec->txerr = 0;
	bec->rxerr = 0;
	mcp2510_state(b->h, state, bec);
	if (b->bus_off)
		*state = CAN_STATE_BUS_OFF;
}

/* What the socket still holds for the chip, which will never take it. */
static void drop_unread(struct bridge *b)
{
	struct can_frame cf;
	ssize_t n;

	while ((n = recv(b->sock, &cf, sizeof(cf), MSG_DONTWAIT)) > 0)
		if (n == (ssize_t)sizeof(cf) && !(cf.can_id & CAN_ERR_FLAG))
			b->counts.chip_drops++;
}

void bridge_stop(struct bridge *b)
{
	struct mcp2510_event ev;

	bus_state(b, &b->last_state, &b->last_bec);
	b->stopped = true;
	if (b->holding) {
		b->holding = false;
		b->counts.chip_drops++;
	}
	/* the frames the chip still held come back aborted */
	mcp2510_down(b->h);
	while (!mcp2510_recv(b->h, &ev, 0))
		if (ev.type == MCP2510_EVENT_TX_ABORTED)
			b->counts.chip_drops++;
	if (!b->listen_only)
		drop_unread(b);
}

void bridge_print_stats(struct bridge *b, FILE *out, const char *prefix)
{
	const struct bridge_counts *c = &b->counts;
	struct mcp2510_stats s;
	struct can_berr_counter bec;
	enum can_state state;

	rxq_refresh(b);
	memset(&s, 0, sizeof(s));
	mcp2510_stats(b->h, &s);
	bus_state(b, &state, &bec);
	fprintf(out, "%s: stats frames: to-iface %llu to-chip %llu error-frames %llu ignored %llu\n",
		prefix, (unsigned long long)c->to_socket,
		(unsigned long long)c->to_chip,
		(unsigned long long)c->error_frames,
		(unsigned long long)c->ignored);
	fprintf(out, "%s: stats lost: rxq-overflow %llu enobufs-retries %llu iface-full %llu tx-aborted %llu bus-off-drops %llu chip-rx-overflow %u event-overflow %u\n",
		prefix, (unsigned long long)c->rxq_drops,
		(unsigned long long)c->enobufs,
		(unsigned long long)c->socket_drops,
		(unsigned long long)c->chip_drops,
		(unsigned long long)c->bus_off_drops,
		s.rx_overflows, s.ring_overflows);
	fprintf(out, "%s: stats bus: state %s tec %u rec %u bus-errors %u bus-off %llu restarts %llu\n",
		prefix, mcp2510_state_name(state), bec.txerr, bec.rxerr,
		s.bus_errors, (unsigned long long)c->bus_offs,
		(unsigned long long)c->restarts);
	fflush(out);
}
