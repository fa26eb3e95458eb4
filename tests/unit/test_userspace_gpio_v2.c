// SPDX-License-Identifier: GPL-2.0
/*
 * The libgpiod 2 backend of the INT line (userspace/lib/gpio_int_v2.c)
 * with libgpiod, the /dev scan and spidev's system calls replaced at link
 * time (-Wl,--wrap=...): the lookups libgpiod 2 no longer does (a chip by
 * number, /dev name or label, a line name on every chip), the request
 * that reaches libgpiod, and INT read as a level as well as by its edges,
 * as the libgpiod 1 backend's tests in test_userspace_transport.c.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include <gpiod.h>

#include "gpio_int.h"
#include "transport.h"

#define FAKE_FD		4242
#define ARRAY_SIZE(a)	(sizeof(a) / sizeof((a)[0]))

/* ---- the fake kernel: spidev's open, close and ioctl ----------------- */

static int spidev_closed;

int __real_close(int fd);

int __wrap_open(const char *path, int flags, ...)
{
	(void)path;
	assert_true(flags & O_RDWR);
	return FAKE_FD;
}

int __wrap_close(int fd)
{
	if (fd == FAKE_FD) {
		spidev_closed++;
		return 0;
	}
	return __real_close(fd);
}

int __wrap_ioctl(int fd, unsigned long req, ...)
{
	(void)req;
	assert_int_equal(fd, FAKE_FD);
	return 0;
}

/* ---- the fake /dev and its GPIO chips --------------------------------- */

struct fake_chip {
	const char *path;
	const char *label;
	unsigned int num_lines;
	const char *names[4];		/* lines 0..3 by name */
	int opens, closes;
};

/* a Raspberry Pi 5 with the simulated chip's INT lines on a third chip */
static struct fake_chip chips[] = {
	{ .path = "/dev/gpiochip0", .label = "gpio-brcmstb@107d508500",
	  .num_lines = 32, .names = { "-", "-", "-", "-" } },
	{ .path = "/dev/gpiochip4", .label = "pinctrl-rp1",
	  .num_lines = 54, .names = { "ID_SDA", "ID_SCL", "GPIO25", "SHARED" } },
	{ .path = "/dev/gpiochip10", .label = "mcp2510-sim",
	  .num_lines = 5, .names = { "INT0", "INT1", "SHARED", "-" } },
};

/* /dev as readdir gives it: unsorted, with other devices */
static const char *const dev_names[] = {
	"null", "gpiochip10", "spidev0.0", "gpiochip4", "gpiochip0",
	"gpiochip99",			/* gone: no longer a GPIO chip */
};

static struct fake_chip *chip_at(const char *path)
{
	size_t i;

	for (i = 0; i < ARRAY_SIZE(chips); i++)
		if (!strcmp(chips[i].path, path))
			return &chips[i];
	return NULL;
}

int __wrap_scandir(const char *dir, struct dirent ***names,
		   int (*filter)(const struct dirent *),
		   int (*compar)(const struct dirent **, const struct dirent **))
{
	struct dirent **list = calloc(ARRAY_SIZE(dev_names), sizeof(*list));
	size_t i;
	int n = 0;

	assert_string_equal(dir, "/dev");
	assert_non_null(list);
	for (i = 0; i < ARRAY_SIZE(dev_names); i++) {
		struct dirent *d = calloc(1, sizeof(*d));

		assert_non_null(d);
		strcpy(d->d_name, dev_names[i]);
		if (filter && !filter(d)) {
			free(d);
			continue;
		}
		list[n++] = d;
	}
	if (compar)
		qsort(list, (size_t)n, sizeof(*list),
		      (int (*)(const void *, const void *))compar);
	*names = list;
	return n;
}

/* ---- the fake libgpiod 2 -------------------------------------------------- */

static char settings_obj, line_cfg_obj, req_cfg_obj, req_obj, buffer_obj;
#define FAKE_SETTINGS	((struct gpiod_line_settings *)&settings_obj)
#define FAKE_LINE_CFG	((struct gpiod_line_config *)&line_cfg_obj)
#define FAKE_REQ_CFG	((struct gpiod_request_config *)&req_cfg_obj)
#define FAKE_REQ	((struct gpiod_line_request *)&req_obj)
#define FAKE_BUFFER	((struct gpiod_edge_event_buffer *)&buffer_obj)

