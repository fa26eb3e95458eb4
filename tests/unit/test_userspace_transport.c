// SPDX-License-Identifier: GPL-2.0
/*
 * The spidev transport and the libgpiod INT line with their system calls
 * and libgpiod replaced at link time (-Wl,--wrap=...): what reaches the
 * kernel (ioctl numbers, spi_ioc_transfer fields, GPIO requests) and how
 * failures come back.  The library runs on top of them for the error
 * mapping at the public edge; this suite links the library without the
 * chip model.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <setjmp.h>
#include <string.h>
#include <time.h>
#include <cmocka.h>
#include <gpiod.h>
#include <linux/spi/spidev.h>

#include "gpio_int.h"
#include "mcp2510.h"
#include "transport.h"

#define FAKE_FD		4242
#define MAX_CALLS	64

/* ---- the fake kernel: open, close, ioctl --------------------------- */

struct ioctl_call {
	unsigned long req;
	uint32_t value;			/* mode, bits or speed written */
	struct spi_ioc_transfer tr;	/* SPI_IOC_MESSAGE(1) */
	uint8_t tx[16];
};

static struct {
	const char *opened;
	int open_errno;			/* 0: open succeeds */
	int closed;
	unsigned long fail_req;		/* ioctl that fails with EIO */
	uint8_t miso;			/* what every rx byte reads */
	struct ioctl_call calls[MAX_CALLS];
	unsigned int ncalls;
} k;

int __real_close(int fd);

int __wrap_open(const char *path, int flags, ...)
{
	assert_true(flags & O_RDWR);
	k.opened = path;
	if (k.open_errno) {
		errno = k.open_errno;
		return -1;
	}
	return FAKE_FD;
}

int __wrap_close(int fd)
{
	if (fd == FAKE_FD) {
		k.closed++;
		return 0;
	}
	return __real_close(fd);
}

static void record_transfer(struct ioctl_call *c, void *arg)
{
	struct spi_ioc_transfer *tr = arg;

	c->tr = *tr;
	if (tr->tx_buf && tr->len <= sizeof(c->tx))
		memcpy(c->tx, (const void *)(uintptr_t)tr->tx_buf, tr->len);
	if (tr->rx_buf)
		memset((void *)(uintptr_t)tr->rx_buf, k.miso, tr->len);
}

int __wrap_ioctl(int fd, unsigned long req, ...)
{
	struct ioctl_call *c;
	va_list ap;
	void *arg;

	va_start(ap, req);
	arg = va_arg(ap, void *);
	va_end(ap);
	assert_int_equal(fd, FAKE_FD);
	assert_true(k.ncalls < MAX_CALLS);
	c = &k.calls[k.ncalls++];
	memset(c, 0, sizeof(*c));
	c->req = req;
	if (req == SPI_IOC_WR_MODE || req == SPI_IOC_WR_BITS_PER_WORD)
		c->value = *(uint8_t *)arg;
	else if (req == SPI_IOC_WR_MAX_SPEED_HZ)
		c->value = *(uint32_t *)arg;
	else if (req == SPI_IOC_MESSAGE(1))
		record_transfer(c, arg);
	if (req == k.fail_req) {
		errno = EIO;
		return -1;
	}
	return 0;
}

/* ---- the fake libgpiod ------------------------------------------------ */

static char chip_obj, line_obj;
#define FAKE_CHIP ((struct gpiod_chip *)&chip_obj)
#define FAKE_LINE ((struct gpiod_line *)&line_obj)

/*
 * The names the library passed, copied: they point into its own stack
 * frame, gone by the time a test looks (libgpiod copies them too).
 */
static struct {
	const char *chip_name;		/* NULL until a chip is opened */
	char chip_buf[64];
	unsigned int offset;
	const char *line_name;		/* NULL until a line is looked up */
	char line_buf[64];
	const char *consumer;
	bool chip_missing, line_busy;
	int level;			/* what gpiod_line_get_value returns */
	int edges;			/* falling edges queued */
	int wait_result;		/* gpiod_line_event_wait with no edge */
	int waits_with_timeout, reads, released, chip_closed;
	int found_anywhere;		/* gpiod_line_find calls */
	long last_timeout_ms;
} g;

static const char *remember(char *buf, size_t size, const char *name)
{
	snprintf(buf, size, "%s", name);
	return buf;
}

