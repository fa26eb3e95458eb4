// SPDX-License-Identifier: GPL-2.0
/*
 * mcp2510ctl commands that need two chips on one bus, which only the
 * simulation gives a single process: exchange (a demonstration) and bench
 * (the SPI cost of a frame).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ctl.h"
#include "frame_text.h"

#define EXCHANGE_DEFAULT	3
#define EXCHANGE_MAX		32
#define BENCH_DEFAULT		1000
/* passes without progress before a run counts as stuck */
#define STALL_LIMIT		1000

struct node {
	struct mcp2510 *h;
	char label[32];
	struct can_frame sent[EXCHANGE_MAX];
	unsigned int nsent;
	unsigned int nreceived;
	unsigned int mismatches;
};

/*
 * "sim" alone gets a bus named after the command, "sim:NAME" keeps NAME.
 * A bus that processes share (sim:CHIP@BUS) is refused: these commands
 * open two chips of one bus from this process and count in its time.
 */
static int sim_bus_spec(struct ctl *c, const char *cmd, char *buf, size_t len)
{
	const char *dev = c->dev.device;

	if (!dev || strncmp(dev, "sim", 3) || (dev[3] && dev[3] != ':')) {
		cli_error(c->args.err, c->args.prog,
			  "%s needs --device sim (two simulated chips on one bus)",
			  cmd);
		return -1;
	}
	if (strchr(dev, '@')) {
		cli_error(c->args.err, c->args.prog,
			  "%s puts two chips on a bus of this process: --device sim or sim:NAME, not %s",
			  cmd, dev);
		return -1;
	}
	snprintf(buf, len, "%s", dev[3] ? dev : "sim:");
	if (!dev[3])
		strncat(buf, cmd, len - strlen(buf) - 1);
	return 0;
}

static int nodes_open(struct ctl *c, const char *bus, struct node *n,
		      unsigned int count)
{
	struct cli_device d = c->dev;
	unsigned int i;

	d.device = bus;
	if (cli_device_timing(&d, &c->args))
		return -1;
	for (i = 0; i < count; i++) {
		memset(&n[i], 0, sizeof(n[i]));
		snprintf(n[i].label, sizeof(n[i].label), "%s.%u",
			 d.opts.variant ? d.opts.variant : "mcp2510", i);
		n[i].h = cli_device_open(&d, &c->args, false);
		if (!n[i].h || cli_device_up(&d, n[i].h, &c->args))
			return -1;
	}
	return 0;
}

static void nodes_close(struct node *n, unsigned int count)
{
	unsigned int i;

	for (i = 0; i < count; i++)
		mcp2510_close(n[i].h);
}

static int count_option(struct ctl *c, void *ctx, int id, const char *value)
{
	int *count = ctx;

	(void)id;
	if (cli_int(value, false, count) || *count <= 0)
		return ctl_bad(c, "--count", value);
	return 0;
}

static const struct cli_option count_options[] = {
	{ "count", true, CLI_OPT_FIRST_OWN },
	{ NULL, false, 0 },
};

/* ---- exchange ---- */

static void exchange_frame(unsigned int node, unsigned int i,
			   struct can_frame *cf)
{
	unsigned int k;

	memset(cf, 0, sizeof(*cf));
	cf->can_id = 0x100 * (node + 1) + i;
	cf->len = (__u8)(i % CAN_MAX_DLEN + 1);
	for (k = 0; k < cf->len; k++)
		cf->data[k] = (__u8)(node << 4 | k);
}

struct seen_frame {
	const struct node *by;
	struct mcp2510_event ev;
};

struct exchange_log {
	struct seen_frame seen[2 * EXCHANGE_MAX];
	unsigned int n;
};

/* Take what @me received; check it against what @peer sent. */
static int exchange_drain(struct node *me, const struct node *peer,
			  struct exchange_log *log)
{
	struct mcp2510_event ev;
	int got = 0;

	while (!mcp2510_recv(me->h, &ev, 0)) {
		if (ev.type != MCP2510_EVENT_RX)
			continue;
		if (me->nreceived >= peer->nsent ||
		    !ctl_same_frame(&ev.frame, &peer->sent[me->nreceived]))
			me->mismatches++;
		me->nreceived++;
		got++;
		if (log->n < sizeof(log->seen) / sizeof(log->seen[0])) {
			log->seen[log->n].by = me;
			log->seen[log->n++].ev = ev;
		}
	}
	return got;
}

