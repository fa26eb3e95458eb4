// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * "sim:NAME@BUS": the chip NAME on the shared simulated bus BUS, reached
 * through its broker (simbus.h).  Each transfer is a round trip; the INT
 * pin is what the broker last said.  The bus runs at wall-clock pace, so
 * a delay is a real sleep and a wait a real wait.
 *
 * A broker that has gone makes every call fail with EIO, as a failed
 * SPI transfer does.
 *
 * The descriptor for poll() is an epoll set of the socket (an INT packet
 * to read) and an eventfd that is readable while INT is known to be low.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>

#include "simbus.h"
#include "transport.h"

#define MISO_ENV	"MCP2510_SIM_MISO"

struct remote {
	struct mcp2510_transport base;
	int sock;
	int event_fd;
	int epoll_fd;
	bool int_low;
	bool signalled;
	struct mcp2510_transport_counts counts;
};

static struct remote *to_remote(struct mcp2510_transport *t)
{
	return (struct remote *)t;
}

static const struct remote *to_remote_const(const struct mcp2510_transport *t)
{
	return (const struct remote *)t;
}

static void set_int(struct remote *r, bool low)
{
	uint64_t v = 1;

	if (low && !r->int_low)
		r->counts.interrupts++;
	r->int_low = low;
	if (low && !r->signalled)
		r->signalled = write(r->event_fd, &v, sizeof(v)) == sizeof(v);
	else if (!low && r->signalled)
		r->signalled = read(r->event_fd, &v, sizeof(v)) != sizeof(v);
}

/* Read packets, INT news on the way, until a REPLY. */
static int roundtrip(struct remote *r, struct simbus_msg *m)
{
	int ret = simbus_send(r->sock, m);

	while (!ret) {
		ret = simbus_recv(r->sock, m);
		if (ret)
			break;
		if (m->op == SIMBUS_REPLY || m->op == SIMBUS_INT)
			set_int(r, m->int_low);
		if (m->op == SIMBUS_REPLY)
			return m->status;
	}
	return ret == -EPIPE ? -EIO : ret;
}

static int remote_xfer(struct mcp2510_transport *t, const uint8_t *tx,
		       uint8_t *rx, unsigned int len)
{
	struct remote *r = to_remote(t);
	struct simbus_msg m = { .op = SIMBUS_XFER, .len = len };
	int ret;

	if (len > SIMBUS_XFER_MAX)
		return -EMSGSIZE;
	memcpy(m.data, tx, len);
	ret = roundtrip(r, &m);
	if (ret)
		return ret;
	if (rx)
		memcpy(rx, m.data, len);
	r->counts.spi_transfers++;
	r->counts.spi_bytes += len;
	return 0;
}

static void remote_delay_us(struct mcp2510_transport *t, unsigned int us)
{
	struct timespec ts = { .tv_sec = us / 1000000u,
			       .tv_nsec = (long)(us % 1000000u) * 1000 };

	(void)t;
	while (nanosleep(&ts, &ts) && errno == EINTR)
		;
}

/* INT packets already there, without blocking. */
static int drain(struct remote *r)
{
	struct pollfd p = { .fd = r->sock, .events = POLLIN };
	struct simbus_msg m;
	int ret;

	while (poll(&p, 1, 0) > 0) {
		ret = simbus_recv(r->sock, &m);
		if (ret)
			return ret == -EPIPE ? -EIO : ret;
		if (m.op == SIMBUS_INT)
			set_int(r, m.int_low);
	}
	return 0;
}

static int64_t mono_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* INT packets that say high do not restart the wait's time. */
static int remote_wait_irq(struct mcp2510_transport *t, int timeout_ms)
{
	struct remote *r = to_remote(t);
	struct pollfd p = { .fd = r->sock, .events = POLLIN };
	int64_t end = mono_ms() + timeout_ms, left = timeout_ms;
	int ret = drain(r);

	while (!ret && !r->int_low) {
		if (timeout_ms >= 0) {
			left = end - mono_ms();
			if (left < 0)
				left = 0;
		}
		ret = poll(&p, 1, (int)left);
		if (ret < 0 && errno == EINTR) {
			ret = 0;
			continue;
		}
		if (ret <= 0)
			return ret < 0 ? -errno : 0;
		ret = drain(r);
	}
	return ret ? ret : 1;
}

static int remote_fd(const struct mcp2510_transport *t)
{
	return to_remote_const(t)->epoll_fd;
}

static void remote_counts(const struct mcp2510_transport *t,
			  struct mcp2510_transport_counts *c)
{
	*c = to_remote_const(t)->counts;
}

static void remote_close(struct mcp2510_transport *t)
{
	struct remote *r = to_remote(t);

	close(r->epoll_fd);
	close(r->event_fd);
	close(r->sock);
	free(r);
}

static const struct mcp2510_transport_ops remote_ops = {
	.xfer = remote_xfer,
	.delay_us = remote_delay_us,
	.wait_irq = remote_wait_irq,
	.fd = remote_fd,
	.counts = remote_counts,
	.close = remote_close,
};

static int epoll_watch(int epfd, int fd)
{
	struct epoll_event ev = { .events = EPOLLIN };

	return epoll_ctl(epfd, EPOLL_CTL_ADD, fd, &ev) ? -errno : 0;
}

/* HELLO with the chip's name and kind and MCP2510_SIM_MISO's fault. */
static int hello(struct remote *r, const char *name,
		 const struct mcp2510_transport_params *p)
{
	const char *miso = getenv(MISO_ENV);
	struct simbus_msg m = { .op = SIMBUS_HELLO, .mcp2515 = p->mcp2515,
				.osc_hz = p->osc_hz };

	if (miso && *miso) {
		if (!strcmp(miso, "low"))
			m.miso = SIMBUS_MISO_LOW;
		else if (!strcmp(miso, "high"))
			m.miso = SIMBUS_MISO_HIGH;
		else
			return -EINVAL;
	}
	strcpy(m.name, name);
	return roundtrip(r, &m);
}

int mcp2510_simbus_open(const char *spec,
			const struct mcp2510_transport_params *p,
			struct mcp2510_transport **out)
{
	const char *at = strchr(spec, '@');
	char name[SIMBUS_NAME_MAX];
	struct remote *r;
	int ret;

	if (!at || (size_t)(at - spec) >= sizeof(name))
		return at ? -ENAMETOOLONG : -EINVAL;
	memcpy(name, spec, (size_t)(at - spec));
	name[at - spec] = '\0';
	ret = simbus_check_name(name);
	if (ret)
		return ret;
	r = calloc(1, sizeof(*r));
	if (!r)
		return -ENOMEM;
	r->base.ops = &remote_ops;
	r->sock = simbus_connect(at + 1);
	if (r->sock < 0) {
		ret = r->sock;
		goto out_free;
	}
	r->event_fd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
	r->epoll_fd = epoll_create1(EPOLL_CLOEXEC);
	if (r->event_fd < 0 || r->epoll_fd < 0)
		ret = -errno;
	if (!ret)
		ret = epoll_watch(r->epoll_fd, r->sock);
	if (!ret)
		ret = epoll_watch(r->epoll_fd, r->event_fd);
	if (!ret)
		ret = hello(r, name, p);
	if (ret)
		goto out_close;
	*out = &r->base;
	return 0;

out_close:
	if (r->epoll_fd >= 0)
		close(r->epoll_fd);
	if (r->event_fd >= 0)
		close(r->event_fd);
	close(r->sock);
out_free:
	free(r);
	return ret;
}