struct gpiod_chip *__wrap_gpiod_chip_open_lookup(const char *descr)
{
	g.chip_name = remember(g.chip_buf, sizeof(g.chip_buf), descr);
	if (g.chip_missing) {
		errno = ENOENT;
		return NULL;
	}
	return FAKE_CHIP;
}

void __wrap_gpiod_chip_close(struct gpiod_chip *chip)
{
	assert_ptr_equal(chip, FAKE_CHIP);
	g.chip_closed++;
}

struct gpiod_line *__wrap_gpiod_chip_get_line(struct gpiod_chip *chip,
					      unsigned int offset)
{
	assert_ptr_equal(chip, FAKE_CHIP);
	g.offset = offset;
	return FAKE_LINE;
}

/* every chip's lines by name: only MCP_INT exists */
struct gpiod_line *__wrap_gpiod_line_find(const char *name)
{
	g.line_name = remember(g.line_buf, sizeof(g.line_buf), name);
	g.found_anywhere++;
	if (strcmp(name, "MCP_INT")) {
		errno = ENOENT;
		return NULL;
	}
	return FAKE_LINE;
}

struct gpiod_chip *__wrap_gpiod_line_get_chip(struct gpiod_line *line)
{
	assert_ptr_equal(line, FAKE_LINE);
	return FAKE_CHIP;
}

struct gpiod_line *__wrap_gpiod_chip_find_line(struct gpiod_chip *chip,
					       const char *name)
{
	assert_ptr_equal(chip, FAKE_CHIP);
	g.line_name = remember(g.line_buf, sizeof(g.line_buf), name);
	if (strcmp(name, "MCP_INT")) {
		errno = ENOENT;
		return NULL;
	}
	return FAKE_LINE;
}

int __wrap_gpiod_line_request_falling_edge_events(struct gpiod_line *line,
						  const char *consumer)
{
	assert_ptr_equal(line, FAKE_LINE);
	g.consumer = consumer;
	if (g.line_busy) {
		errno = EBUSY;
		return -1;
	}
	return 0;
}

void __wrap_gpiod_line_release(struct gpiod_line *line)
{
	assert_ptr_equal(line, FAKE_LINE);
	g.released++;
}

int __wrap_gpiod_line_get_value(struct gpiod_line *line)
{
	assert_ptr_equal(line, FAKE_LINE);
	return g.level;
}

int __wrap_gpiod_line_event_wait(struct gpiod_line *line,
				 const struct timespec *timeout)
{
	assert_ptr_equal(line, FAKE_LINE);
	if (timeout && (timeout->tv_sec || timeout->tv_nsec)) {
		g.waits_with_timeout++;
		g.last_timeout_ms = timeout->tv_sec * 1000 + timeout->tv_nsec / 1000000;
	}
	if (g.edges)
		return 1;
	if (g.wait_result < 0)
		errno = EIO;
	return g.wait_result;
}

int __wrap_gpiod_line_event_read(struct gpiod_line *line,
				 struct gpiod_line_event *ev)
{
	assert_ptr_equal(line, FAKE_LINE);
	assert_true(g.edges > 0);
	g.edges--;
	g.reads++;
	ev->event_type = GPIOD_LINE_EVENT_FALLING_EDGE;
	return 0;
}

int __wrap_gpiod_line_event_get_fd(struct gpiod_line *line)
{
	assert_ptr_equal(line, FAKE_LINE);
	return 77;
}

/* ---- helpers -------------------------------------------------------------- */

static int reset_fakes(void **state)
{
	(void)state;
	memset(&k, 0, sizeof(k));
	memset(&g, 0, sizeof(g));
	g.level = 1;			/* INT idle (high) */
	return 0;
}

static struct mcp2510_transport_params params(uint32_t hz, uint8_t mode)
{
	struct mcp2510_transport_params p = {
		.spi_hz = hz, .spi_mode = mode, .poll_ms = 2,
		.osc_hz = 16000000,
	};
	return p;
}

static struct mcp2510_transport *open_spidev(uint32_t hz, uint8_t mode)
{
	struct mcp2510_transport_params p = params(hz, mode);
	struct mcp2510_transport *t = NULL;

	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), 0);
	assert_non_null(t);
	return t;
}

/* ---- spidev ------------------------------------------------------------- */

