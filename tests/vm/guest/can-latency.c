// SPDX-License-Identifier: GPL-2.0
/*
 * can-latency: how long a lone frame takes through a CAN interface, end to
 * end, against the simulated bus's own record of when it ended.
 *
 *   can-latency tx IFACE COUNT MONITOR
 *	sends COUNT frames, one at a time: each is written when the previous
 *	one has come back as the interface's echo.  Prints per frame
 *	"FRAME NS": from just before write() to its end on the bus.
 *   can-latency rx IFACE COUNT INJECT MONITOR
 *	has the phantom node send COUNT frames, one at a time (written to
 *	the simulator's INJECT file once the previous one was received).
 *	Prints per frame "FRAME NS STAMP_NS": from its end on the bus to
 *	the return of recvmsg(), and to its receive timestamp.
 *
 * MONITOR is the simulator's monitor_times (CLOCK_REALTIME ends of frames);
 * each frame is unique, so it is found there by its text.  A frame not
 * found is printed as "FRAME missing".  No frame for 3 s ends the run.
 * Exit 0, or 2 on an error.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
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

#define IDLE_MS		3000
#define TEXT_LEN	40

struct sample {
	char text[TEXT_LEN];
	int64_t before, after, stamp;	/* CLOCK_REALTIME ns */
};

static void die(const char *what)
{
	fprintf(stderr, "can-latency: %s: %s\n", what, strerror(errno));
	exit(2);
}

static int64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_REALTIME, &ts);
	return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

/* cansend syntax, as the simulator's monitor writes frames */
static void frame_text(const struct can_frame *cf, char *buf)
{
	unsigned int i;
	int n;

	n = sprintf(buf, "%03X#", cf->can_id & CAN_SFF_MASK);
	for (i = 0; i < cf->len && i < CAN_MAX_DLEN; i++)
		n += sprintf(buf + n, "%02X", cf->data[i]);
}

/* frame @i of a run: a standard id and the index in the data, all unique */
static struct can_frame frame_no(long i)
{
	struct can_frame cf = { .can_id = 0x2a0, .len = 8 };
	int b;

	for (b = 0; b < 8; b++)
		cf.data[b] = (unsigned char)(i >> (8 * (7 - b)));
	return cf;
}

static int open_on(const char *ifname, int own)
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
static int receive(int s, struct can_frame *cf, int64_t *stamp)
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
			*stamp = (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
		}
	return 1;
}

/* 1 once frame @want came back, 0 when nothing came for IDLE_MS */
static int receive_this(int s, const struct can_frame *want,
			struct sample *got)
{
	struct can_frame cf;

	while (receive(s, &cf, &got->stamp)) {
		got->after = now_ns();
		if (cf.can_id == want->can_id && cf.len == want->len &&
		    !memcmp(cf.data, want->data, want->len))
			return 1;
	}
	return 0;
}

static long run_tx(int s, struct sample *smp, long count)
{
	long n;

	for (n = 0; n < count; n++) {
		struct can_frame cf = frame_no(n);

		frame_text(&cf, smp[n].text);
		smp[n].before = now_ns();
		if (write(s, &cf, sizeof(cf)) != sizeof(cf))
			die("write");
		if (!receive_this(s, &cf, &smp[n]))
			break;
	}
	return n;
}

static long run_rx(int s, const char *inject, struct sample *smp, long count)
{
	long n;

	for (n = 0; n < count; n++) {
		struct can_frame cf = frame_no(n);
		char line[TEXT_LEN + 1];
		int fd, len;

		frame_text(&cf, smp[n].text);
		len = snprintf(line, sizeof(line), "%s\n", smp[n].text);
		fd = open(inject, O_WRONLY);
		if (fd < 0)
			die(inject);
		if (write(fd, line, len) != len)
			die("inject");
		close(fd);
		if (!receive_this(s, &cf, &smp[n]))
			break;
	}
	return n;
}

/*
 * The end of @text on the bus, CLOCK_REALTIME, 0 when not there: its last
 * error-free passage (a frame an error destroyed is sent again).
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

static void print_samples(const char *monitor, const struct sample *smp,
			  long n, int tx)
{
	FILE *mon = fopen(monitor, "r");
	long i;

	if (!mon)
		die(monitor);
	for (i = 0; i < n; i++) {
		int64_t end = end_of(mon, smp[i].text);

		if (!end)
			printf("%s missing\n", smp[i].text);
		else if (tx)
			printf("%s %" PRId64 "\n", smp[i].text, end - smp[i].before);
		else
			printf("%s %" PRId64 " %" PRId64 "\n", smp[i].text,
			       smp[i].after - end, smp[i].stamp - end);
	}
	fclose(mon);
}

static void usage(void)
{
	fprintf(stderr, "usage: can-latency tx IFACE COUNT MONITOR\n"
			"       can-latency rx IFACE COUNT INJECT MONITOR\n");
	exit(2);
}

int main(int argc, char **argv)
{
	struct sample *smp;
	long count, n;
	int tx, s;

	if (argc < 5)
		usage();
	tx = !strcmp(argv[1], "tx");
	if ((tx && argc != 5) || (!tx && (strcmp(argv[1], "rx") || argc != 6)))
		usage();
	count = strtol(argv[3], NULL, 0);
	if (count <= 0)
		usage();
	smp = calloc(count, sizeof(*smp));
	if (!smp)
		die("calloc");
	s = open_on(argv[2], tx);
	n = tx ? run_tx(s, smp, count) : run_rx(s, argv[4], smp, count);
	close(s);
	print_samples(argv[argc - 1], smp, n, tx);
	free(smp);
	return n == count ? 0 : 2;
}
