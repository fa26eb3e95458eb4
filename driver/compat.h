/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The driver is written against the newest kernel's API.  What an older
 * kernel (down to 6.1) lacks of it is supplied here, and only here: the
 * root Kbuild greps the headers it builds against and defines
 * MCP2510_HAVE_<feature> for each piece that is there.
 */
#ifndef MCP2510_COMPAT_H
#define MCP2510_COMPAT_H

#include <linux/can/dev.h>
#include <linux/can/rx-offload.h>
#include <linux/can/skb.h>
#include <linux/workqueue.h>

/*
 * From 6.18 can-dev gives a classical CAN interface an MTU range of
 * CAN_MTU alone and the core refuses anything else; 6.19 dropped
 * can_change_mtu().  Before that an interface without the callback took
 * any MTU, CAN FD's included, so it is can-dev's check there.
 */
#ifdef MCP2510_HAVE_CAN_CHANGE_MTU
#define mcp2510_change_mtu	can_change_mtu
#else
#define mcp2510_change_mtu	NULL
#endif

/*
 * Before 6.6 can-dev's only echo helper sorts by timestamp: with every
 * skb stamped 0 it appends, as the tail helper does.
 */
#ifndef MCP2510_HAVE_ECHO_QUEUE_TAIL
static inline unsigned int
can_rx_offload_get_echo_skb_queue_tail(struct can_rx_offload *offload,
				       unsigned int idx,
				       unsigned int *frame_len_ptr)
{
	return can_rx_offload_get_echo_skb(offload, idx, 0, frame_len_ptr);
}
#endif

/*
 * can-dev keeps an echo skb's length on the wire in the skb's CAN
 * extension in 7.x, in its headroom before.  alloc_can_skb() leaves the
 * field unset, so the driver writes 0 into the frames it receives.
 */
static inline void mcp2510_skb_set_frame_len(struct sk_buff *skb,
					     unsigned int frame_len)
{
#ifdef MCP2510_HAVE_CAN_SKB_EXT
	struct can_skb_ext *csx = can_skb_ext_find(skb);

	if (csx)
		csx->can_framelen = frame_len;
#else
	can_skb_prv(skb)->frame_len = frame_len;
#endif
}

static inline unsigned int mcp2510_skb_frame_len(struct sk_buff *skb)
{
#ifdef MCP2510_HAVE_CAN_SKB_EXT
	struct can_skb_ext *csx = can_skb_ext_find(skb);

	return csx ? csx->can_framelen : 0;
#else
	return can_skb_prv(skb)->frame_len;
#endif
}

/*
 * system_wq was renamed system_percpu_wq (a per-CPU queue, as before); 7.x
 * marks the old name deprecated and warns at its first use.
 */
#ifndef MCP2510_HAVE_SYSTEM_PERCPU_WQ
#define system_percpu_wq	system_wq
#endif

#endif /* MCP2510_COMPAT_H */
