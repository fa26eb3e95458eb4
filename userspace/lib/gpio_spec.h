/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * The INT line's "CHIP:LINE" spec, parsed once for both libgpiod
 * backends (gpio_int_v1.c, gpio_int_v2.c).
 */
#ifndef MCP2510_GPIO_SPEC_H
#define MCP2510_GPIO_SPEC_H

#include <limits.h>
#include <stdbool.h>

struct mcp2510_gpio_spec {
	/* "" when the spec named a line only: look on every chip */
	char chip[PATH_MAX];
	const char *line;	/* points into the parsed string */
	bool by_offset;		/* line is a number: offset on chip */
	unsigned int offset;
};

/*
 * "CHIP:LINE" (split at the last colon: chip paths have none) or a bare
 * line name.  A bare number is refused: an offset means nothing without
 * its chip.  0 or -EINVAL.
 */
int mcp2510_gpio_spec_parse(const char *spec, struct mcp2510_gpio_spec *out);

/* true when @s is a non-empty string of decimal digits fitting @value */
bool mcp2510_gpio_parse_uint(const char *s, unsigned int *value);

#endif /* MCP2510_GPIO_SPEC_H */