static void test_open_configures_mode_bits_speed(void **state)
{
	struct mcp2510_transport *t;

	(void)state;
	t = open_spidev(5000000, 0);
	assert_string_equal(k.opened, "/dev/spidev0.0");
	assert_int_equal(k.ncalls, 3);
	assert_int_equal(k.calls[0].req, SPI_IOC_WR_MODE);
	assert_int_equal(k.calls[0].value, SPI_MODE_0);
	assert_int_equal(k.calls[1].req, SPI_IOC_WR_BITS_PER_WORD);
	assert_int_equal(k.calls[1].value, 8);
	assert_int_equal(k.calls[2].req, SPI_IOC_WR_MAX_SPEED_HZ);
	assert_int_equal(k.calls[2].value, 5000000);
	t->ops->close(t);
	assert_int_equal(k.closed, 1);
}

static void test_open_mode_3_and_refuses_others(void **state)
{
	struct mcp2510_transport_params p = params(10000000, 1);
	struct mcp2510_transport *t;

	(void)state;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), -EINVAL);
	assert_null(k.opened);
	t = open_spidev(10000000, 3);
	assert_int_equal(k.calls[0].value, SPI_MODE_3);
	assert_int_equal(k.calls[2].value, 10000000);
	t->ops->close(t);
}

static void test_open_failures(void **state)
{
	struct mcp2510_transport_params p = params(5000000, 0);
	struct mcp2510_transport *t;

	(void)state;
	k.open_errno = EACCES;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), -EACCES);
	k.open_errno = 0;
	k.fail_req = SPI_IOC_WR_MAX_SPEED_HZ;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), -EIO);
	assert_int_equal(k.closed, 1);
}

static void test_one_transfer_per_cs_low_period(void **state)
{
	const uint8_t tx[3] = { 0x03, 0x0e, 0x00 };
	struct mcp2510_transport_counts c;
	struct mcp2510_transport *t;
	uint8_t rx[3] = { 0 };

	(void)state;
	t = open_spidev(5000000, 0);
	k.ncalls = 0;
	k.miso = 0x80;
	assert_int_equal(t->ops->xfer(t, tx, rx, sizeof(tx)), 0);
	assert_int_equal(k.ncalls, 1);
	assert_int_equal(k.calls[0].req, SPI_IOC_MESSAGE(1));
	assert_int_equal(k.calls[0].tr.len, 3);
	assert_int_equal(k.calls[0].tr.speed_hz, 5000000);
	assert_int_equal(k.calls[0].tr.bits_per_word, 8);
	assert_int_equal(k.calls[0].tr.cs_change, 0);
	assert_int_equal(k.calls[0].tr.delay_usecs, 0);
	assert_memory_equal(k.calls[0].tx, tx, sizeof(tx));
	assert_int_equal(rx[2], 0x80);
	/* a write-only transfer passes no receive buffer */
	assert_int_equal(t->ops->xfer(t, tx, NULL, 1), 0);
	assert_int_equal(k.calls[1].tr.rx_buf, 0);
	t->ops->counts(t, &c);
	assert_int_equal(c.spi_transfers, 2);
	assert_int_equal(c.spi_bytes, 4);
	t->ops->close(t);
}

static void test_transfer_failure_is_eio(void **state)
{
	const uint8_t tx[1] = { 0xc0 };
	struct mcp2510_transport_counts c;
	struct mcp2510_transport *t;

	(void)state;
	t = open_spidev(5000000, 0);
	k.fail_req = SPI_IOC_MESSAGE(1);
	assert_int_equal(t->ops->xfer(t, tx, NULL, 1), -EIO);
	t->ops->counts(t, &c);
	assert_int_equal(c.spi_transfers, 0);
	t->ops->close(t);
}

/* ---- the public edge over a fake spidev ------------------------------- */

static void test_library_maps_errors_to_errno(void **state)
{
	struct mcp2510_options o;

	(void)state;
	mcp2510_options_init(&o);
	k.open_errno = ENOENT;
	errno = 0;
	assert_null(mcp2510_open("spidev:/dev/spidev9.9", &o));
	assert_int_equal(errno, ENOENT);
	k.open_errno = 0;
	k.fail_req = SPI_IOC_MESSAGE(1);
	errno = 0;
	assert_null(mcp2510_open("spidev:/dev/spidev0.0", &o));
	assert_int_equal(errno, EIO);
	assert_int_equal(k.closed, 1);
	errno = 0;
	assert_null(mcp2510_open("usb:0", &o));
	assert_int_equal(errno, EINVAL);
	o.variant = "mcp9999";
	assert_null(mcp2510_open("spidev:/dev/spidev0.0", &o));
	assert_int_equal(errno, EINVAL);
}

