// SPDX-License-Identifier: GPL-2.0
/*
 * The one number grammar of both tools' command lines, as mcp2510ctl(1)
 * documents it.
 */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"

int cli_u32(const char *s, uint32_t *out)
{
	unsigned long long v, scale = 1;
	char *end;

	if (s[0] < '0' || s[0] > '9')
		return -1;
	errno = 0;
	v = strtoull(s, &end, 10);
	if (errno)
		return -1;
	/* k and M in either case: nothing here is in millihertz */
	if (*end == 'k' || *end == 'K')
		scale = 1000;
	else if (*end == 'm' || *end == 'M')
		scale = 1000000;
	if (scale != 1)
		end++;
	/* "16MHz", "500kHz", "16000000Hz", any case */
	if (!strcasecmp(end, "hz"))
		end += 2;
	if (*end || v > UINT32_MAX / scale)
		return -1;
	*out = (uint32_t)(v * scale);
	return 0;
}

int cli_int(const char *s, bool allow_forever, int *out)
{
	uint32_t v;

	if (allow_forever && !strcmp(s, "-1")) {
		*out = -1;
		return 0;
	}
	if (cli_u32(s, &v) || v > INT32_MAX)
		return -1;
	*out = (int)v;
	return 0;
}

/*
 * "0.875" (a fraction), "87.5%" (a percentage) or "875" (tenths of a
 * percent, whole, as can-calc-bit-timing -s takes it), from 10.0 % to
 * 99.9 %; anything else, "87.5" or "1" say, is refused rather than
 * guessed at.
 */
int cli_sample_point(const char *s, uint32_t *out)
{
	double v;
	char *end;

	if ((s[0] < '0' || s[0] > '9') && s[0] != '.')
		return -1;
	errno = 0;
	v = strtod(s, &end);
	if (errno || end == s)
		return -1;
	if (!strcmp(end, "%"))
		v *= 10;
	else if (*end)
		return -1;
	else if (v < 1)
		v *= 1000;
	else if (strchr(s, '.'))
		return -1;
	v += 0.5;
	if (v < 100 || v >= 1000)
		return -1;
	*out = (uint32_t)v;
	return 0;
}
