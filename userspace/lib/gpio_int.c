// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * INT through libgpiod (v1 API).  The pin is active low and stays low
 * while any enabled flag is set, so besides falling edges we look at the
 * level: an INT already low when the line is requested, or one that
 * stayed low through a service pass, produces no new edge.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <gpiod.h>

#include "gpio_int.h"

#define CONSUMER "mcp2510"

struct mcp2510_int_line {
	struct gpiod_chip *chip;
	struct gpiod_line *line;
};

static int errno_or(int fallback)
{
	return errno ? -errno : -fallback;
}

/* Split "CHIP:LINE" at its last colon (chip paths have none). */
static int split_spec(const char *spec, char *chip, size_t chip_len,
		      const char **line)
{
	const char *colon = strrchr(spec, ':');
	size_t n;

	if (!colon || colon == spec || !colon[1])
		return -EINVAL;
	n = (size_t)(colon - spec);
	if (n >= chip_len)
		return -EINVAL;
	memcpy(chip, spec, n);
	chip[n] = '\0';
	*line = colon + 1;
	return 0;
}

static struct gpiod_line *find_line(struct gpiod_chip *chip, const char *name)
{
	char *end;
	unsigned long offset;

	errno = 0;
	offset = strtoul(name, &end, 10);
	if (*end)
		return gpiod_chip_find_line(chip, name);
	if (errno || offset > UINT_MAX)
		return NULL;
	return gpiod_chip_get_line(chip, (unsigned int)offset);
}

int mcp2510_int_line_open(const char *spec, struct mcp2510_int_line **out)
{
	struct mcp2510_int_line *l;
	const char *line_name;
	char chip_name[PATH_MAX];
	int ret;

	ret = split_spec(spec, chip_name, sizeof(chip_name), &line_name);
	if (ret)
		return ret;
	l = calloc(1, sizeof(*l));
	if (!l)
		return -ENOMEM;
	errno = 0;
	l->chip = gpiod_chip_open_lookup(chip_name);
	if (!l->chip) {
		ret = errno_or(ENODEV);
		goto out_free;
	}
	errno = 0;
	l->line = find_line(l->chip, line_name);
	if (!l->line) {
		ret = errno_or(ENOENT);
		goto out_close;
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
