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

MCP2510_ABI_LAYOUT(struct mcp2510_options, 112);

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

/* "spidev:PATH", "sim", "sim:NAME" or "sim:NAME@BUS". */
static int transport_open(const char *spec,
			  const struct mcp2510_transport_params *p,
			  struct mcp2510_transport **out)
{
	size_t plen = strlen(SPIDEV_PREFIX);

	if (!strncmp(spec, SPIDEV_PREFIX, plen) && spec[plen])
		return mcp2510_spidev_open(spec + plen, p, out);
	if (!strcmp(spec, SIM_NAME)) {
		return mcp2510_sim_open("", p, out);
	}
	if (!strncmp(spec, SIM_NAME ":", strlen(SIM_NAME ":")) &&
	    spec[strlen(SIM_NAME ":")]) {
		spec += strlen(SIM_NAME ":");
		if (strchr(spec, '@'))
			return mcp2510_simbus_open(spec, p, out);
		return mcp2510_sim_open(spec, p, out);
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

/*
 * Write @a then @b to @reg and read each back: a MISO stuck low or high,
 * or one that echoes MOSI, cannot return both.  0 or -ENODEV.
 */
static int readback_check(struct mcp2510 *h, u8 reg, u8 a, u8 b)
{
	const u8 pattern[2] = { a, b };
	unsigned int i;
	u8 got;
	int ret;

	for (i = 0; i < ARRAY_SIZE(pattern); i++) {
		ret = mcp2510_reg_write(&h->chip, reg, &pattern[i], 1);
		if (!ret)
			ret = mcp2510_reg_read(&h->chip, reg, &got, 1);
		if (ret)
			return ret;
		if (got != pattern[i])
			return -ENODEV;
	}
	return 0;
}

/*
 * After a reset: the core checked the reset values, as the kernel
 * driver's probe does; a configuration register (writable now, in
 * configuration mode) must also keep what is written to it.  CNF1 goes
 * back to its reset value.
 */
static int chip_reset_check(struct mcp2510 *h)
{
	static const u8 cnf1_reset;
	int ret;

	ret = mcp2510_hw_reset(&h->chip);
	if (ret)
		return ret;
	ret = readback_check(h, MCP2510_REG_CNF1, 0xa5, 0x5a);
	if (ret)
		return ret;
	return mcp2510_reg_write(&h->chip, MCP2510_REG_CNF1, &cnf1_reset, 1);
}

/*
 * Without a reset, disturbing nothing: the mode registers must hold an
 * operating mode a chip can be in, and the last data byte of TXB2 must
 * keep what is written to it (its old value is put back).  A buffer
 * with TXREQ set is locked, but a set bit next to clear ones already
 * tells a chip from a stuck line.
 */
static int chip_answers(struct mcp2510 *h)
{
	const u8 reg = MCP2510_REG_TXBD(2, 7);
	u8 mode[2], ctrl, old;	/* CANSTAT, CANCTRL */
	int ret;

	ret = mcp2510_reg_read(&h->chip, MCP2510_REG_CANSTAT, mode, 2);
	if (ret)
		return ret;
	if (mode[0] == 0xff || mode[1] == 0xff ||
	    FIELD_GET(MCP2510_CANSTAT_OPMOD_MASK, mode[0]) > MCP2510_MODE_CONFIG)
		return -ENODEV;
	ret = mcp2510_reg_read(&h->chip, MCP2510_REG_TXBCTRL(2), &ctrl, 1);
	if (ret)
		return ret;
	if (ctrl & MCP2510_TXBCTRL_TXREQ)
		return ctrl == 0xff ? -ENODEV : 0;
	ret = mcp2510_reg_read(&h->chip, reg, &old, 1);
	if (!ret)
		ret = readback_check(h, reg, 0xa5, 0x5a);
	if (ret)
		return ret;
	return mcp2510_reg_write(&h->chip, reg, &old, 1);
}

/*
 * The acceptance filters the chip holds, if someone programmed them
 * since its last reset (the filter command, another program): RESET
 * clears RXM and BUKT in RXBnCTRL and every writer of filters sets at
 * least one of them (rollover is on by default), so a chip with them all
 * clear has filters nobody chose, say the power-on garbage of the
 * filter registers.  Read before the reset that clears RXBnCTRL; 1 when
 * @f holds programmed filters, 0 when not.
 */
static int chip_filters(struct mcp2510 *h, struct mcp2510_filters *f)
{
	u8 regs[MCP2510_REG_RXM(MCP2510_MASK_COUNT)], ctrl[2];
	unsigned int i;
	int ret;

	ret = mcp2510_reg_read(&h->chip, MCP2510_REG_RXBCTRL(0), &ctrl[0], 1);
	if (!ret)
		ret = mcp2510_reg_read(&h->chip, MCP2510_REG_RXBCTRL(1),
				       &ctrl[1], 1);
	if (ret)
		return ret;
	/* a missing chip reads all ones; the reset check will say so */
	if (ctrl[0] == 0xff ||
	    !((ctrl[0] & (MCP2510_RXBCTRL_RXM_MASK | MCP2510_RXB0CTRL_BUKT)) |
	      (ctrl[1] & MCP2510_RXBCTRL_RXM_MASK)))
		return 0;
	ret = mcp2510_reg_read(&h->chip, 0, regs, sizeof(regs));
	if (ret)
		return ret;
	for (i = 0; i < MCP2510_FILTER_COUNT; i++)
		mcp2510_filter_id_decode(regs + MCP2510_REG_RXF(i), false,
				 &f->filter[i]);
	for (i = 0; i < MCP2510_MASK_COUNT; i++)
		mcp2510_filter_id_decode(regs + MCP2510_REG_RXM(i), true, &f->mask[i]);
	f->rxm[0] = FIELD_GET(MCP2510_RXBCTRL_RXM_MASK, ctrl[0]);
	f->rxm[1] = FIELD_GET(MCP2510_RXBCTRL_RXM_MASK, ctrl[1]);
	f->rollover = ctrl[0] & MCP2510_RXB0CTRL_BUKT;
	return mcp2510_filters_check(f) ? 0 : 1;
}

/* Reset and check the chip, keeping the filters it was given. */
static int chip_reset_keep_filters(struct mcp2510 *h)
{
	struct mcp2510_filters f;
	int kept, ret;

	kept = chip_filters(h, &f);
	if (kept < 0)
		return kept;
	ret = chip_reset_check(h);
	if (ret)
		return ret;
	h->reset_done = true;
	if (!kept)
		return 0;
	ret = mcp2510_filters_apply(&h->chip, &f);
	if (!ret)
		h->filters = f;
	return ret;
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
	int ret;

	ret = mcp2510_init(&h->chip, v, o->osc_hz, &lib_ops,
			   &mcp2510_lib_events, h);
	if (ret)
		return ret;
	/* The library drains every flag per pass, as an edge input needs. */
	h->chip.irq_edge = true;
	ret = transport_open(spec, &p, &h->transport);
	if (ret)
		return ret;
	if (h->transport->ops->set_irq_hook)
		h->transport->ops->set_irq_hook(h->transport,
						mcp2510_irq_hook, h);
	ret = pollset_open(h);
	if (ret)
		return ret;
	/* a simulated chip is new, so looking without a reset is safe too */
	if (o->no_reset)
		return chip_answers(h);
	return chip_reset_keep_filters(h);
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
	if (!transport || !v ||
	    !mcp2510_reserved_zero(o->reserved, sizeof(o->reserved))) {
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
	h->reset_done = !ret;
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