static struct {
	const char *consumer;
	struct fake_chip *requested_on;
	unsigned int offset;
	size_t num_offsets;
	int direction, edge;
	bool line_busy;
	int level;			/* 1 high, 0 low, -1 read error */
	int edges;			/* falling edges queued */
	int wait_result;		/* wait with no edge queued */
	int waits_with_timeout, reads, released;
	int64_t last_timeout_ns;
	size_t buffer_capacity;
	/* what was allocated and not freed */
	int settings, line_cfgs, req_cfgs, buffers, infos;
} g;

static struct fake_chip *fake(struct gpiod_chip *chip)
{
	struct fake_chip *c = (struct fake_chip *)chip;

	assert_true(c >= chips && c < chips + ARRAY_SIZE(chips));
	return c;
}

bool __wrap_gpiod_is_gpiochip_device(const char *path)
{
	return chip_at(path) != NULL;
}

struct gpiod_chip *__wrap_gpiod_chip_open(const char *path)
{
	struct fake_chip *c = chip_at(path);

	if (!c) {
		errno = ENOENT;
		return NULL;
	}
	c->opens++;
	return (struct gpiod_chip *)c;
}

void __wrap_gpiod_chip_close(struct gpiod_chip *chip)
{
	fake(chip)->closes++;
}

struct gpiod_chip_info *__wrap_gpiod_chip_get_info(struct gpiod_chip *chip)
{
	fake(chip);
	g.infos++;
	return (struct gpiod_chip_info *)chip;
}

const char *__wrap_gpiod_chip_info_get_label(struct gpiod_chip_info *info)
{
	return fake((struct gpiod_chip *)info)->label;
}

void __wrap_gpiod_chip_info_free(struct gpiod_chip_info *info)
{
	fake((struct gpiod_chip *)info);
	g.infos--;
}

int __wrap_gpiod_chip_get_line_offset_from_name(struct gpiod_chip *chip,
						const char *name)
{
	struct fake_chip *c = fake(chip);
	int i;

	for (i = 0; i < (int)ARRAY_SIZE(c->names); i++)
		if (!strcmp(c->names[i], name))
			return i;
	errno = ENOENT;
	return -1;
}

struct gpiod_line_settings *__wrap_gpiod_line_settings_new(void)
{
	g.settings++;
	return FAKE_SETTINGS;
}

void __wrap_gpiod_line_settings_free(struct gpiod_line_settings *s)
{
	assert_ptr_equal(s, FAKE_SETTINGS);
	g.settings--;
}

int __wrap_gpiod_line_settings_set_direction(struct gpiod_line_settings *s,
					     enum gpiod_line_direction d)
{
	assert_ptr_equal(s, FAKE_SETTINGS);
	g.direction = d;
	return 0;
}

int __wrap_gpiod_line_settings_set_edge_detection(struct gpiod_line_settings *s,
						  enum gpiod_line_edge edge)
{
	assert_ptr_equal(s, FAKE_SETTINGS);
	g.edge = edge;
	return 0;
}

struct gpiod_line_config *__wrap_gpiod_line_config_new(void)
{
	g.line_cfgs++;
	return FAKE_LINE_CFG;
}

void __wrap_gpiod_line_config_free(struct gpiod_line_config *cfg)
{
	assert_ptr_equal(cfg, FAKE_LINE_CFG);
	g.line_cfgs--;
}

int __wrap_gpiod_line_config_add_line_settings(struct gpiod_line_config *cfg,
					       const unsigned int *offsets,
					       size_t num_offsets,
					       struct gpiod_line_settings *s)
{
	assert_ptr_equal(cfg, FAKE_LINE_CFG);
	assert_ptr_equal(s, FAKE_SETTINGS);
	g.num_offsets = num_offsets;
	g.offset = offsets[0];
	return 0;
}

