/* SPDX-License-Identifier: GPL-2.0 */
/*
 * CAN frames as text, the way can-utils writes them: cansend's FRAME
 * argument and candump's log format (-L), so the tools' input and output
 * can be pasted to and from cansend, candump and canplayer.
 */
#ifndef MCP2510_FRAME_TEXT_H
#define MCP2510_FRAME_TEXT_H

#include <stddef.h>
#include <time.h>
#include <linux/can.h>

/* Longest "ID#DATA_D" (error frame id, 8 data bytes, raw DLC) plus NUL. */
#define FRAME_TEXT_MAX		(8 + 1 + 2 * CAN_MAX_DLEN + 2 + 1)
/* Longest candump -L line without the newline, plus its NUL. */
#define FRAME_LOG_MAX(label_len)	(32 + (label_len) + FRAME_TEXT_MAX)

/*
 * Parse cansend syntax: "123#DEADBEEF" (3 hex digits: standard id),
 * "12345678#11" (8 hex digits: extended id), "123#" (no data),
 * "123#11.22.33" (one dot at most before each byte), "123#R" and
 * "123#R3" (remote frame, with its length), and after 8 data bytes or R8
 * a raw DLC "_9" to "_F" (len8_dlc), as can-utils' lib.c takes them.
 * Returns 0, or -1 with *why naming what is wrong.  CAN FD ("##") and
 * error frames are refused.
 */
int frame_parse(const char *text, struct can_frame *cf, const char **why);

/* "ID#DATA" (with "_D" for a raw DLC) as candump prints it; the length. */
int frame_format(const struct can_frame *cf, char *buf, size_t len);

/* "(SECONDS.MICROS) LABEL ID#DATA"; returns the length, -1 if too long. */
int frame_format_log(const struct can_frame *cf, const struct timespec *ts,
		     const char *label, char *buf, size_t len);

#endif /* MCP2510_FRAME_TEXT_H */
