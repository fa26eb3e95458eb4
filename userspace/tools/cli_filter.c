// SPDX-License-Identifier: GPL-2.0
/* Acceptance filter settings from the command line, NAME=VALUE. */
#include <string.h>
#include <strings.h>

#include "cli.h"

static bool filter_setting_is_id(const char *name)
{
	struct mcp2510_hw_filters scratch;

	mcp2510_hw_filters_default(&scratch);
	return (!strncmp(name, "mask", 4) || !strncmp(name, "filter", 6)) &&
	       !mcp2510_hw_filters_set(&scratch, name, "0");
}

static bool filter_setting_known(const char *name)
{
	struct mcp2510_hw_filters scratch;

	mcp2510_hw_filters_default(&scratch);
	return !mcp2510_hw_filters_set(&scratch, name, "0") ||
	       !mcp2510_hw_filters_set(&scratch, name, "any");
}

/* Why mcp2510_hw_filters_set() refused NAME=VALUE, as one line. */
static void filter_why(struct cli_args *a, const char *arg, const char *name,
		       const char *value)
{
	if (!filter_setting_known(name))
		cli_error(a->err, a->prog,
			  "unknown filter setting '%s' in '%s' (mask0-1, filter0-5, rxm0-1, rollover)",
			  name, arg);
	else if (filter_setting_is_id(name) && !strncasecmp(value, "0x", 2) &&
		 value[2])
		cli_error(a->err, a->prog,
			  "'%s': write the id in hex without 0x, an x after it for a 29-bit id (%s=123, %s=1fffffffx)",
			  arg, name, name);
	else if (filter_setting_is_id(name))
		cli_error(a->err, a->prog,
			  "'%s': the id must be hex, up to 7ff (11 bit) or up to 1fffffff followed by x (29 bit)",
			  arg);
	else if (!strncmp(name, "rxm", 3))
		cli_error(a->err, a->prog,
			  "'%s': a receive mode is filtered, std, ext or any", arg);
	else
		cli_error(a->err, a->prog, "'%s': rollover is 0 or 1", arg);
}

int cli_filter_assign(struct cli_args *a, struct mcp2510_hw_filters *f,
		      const char *arg)
{
	const char *eq = strchr(arg, '=');
	size_t n = eq ? (size_t)(eq - arg) : 0;
	char name[16];

	if (!eq || !n || n >= sizeof(name)) {
		cli_error(a->err, a->prog,
			  "filter setting '%s' is not NAME=VALUE (e.g. mask0=7ff filter0=123)",
			  arg);
		return -1;
	}
	memcpy(name, arg, n);
	name[n] = '\0';
	if (!mcp2510_hw_filters_set(f, name, eq + 1))
		return 0;
	filter_why(a, arg, name, eq + 1);
	return -1;
}

int cli_device_add_filter(struct cli_device *d, struct cli_args *a,
			  const char *arg)
{
	struct mcp2510_hw_filters scratch;

	mcp2510_hw_filters_default(&scratch);
	if (cli_filter_assign(a, &scratch, arg))
		return -1;
	if (d->nfilters == CLI_MAX_FILTERS) {
		cli_error(a->err, a->prog, "more than %d --filter settings",
			  CLI_MAX_FILTERS);
		return -1;
	}
	d->filters[d->nfilters++] = arg;
	return 0;
}

int cli_device_apply_filters(const struct cli_device *d, struct mcp2510 *h,
			     struct cli_args *a)
{
	struct mcp2510_hw_filters f;
	unsigned int i;

	if (!d->nfilters)
		return 0;
	mcp2510_get_filters(h, &f);
	for (i = 0; i < d->nfilters; i++)
		if (cli_filter_assign(a, &f, d->filters[i]))
			return -1;
	if (mcp2510_set_filters(h, &f)) {
		cli_error_errno(a, "setting the filters");
		return -1;
	}
	return 0;
}