struct gpiod_request_config *__wrap_gpiod_request_config_new(void)
{
	g.req_cfgs++;
	return FAKE_REQ_CFG;
}

void __wrap_gpiod_request_config_free(struct gpiod_request_config *cfg)
{
	assert_ptr_equal(cfg, FAKE_REQ_CFG);
	g.req_cfgs--;
}

void __wrap_gpiod_request_config_set_consumer(struct gpiod_request_config *cfg,
					      const char *consumer)
{
	assert_ptr_equal(cfg, FAKE_REQ_CFG);
	g.consumer = consumer;
}

struct gpiod_line_request *
__wrap_gpiod_chip_request_lines(struct gpiod_chip *chip,
				struct gpiod_request_config *req_cfg,
				struct gpiod_line_config *line_cfg)
{
	struct fake_chip *c = fake(chip);

	assert_ptr_equal(req_cfg, FAKE_REQ_CFG);
	assert_ptr_equal(line_cfg, FAKE_LINE_CFG);
	if (g.offset >= c->num_lines) {
		errno = EINVAL;
		return NULL;
	}
	if (g.line_busy) {
		errno = EBUSY;
		return NULL;
	}
	g.requested_on = c;
	return FAKE_REQ;
}

void __wrap_gpiod_line_request_release(struct gpiod_line_request *req)
{
	assert_ptr_equal(req, FAKE_REQ);
	g.released++;
}

enum gpiod_line_value
__wrap_gpiod_line_request_get_value(struct gpiod_line_request *req,
				    unsigned int offset)
{
	assert_ptr_equal(req, FAKE_REQ);
	assert_int_equal(offset, g.offset);
	if (g.level < 0) {
		errno = EIO;
		return GPIOD_LINE_VALUE_ERROR;
	}
	return g.level ? GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE;
}

int __wrap_gpiod_line_request_wait_edge_events(struct gpiod_line_request *req,
					       int64_t timeout_ns)
{
	assert_ptr_equal(req, FAKE_REQ);
	if (timeout_ns) {
		g.waits_with_timeout++;
		g.last_timeout_ns = timeout_ns;
	}
	if (g.edges)
		return 1;
	if (g.wait_result < 0)
		errno = EIO;
	return g.wait_result;
}

int __wrap_gpiod_line_request_read_edge_events(struct gpiod_line_request *req,
					       struct gpiod_edge_event_buffer *buf,
					       size_t max_events)
{
	int n;

	assert_ptr_equal(req, FAKE_REQ);
	assert_ptr_equal(buf, FAKE_BUFFER);
	assert_true(max_events <= g.buffer_capacity);
	assert_true(g.edges > 0);
	n = g.edges < (int)max_events ? g.edges : (int)max_events;
	g.edges -= n;
	g.reads++;
	return n;
}

int __wrap_gpiod_line_request_get_fd(struct gpiod_line_request *req)
{
	assert_ptr_equal(req, FAKE_REQ);
	return 77;
}

struct gpiod_edge_event_buffer *__wrap_gpiod_edge_event_buffer_new(size_t capacity)
{
	g.buffer_capacity = capacity;
	g.buffers++;
	return FAKE_BUFFER;
}

void __wrap_gpiod_edge_event_buffer_free(struct gpiod_edge_event_buffer *buf)
{
	assert_ptr_equal(buf, FAKE_BUFFER);
	g.buffers--;
}

/* ---- helpers -------------------------------------------------------------- */

static int reset_fakes(void **state)
{
	size_t i;

	(void)state;
	memset(&g, 0, sizeof(g));
	g.level = 1;			/* INT idle (high) */
	for (i = 0; i < ARRAY_SIZE(chips); i++)
		chips[i].opens = chips[i].closes = 0;
	spidev_closed = 0;
	return 0;
}

/* every chip opened was closed, every object freed */
static void assert_all_released(void)
{
	size_t i;

	for (i = 0; i < ARRAY_SIZE(chips); i++)
		assert_int_equal(chips[i].opens, chips[i].closes);
	assert_int_equal(g.settings, 0);
	assert_int_equal(g.line_cfgs, 0);
	assert_int_equal(g.req_cfgs, 0);
	assert_int_equal(g.buffers, 0);
	assert_int_equal(g.infos, 0);
}

