// SPDX-License-Identifier: LGPL-2.1-or-later
/* The INT line's "CHIP:LINE" spec, common to both libgpiod backends. */
#define _GNU_SOURCE
#include <errno.h>
#include <string.h>

#include "gpio_spec.h"

bool mcp2510_gpio_parse_uint(const char *s, unsigned int *value)
{
	unsigned long long v = 0;

	if (!*s)
		return false;
	for (; *s; s++) {
		if (*s < '0' || *s > '9')
			return false;
		v = v * 10 + (unsigned int)(*s - '0');
		if (v > UINT_MAX)
			return false;
	}
	*value = (unsigned int)v;
	return true;
}

int mcp2510_gpio_spec_parse(const char *spec, struct mcp2510_gpio_spec *out)
{
	const char *colon;
	size_t n = 0;

	if (!spec || !*spec)
		return -EINVAL;
	colon = strrchr(spec, ':');
	if (colon) {
		n = (size_t)(colon - spec);
		if (!n || n >= sizeof(out->chip))
			return -EINVAL;
		out->line = colon + 1;
	} else {
		out->line = spec;
	}
	memcpy(out->chip, spec, n);
	out->chip[n] = '\0';
	if (!*out->line)
		return -EINVAL;
	out->by_offset = mcp2510_gpio_parse_uint(out->line, &out->offset);
	/* a number alone: an offset on which chip? */
	if (out->by_offset && !n)
		return -EINVAL;
	return 0;
}
