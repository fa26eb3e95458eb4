/* SPDX-License-Identifier: GPL-2.0 */
/*
 * What can-flood and can-transit share: a CAN_RAW socket bound to one
 * interface that receives every frame, none, or one identifier's.  The
 * program that includes this defines die(), which reports and exits.
 */
#ifndef CAN_SOCKET_H
#define CAN_SOCKET_H

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <stdint.h>
#include <sys/socket.h>

#define RECEIVE_ALL	(-1)
#define RECEIVE_NONE	(-2)

/*
 * A socket on @ifname receiving @want: RECEIVE_ALL, RECEIVE_NONE (a
 * sender: no queue to fill) or one identifier, with CAN_EFF_FLAG for an
 * extended one.
 */
static int can_socket(const char *ifname, int64_t want)
{
	struct sockaddr_can addr = { .can_family = AF_CAN };
	struct can_filter only = { .can_mask = CAN_EFF_FLAG | CAN_RTR_FLAG |
					       CAN_EFF_MASK };
	int s = socket(PF_CAN, SOCK_RAW, CAN_RAW);

	if (s < 0)
		die("socket");
	only.can_id = (canid_t)want;
	if (want != RECEIVE_ALL &&
	    setsockopt(s, SOL_CAN_RAW, CAN_RAW_FILTER, &only,
		       want == RECEIVE_NONE ? 0 : sizeof(only)) < 0)
		die("CAN_RAW_FILTER");
	addr.can_ifindex = (int)if_nametoindex(ifname);
	if (!addr.can_ifindex)
		die(ifname);
	if (bind(s, (struct sockaddr *)&addr, sizeof(addr)) < 0)
		die("bind");
	return s;
}

#endif