static struct mcp2510_int_line *open_line(const char *spec)
{
	struct mcp2510_int_line *l = NULL;

	assert_int_equal(mcp2510_int_line_open(spec, &l), 0);
	assert_non_null(l);
	/* only the configuration objects were let go of */
	assert_int_equal(g.settings, 0);
	assert_int_equal(g.line_cfgs, 0);
	assert_int_equal(g.req_cfgs, 0);
	assert_int_equal(g.infos, 0);
	return l;
}

/* @spec's line is @offset on @chip, and closing it releases everything */
static void expect_line(const char *spec, struct fake_chip *chip,
			unsigned int offset)
{
	struct mcp2510_int_line *l;

	reset_fakes(NULL);
	l = open_line(spec);
	assert_ptr_equal(g.requested_on, chip);
	assert_int_equal(g.offset, offset);
	assert_int_equal(chip->opens - chip->closes, 1);
	mcp2510_int_line_close(l);
	assert_int_equal(g.released, 1);
	assert_all_released();
}

/* ---- INT through libgpiod 2 -------------------------------------------- */

static void test_v2_int_line_request(void **state)
{
	struct mcp2510_int_line *l;

	(void)state;
	l = open_line("gpiochip0:25");
	assert_ptr_equal(g.requested_on, &chips[0]);
	assert_int_equal(g.num_offsets, 1);
	assert_int_equal(g.offset, 25);
	assert_int_equal(g.direction, GPIOD_LINE_DIRECTION_INPUT);
	assert_int_equal(g.edge, GPIOD_LINE_EDGE_FALLING);
	assert_string_equal(g.consumer, "mcp2510");
	assert_true(g.buffer_capacity > 0);
	assert_int_equal(mcp2510_int_line_fd(l), 77);
	mcp2510_int_line_close(l);
	assert_int_equal(g.released, 1);
	assert_all_released();
}

static void test_v2_chip_by_path_number_name_label(void **state)
{
	(void)state;
	expect_line("/dev/gpiochip4:GPIO25", &chips[1], 2);
	expect_line("gpiochip10:INT1", &chips[2], 1);
	expect_line("4:7", &chips[1], 7);
	expect_line("10:3", &chips[2], 3);
	/* by label: the chips before it opened, looked at and closed */
	expect_line("pinctrl-rp1:GPIO25", &chips[1], 2);
	assert_int_equal(chips[0].opens, 1);
	assert_int_equal(chips[2].opens, 0);
	expect_line("mcp2510-sim:4", &chips[2], 4);
}

static void test_v2_line_name_on_every_chip(void **state)
{
	(void)state;
	/* a Pi 5's header pin, wherever pinctrl-rp1 was numbered */
	expect_line("GPIO25", &chips[1], 2);
	expect_line("INT0", &chips[2], 0);
	/* the first chip by number has it: gpiochip4 before gpiochip10 */
	expect_line("SHARED", &chips[1], 3);
}

static void test_v2_bad_specs(void **state)
{
	struct mcp2510_int_line *l;

	(void)state;
	assert_int_equal(mcp2510_int_line_open("gpiochip0:", &l), -EINVAL);
	assert_int_equal(mcp2510_int_line_open(":5", &l), -EINVAL);
	assert_int_equal(mcp2510_int_line_open("", &l), -EINVAL);
	/* an offset without its chip */
	assert_int_equal(mcp2510_int_line_open("25", &l), -EINVAL);
	assert_int_equal(chips[0].opens + chips[1].opens + chips[2].opens, 0);
	/* no such line on the chip */
	assert_int_equal(mcp2510_int_line_open("gpiochip4:NOPE", &l), -ENOENT);
	assert_int_equal(chips[1].closes, 1);
	/* no such chip by number, name or label */
	assert_int_equal(mcp2510_int_line_open("7:1", &l), -ENOENT);
	assert_int_equal(mcp2510_int_line_open("gpiochip99:1", &l), -ENOENT);
	assert_int_equal(mcp2510_int_line_open("/dev/gpiochip7:1", &l), -ENOENT);
	assert_int_equal(mcp2510_int_line_open("pinctrl-bcm2835:1", &l), -ENOENT);
	/* no chip has the line */
	assert_int_equal(mcp2510_int_line_open("NOPE", &l), -ENOENT);
	/* the scans for "7", "gpiochip99", "pinctrl-bcm2835" and "NOPE" */
	assert_int_equal(chips[2].opens, 4);
	/* past the chip's last line */
	assert_int_equal(mcp2510_int_line_open("gpiochip10:5", &l), -EINVAL);
	g.line_busy = true;
	assert_int_equal(mcp2510_int_line_open("gpiochip0:1", &l), -EBUSY);
	assert_all_released();
}

