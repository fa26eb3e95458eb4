// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * INT through libgpiod 1 (gpio_int_v2.c is the libgpiod 2 backend; the
 * build picks one).  The pin is active low and stays low while any
 * enabled flag is set, so besides falling edges we look at the level:
 * an INT already low when the line is requested, or one that stayed low
 * through a service pass, produces no new edge.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdlib.h>
#include <gpiod.h>

#include "gpio_int.h"
#include "gpio_spec.h"

#define CONSUMER "mcp2510"

struct mcp2510_int_line {
	struct gpiod_chip *chip;
	struct gpiod_line *line;
};

static int errno_or(int fallback)
{
	return errno ? -errno : -fallback;
}

/*
 * The line of @spec, with the chip that owns it in *chip, or NULL with
 * errno set (ENODEV: no such chip, ENOENT: no such line).  A bare line
 * name is looked up on every chip, as gpiod_line_find() does.
 */
static struct gpiod_line *find_line(const struct mcp2510_gpio_spec *spec,
				    struct gpiod_chip **chip)
{
	struct gpiod_line *line;

	errno = 0;
	if (!spec->chip[0]) {
		line = gpiod_line_find(spec->line);
		if (!line) {
			errno = -errno_or(ENOENT);
			return NULL;
		}
		*chip = gpiod_line_get_chip(line);
		return line;
	}
	*chip = gpiod_chip_open_lookup(spec->chip);
	if (!*chip) {
		errno = -errno_or(ENODEV);
		return NULL;
	}
	errno = 0;
	if (spec->by_offset)
		line = gpiod_chip_get_line(*chip, spec->offset);
	else
		line = gpiod_chip_find_line(*chip, spec->line);
	if (!line) {
		errno = -errno_or(ENOENT);
		gpiod_chip_close(*chip);
	}
	return line;
}

int mcp2510_int_line_open(const char *spec, struct mcp2510_int_line **out)
{
	struct mcp2510_gpio_spec parsed;
	struct mcp2510_int_line *l;
	int ret;

	ret = mcp2510_gpio_spec_parse(spec, &parsed);
	if (ret)
		return ret;
	l = calloc(1, sizeof(*l));
	if (!l)
		return -ENOMEM;
	l->line = find_line(&parsed, &l->chip);
	if (!l->line) {
		ret = -errno;
		goto out_free;
	}
	errno = 0;
	if (gpiod_line_request_falling_edge_events(l->line, CONSUMER)) {
		ret = errno_or(EBUSY);
		goto out_close;
	}
	*out = l;
	return 0;

out_close:
	gpiod_chip_close(l->chip);
out_free:
	free(l);
	return ret;
}

static int drain_edges(struct mcp2510_int_line *l)
{
	const struct timespec now = { 0, 0 };
	struct gpiod_line_event ev;
	int ret;

	while ((ret = gpiod_line_event_wait(l->line, &now)) == 1) {
		if (gpiod_line_event_read(l->line, &ev))
			return errno_or(EIO);
	}
	return ret < 0 ? errno_or(EIO) : 0;
}

static int int_asserted(struct mcp2510_int_line *l)
{
	int level = gpiod_line_get_value(l->line);

	if (level < 0)
		return errno_or(EIO);
	return level == 0;
}

int mcp2510_int_line_wait(struct mcp2510_int_line *l, int timeout_ms)
{
	struct timespec ts = {
		.tv_sec = timeout_ms / 1000,
		.tv_nsec = (long)(timeout_ms % 1000) * 1000000L,
	};
	int ret;

	ret = int_asserted(l);
	if (ret < 0)
		return ret;
	if (!ret) {
		ret = gpiod_line_event_wait(l->line,
					    timeout_ms < 0 ? NULL : &ts);
		if (ret <= 0)
			return ret < 0 ? errno_or(EIO) : 0;
	}
	/* Serviced now: edges queued until here must not wake us again. */
	ret = drain_edges(l);
	return ret ? ret : 1;
}

int mcp2510_int_line_fd(const struct mcp2510_int_line *l)
{
	return gpiod_line_event_get_fd(l->line);
}

void mcp2510_int_line_close(struct mcp2510_int_line *l)
{
	if (!l)
		return;
	gpiod_line_release(l->line);
	gpiod_chip_close(l->chip);
	free(l);
}
