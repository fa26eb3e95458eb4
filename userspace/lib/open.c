// SPDX-License-Identifier: LGPL-2.1-or-later
/* Opening and closing a handle: options, variant, transport, first reset. */
#define _GNU_SOURCE
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/epoll.h>

#include "handle.h"

#define SPIDEV_PREFIX	"spidev:"
#define SIM_NAME	"sim"

int mcp2510_fail(int ret)
{
	if (ret >= 0)
		return ret;
	errno = -ret;
	return -1;
}

void mcp2510_options_init(struct mcp2510_options *o)
{
	memset(o, 0, sizeof(*o));
	o->osc_hz = MCP2510_DEFAULT_OSC_HZ;
	o->poll_ms = MCP2510_DEFAULT_POLL_MS;
	o->tx_timeout_ms = MCP2510_DEFAULT_TX_TIMEOUT_MS;
}

static const struct mcp2510_variant *variant_by_name(const char *name)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510,
		MCP2510_MODEL_MCP2515,
		MCP2510_MODEL_MCP25625,
	};
	unsigned int i;

	if (!name)
		return mcp2510_variant_get(MCP2510_MODEL_MCP2510);
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		const struct mcp2510_variant *v = mcp2510_variant_get(models[i]);

		if (v && !strcmp(v->name, name))
			return v;
	}
	return NULL;
}

static int ops_xfer(void *ctx, const u8 *tx, u8 *rx, unsigned int len)
{
	struct mcp2510_transport *t = ((struct mcp2510 *)ctx)->transport;

	return t->ops->xfer(t, tx, rx, len);
}

static int ops_xfer_msg(void *ctx, const struct mcp2510_xfer *x,
			unsigned int n)
{
	struct mcp2510_transport *t = ((struct mcp2510 *)ctx)->transport;
	struct mcp2510_transport_xfer tx[MCP2510_XFER_MSG_MAX];
	unsigned int i;
	int err;

	if (n > MCP2510_XFER_MSG_MAX)
		return -EINVAL;
	if (!t->ops->xfer_msg) {
		for (i = 0; i < n; i++) {
			err = t->ops->xfer(t, x[i].tx, x[i].rx, x[i].len);
			if (err)
				return err;
		}
		return 0;
	}
	for (i = 0; i < n; i++) {
		tx[i].tx = x[i].tx;
		tx[i].rx = x[i].rx;
		tx[i].len = x[i].len;
	}
	return t->ops->xfer_msg(t, tx, n);
}

static void ops_delay_us(void *ctx, unsigned int us)
{
	struct mcp2510_transport *t = ((struct mcp2510 *)ctx)->transport;

	t->ops->delay_us(t, us);
}

static const struct mcp2510_ops lib_ops = {
	.xfer = ops_xfer,
	.xfer_msg = ops_xfer_msg,
	.delay_us = ops_delay_us,
};

/* "spidev:PATH", "sim" or "sim:NAME". */
static int transport_open(const char *spec,
			  const struct mcp2510_transport_params *p,
			  struct mcp2510_transport **out, bool *is_sim)
{
	size_t plen = strlen(SPIDEV_PREFIX);

	*is_sim = false;
	if (!strncmp(spec, SPIDEV_PREFIX, plen) && spec[plen])
		return mcp2510_spidev_open(spec + plen, p, out);
	if (!strcmp(spec, SIM_NAME)) {
		*is_sim = true;
		return mcp2510_sim_open("", p, out);
	}
	if (!strncmp(spec, SIM_NAME ":", strlen(SIM_NAME ":")) &&
	    spec[strlen(SIM_NAME ":")]) {
		*is_sim = true;
		return mcp2510_sim_open(spec + strlen(SIM_NAME ":"), p, out);
	}
	return -EINVAL;
}

static int epoll_add(int epfd, int fd)
{
	struct epoll_event ev = { .events = EPOLLIN };

	if (fd < 0)
		return 0;
	ev.data.fd = fd;
	return epoll_ctl(epfd, EPOLL_CTL_ADD, fd, &ev) < 0 ? -errno : 0;
}