static void test_library_default_speed_follows_variant(void **state)
{
	struct mcp2510_options o;

	(void)state;
	mcp2510_options_init(&o);
	o.variant = "mcp2515";
	k.fail_req = SPI_IOC_MESSAGE(1);	/* stop after configuring */
	assert_null(mcp2510_open("spidev:/dev/spidev0.0", &o));
	assert_int_equal(k.calls[2].req, SPI_IOC_WR_MAX_SPEED_HZ);
	assert_int_equal(k.calls[2].value, 10000000);
	memset(&k, 0, sizeof(k));
	k.fail_req = SPI_IOC_MESSAGE(1);
	o.variant = NULL;
	assert_null(mcp2510_open("spidev:/dev/spidev0.0", &o));
	assert_int_equal(k.calls[2].value, 5000000);
}

static void test_library_without_model_refuses_sim(void **state)
{
	(void)state;
	errno = 0;
	assert_null(mcp2510_open("sim", NULL));
	assert_int_equal(errno, EPROTONOSUPPORT);
}

/* ---- INT through libgpiod ---------------------------------------------- */

static struct mcp2510_int_line *open_line(const char *spec)
{
	struct mcp2510_int_line *l = NULL;

	assert_int_equal(mcp2510_int_line_open(spec, &l), 0);
	assert_non_null(l);
	return l;
}

static void test_int_line_request(void **state)
{
	struct mcp2510_int_line *l;

	(void)state;
	l = open_line("gpiochip0:25");
	assert_string_equal(g.chip_name, "gpiochip0");
	assert_int_equal(g.offset, 25);
	assert_string_equal(g.consumer, "mcp2510");
	assert_int_equal(mcp2510_int_line_fd(l), 77);
	mcp2510_int_line_close(l);
	assert_int_equal(g.released, 1);
	assert_int_equal(g.chip_closed, 1);
	/* a path, and a line given by name */
	l = open_line("/dev/gpiochip1:MCP_INT");
	assert_string_equal(g.chip_name, "/dev/gpiochip1");
	assert_string_equal(g.line_name, "MCP_INT");
	mcp2510_int_line_close(l);
	assert_int_equal(g.found_anywhere, 0);
	/* a line name alone: looked up on every chip, its chip closed after */
	g.chip_name = NULL;
	l = open_line("MCP_INT");
	assert_int_equal(g.found_anywhere, 1);
	assert_null(g.chip_name);
	assert_string_equal(g.consumer, "mcp2510");
	mcp2510_int_line_close(l);
	assert_int_equal(g.chip_closed, 3);
}

static void test_int_line_bad_specs(void **state)
{
	struct mcp2510_int_line *l;

	(void)state;
	assert_int_equal(mcp2510_int_line_open("gpiochip0:", &l), -EINVAL);
	assert_int_equal(mcp2510_int_line_open(":5", &l), -EINVAL);
	assert_int_equal(mcp2510_int_line_open("", &l), -EINVAL);
	/* an offset without its chip */
	assert_int_equal(mcp2510_int_line_open("25", &l), -EINVAL);
	assert_null(g.chip_name);
	assert_int_equal(g.found_anywhere, 0);
	assert_int_equal(mcp2510_int_line_open("gpiochip0:NOPE", &l), -ENOENT);
	assert_int_equal(g.chip_closed, 1);
	/* not a number: a name, which no chip has */
	assert_int_equal(mcp2510_int_line_open("gpiochip0:25x", &l), -ENOENT);
	assert_string_equal(g.line_name, "25x");
	assert_int_equal(mcp2510_int_line_open("NOPE", &l), -ENOENT);
	assert_int_equal(g.found_anywhere, 1);
	/* a chip alone is taken for a line name */
	assert_int_equal(mcp2510_int_line_open("gpiochip0", &l), -ENOENT);
	assert_string_equal(g.line_name, "gpiochip0");
	assert_int_equal(g.chip_closed, 2);
	g.chip_missing = true;
	assert_int_equal(mcp2510_int_line_open("gpiochip7:1", &l), -ENOENT);
	g.chip_missing = false;
	g.line_busy = true;
	assert_int_equal(mcp2510_int_line_open("gpiochip0:1", &l), -EBUSY);
}

