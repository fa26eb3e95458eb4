// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * The chip on a Linux spidev device: one SPI_IOC_MESSAGE(1) per
 * chip-select-low period (or one message for a few), INT on a GPIO line or, without one, a periodic
 * timer telling the library when to look at the chip.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sys/ioctl.h>
#include <sys/timerfd.h>
#include <linux/spi/spidev.h>

#include "gpio_int.h"
#include "transport.h"

struct spidev_transport {
	struct mcp2510_transport base;
	int fd;
	uint32_t speed_hz;
	struct mcp2510_int_line *int_line;	/* NULL: poll with timer_fd */
	int timer_fd;
	struct mcp2510_transport_counts counts;
};

static struct spidev_transport *to_spidev(struct mcp2510_transport *t)
{
	return (struct spidev_transport *)t;
}

static const struct spidev_transport *
to_spidev_const(const struct mcp2510_transport *t)
{
	return (const struct spidev_transport *)t;
}

static int spidev_xfer(struct mcp2510_transport *t, const uint8_t *tx,
		       uint8_t *rx, unsigned int len)
{
	struct spidev_transport *s = to_spidev(t);
	struct spi_ioc_transfer tr;

	memset(&tr, 0, sizeof(tr));
	tr.tx_buf = (uintptr_t)tx;
	tr.rx_buf = (uintptr_t)rx;
	tr.len = len;
	tr.speed_hz = s->speed_hz;
	tr.bits_per_word = 8;
	/* cs_change 0: CS rises after the transfer, which ends the command */
	if (ioctl(s->fd, SPI_IOC_MESSAGE(1), &tr) < 0)
		return -EIO;
	s->counts.spi_transfers++;
	s->counts.spi_bytes += len;
	return 0;
}

#define SPIDEV_MSG_MAX	4

/*
 * One SPI_IOC_MESSAGE of @n transfers, cs_change on all but the last: CS
 * rises between them for the controller's cs_change delay (spidev does
 * not let us set it; the SPI core's default is 10 us), with no return to
 * userspace in between.
 */
static int spidev_xfer_msg(struct mcp2510_transport *t,
			   const struct mcp2510_transport_xfer *x,
			   unsigned int n)
{
	struct spidev_transport *s = to_spidev(t);
	struct spi_ioc_transfer tr[SPIDEV_MSG_MAX];
	unsigned int i;

	if (!n || n > SPIDEV_MSG_MAX)
		return -EINVAL;
	memset(tr, 0, sizeof(tr));
	for (i = 0; i < n; i++) {
		tr[i].tx_buf = (uintptr_t)x[i].tx;
		tr[i].rx_buf = (uintptr_t)x[i].rx;
		tr[i].len = x[i].len;
		tr[i].speed_hz = s->speed_hz;
		tr[i].bits_per_word = 8;
		tr[i].cs_change = i + 1 < n;
	}
	if (ioctl(s->fd, SPI_IOC_MESSAGE(n), tr) < 0)
		return -EIO;
	for (i = 0; i < n; i++) {
		s->counts.spi_transfers++;
		s->counts.spi_bytes += x[i].len;
	}
	return 0;
}

static void spidev_delay_us(struct mcp2510_transport *t, unsigned int us)
{
	struct timespec ts = {
		.tv_sec = us / 1000000u,
		.tv_nsec = (long)(us % 1000000u) * 1000L,
	};

	(void)t;
	while (nanosleep(&ts, &ts) && errno == EINTR)
		;
}

/* The polling fallback: "service the chip" whenever the timer expired. */
static int timer_wait(int fd, int timeout_ms)
{
	struct pollfd pfd = { .fd = fd, .events = POLLIN };
	uint64_t expirations;
	int ret;

	ret = poll(&pfd, 1, timeout_ms);
	/* a signal: look at the chip now, it costs one transfer */
	if (ret < 0)
		return errno == EINTR ? 1 : -errno;
	if (ret == 0)
		return 0;
	if (read(fd, &expirations, sizeof(expirations)) < 0 && errno != EAGAIN)
		return -errno;
	return 1;
}