/* One descriptor for the caller's poll(): the ring and the INT source. */
static int pollset_open(struct mcp2510 *h)
{
	const struct mcp2510_transport *t = h->transport;
	int ret;

	h->epoll_fd = epoll_create1(EPOLL_CLOEXEC);
	if (h->epoll_fd < 0)
		return -errno;
	ret = epoll_add(h->epoll_fd, h->ring.fd);
	if (!ret)
		ret = epoll_add(h->epoll_fd, t->ops->fd(t));
	return ret;
}

/* Without a reset: a chip that answers does not read as all ones. */
static int chip_answers(struct mcp2510 *h)
{
	u8 canstat;
	int ret;

	ret = mcp2510_reg_read(&h->chip, MCP2510_REG_CANSTAT, &canstat, 1);
	if (ret)
		return ret;
	return canstat == 0xff ? -ENODEV : 0;
}

static int handle_setup(struct mcp2510 *h, const char *spec,
			const struct mcp2510_options *o,
			const struct mcp2510_variant *v)
{
	struct mcp2510_transport_params p = {
		.spi_hz = o->spi_hz ? o->spi_hz : v->spi_default_hz,
		.spi_mode = o->spi_mode,
		.int_line = o->int_line,
		.poll_ms = o->poll_ms,
		.osc_hz = o->osc_hz,
		.mcp2515 = v->has_buffer_instrs,
	};
	bool is_sim;
	int ret;

	ret = mcp2510_init(&h->chip, v, o->osc_hz, &lib_ops,
			   &mcp2510_lib_events, h);
	if (ret)
		return ret;
	/* The library drains every flag per pass, as an edge input needs. */
	h->chip.irq_edge = true;
	ret = transport_open(spec, &p, &h->transport, &is_sim);
	if (ret)
		return ret;
	if (h->transport->ops->set_irq_hook)
		h->transport->ops->set_irq_hook(h->transport,
						mcp2510_irq_hook, h);
	ret = pollset_open(h);
	if (ret)
		return ret;
	if (o->no_reset && !is_sim)
		return chip_answers(h);
	return mcp2510_hw_reset(&h->chip);
}

struct mcp2510 *mcp2510_open(const char *transport,
			     const struct mcp2510_options *o)
{
	const struct mcp2510_variant *v;
	struct mcp2510_options defaults;
	struct mcp2510 *h;
	int ret;

	if (!o) {
		mcp2510_options_init(&defaults);
		o = &defaults;
	}
	v = variant_by_name(o->variant);
	if (!transport || !v) {
		errno = EINVAL;
		return NULL;
	}
	h = calloc(1, sizeof(*h));
	if (!h) {
		errno = ENOMEM;
		return NULL;
	}
	h->epoll_fd = -1;
	h->tx_timeout_ms = o->tx_timeout_ms;
	h->state = CAN_STATE_STOPPED;
	mcp2510_filters_default(&h->filters);
	ret = mcp2510_ring_init(&h->ring);
	if (!ret)
		ret = handle_setup(h, transport, o, v);
	if (ret) {
		mcp2510_close(h);
		errno = -ret;
		return NULL;
	}
	return h;
}

void mcp2510_close(struct mcp2510 *h)
{
	if (!h)
		return;
	if (h->running)
		mcp2510_down(h);
	if (h->epoll_fd >= 0)
		close(h->epoll_fd);
	if (h->transport)
		h->transport->ops->close(h->transport);
	mcp2510_ring_free(&h->ring);
	free(h);
}

int mcp2510_reset(struct mcp2510 *h)
{
	int ret;

	/* stopping first reports the frames the reset throws away */
	if (h->running)
		mcp2510_down(h);
	ret = mcp2510_hw_reset(&h->chip);
	h->running = false;
	h->state = CAN_STATE_STOPPED;
	return mcp2510_fail(ret);
}

const char *mcp2510_variant_name(const struct mcp2510 *h)
{
	return h->chip.variant->name;
}

uint32_t mcp2510_osc_hz(const struct mcp2510 *h)
{
	return h->chip.osc_hz;
}
