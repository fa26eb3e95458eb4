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
#include <fcntl.h>
#include <inttypes.h>
#include <unistd.h>

#include "stamped_rx.h"

struct sample {
	char text[TEXT_LEN];
	int64_t before, after, stamp;	/* CLOCK_REALTIME ns */
};

/* frame @i of a run: a standard id and the index in the data, all unique */
static struct can_frame frame_no(long i)
{
	struct can_frame cf = { .can_id = 0x2a0, .len = 8 };
	int b;

	for (b = 0; b < 8; b++)
		cf.data[b] = (unsigned char)(i >> (8 * (7 - b)));
	return cf;
}

/* 1 once frame @want came back, 0 when nothing came for IDLE_MS */
static int receive_this(int s, const struct can_frame *want,
			struct sample *got)
{
	struct can_frame cf;

	while (stamped_receive(s, &cf, &got->stamp)) {
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

static void print_samples(const char *monitor, const struct sample *smp,
			  long n, int tx)
{
	FILE *mon = fopen(monitor, "r");
	long i;

	if (!mon)
		die(monitor);
	for (i = 0; i < n; i++) {
		int64_t end = end_on_bus(mon, smp[i].text);

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
	s = stamped_socket(argv[2], tx);
	n = tx ? run_tx(s, smp, count) : run_rx(s, argv[4], smp, count);
	close(s);
	print_samples(argv[argc - 1], smp, n, tx);
	free(smp);
	return n == count ? 0 : 2;
}
