// SPDX-License-Identifier: GPL-2.0
/*
 * can-flood: a flood of unique CAN frames and the count, at the far side,
 * of what arrived (flood_count.h: the frames and the four kinds of
 * damage).  Plain SocketCAN, for the rig and for boards alike.
 *
 *   can-flood send IFACE COUNT [-i ID] [-s START] [-r EVERY:FILE:TEXT]
 *	writes COUNT frames to IFACE as fast as it takes them (ENOBUFS:
 *	waits a millisecond and tries again; no progress for IDLE_MS fails)
 *   can-flood recv IFACE COUNT [-i ID] [-s START] [-w WORD] [-t MS] [-l MS] [-o]
 *	counts the frames IFACE's socket receives
 *   can-flood check COUNT [-i ID] [-s START] [-w WORD] [-t MS] [-l MS] [-o] [-f FILE]
 *	counts the frames of text lines in cansend syntax (candump -L, the
 *	simulator's bus monitor) from standard input, or from FILE, which is
 *	followed as it grows
 *
 *   -i ID    the flood's identifier, hex (8 digits: extended); 123
 *   -s START the sequence number of the first frame; 0
 *   -w WORD  the check word is WORD, as eight hex digits of data bytes 4-7
 *            (a sender that only counts); without: the CRC-32
 *   -t MS    no frame for MS ms ends the count (before the first: 60 s); 3000
 *   -l MS    once every frame came, no frame for MS ms ends it; 1000
 *   -o       only frames with the flood's identifier count: the others are
 *            another sender's, not damaged frames of the flood
 *   -r EVERY:FILE:TEXT  after every EVERY frames written, TEXT written to
 *            FILE, its errors ignored: the rig's phantom node as a rival
 *            sender whose frames keep pace with the flood however slowly
 *            the host runs (tests/vm/rig.sh, burst_under_rival)
 *
 * recv and check print "ready" once listening, then one line:
 *
 *   flood: mode=recv frames=COUNT received=R lost=L duplicated=D
 *          reordered=O corrupted=C lossless=0|1 sock_drops=S cpu_us=U
 *
 * (one line; sock_drops: frames the receiving socket's queue dropped, by
 * SO_RXQ_OVFL; cpu_us: the tool's own CPU time).  send prints
 * "flood: mode=send frames=COUNT sent=N enobufs=E cpu_us=U".
 * Exit 0 (received: lossless), 1 (not lossless) or 2 (an error).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "flood_count.h"

#define FIRST_FRAME_MS	60000
#define NAP_MS		20	/* between reads of what came meanwhile */

struct opts {
	struct flood f;
	int idle_ms, linger_ms;
	int only_id;
	const char *file;
	unsigned long rival_every;
	const char *rival_file, *rival_text;
};

static void die(const char *what)
{
	fprintf(stderr, "can-flood: %s: %s\n", what, strerror(errno));
	exit(2);
}

#include "can_socket.h"

static void usage(void)
{
	fprintf(stderr,
		"usage: can-flood send IFACE COUNT [-i ID] [-s START] [-r EVERY:FILE:TEXT]\n"
		"       can-flood recv IFACE COUNT [-i ID] [-s START] [-w WORD] [-t MS] [-l MS] [-o]\n"
		"       can-flood check COUNT [-i ID] [-s START] [-w WORD] [-t MS] [-l MS] [-o] [-f FILE]\n");
	exit(2);
}

