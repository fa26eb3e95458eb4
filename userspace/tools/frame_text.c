// SPDX-License-Identifier: GPL-2.0
/* cansend syntax in, candump -L syntax out. */
#include <stdio.h>
#include <string.h>

#include "frame_text.h"
#include "mcp2510_core.h"

#define SFF_DIGITS	3
#define EFF_DIGITS	8

static int fail(const char **why, const char *what)
{
	*why = what;
	return -1;
}

static int parse_id(const char *text, size_t digits, canid_t *id,
		    const char **why)
{
	canid_t v = 0;
	size_t i;

	if (digits != SFF_DIGITS && digits != EFF_DIGITS)
		return fail(why, "identifier must be 3 (standard) or 8 (extended) hex digits");
	for (i = 0; i < digits; i++) {
		int d = mcp2510_hex_digit(text[i]);

		if (d < 0)
			return fail(why, "identifier is not hexadecimal");
		v = (v << 4) | (canid_t)d;
	}
	if (digits == SFF_DIGITS) {
		if (v > CAN_SFF_MASK)
			return fail(why, "standard identifier above 7FF");
		*id = v;
		return 0;
	}
	if (v & CAN_ERR_FLAG)
		return fail(why, "error frames cannot be sent");
	if (v > CAN_EFF_MASK)
		return fail(why, "extended identifier above 1FFFFFFF");
	*id = v | CAN_EFF_FLAG;
	return 0;
}

/*
 * "_D" after a length of 8: the raw DLC 9..F that Classical CAN may carry
 * (cansend's syntax, sent with cc-len8-dlc on).
 */
static int parse_raw_dlc(const char *p, struct can_frame *cf, const char **why)
{
	int d;

	if (!p[0])
		return 0;
	if (p[0] != '_')
		return fail(why, "data must be pairs of hex digits");
	if (cf->len != CAN_MAX_DLEN)
		return fail(why, "a raw DLC (_9 to _F) comes only after 8 data bytes or R8");
	d = mcp2510_hex_digit(p[1]);
	if (d < 0 || p[2])
		return fail(why, "a raw DLC is one hex digit, _9 to _F");
	if (d <= CAN_MAX_DLEN)
		return fail(why, "a raw DLC is 9 to F (0-8 is the length itself)");
	cf->len8_dlc = (__u8)d;
	return 0;
}

static int parse_remote(const char *p, struct can_frame *cf, const char **why)
{
	cf->can_id |= CAN_RTR_FLAG;
	if (!p[0])
		return 0;
	if (p[0] < '0' || p[0] > '8' || (p[1] && p[1] != '_'))
		return fail(why, "remote frame length must be one digit 0-8");
	cf->len = (__u8)(p[0] - '0');
	if (p[1] && cf->len != CAN_MAX_DLEN)
		return fail(why, "a raw DLC (_9 to _F) comes only after 8 data bytes or R8");
	return parse_raw_dlc(p + 1, cf, why);
}

/* As cansend: one optional dot before each byte, or at the end. */
static int parse_data(const char *p, struct can_frame *cf, const char **why)
{
	while (*p && *p != '_') {
		int hi, lo;

		if (*p == '.')
			p++;
		if (!*p)
			break;
		if (*p == '.')
			return fail(why, "one dot at most between data bytes");
		hi = mcp2510_hex_digit(p[0]);
		lo = hi < 0 ? -1 : mcp2510_hex_digit(p[1]);
		if (lo < 0)
			return fail(why, "data must be pairs of hex digits");
		if (cf->len == CAN_MAX_DLEN)
			return fail(why, "more than 8 data bytes");
		cf->data[cf->len++] = (__u8)(hi << 4 | lo);
		p += 2;
	}
	return parse_raw_dlc(p, cf, why);
}

int frame_parse(const char *text, struct can_frame *cf, const char **why)
{
	const char *hash = strchr(text, '#');

	memset(cf, 0, sizeof(*cf));
	if (!hash)
		return fail(why, "missing '#' between identifier and data");
	if (parse_id(text, (size_t)(hash - text), &cf->can_id, why))
		return -1;
	if (hash[1] == '#')
		return fail(why, "CAN FD frames are not supported");
	if (hash[1] == 'R' || hash[1] == 'r')
		return parse_remote(hash + 2, cf, why);
	return parse_data(hash + 1, cf, why);
}

static int format_id(const struct can_frame *cf, char *buf, size_t len)
{
	canid_t id = cf->can_id;

	if (id & CAN_ERR_FLAG)
		return snprintf(buf, len, "%08X",
				id & (CAN_ERR_MASK | CAN_ERR_FLAG));
	if (id & CAN_EFF_FLAG)
		return snprintf(buf, len, "%08X", id & CAN_EFF_MASK);
	return snprintf(buf, len, "%03X", id & CAN_SFF_MASK);
}

int frame_format(const struct can_frame *cf, char *buf, size_t len)
{
	unsigned int i, dlen = cf->len > CAN_MAX_DLEN ? CAN_MAX_DLEN : cf->len;
	char tmp[FRAME_TEXT_MAX];
	int n = format_id(cf, tmp, sizeof(tmp));

	tmp[n++] = '#';
	if (cf->can_id & CAN_RTR_FLAG && !(cf->can_id & CAN_ERR_FLAG)) {
		tmp[n++] = 'R';
		if (dlen)
			tmp[n++] = (char)('0' + dlen);
	} else {
		for (i = 0; i < dlen; i++)
			n += snprintf(tmp + n, sizeof(tmp) - (size_t)n, "%02X",
				      cf->data[i]);
	}
	if (dlen == CAN_MAX_DLEN && cf->len8_dlc > CAN_MAX_DLEN &&
	    cf->len8_dlc <= CAN_MAX_RAW_DLC && !(cf->can_id & CAN_ERR_FLAG))
		n += snprintf(tmp + n, sizeof(tmp) - (size_t)n, "_%X",
			      cf->len8_dlc);
	tmp[n] = '\0';
	return snprintf(buf, len, "%s", tmp);
}

int frame_format_log(const struct can_frame *cf, const struct timespec *ts,
		     const char *label, char *buf, size_t len)
{
	char frame[FRAME_TEXT_MAX];
	int n;

	frame_format(cf, frame, sizeof(frame));
	n = snprintf(buf, len, "(%010lld.%06ld) %s %s", (long long)ts->tv_sec,
		     ts->tv_nsec / 1000, label, frame);
	return n < 0 || (size_t)n >= len ? -1 : n;
}