static void test_int_wait_edge_level_timeout(void **state)
{
	struct mcp2510_int_line *l;

	(void)state;
	l = open_line("gpiochip0:25");
	/* idle, no edge: the wait times out with the caller's timeout */
	assert_int_equal(mcp2510_int_line_wait(l, 250), 0);
	assert_int_equal(g.last_timeout_ms, 250);
	/* a falling edge: serviced, and the edge consumed */
	g.edges = 1;
	assert_int_equal(mcp2510_int_line_wait(l, 250), 1);
	assert_int_equal(g.edges, 0);
	/* INT already low without an edge (asserted before the request) */
	g.level = 0;
	g.edges = 2;
	g.waits_with_timeout = 0;
	assert_int_equal(mcp2510_int_line_wait(l, 250), 1);
	assert_int_equal(g.waits_with_timeout, 0);
	assert_int_equal(g.edges, 0);
	/* failures are errors, not interrupts */
	g.level = 1;
	g.wait_result = -1;
	assert_int_equal(mcp2510_int_line_wait(l, 10), -EIO);
	mcp2510_int_line_close(l);
}

static void test_spidev_uses_the_int_line(void **state)
{
	struct mcp2510_transport_params p = params(5000000, 0);
	struct mcp2510_transport_counts c;
	struct mcp2510_transport *t;

	(void)state;
	p.int_line = "gpiochip2:7";
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), 0);
	assert_int_equal(g.offset, 7);
	assert_int_equal(t->ops->fd(t), 77);
	g.edges = 1;
	assert_int_equal(t->ops->wait_irq(t, 100), 1);
	assert_int_equal(t->ops->wait_irq(t, 100), 0);
	t->ops->counts(t, &c);
	assert_int_equal(c.interrupts, 1);
	t->ops->close(t);
	assert_int_equal(g.released, 1);
	/* a line that cannot be had fails the open and closes the device */
	g.line_busy = true;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), -EBUSY);
	assert_int_equal(k.closed, 2);
}

static void test_polling_without_int_line(void **state)
{
	struct mcp2510_transport_params p = params(5000000, 0);
	struct mcp2510_transport *t;
	struct timespec t0, t1;
	long ms;

	(void)state;
	p.poll_ms = 20;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), 0);
	assert_true(t->ops->fd(t) >= 0);
	clock_gettime(CLOCK_MONOTONIC, &t0);
	assert_int_equal(t->ops->wait_irq(t, 1000), 1);
	clock_gettime(CLOCK_MONOTONIC, &t1);
	ms = (t1.tv_sec - t0.tv_sec) * 1000 + (t1.tv_nsec - t0.tv_nsec) / 1000000;
	assert_in_range(ms, 10, 900);
	/* not due yet: a look without waiting finds nothing */
	assert_int_equal(t->ops->wait_irq(t, 0), 0);
	t->ops->close(t);
	p.poll_ms = 0;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), -EINVAL);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup(test_open_configures_mode_bits_speed, reset_fakes),
		cmocka_unit_test_setup(test_open_mode_3_and_refuses_others, reset_fakes),
		cmocka_unit_test_setup(test_open_failures, reset_fakes),
		cmocka_unit_test_setup(test_one_transfer_per_cs_low_period, reset_fakes),
		cmocka_unit_test_setup(test_transfer_failure_is_eio, reset_fakes),
		cmocka_unit_test_setup(test_library_maps_errors_to_errno, reset_fakes),
		cmocka_unit_test_setup(test_library_default_speed_follows_variant, reset_fakes),
		cmocka_unit_test_setup(test_library_without_model_refuses_sim, reset_fakes),
		cmocka_unit_test_setup(test_int_line_request, reset_fakes),
		cmocka_unit_test_setup(test_int_line_bad_specs, reset_fakes),
		cmocka_unit_test_setup(test_int_wait_edge_level_timeout, reset_fakes),
		cmocka_unit_test_setup(test_spidev_uses_the_int_line, reset_fakes),
		cmocka_unit_test_setup(test_polling_without_int_line, reset_fakes),
	};

	return cmocka_run_group_tests_name("userspace_transport", tests, NULL, NULL);
}
