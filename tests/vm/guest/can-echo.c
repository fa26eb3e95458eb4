// SPDX-License-Identifier: GPL-2.0
/*
 * can-echo IFACE: what the local sockets see of a frame sent on IFACE,
 * for every combination of the sender's CAN_RAW_LOOPBACK and
 * CAN_RAW_RECV_OWN_MSGS.
 *
 * Per combination a sender and a listener socket are opened on IFACE; the
 * sender sends three frames (ids 0x1LO, LO = loopback * 0x20 + own * 0x10
 * + n), then a third socket sends the marker 0x7FF.  Echoes reach the
 * sockets in completion order, so once both have the marker nothing more
 * of the sender's frames can come.  One line per combination:
 *
 *   loopback=L recv_own=O sender: IDS listener: IDS
 *
 * IDS are the received ids in order, "c" appended when the frame came
 * with MSG_CONFIRM (the socket's own frame), "-" when none came.  Exit 1
 * when a marker does not arrive within 10 s, 2 on a socket error.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define FRAMES		3
#define MARKER_ID	0x7ff
#define WAIT_MS		10000

static void die(const char *what)
{
	fprintf(stderr, "can-echo: %s: %s\n", what, strerror(errno));
	exit(2);
}

static int open_on(int ifindex)
{
	struct sockaddr_can addr = { .can_family = AF_CAN };
	int s;

	s = socket(PF_CAN, SOCK_RAW, CAN_RAW);
	if (s < 0)
		die("socket");
	addr.can_ifindex = ifindex;
	if (bind(s, (struct sockaddr *)&addr, sizeof(addr)) < 0)
		die("bind");
	return s;
}

static void set_opt(int s, int name, int value)
{
	if (setsockopt(s, SOL_CAN_RAW, name, &value, sizeof(value)) < 0)
		die("setsockopt");
}

static void send_id(int s, canid_t id)
{
	struct can_frame cf = { .can_id = id, .len = 1, .data = { 0x5a } };

	if (write(s, &cf, sizeof(cf)) != sizeof(cf))
		die("write");
}

struct seen {
	char text[128];
	int marker;
};

static void note(struct seen *seen, const struct can_frame *cf, int flags)
{
	size_t used = strlen(seen->text);

	if ((cf->can_id & CAN_SFF_MASK) == MARKER_ID) {
		seen->marker = 1;
		return;
	}
	snprintf(seen->text + used, sizeof(seen->text) - used, " %03x%s",
		 cf->can_id & CAN_SFF_MASK, flags & MSG_CONFIRM ? "c" : "");
}

static void take_one(int s, struct seen *seen)
{
	struct can_frame cf;
	struct iovec iov = { .iov_base = &cf, .iov_len = sizeof(cf) };
	struct msghdr msg = { .msg_iov = &iov, .msg_iovlen = 1 };

	if (recvmsg(s, &msg, MSG_DONTWAIT) < 0) {
		if (errno == EAGAIN)
			return;
		die("recvmsg");
	}
	note(seen, &cf, msg.msg_flags);
}

static long now_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

/* Read both sockets until each has had the marker. */
static int collect(int sender, int listener, struct seen *s_seen,
		   struct seen *l_seen)
{
	long end = now_ms() + WAIT_MS;

	while (!s_seen->marker || !l_seen->marker) {
		struct pollfd fds[2] = {
			{ .fd = sender, .events = POLLIN },
			{ .fd = listener, .events = POLLIN },
		};
		long left = end - now_ms();

		if (left <= 0)
			return -1;
		if (poll(fds, 2, (int)left) < 0)
			die("poll");
		if (fds[0].revents & POLLIN)
			take_one(sender, s_seen);
		if (fds[1].revents & POLLIN)
			take_one(listener, l_seen);
	}
	return 0;
}

static int run_case(int ifindex, int loopback, int recv_own)
{
	struct seen s_seen = { "", 0 }, l_seen = { "", 0 };
	int sender, listener, marker, n, ret;
	canid_t base = 0x100 + loopback * 0x20 + recv_own * 0x10;

	sender = open_on(ifindex);
	listener = open_on(ifindex);
	marker = open_on(ifindex);
	set_opt(sender, CAN_RAW_LOOPBACK, loopback);
	set_opt(sender, CAN_RAW_RECV_OWN_MSGS, recv_own);

	for (n = 0; n < FRAMES; n++)
		send_id(sender, base + n);
	send_id(marker, MARKER_ID);
	ret = collect(sender, listener, &s_seen, &l_seen);

	printf("loopback=%d recv_own=%d sender:%s listener:%s%s\n",
	       loopback, recv_own, s_seen.text[0] ? s_seen.text : " -",
	       l_seen.text[0] ? l_seen.text : " -",
	       ret ? " (no marker)" : "");
	close(marker);
	close(listener);
	close(sender);
	return ret;
}

int main(int argc, char **argv)
{
	int ifindex, loopback, recv_own, failed = 0;

	if (argc != 2) {
		fprintf(stderr, "usage: can-echo IFACE\n");
		return 2;
	}
	ifindex = (int)if_nametoindex(argv[1]);
	if (!ifindex)
		die(argv[1]);
	for (loopback = 0; loopback <= 1; loopback++)
		for (recv_own = 0; recv_own <= 1; recv_own++)
			if (run_case(ifindex, loopback, recv_own))
				failed = 1;
	return failed;
}
