// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * INT through libgpiod 2 (gpio_int_v1.c is the libgpiod 1 backend; the
 * build picks one).  The pin is active low and stays low while any
 * enabled flag is set, so besides falling edges we look at the level:
 * an INT already low when the line is requested, or one that stayed low
 * through a service pass, produces no new edge.
 *
 * libgpiod 2 opens chips by path only and finds line names on one chip
 * only, so the lookups that libgpiod 1 did are done here: a chip by
 * path, number, /dev name or label, a bare line name on every chip (a
 * Raspberry Pi 5's header pins are on the chip labelled pinctrl-rp1,
 * whose number changes between kernels).
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <gpiod.h>

#include "gpio_int.h"
#include "gpio_spec.h"

#define CONSUMER "mcp2510"
#define DEV_DIR "/dev"
/* edges read per call while draining; more just take another call */
#define EDGE_BUFFER 16

struct mcp2510_int_line {
	struct gpiod_chip *chip;
	struct gpiod_line_request *req;
	struct gpiod_edge_event_buffer *edges;
	unsigned int offset;
};

static int errno_or(int fallback)
{
	return errno ? -errno : -fallback;
}

/* ---- finding the chip and the line -------------------------------------- */

static int is_chip_entry(const struct dirent *d)
{
	return !strncmp(d->d_name, "gpiochip", 8);
}

/* true when @chip is the one sought (@what); may fill *offset */
typedef bool (*chip_match_fn)(struct gpiod_chip *chip, const char *what,
			      unsigned int *offset);

/*
 * Open the chips of /dev in their numbers' order and return the first
 * that @match accepts, the others closed again.  NULL with errno ENOENT
 * when none does.
 */
static struct gpiod_chip *scan_chips(chip_match_fn match, const char *what,
				     unsigned int *offset)
{
	struct gpiod_chip *found = NULL, *chip;
	struct dirent **names;
	char path[sizeof(DEV_DIR) + 256];
	int n, i;

	n = scandir(DEV_DIR, &names, is_chip_entry, versionsort);
	if (n < 0)
		return NULL;
	for (i = 0; i < n; i++) {
		if (!found) {
			snprintf(path, sizeof(path), DEV_DIR "/%s",
				 names[i]->d_name);
			/* a chip we may not open is not the one */
			chip = gpiod_is_gpiochip_device(path) ?
			       gpiod_chip_open(path) : NULL;
			if (chip && match(chip, what, offset))
				found = chip;
			else if (chip)
				gpiod_chip_close(chip);
		}
		free(names[i]);
	}
	free(names);
	errno = found ? 0 : ENOENT;
	return found;
}

static bool label_is(struct gpiod_chip *chip, const char *label,
		     unsigned int *offset)
{
	struct gpiod_chip_info *info = gpiod_chip_get_info(chip);
	bool same;

	(void)offset;
	if (!info)
		return false;
	same = !strcmp(gpiod_chip_info_get_label(info), label);
	gpiod_chip_info_free(info);
	return same;
}

static bool has_line(struct gpiod_chip *chip, const char *name,
		     unsigned int *offset)
{
	int off = gpiod_chip_get_line_offset_from_name(chip, name);

	if (off < 0)
		return false;
	*offset = (unsigned int)off;
	return true;
}

/*
 * The chip as libgpiod 1's gpiod_chip_open_lookup() took it: a path, a
 * number N for /dev/gpiochipN, a name in /dev, else a label.  NULL with
 * errno set.
 */
static struct gpiod_chip *open_chip(const char *chip)
{
	char path[sizeof(DEV_DIR) + PATH_MAX];
	unsigned int number;

	if (strchr(chip, '/'))
		return gpiod_chip_open(chip);
	if (mcp2510_gpio_parse_uint(chip, &number))
		snprintf(path, sizeof(path), DEV_DIR "/gpiochip%u", number);
	else
		snprintf(path, sizeof(path), DEV_DIR "/%s", chip);
	if (gpiod_is_gpiochip_device(path))
		return gpiod_chip_open(path);
	return scan_chips(label_is, chip, NULL);
}

/*
 * The chip and offset of @spec into @l, or -errno: ENOENT for no such
 * chip or line, as libgpiod 1's lookups (other errors as they come).
 */
