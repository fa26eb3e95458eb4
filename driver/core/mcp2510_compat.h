/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The one place that knows whether this code is built into the kernel or
 * into a userspace program.  The portable driver core and the simulated chip
 * include only this header for types, bit helpers and the SocketCAN
 * definitions, so the same source compiles in both homes unchanged.
 */
#ifndef MCP2510_COMPAT_H
#define MCP2510_COMPAT_H

#ifdef __KERNEL__

#include <linux/bitfield.h>
#include <linux/bits.h>
#include <linux/errno.h>
#include <linux/kernel.h>
#include <linux/limits.h>
#include <linux/string.h>
#include <linux/types.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/netlink.h>
/* 6.1's length.h includes nothing and names sk_buff in a prototype. */
struct sk_buff;
#include <linux/can/length.h>

#else /* userspace */

#include <errno.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <linux/types.h>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/netlink.h>

/* The kernel's names, over the fixed-size types <linux/types.h> gives. */
typedef __u8 u8;
typedef __u16 u16;
typedef __u32 u32;
typedef __u64 u64;
typedef __s32 s32;
typedef __s64 s64;

#define BIT(n)			(1UL << (n))
#define GENMASK(h, l)		((~0ULL >> (63 - (h))) & (~0ULL << (l)))
#define FIELD_PREP(mask, val)	(((val) << __builtin_ctzll(mask)) & (mask))
#define FIELD_GET(mask, reg)	(((reg) & (mask)) >> __builtin_ctzll(mask))
#define ARRAY_SIZE(a)		(sizeof(a) / sizeof((a)[0]))
#define DIV_ROUND_CLOSEST(x, d)	mcp2510_div_round_closest(x, d)
#define DIV_ROUND_UP(x, d)	mcp2510_div_round_up(x, d)
#define U32_MAX			UINT32_MAX
#define U64_MAX			UINT64_MAX

/* Functions, not macros: each argument is evaluated once. */
static inline u64 mcp2510_div_round_closest(u64 x, u64 d)
{
	return (x + d / 2) / d;
}

static inline u64 mcp2510_div_round_up(u64 x, u64 d)
{
	return (x + d - 1) / d;
}

#ifndef fallthrough
#define fallthrough		__attribute__((__fallthrough__))
#endif

/*
 * The kernel's Classical CAN raw-DLC helpers (<linux/can/length.h>), which
 * no uapi header offers.  The DLC of a frame: len8_dlc when the mode is on,
 * the length is 8 and len8_dlc is a DLC above 8, else the length.
 */
static inline u8 can_get_cc_dlc(const struct can_frame *cf, u32 ctrlmode)
{
	if ((ctrlmode & CAN_CTRLMODE_CC_LEN8_DLC) &&
	    cf->len == CAN_MAX_DLEN && cf->len8_dlc > CAN_MAX_DLEN &&
	    cf->len8_dlc <= CAN_MAX_RAW_DLC)
		return cf->len8_dlc;
	return cf->len;
}

/* Length from a received DLC (0..15), keeping a DLC above 8 if asked. */
static inline void can_frame_set_cc_len(struct can_frame *cf, u8 dlc,
					u32 ctrlmode)
{
	if ((ctrlmode & CAN_CTRLMODE_CC_LEN8_DLC) && dlc > CAN_MAX_DLEN)
		cf->len8_dlc = dlc;
	cf->len = dlc > CAN_MAX_DLEN ? CAN_MAX_DLEN : dlc;
}

#endif /* __KERNEL__ */

#endif /* MCP2510_COMPAT_H */