static int by_time(const void *a, const void *b)
{
	const struct timespec *x = &((const struct seen_frame *)a)->ev.ts;
	const struct timespec *y = &((const struct seen_frame *)b)->ev.ts;

	if (x->tv_sec != y->tv_sec)
		return x->tv_sec < y->tv_sec ? -1 : 1;
	if (x->tv_nsec != y->tv_nsec)
		return x->tv_nsec < y->tv_nsec ? -1 : 1;
	return 0;
}

/* Both nodes' receptions as one capture, in the order they happened. */
static void exchange_print(struct ctl *c, struct exchange_log *log)
{
	unsigned int i;

	qsort(log->seen, log->n, sizeof(log->seen[0]), by_time);
	for (i = 0; i < log->n; i++)
		ctl_print_frame(c, &log->seen[i].ev, log->seen[i].by->label);
}

static int exchange_send(struct ctl *c, struct node *n, unsigned int count)
{
	unsigned int i, k;

	for (i = 0; i < count; i++) {
		for (k = 0; k < 2; k++) {
			exchange_frame(k, i, &n[k].sent[n[k].nsent]);
			if (mcp2510_send(n[k].h, &n[k].sent[n[k].nsent], 0)) {
				cli_error_errno(&c->args, "send");
				return -1;
			}
			n[k].nsent++;
		}
	}
	return 0;
}

static int exchange_frames(struct ctl *c, struct node *n, unsigned int count)
{
	struct exchange_log log = { .n = 0 };
	unsigned int stalls = 0;

	if (exchange_send(c, n, count))
		return EXIT_FAIL;
	while ((n[0].nreceived < count || n[1].nreceived < count) &&
	       stalls < STALL_LIMIT) {
		if (exchange_drain(&n[0], &n[1], &log) +
		    exchange_drain(&n[1], &n[0], &log))
			stalls = 0;
		else
			stalls++;
	}
	exchange_print(c, &log);
	if (n[0].nreceived == count && n[1].nreceived == count &&
	    !n[0].mismatches && !n[1].mismatches)
		return 0;
	cli_error(c->args.err, c->args.prog,
		  "exchange: %s received %u of %u frames, %s %u of %u",
		  n[0].label, n[0].nreceived, count, n[1].label,
		  n[1].nreceived, count);
	return EXIT_FAIL;
}

static int exchange_run(struct ctl *c)
{
	int count = EXCHANGE_DEFAULT, ret;
	struct node n[2];
	char bus[64];
	bool done;

	ret = ctl_parse(c, &ctl_exchange, count_options, count_option, &count,
			0, 0, &done);
	if (done)
		return ret;
	if (sim_bus_spec(c, "exchange", bus, sizeof(bus)))
		return EXIT_USAGE;
	if (count > EXCHANGE_MAX) {
		cli_error(c->args.err, c->args.prog,
			  "exchange: --count is at most %d", EXCHANGE_MAX);
		return EXIT_USAGE;
	}
	memset(n, 0, sizeof(n));
	ret = nodes_open(c, bus, n, 2) ? EXIT_FAIL :
		exchange_frames(c, n, (unsigned int)count);
	nodes_close(n, 2);
	return ret;
}

const struct ctl_command ctl_exchange = {
	.name = "exchange",
	.summary = "two simulated chips on one bus send each other frames",
	.help =
"Usage: mcp2510ctl --device sim exchange [--count N]\n"
"Put two simulated chips on one bus at --bitrate, let each send N frames\n"
"(default 3, at most 32; node 0 uses ids 100.., node 1 ids 200..) and\n"
"print what each receives in candump -L format, labelled VARIANT.0 and\n"
"VARIANT.1.  Exit 0 when each received exactly what the other sent.\n",
	.run = exchange_run,
	.options = count_options,
	.needs_device = true,
};

/* ---- bench ---- */

struct bench_result {
	struct mcp2510_stats tx0, tx1, rx0, rx1;
	double cpu_s;
};

static double cpu_seconds(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
	return (double)ts.tv_sec + (double)ts.tv_nsec / 1e9;
}