static long now_ms(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

static void nap_ms(long ms)
{
	struct timespec ts = { ms / 1000, ms % 1000 * 1000000L };

	nanosleep(&ts, NULL);
}

static long cpu_us(void)
{
	struct rusage ru;

	getrusage(RUSAGE_SELF, &ru);
	return (ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1000000L +
	       ru.ru_utime.tv_usec + ru.ru_stime.tv_usec;
}

static unsigned long number(const char *s, int base)
{
	unsigned long v;

	if (flood_number(s, base, &v))
		usage();
	return v;
}

/* -r EVERY:FILE:TEXT */
static void parse_rival(char *arg, struct opts *o)
{
	char *file = strchr(arg, ':'), *text;

	if (!file || !(text = strchr(file + 1, ':')))
		usage();
	*file++ = '\0';
	*text++ = '\0';
	o->rival_every = number(arg, 10);
	if (!o->rival_every || !*file)
		usage();
	o->rival_file = file;
	o->rival_text = text;
}

static void parse_opts(int argc, char **argv, struct opts *o)
{
	struct can_frame cf;
	char text[32];
	int c;

	o->f.id = 0x123;
	o->idle_ms = 3000;
	o->linger_ms = 1000;
	while ((c = getopt(argc, argv, "i:s:w:t:l:of:r:")) != -1) {
		switch (c) {
		case 'i':
			if (flood_id(optarg, &o->f.id))
				usage();
			break;
		case 's':
			o->f.start = (uint32_t)number(optarg, 0);
			break;
		case 'w':
			snprintf(text, sizeof(text), "000#%s", optarg);
			if (strlen(optarg) != 8 || flood_text_frame(text, &cf))
				usage();
			o->f.fixed = 1;
			o->f.word = flood_le32(cf.data);
			break;
		case 't':
			o->idle_ms = (int)number(optarg, 10);
			break;
		case 'l':
			o->linger_ms = (int)number(optarg, 10);
			break;
		case 'o':
			o->only_id = 1;
			break;
		case 'f':
			o->file = optarg;
			break;
		case 'r':
			parse_rival(optarg, o);
			break;
		default:
			usage();
		}
	}
}

/* the rival's line, once more; a run still under way refuses it */
static void rival_write(const struct opts *o)
{
	int fd = open(o->rival_file, O_WRONLY);

	if (fd < 0)
		die(o->rival_file);
	if (write(fd, o->rival_text, strlen(o->rival_text)) < 0 &&
	    errno != EBUSY)
		die(o->rival_file);
	close(fd);
}

static int run_send(const char *ifname, const struct opts *o)
{
	int s = can_socket(ifname, RECEIVE_NONE);
	long enobufs = 0, stuck_since = 0;
	uint32_t n = 0;

	while (n < o->f.count) {
		struct can_frame cf = flood_frame(&o->f, n);

		if (write(s, &cf, sizeof(cf)) == sizeof(cf)) {
			n++;
			stuck_since = 0;
			if (o->rival_every && !(n % o->rival_every))
				rival_write(o);
			continue;
		}
		if (errno != ENOBUFS)
			die("write");
		enobufs++;
		if (!stuck_since)
			stuck_since = now_ms();
		else if (now_ms() - stuck_since > o->idle_ms)
			die("write");
		nap_ms(1);
	}
	printf("flood: mode=send frames=%u sent=%u enobufs=%ld cpu_us=%ld\n",
	       o->f.count, n, enobufs, cpu_us());
	close(s);
	return 0;
}

/* when the count ends: IDLE_MS without a frame, LINGER_MS once all came */
static long deadline(const struct opts *o, const struct flood_count *c,
		     long last)
{
	if (!c->received)
		return last + FIRST_FRAME_MS;
	return last + (c->unique == o->f.count ? o->linger_ms : o->idle_ms);
}

/* a frame waiting at @s into @cf: 1, or 0 with none; *@drops: SO_RXQ_OVFL */
static int socket_frame(int s, struct can_frame *cf, uint32_t *drops)
{
	char ctrl[CMSG_SPACE(sizeof(uint32_t))];
	struct iovec iov = { .iov_base = cf, .iov_len = sizeof(*cf) };
	struct msghdr msg = {
		.msg_iov = &iov, .msg_iovlen = 1,
		.msg_control = ctrl, .msg_controllen = sizeof(ctrl),
	};
	struct cmsghdr *cm;

	if (recvmsg(s, &msg, MSG_DONTWAIT) < 0) {
		if (errno == EAGAIN || errno == EINTR)
			return 0;
		die("recvmsg");
	}
	for (cm = CMSG_FIRSTHDR(&msg); cm; cm = CMSG_NXTHDR(&msg, cm))
		if (cm->cmsg_level == SOL_SOCKET && cm->cmsg_type == SO_RXQ_OVFL)
			memcpy(drops, CMSG_DATA(cm), sizeof(*drops));
	return 1;
}

static void recv_socket(const char *ifname, const struct opts *o,
			struct flood_count *c, uint32_t *drops)
{
	int s = can_socket(ifname, o->only_id ? (int64_t)o->f.id : RECEIVE_ALL);
	int on = 1, size = 8 << 20;
	struct can_frame cf;
	long last;

	if (setsockopt(s, SOL_SOCKET, SO_RXQ_OVFL, &on, sizeof(on)) < 0)
		die("SO_RXQ_OVFL");
	/* room for a whole flood where allowed (root), else the limit */
	if (setsockopt(s, SOL_SOCKET, SO_RCVBUFFORCE, &size, sizeof(size)) < 0 &&
	    setsockopt(s, SOL_SOCKET, SO_RCVBUF, &size, sizeof(size)) < 0)
		die("SO_RCVBUF");
	printf("ready\n");
	fflush(stdout);
	/*
	 * Frames wait in the socket's queue and are taken every NAP_MS: a
	 * wake-up per frame would cost the host under test more CPU than
	 * its driver does.
	 */
	last = now_ms();
	while (now_ms() < deadline(o, c, last)) {
		nap_ms(NAP_MS);
		while (socket_frame(s, &cf, drops)) {
			flood_count_frame(c, &o->f, &cf);
			last = now_ms();
		}
	}
	close(s);
}

/* the next line of @fd into @line, following a file at its end; 0 by @end */
static int text_line(int fd, int follow, long end, char *line, size_t size)
{
	static char buf[4096];
	static size_t have;
	size_t len;
	char *nl;
	ssize_t r;

	while (!(nl = memchr(buf, '\n', have))) {
		if (have == sizeof(buf))
			have = 0;	/* a line that long holds no frame */
		r = read(fd, buf + have, sizeof(buf) - have);
		if (r < 0 && errno != EINTR)
			die("read");
		if (r > 0) {
			have += (size_t)r;
			continue;
		}
		if (!r && !follow)
			return 0;
		if (now_ms() >= end)
			return 0;
		nap_ms(NAP_MS);
	}
	len = (size_t)(nl - buf) < size ? (size_t)(nl - buf) : size - 1;
	memcpy(line, buf, len);
	line[len] = '\0';
	have -= (size_t)(nl + 1 - buf);
	memmove(buf, nl + 1, have);
	return 1;
}

static void recv_text(const struct opts *o, struct flood_count *c)
{
	int fd = o->file ? open(o->file, O_RDONLY) : 0;
	struct can_frame cf;
	char line[256];
	long last;

	if (fd < 0)
		die(o->file);
	printf("ready\n");
	fflush(stdout);
	last = now_ms();
	while (text_line(fd, !!o->file, deadline(o, c, last), line, sizeof(line)))
		if (!flood_text_frame(line, &cf) &&
		    (!o->only_id || cf.can_id == o->f.id)) {
			flood_count_frame(c, &o->f, &cf);
			last = now_ms();
		}
	if (fd)
		close(fd);
}

static int run_recv(const char *ifname, const struct opts *o)
{
	struct flood_count c;
	uint32_t drops = 0;
	int lossless;

	if (flood_count_init(&c, &o->f))
		die("calloc");
	if (ifname)
		recv_socket(ifname, o, &c, &drops);
	else
		recv_text(o, &c);
	lossless = flood_lossless(&c, &o->f);
	printf("flood: mode=%s frames=%u received=%u lost=%u duplicated=%u"
	       " reordered=%u corrupted=%u lossless=%d sock_drops=%u cpu_us=%ld\n",
	       ifname ? "recv" : "check", o->f.count, c.received,
	       flood_lost(&c, &o->f), c.duplicated, c.reordered, c.corrupted,
	       lossless, drops, cpu_us());
	flood_count_free(&c);
	return lossless ? 0 : 1;
}

int main(int argc, char **argv)
{
	const char *mode, *ifname = NULL;
	struct opts o = { 0 };
	int args;

	if (argc < 3)
		usage();
	mode = argv[1];
	args = strcmp(mode, "check") ? 2 : 1;
	if (args == 2) {
		if (argc < 4)
			usage();
		ifname = argv[2];
	}
	o.f.count = (uint32_t)number(argv[1 + args], 0);
	if (!o.f.count)
		usage();
	optind = 2 + args;
	parse_opts(argc, argv, &o);
	if (optind != argc)
		usage();
	if (!strcmp(mode, "send") && !o.f.fixed && !o.file)
		return run_send(ifname, &o);
	if (o.rival_every && strcmp(mode, "send"))
		usage();
	if (!strcmp(mode, "recv") && !o.file)
		return run_recv(ifname, &o);
	if (!strcmp(mode, "check"))
		return run_recv(NULL, &o);
	usage();
	return 2;
}
