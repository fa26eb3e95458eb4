// SPDX-License-Identifier: GPL-2.0
/*
 * Classic CAN frames as can-utils writes them (cansend, candump -L):
 *   123#DEADBEEF     standard identifier: exactly 3 hex digits
 *   12345678#11.22   extended identifier: exactly 8 hex digits
 *   123#             no data
 *   123#R  123#R4    remote frame, optionally with its length
 *   123#1122334455667788_E   eight bytes sent with the raw DLC 0xE (9..F)
 * Data bytes are two hex digits each, optionally separated by '.'.
 * The same syntax in and out, so what a test injects it can grep for in
 * the bus monitor.
 */
#include <linux/can.h>
#include <linux/kernel.h>
#include <linux/string.h>

#include "kmod.h"

#define SFF_ID_DIGITS	3
#define EFF_ID_DIGITS	8

static int parse_id(const char *text, size_t digits, struct can_frame *cf)
{
	u32 id = 0;
	size_t i;
	int v;

	for (i = 0; i < digits; i++) {
		v = hex_to_bin(text[i]);
		if (v < 0)
			return -EINVAL;
		id = id << 4 | v;
	}
	if (digits == SFF_ID_DIGITS) {
		if (id > CAN_SFF_MASK)
			return -EINVAL;
		cf->can_id = id;
	} else {
		if (id > CAN_EFF_MASK)
			return -EINVAL;
		cf->can_id = id | CAN_EFF_FLAG;
	}
	return 0;
}

static int parse_remote(const char *text, struct can_frame *cf)
{
	cf->can_id |= CAN_RTR_FLAG;
	if (!*text)
		return 0;
	if (text[0] < '0' || text[0] > '0' + CAN_MAX_DLEN || text[1])
		return -EINVAL;
	cf->len = text[0] - '0';
	return 0;
}

/* "_X" after eight data bytes: the DLC on the wire is X, 9..F. */
static int parse_raw_dlc(const char *text, struct can_frame *cf)
{
	int dlc = hex_to_bin(text[0]);

	if (cf->len != CAN_MAX_DLEN || dlc <= CAN_MAX_DLEN || text[1])
		return -EINVAL;
	cf->len8_dlc = dlc;
	return 0;
}

static int parse_data(const char *text, struct can_frame *cf)
{
	int hi, lo;

	while (*text) {
		if (*text == '.') {
			text++;
			continue;
		}
		if (*text == '_')
			return parse_raw_dlc(text + 1, cf);
		if (cf->len == CAN_MAX_DLEN)
			return -EINVAL;
		hi = hex_to_bin(text[0]);
		lo = hi < 0 ? -1 : hex_to_bin(text[1]);
		if (lo < 0)
			return -EINVAL;
		cf->data[cf->len++] = hi << 4 | lo;
		text += 2;
	}
	return 0;
}

int mcp2510_sim_frame_parse(const char *text, struct can_frame *cf)
{
	const char *hash = strchr(text, '#');
	size_t digits;
	int ret;

	memset(cf, 0, sizeof(*cf));
	if (!hash)
		return -EINVAL;
	digits = hash - text;
	if (digits != SFF_ID_DIGITS && digits != EFF_ID_DIGITS)
		return -EINVAL;
	ret = parse_id(text, digits, cf);
	if (ret)
		return ret;
	/* "##" is CAN FD, which neither chip speaks */
	if (hash[1] == 'R' || hash[1] == 'r')
		return parse_remote(hash + 2, cf);
	return parse_data(hash + 1, cf);
}

int mcp2510_sim_frame_format(char *buf, size_t size, const struct can_frame *cf)
{
	int n;
	u8 i;

	if (cf->can_id & CAN_EFF_FLAG)
		n = scnprintf(buf, size, "%08X#", cf->can_id & CAN_EFF_MASK);
	else
		n = scnprintf(buf, size, "%03X#", cf->can_id & CAN_SFF_MASK);
	if (cf->can_id & CAN_RTR_FLAG) {
		n += scnprintf(buf + n, size - n, "R");
		if (cf->len)
			n += scnprintf(buf + n, size - n, "%u", cf->len);
		return n;
	}
	for (i = 0; i < cf->len && i < CAN_MAX_DLEN; i++)
		n += scnprintf(buf + n, size - n, "%02X", cf->data[i]);
	if (cf->len == CAN_MAX_DLEN && cf->len8_dlc > CAN_MAX_DLEN &&
	    cf->len8_dlc <= CAN_MAX_RAW_DLC)
		n += scnprintf(buf + n, size - n, "_%X", cf->len8_dlc);
	return n;
}
