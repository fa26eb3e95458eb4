// SPDX-License-Identifier: GPL-2.0
/*
 * can-tstamp IFACE COUNT MONITOR: how far the receive timestamps of a
 * CAN interface are from the end of each frame on the simulated bus.
 *
 * Prints "ready" once listening on IFACE, then takes up to COUNT frames
 * (stopping after 3 s without one) with their SO_TIMESTAMPNS stamp and
 * the CLOCK_REALTIME right after recvmsg() returned them.  Then it reads
 * MONITOR (the simulator's debugfs monitor_times), finds each frame there
 * (every frame must be unique, as a flood's are) and prints per frame
 *
 *   FRAME STAMP-END RECV-STAMP STAMP-PREV
 *
 * in ns: the stamp after the frame ended on the bus, the time recvmsg()
 * returned it after its stamp, and the stamp after the previous frame's
 * (0 for the first).  A frame missing from MONITOR is printed as
 * "FRAME missing".  Exit 0, or 2 on an error.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <inttypes.h>
#include <linux/can.h>
#include <net/if.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#define IDLE_MS		3000
#define TEXT_LEN	40

struct got {
	char text[TEXT_LEN];
	int64_t stamp, recv;
};

static void die(const char *what)
{
	fprintf(stderr, "can-tstamp: %s: %s\n", what, strerror(errno));
	exit(2);
}

static int64_t ts_ns(const struct timespec *ts)
{
	return (int64_t)ts->tv_sec * 1000000000 + ts->tv_nsec;
}

/* cansend syntax, as the simulator's monitor writes frames */
static void frame_text(const struct can_frame *cf, char *buf)
{
	int n;
	unsigned int i;

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

static int open_on(const char *ifname)
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
	if (bind(s, (struct sockaddr *)&addr, sizeof(addr)) < 0)
		die("bind");
	return s;
}

/* 1 with a frame, 0 when none came for IDLE_MS */
static int receive(int s, struct got *g)
{
	struct pollfd p = { .fd = s, .events = POLLIN };
	char ctrl[CMSG_SPACE(sizeof(struct timespec))];
	struct can_frame cf;
	struct iovec iov = { .iov_base = &cf, .iov_len = sizeof(cf) };
	struct msghdr msg = {
		.msg_iov = &iov, .msg_iovlen = 1,
		.msg_control = ctrl, .msg_controllen = sizeof(ctrl),
	};
	struct cmsghdr *c;
	struct timespec now;
	int r;

	r = poll(&p, 1, IDLE_MS);
	if (r < 0)
		die("poll");
	if (!r)
		return 0;
	if (recvmsg(s, &msg, 0) < 0)
		die("recvmsg");
	clock_gettime(CLOCK_REALTIME, &now);
	g->recv = ts_ns(&now);
	g->stamp = 0;
	for (c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
		if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMPNS) {
			struct timespec ts;

			memcpy(&ts, CMSG_DATA(c), sizeof(ts));
			g->stamp = ts_ns(&ts);
		}
	frame_text(&cf, g->text);
	return 1;
}

/*
 * The end of @text on the bus, CLOCK_REALTIME, 0 when not there: its
 * last error-free passage (a frame an error destroyed is sent again).
 */
static int64_t end_of(FILE *mon, const char *text)
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

int main(int argc, char **argv)
{
	struct got *g;
	long count, n = 0, i;
	FILE *mon;
	int s;

	if (argc != 4) {
		fprintf(stderr, "usage: can-tstamp IFACE COUNT MONITOR\n");
		return 2;
	}
	count = strtol(argv[2], NULL, 0);
	if (count <= 0)
		return 2;
	g = calloc(count, sizeof(*g));
	if (!g)
		die("calloc");
	s = open_on(argv[1]);
	printf("ready\n");
	fflush(stdout);
	while (n < count && receive(s, &g[n]))
		n++;
	close(s);

	mon = fopen(argv[3], "r");
	if (!mon)
		die(argv[3]);
	for (i = 0; i < n; i++) {
		int64_t end = end_of(mon, g[i].text);

		if (!end) {
			printf("%s missing\n", g[i].text);
			continue;
		}
		printf("%s %" PRId64 " %" PRId64 " %" PRId64 "\n", g[i].text,
		       g[i].stamp - end, g[i].recv - g[i].stamp,
		       i ? g[i].stamp - g[i - 1].stamp : 0);
	}
	fclose(mon);
	free(g);
	return 0;
}