/* Events the sender produces are not needed; only the count of RX. */
static unsigned int drain(struct mcp2510 *h)
{
	struct mcp2510_event ev;
	unsigned int rx = 0;

	while (!mcp2510_recv(h, &ev, 0))
		rx += ev.type == MCP2510_EVENT_RX;
	return rx;
}

static int bench_frames(struct node *n, unsigned int count)
{
	struct can_frame cf = { .can_id = 0x123, .len = CAN_MAX_DLEN };
	unsigned int sent = 0, received = 0, stalls = 0;

	while (received < count && stalls < STALL_LIMIT) {
		unsigned int before = sent + received;

		while (sent < count) {
			memcpy(cf.data, &sent, sizeof(sent));
			if (mcp2510_send(n[0].h, &cf, MCP2510_SEND_NONBLOCK))
				break;
			sent++;
		}
		drain(n[0].h);
		received += drain(n[1].h);
		stalls = sent + received == before ? stalls + 1 : 0;
	}
	return received == count ? 0 : -1;
}

static int bench_measure(struct node *n, unsigned int count,
			 struct bench_result *r)
{
	double t0;
	int ret;

	mcp2510_stats(n[0].h, &r->tx0);
	mcp2510_stats(n[1].h, &r->rx0);
	t0 = cpu_seconds();
	ret = bench_frames(n, count);
	r->cpu_s = cpu_seconds() - t0;
	mcp2510_stats(n[0].h, &r->tx1);
	mcp2510_stats(n[1].h, &r->rx1);
	return ret;
}

static void bench_print(struct ctl *c, const struct bench_result *r,
			unsigned int count)
{
	double f = count;

	fprintf(c->out,
		"bench: %u frames of 8 bytes, %s, %" PRIu32 " Hz oscillator, %" PRIu32 " bit/s\n",
		count, c->dev.opts.variant ? c->dev.opts.variant : "mcp2510",
		c->dev.opts.osc_hz, c->dev.bitrate);
	fprintf(c->out, "tx: %.2f spi transfers/frame, %.2f spi bytes/frame\n",
		(double)(r->tx1.spi_transfers - r->tx0.spi_transfers) / f,
		(double)(r->tx1.spi_bytes - r->tx0.spi_bytes) / f);
	fprintf(c->out, "rx: %.2f spi transfers/frame, %.2f spi bytes/frame\n",
		(double)(r->rx1.spi_transfers - r->rx0.spi_transfers) / f,
		(double)(r->rx1.spi_bytes - r->rx0.spi_bytes) / f);
	fprintf(c->out,
		"cpu: %.2f us/frame (library, driver core and chip model together)\n",
		r->cpu_s * 1e6 / f);
}

static int bench_run(struct ctl *c)
{
	struct bench_result r;
	unsigned int count = BENCH_DEFAULT;
	struct node n[2];
	char bus[64];
	bool done;
	int ret;

	ret = ctl_parse(c, &ctl_bench, NULL, NULL, NULL, 0, 1, &done);
	if (done)
		return ret;
	if (c->npos && (cli_u32(c->pos[0], &count) || !count)) {
		ctl_bad(c, "frame count", c->pos[0]);
		return EXIT_USAGE;
	}
	if (sim_bus_spec(c, "bench", bus, sizeof(bus)))
		return EXIT_USAGE;
	memset(n, 0, sizeof(n));
	ret = EXIT_FAIL;
	if (nodes_open(c, bus, n, 2))
		goto out_close;
	if (bench_measure(n, count, &r)) {
		cli_error(c->args.err, c->args.prog, "bench: frames were lost");
		goto out_close;
	}
	bench_print(c, &r, count);
	ret = 0;

out_close:
	nodes_close(n, 2);
	return ret;
}

const struct ctl_command ctl_bench = {
	.name = "bench",
	.summary = "SPI transfers, bytes and CPU time per frame (simulated)",
	.help =
"Usage: mcp2510ctl --device sim [--variant V] bench [N]\n"
"Send N (default 1000) 8-byte frames from one simulated chip to another\n"
"and print, from the simulated chips' counters, the SPI transfers and\n"
"bytes each frame cost the sender and the receiver, and the CPU time per\n"
"frame of the whole process (library, driver core and chip model).\n",
	.run = bench_run,
	.needs_device = true,
};