static int find_line(const struct mcp2510_gpio_spec *spec,
		     struct mcp2510_int_line *l)
{
	errno = 0;
	if (!spec->chip[0]) {
		l->chip = scan_chips(has_line, spec->line, &l->offset);
		return l->chip ? 0 : -ENOENT;
	}
	l->chip = open_chip(spec->chip);
	if (!l->chip)
		return errno_or(ENODEV);
	if (spec->by_offset) {
		/* the request fails with EINVAL past the last line */
		l->offset = spec->offset;
		return 0;
	}
	if (has_line(l->chip, spec->line, &l->offset))
		return 0;
	gpiod_chip_close(l->chip);
	return -ENOENT;
}

/* ---- the request ----------------------------------------------------------- */

/* Falling edges on an input, as libgpiod 1's falling-edge request. */
static struct gpiod_line_request *request_edges(struct mcp2510_int_line *l)
{
	struct gpiod_line_request *req = NULL;
	struct gpiod_line_settings *settings;
	struct gpiod_request_config *req_cfg = NULL;
	struct gpiod_line_config *line_cfg = NULL;

	settings = gpiod_line_settings_new();
	if (!settings)
		return NULL;
	if (gpiod_line_settings_set_direction(settings,
					      GPIOD_LINE_DIRECTION_INPUT) ||
	    gpiod_line_settings_set_edge_detection(settings,
						   GPIOD_LINE_EDGE_FALLING))
		goto out_settings;
	line_cfg = gpiod_line_config_new();
	if (!line_cfg ||
	    gpiod_line_config_add_line_settings(line_cfg, &l->offset, 1,
						settings))
		goto out_line_cfg;
	req_cfg = gpiod_request_config_new();
	if (!req_cfg)
		goto out_line_cfg;
	gpiod_request_config_set_consumer(req_cfg, CONSUMER);
	req = gpiod_chip_request_lines(l->chip, req_cfg, line_cfg);
	gpiod_request_config_free(req_cfg);
out_line_cfg:
	gpiod_line_config_free(line_cfg);
out_settings:
	gpiod_line_settings_free(settings);
	return req;
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
	ret = find_line(&parsed, l);
	if (ret)
		goto out_free;
	errno = 0;
	l->edges = gpiod_edge_event_buffer_new(EDGE_BUFFER);
	if (!l->edges) {
		ret = errno_or(ENOMEM);
		goto out_close;
	}
	errno = 0;
	l->req = request_edges(l);
	if (!l->req) {
		ret = errno_or(EBUSY);
		goto out_buffer;
	}
	*out = l;
	return 0;

out_buffer:
	gpiod_edge_event_buffer_free(l->edges);
out_close:
	gpiod_chip_close(l->chip);
out_free:
	free(l);
	return ret;
}

/* ---- waiting ------------------------------------------------------------- */

static int drain_edges(struct mcp2510_int_line *l)
{
	int ret;

	while ((ret = gpiod_line_request_wait_edge_events(l->req, 0)) == 1) {
		if (gpiod_line_request_read_edge_events(l->req, l->edges,
							EDGE_BUFFER) < 0)
			return errno_or(EIO);
	}
	return ret < 0 ? errno_or(EIO) : 0;
}

static int int_asserted(struct mcp2510_int_line *l)
{
	enum gpiod_line_value level;

	level = gpiod_line_request_get_value(l->req, l->offset);
	if (level == GPIOD_LINE_VALUE_ERROR)
		return errno_or(EIO);
	/* not requested active-low: inactive is the pin low */
	return level == GPIOD_LINE_VALUE_INACTIVE;
}

int mcp2510_int_line_wait(struct mcp2510_int_line *l, int timeout_ms)
{
	/* libgpiod 2 waits for ever on a negative timeout */
	int64_t timeout_ns = timeout_ms < 0 ? -1 : timeout_ms * 1000000LL;
	int ret;

	ret = int_asserted(l);
	if (ret < 0)
		return ret;
	if (!ret) {
		ret = gpiod_line_request_wait_edge_events(l->req, timeout_ns);
		if (ret <= 0)
			return ret < 0 ? errno_or(EIO) : 0;
	}
	/* Serviced now: edges queued until here must not wake us again. */
	ret = drain_edges(l);
	return ret ? ret : 1;
}

int mcp2510_int_line_fd(const struct mcp2510_int_line *l)
{
	return gpiod_line_request_get_fd(l->req);
}

void mcp2510_int_line_close(struct mcp2510_int_line *l)
{
	if (!l)
		return;
	gpiod_line_request_release(l->req);
	gpiod_edge_event_buffer_free(l->edges);
	gpiod_chip_close(l->chip);
	free(l);
}