static int spidev_wait_irq(struct mcp2510_transport *t, int timeout_ms)
{
	struct spidev_transport *s = to_spidev(t);
	int ret;

	if (s->int_line)
		ret = mcp2510_int_line_wait(s->int_line, timeout_ms);
	else
		ret = timer_wait(s->timer_fd, timeout_ms);
	if (ret > 0)
		s->counts.interrupts++;
	return ret;
}

static int spidev_fd(const struct mcp2510_transport *t)
{
	const struct spidev_transport *s = to_spidev_const(t);

	return s->int_line ? mcp2510_int_line_fd(s->int_line) : s->timer_fd;
}

static void spidev_counts(const struct mcp2510_transport *t,
			  struct mcp2510_transport_counts *c)
{
	*c = to_spidev_const(t)->counts;
}

static void spidev_close(struct mcp2510_transport *t)
{
	struct spidev_transport *s = to_spidev(t);

	mcp2510_int_line_close(s->int_line);
	if (s->timer_fd >= 0)
		close(s->timer_fd);
	close(s->fd);
	free(s);
}

static const struct mcp2510_transport_ops spidev_ops = {
	.xfer = spidev_xfer,
	.xfer_msg = spidev_xfer_msg,
	.delay_us = spidev_delay_us,
	.wait_irq = spidev_wait_irq,
	.fd = spidev_fd,
	.counts = spidev_counts,
	.close = spidev_close,
};

static int spidev_configure(int fd, const struct mcp2510_transport_params *p)
{
	uint8_t mode = p->spi_mode == 3 ? SPI_MODE_3 : SPI_MODE_0;
	uint8_t bits = 8;
	uint32_t speed = p->spi_hz;

	/* ENOTTY passes through: the caller can say "not a spidev device" */
	if (ioctl(fd, SPI_IOC_WR_MODE, &mode) < 0 ||
	    ioctl(fd, SPI_IOC_WR_BITS_PER_WORD, &bits) < 0 ||
	    ioctl(fd, SPI_IOC_WR_MAX_SPEED_HZ, &speed) < 0)
		return errno == ENOTTY ? -ENOTTY : -EIO;
	return 0;
}

static int poll_timer_open(unsigned int interval_ms)
{
	struct itimerspec its = {
		.it_interval.tv_sec = interval_ms / 1000u,
		.it_interval.tv_nsec = (long)(interval_ms % 1000u) * 1000000L,
	};
	int fd;

	its.it_value = its.it_interval;
	fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
	if (fd < 0)
		return -errno;
	if (timerfd_settime(fd, 0, &its, NULL) < 0) {
		int err = -errno;

		close(fd);
		return err;
	}
	return fd;
}

/* INT on a GPIO line if one is named, else the polling timer. */
static int spidev_irq_open(struct spidev_transport *s,
			   const struct mcp2510_transport_params *p)
{
	int fd;

	if (p->int_line)
		return mcp2510_int_line_open(p->int_line, &s->int_line);
	if (!p->poll_ms)
		return -EINVAL;
	fd = poll_timer_open(p->poll_ms);
	if (fd < 0)
		return fd;
	s->timer_fd = fd;
	return 0;
}

int mcp2510_spidev_open(const char *path,
			const struct mcp2510_transport_params *p,
			struct mcp2510_transport **out)
{
	struct spidev_transport *s;
	int ret;

	if (p->spi_mode != 0 && p->spi_mode != 3)
		return -EINVAL;
	s = calloc(1, sizeof(*s));
	if (!s)
		return -ENOMEM;
	s->base.ops = &spidev_ops;
	s->speed_hz = p->spi_hz;
	s->timer_fd = -1;
	s->fd = open(path, O_RDWR | O_CLOEXEC);
	if (s->fd < 0) {
		ret = -errno;
		goto out_free;
	}
	ret = spidev_configure(s->fd, p);
	if (ret)
		goto out_close;
	ret = spidev_irq_open(s, p);
	if (ret)
		goto out_close;
	*out = &s->base;
	return 0;

out_close:
	close(s->fd);
out_free:
	free(s);
	return ret;
}