static void test_v2_wait_edge_level_timeout(void **state)
{
	struct mcp2510_int_line *l;

	(void)state;
	l = open_line("gpiochip0:25");
	/* idle, no edge: the wait times out with the caller's timeout */
	assert_int_equal(mcp2510_int_line_wait(l, 250), 0);
	assert_int_equal(g.last_timeout_ns, 250000000);
	/* a falling edge: serviced, and the edge consumed */
	g.edges = 1;
	assert_int_equal(mcp2510_int_line_wait(l, 250), 1);
	assert_int_equal(g.edges, 0);
	/* INT already low without an edge (asserted before the request) */
	g.level = 0;
	g.edges = 20;			/* more than one read takes */
	g.waits_with_timeout = 0;
	g.reads = 0;
	assert_int_equal(mcp2510_int_line_wait(l, 250), 1);
	assert_int_equal(g.waits_with_timeout, 0);
	assert_int_equal(g.edges, 0);
	assert_int_equal(g.reads, 2);
	/* no timeout: libgpiod 2 waits for ever on a negative one */
	g.level = 1;
	g.edges = 1;
	assert_int_equal(mcp2510_int_line_wait(l, -1), 1);
	assert_true(g.last_timeout_ns < 0);
	/* failures are errors, not interrupts */
	g.wait_result = -1;
	assert_int_equal(mcp2510_int_line_wait(l, 10), -EIO);
	g.wait_result = 0;
	g.level = -1;
	assert_int_equal(mcp2510_int_line_wait(l, 10), -EIO);
	mcp2510_int_line_close(l);
	assert_all_released();
}

static void test_v2_spidev_uses_the_int_line(void **state)
{
	struct mcp2510_transport_params p = {
		.spi_hz = 5000000, .poll_ms = 2, .osc_hz = 16000000,
		.int_line = "mcp2510-sim:INT1",
	};
	struct mcp2510_transport_counts c;
	struct mcp2510_transport *t;

	(void)state;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), 0);
	assert_ptr_equal(g.requested_on, &chips[2]);
	assert_int_equal(g.offset, 1);
	assert_int_equal(t->ops->fd(t), 77);
	g.edges = 1;
	assert_int_equal(t->ops->wait_irq(t, 100), 1);
	assert_int_equal(t->ops->wait_irq(t, 100), 0);
	t->ops->counts(t, &c);
	assert_int_equal(c.interrupts, 1);
	t->ops->close(t);
	assert_int_equal(g.released, 1);
	assert_all_released();
	/* a line that cannot be had fails the open and closes the device */
	g.line_busy = true;
	assert_int_equal(mcp2510_spidev_open("/dev/spidev0.0", &p, &t), -EBUSY);
	assert_int_equal(spidev_closed, 2);
	assert_all_released();
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup(test_v2_int_line_request, reset_fakes),
		cmocka_unit_test_setup(test_v2_chip_by_path_number_name_label, reset_fakes),
		cmocka_unit_test_setup(test_v2_line_name_on_every_chip, reset_fakes),
		cmocka_unit_test_setup(test_v2_bad_specs, reset_fakes),
		cmocka_unit_test_setup(test_v2_wait_edge_level_timeout, reset_fakes),
		cmocka_unit_test_setup(test_v2_spidev_uses_the_int_line, reset_fakes),
	};

	return cmocka_run_group_tests_name("userspace_gpio_v2", tests, NULL, NULL);
}
