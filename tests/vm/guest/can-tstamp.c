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
#include <inttypes.h>
#include <unistd.h>

#include "stamped_rx.h"

struct got {
	char text[TEXT_LEN];
	int64_t stamp, recv;
};

/* 1 with a frame, 0 when none came for IDLE_MS */
static int receive(int s, struct got *g)
{
	struct can_frame cf;

	if (!stamped_receive(s, &cf, &g->stamp))
		return 0;
	g->recv = now_ns();
	frame_text(&cf, g->text);
	return 1;
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
	s = stamped_socket(argv[1], 0);
	printf("ready\n");
	fflush(stdout);
	while (n < count && receive(s, &g[n]))
		n++;
	close(s);

	mon = fopen(argv[3], "r");
	if (!mon)
		die(argv[3]);
	for (i = 0; i < n; i++) {
		int64_t end = end_on_bus(mon, g[i].text);

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
