/* SPDX-License-Identifier: GPL-2.0 */
/*
 * What can-tstamp and can-latency share: a CAN_RAW socket that hands each
 * frame over with its SO_TIMESTAMPNS receive timestamp, and the lookup of
 * a frame's end in the simulator's monitor_times, the bus's own record.
 * Times are CLOCK_REALTIME nanoseconds, the clock of both.
 */
#ifndef STAMPED_RX_H
#define STAMPED_RX_H

#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>

#define IDLE_MS		3000	/* no frame for this long ends a run */
#define TEXT_LEN	40

static void die(const char *what)
{
	fprintf(stderr, "%s: %s: %s\n", program_invocation_short_name, what,
		strerror(errno));
	exit(2);
}

static int64_t ns_of(const struct timespec *ts)
{
	return (int64_t)ts->tv_sec * 1000000000 + ts->tv_nsec;
}

static int64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_REALTIME, &ts);
	return ns_of(&ts);
}

/* cansend syntax, as the simulator's monitor writes frames */
static void frame_text(const struct can_frame *cf, char *buf)
{
	unsigned int i;
	int n;

	if (cf->can_id & CAN_EFF_FLAG)
		n = sprintf(buf, "%08X#", cf->can_id & CAN_EFF_MASK);
	else
		n = sprintf(buf, "%03X#", cf->can_id & CAN_SFF_MASK);
	if (cf->can_id & CAN_RTR_FLAG) {
		sprintf(buf + n, "R%u", cf->len);
		return;
	}
	for (i = 0; i < cf->len && i < CAN_MAX_DLEN; i++)
		n += sprintf(buf + n, "%02X", cf->data[i]);
}

/* A timestamping socket bound to @ifname; @own: it gets its own frames too. */
static int stamped_socket(const char *ifname, int own)
{
	struct sockaddr_can addr = { .can_family = AF_CAN };
	int s, on = 1;

	s = socket(PF_CAN, SOCK_RAW, CAN_RAW);
	if (s < 0)
		die("socket");
	addr.can_ifindex = if_nametoindex(ifname);
	if (!addr.can_ifindex)
		die(ifname);
	if (setsockopt(s, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof(on)) < 0)
		die("SO_TIMESTAMPNS");
	if (own && setsockopt(s, SOL_CAN_RAW, CAN_RAW_RECV_OWN_MSGS, &on,
			      sizeof(on)) < 0)
		die("CAN_RAW_RECV_OWN_MSGS");
	if (bind(s, (struct sockaddr *)&addr, sizeof(addr)) < 0)
		die("bind");
	return s;
}

/* 1 with a frame in @cf (@stamp its receive timestamp), 0 after IDLE_MS */
static int stamped_receive(int s, struct can_frame *cf, int64_t *stamp)
{
	struct pollfd p = { .fd = s, .events = POLLIN };
	char ctrl[CMSG_SPACE(sizeof(struct timespec))];
	struct iovec iov = { .iov_base = cf, .iov_len = sizeof(*cf) };
	struct msghdr msg = {
		.msg_iov = &iov, .msg_iovlen = 1,
		.msg_control = ctrl, .msg_controllen = sizeof(ctrl),
	};
	struct cmsghdr *c;
	int r;

	r = poll(&p, 1, IDLE_MS);
	if (r < 0)
		die("poll");
	if (!r)
		return 0;
	if (recvmsg(s, &msg, 0) < 0)
		die("recvmsg");
	*stamp = 0;
	for (c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
		if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMPNS) {
			struct timespec ts;

			memcpy(&ts, CMSG_DATA(c), sizeof(ts));
			*stamp = ns_of(&ts);
		}
	return 1;
}

/*
 * The end of @text on the bus, 0 when not there: its last error-free
 * passage (a frame an error destroyed is sent again).  Every frame of a
 * run is unique, so its text finds it.
 */
static int64_t end_on_bus(FILE *mon, const char *text)
{
	char line[256], frame[TEXT_LEN + 8], outcome[32];
	unsigned long long bus, end, seen;
	int64_t found = 0;

	rewind(mon);
	while (fgets(line, sizeof(line), mon))
		if (sscanf(line, "%llu %llu %llu %*s %47s %31s", &bus, &end,
			   &seen, frame, outcome) == 5 &&
		    !strcmp(frame, text) && !strcmp(outcome, "ok"))
			found = (int64_t)end;
	return found;
}

#endif /* STAMPED_RX_H */
