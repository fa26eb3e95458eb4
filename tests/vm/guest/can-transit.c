// SPDX-License-Identifier: GPL-2.0
/*
 * can-transit: how long a lone frame takes from one CAN interface to
 * another on the same bus, on one host (a board with two chips, or the
 * rig): frame n of a flood (flood_count.h) is written to FROM once frame
 * n - 1 has arrived at TO, and its transit runs from just before write()
 * to the return of recvmsg() at TO.  Both ends read CLOCK_MONOTONIC.
 *
 *   can-transit FROM TO COUNT [-i ID] [-t MS]
 *
 *   -i ID   the frames' identifier, hex (8 digits: extended); 7ff
 *   -t MS   a frame not at TO after MS ms is lost, the next one goes; 1000
 *
 * Prints one line:
 *
 *   transit: frames=COUNT received=R lost=L damaged=D min_us=N
 *            median_us=N p99_us=N max_us=N
 *
 * (the frames counted as can-flood counts them, damaged being the
 * duplicated, reordered and corrupted ones; the times over the frames that
 * arrived, "-" when none did).  Exit 0, 1 when a frame was lost or
 * damaged, 2 on an error.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include "flood_count.h"

static void die(const char *what)
{
	fprintf(stderr, "can-transit: %s: %s\n", what, strerror(errno));
	exit(2);
}

#include "can_socket.h"

static void usage(void)
{
	fprintf(stderr, "usage: can-transit FROM TO COUNT [-i ID] [-t MS]\n");
	exit(2);
}

static int64_t now_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

static unsigned long number(const char *s, int base)
{
	unsigned long v;

	if (flood_number(s, base, &v))
		usage();
	return v;
}

/*
 * Frames at @s until frame @n of @f came (1, its arrival in *@at) or
 * @timeout_ms passed without it (0); each one is counted into @c.
 */
static int await_frame(int s, const struct flood *f, uint32_t n,
		       struct flood_count *c, int timeout_ms, int64_t *at)
{
	const struct can_frame want = flood_frame(f, n);
	int64_t end = now_ns() + timeout_ms * 1000000LL;
	struct pollfd p = { .fd = s, .events = POLLIN };
	struct can_frame cf;

	for (;;) {
		int64_t left = end - now_ns();

		if (left <= 0)
			return 0;
		if (poll(&p, 1, (int)(left / 1000000 + 1)) < 0 && errno != EINTR)
			die("poll");
		if (!(p.revents & POLLIN))
			continue;
		if (read(s, &cf, sizeof(cf)) != sizeof(cf))
			die("read");
		*at = now_ns();
		flood_count_frame(c, f, &cf);
		if (cf.can_id == want.can_id && cf.len == want.len &&
		    !memcmp(cf.data, want.data, sizeof(want.data)))
			return 1;
	}
}

static int by_value(const void *a, const void *b)
{
	int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;

	return (x > y) - (x < y);
}

static void print_us(const char *name, const int64_t *ns, uint32_t n,
		     uint32_t rank)
{
	if (!n)
		printf(" %s=-", name);
	else
		printf(" %s=%lld", name, (long long)(ns[rank] / 1000));
}

int main(int argc, char **argv)
{
	struct flood f = { .id = 0x7ff };
	struct flood_count c;
	int timeout_ms = 1000, tx, rx, opt, ok;
	uint32_t n, arrived = 0;
	int64_t *transit;

	if (argc < 4)
		usage();
	f.count = (uint32_t)number(argv[3], 0);
	optind = 4;
	while ((opt = getopt(argc, argv, "i:t:")) != -1) {
		if (opt == 'i') {
			if (flood_id(optarg, &f.id))
				usage();
		} else if (opt == 't') {
			timeout_ms = (int)number(optarg, 10);
		} else {
			usage();
		}
	}
	if (optind != argc || !f.count)
		usage();
	transit = calloc(f.count, sizeof(*transit));
	if (!transit || flood_count_init(&c, &f))
		die("calloc");
	tx = can_socket(argv[1], RECEIVE_NONE);
	rx = can_socket(argv[2], f.id);

	for (n = 0; n < f.count; n++) {
		struct can_frame cf = flood_frame(&f, n);
		int64_t sent = now_ns(), at;

		if (write(tx, &cf, sizeof(cf)) != sizeof(cf))
			die("write");
		if (await_frame(rx, &f, n, &c, timeout_ms, &at))
			transit[arrived++] = at - sent;
	}
	qsort(transit, arrived, sizeof(*transit), by_value);
	ok = flood_lossless(&c, &f);
	printf("transit: frames=%u received=%u lost=%u damaged=%u", f.count,
	       c.received, flood_lost(&c, &f), c.corrupted + c.duplicated +
	       c.reordered);
	print_us("min_us", transit, arrived, 0);
	print_us("median_us", transit, arrived, arrived / 2);
	print_us("p99_us", transit, arrived, arrived ? (arrived * 99) / 100 : 0);
	print_us("max_us", transit, arrived, arrived ? arrived - 1 : 0);
	printf("\n");
	flood_count_free(&c);
	free(transit);
	return ok ? 0 : 1;
}
