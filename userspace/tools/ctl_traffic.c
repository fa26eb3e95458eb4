// SPDX-License-Identifier: GPL-2.0
/* mcp2510ctl commands that put frames on the bus: send, dump, selftest. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "ctl.h"
#include "frame_text.h"

#define DEFAULT_TIMEOUT_MS	1000

enum {
	OPT_COUNT = CLI_OPT_FIRST_OWN,
	OPT_TIMEOUT,
	OPT_FILTER,
	OPT_LABEL,
};

static const struct cli_option dump_options[] = {
	{ "count", true, OPT_COUNT },
	{ "timeout", true, OPT_TIMEOUT },
	{ "filter", true, OPT_FILTER },
	{ "label", true, OPT_LABEL },
	{ NULL, false, 0 },
};

/* send and selftest only wait */
static const struct cli_option timeout_options[] = {
	{ "timeout", true, OPT_TIMEOUT },
	{ NULL, false, 0 },
};

struct traffic_opts {
	int count;			/* frames to wait for, -1: no limit */
	int timeout_ms;
	const char *label;
	bool accept_all;		/* selftest: every frame must come back */
	bool may_wait_forever;		/* dump: --timeout -1 */
	struct can_frame frames[CTL_MAX_ARGS];	/* send's, one per argument */
};

static int traffic_option(struct ctl *c, void *ctx, int id, const char *value)
{
	struct traffic_opts *t = ctx;

	switch (id) {
	case OPT_COUNT:
		if (cli_int(value, false, &t->count))
			return ctl_bad(c, "--count", value);
		/* candump -n 0 is refused too */
		if (!t->count)
			cli_error(c->args.err, c->args.prog,
				  "--count 0: count 1 or more frames, or leave it out for no limit");
		return t->count ? 0 : -1;
	case OPT_TIMEOUT:
		if (!t->may_wait_forever && !strcmp(value, "-1")) {
			/* on a lone node the retransmissions would never end */
			cli_error(c->args.err, c->args.prog,
				  "--timeout -1 (forever) is for dump only: give the milliseconds to wait");
			return -1;
		}
		return cli_int(value, true, &t->timeout_ms) ?
			ctl_bad(c, "--timeout", value) : 0;
	case OPT_LABEL:
		t->label = value;
		return 0;
	case OPT_FILTER:
		return cli_device_add_filter(&c->dev, &c->args, value);
	default:
		return -1;
	}
}

static void traffic_defaults(struct traffic_opts *t)
{
	memset(t, 0, sizeof(*t));
	t->count = -1;
	t->timeout_ms = DEFAULT_TIMEOUT_MS;
}

static const char *label_of(const struct traffic_opts *t, struct mcp2510 *h)
{
	return t->label ? t->label : mcp2510_variant_name(h);
}

static bool filters_are_default(const struct mcp2510_hw_filters *f)
{
	struct mcp2510_hw_filters def;
	char a[64], b[64];
	unsigned int i;

	mcp2510_hw_filters_default(&def);
	for (i = 0; i < MCP2510_HW_FILTER_SETTINGS; i++) {
		mcp2510_hw_filters_format(f, i, a, sizeof(a));
		mcp2510_hw_filters_format(&def, i, b, sizeof(b));
		if (strcmp(a, b))
			return false;
	}
	return true;
}

/* The default filters instead of those the chip kept, saying so. */
static int accept_all(struct ctl *c, struct mcp2510 *h)
{
	struct mcp2510_hw_filters f;

	mcp2510_get_filters(h, &f);
	if (filters_are_default(&f))
		return 0;
	cli_error(c->args.err, c->args.prog,
		  "note: the chip's acceptance filters are reset to accept every frame");
	mcp2510_hw_filters_default(&f);
	if (mcp2510_set_filters(h, &f)) {
		cli_error_errno(&c->args, "setting the filters");
		return -1;
	}
	return 0;
}

static struct mcp2510 *open_up(struct ctl *c, const struct traffic_opts *t)
{
	struct mcp2510 *h;

	if (cli_device_timing(&c->dev, &c->args))
		return NULL;
	h = cli_device_open(&c->dev, &c->args, false);
	if (!h)
		return NULL;
	if (t->accept_all && accept_all(c, h))
		goto out_close;
	if (cli_device_up(&c->dev, h, &c->args))
		goto out_close;
	return h;

out_close:
	mcp2510_close(h);
	return NULL;
}

static void warn_ring_overflows(struct ctl *c, struct mcp2510 *h)
{
	struct mcp2510_stats s;

	if (!mcp2510_stats(h, &s) && s.ring_overflows)
		cli_error(c->args.err, c->args.prog,
			  "warning: %u events lost to a full event ring",
			  s.ring_overflows);
}

/* ---- send ---- */

static int parse_frames(struct ctl *c, struct can_frame *frames)
{
	const char *why;
	int i;

	for (i = 0; i < c->npos; i++) {
		if (frame_parse(c->pos[i], &frames[i], &why)) {
			cli_error(c->args.err, c->args.prog, "bad frame '%s': %s",
				  c->pos[i], why);
			return -1;
		}
		/* a raw DLC goes out only with cc-len8-dlc on */
		if (frames[i].len8_dlc)
			c->dev.ctrlmode |= CAN_CTRLMODE_CC_LEN8_DLC;
	}
	return 0;
}

static int send_failed(struct ctl *c, struct mcp2510 *h, const char *why)
{
	struct can_berr_counter bec = { 0, 0 };
	enum can_state st = CAN_STATE_STOPPED;

	mcp2510_state(h, &st, &bec);
	cli_error(c->args.err, c->args.prog, "send: %s (state %s, tec %u, rec %u)",
		  why, mcp2510_state_name(st), bec.txerr, bec.rxerr);
	return EXIT_FAIL;
}

/* Queue every frame, then wait until the chip reports each one sent. */
static int send_all(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	const struct traffic_opts *t = ctx;
	struct mcp2510_event ev;
	int i, done = 0;

	for (i = 0; i < c->npos; i++)
		if (mcp2510_send(h, &t->frames[i], 0))
			return send_failed(c, h, "no transmit buffer became free");
	while (done < c->npos) {
		if (mcp2510_recv(h, &ev, t->timeout_ms))
			return send_failed(c, h, "not acknowledged in time");
		if (ev.type == MCP2510_EVENT_TX_ABORTED)
			return send_failed(c, h, "frame aborted");
		if (ev.type == MCP2510_EVENT_TX_DONE)
			done++;
	}
	return 0;
}

static int send_run(struct ctl *c)
{
	struct traffic_opts t;
	bool done;
	int ret;

	traffic_defaults(&t);
	ret = ctl_parse(c, &ctl_send, timeout_options, traffic_option, &t, 1,
			CTL_MAX_ARGS, &done);
	if (done)
		return ret;
	if (c->dev.ctrlmode & CAN_CTRLMODE_LISTENONLY) {
		cli_error(c->args.err, c->args.prog,
			  "send: --listen-only never transmits (no ACK, no frame): leave it out to send");
		return EXIT_USAGE;
	}
	if (parse_frames(c, t.frames))
		return EXIT_USAGE;
	return ctl_on_chip(c, open_up(c, &t), send_all, &t);
}

const struct ctl_command ctl_send = {
	.name = "send",
	.summary = "send frames in cansend syntax",
	.help =
"Usage: mcp2510ctl --device DEV send [-t|--timeout MS] FRAME...\n"
"Bring the chip up at --bitrate, send each FRAME in order and wait until\n"
"every one was acknowledged on the bus (exit 1 if not within MS, default\n"
"1000).  FRAME in cansend syntax:\n"
"  123#DEADBEEF   standard id (3 hex digits), up to 8 data bytes\n"
"  12345678#11    extended id (8 hex digits)\n"
"  123#           no data;   123#11.22.33   a dot before any byte\n"
"  123#R  123#R3  remote frame, optionally with its length\n"
"  123#1122334455667788_9   123#R8_9\n"
"                 after 8 bytes: a raw DLC 9 to F (sent with cc-len8-dlc on)\n",
	.run = send_run,
	.needs_device = true,
	.options = timeout_options,
};

/* ---- dump ---- */

/*
 * The capture ended without a frame for t->timeout_ms; with no timeout
 * that means the simulated bus has nothing scheduled, ever.  Exit 1 when
 * --count frames did not come.
 */
static int dump_ended(struct ctl *c, const struct traffic_opts *t, int seen)
{
	if (t->timeout_ms < 0)
		cli_error(c->args.err, c->args.prog,
			  "dump: the simulated bus has gone quiet for good (no node on it sends), stopping");
	if (t->count < 0 || seen >= t->count)
		return 0;
	if (t->timeout_ms >= 0)
		cli_error(c->args.err, c->args.prog,
			  "dump: %d of %d frames, then none for %d ms",
			  seen, t->count, t->timeout_ms);
	else
		cli_error(c->args.err, c->args.prog, "dump: %d of %d frames",
			  seen, t->count);
	return EXIT_FAIL;
}

static int dump_frames(struct ctl *c, struct mcp2510 *h,
		       const struct traffic_opts *t)
{
	struct mcp2510_event ev;
	int seen = 0;

	while (t->count < 0 || seen < t->count) {
		if (mcp2510_recv(h, &ev, t->timeout_ms)) {
			if (errno == ETIMEDOUT || errno == EAGAIN)
				return dump_ended(c, t, seen);
			cli_error_errno(&c->args, "receiving");
			return EXIT_FAIL;
		}
		if (ev.type != MCP2510_EVENT_RX && ev.type != MCP2510_EVENT_ERROR)
			continue;
		ctl_print_frame(c, &ev, label_of(t, h));
		seen++;
	}
	return 0;
}

/* Even a failed capture says whether the ring dropped events. */
static int dump_capture(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	int ret = dump_frames(c, h, ctx);

	warn_ring_overflows(c, h);
	return ret;
}

static int dump_run(struct ctl *c)
{
	struct traffic_opts t;
	bool done;
	int ret;

	traffic_defaults(&t);
	t.timeout_ms = -1;
	t.may_wait_forever = true;
	ret = ctl_parse(c, &ctl_dump, dump_options, traffic_option, &t, 0, 0,
			&done);
	if (done)
		return ret;
	return ctl_on_chip(c, open_up(c, &t), dump_capture, &t);
}

const struct ctl_command ctl_dump = {
	.name = "dump",
	.summary = "print received frames in candump -L format",
	.help =
"Usage: mcp2510ctl --device DEV dump [-n|--count N] [-t|--timeout MS]\n"
"                  [--filter NAME=VALUE]... [--label NAME]\n"
"Bring the chip up at --bitrate and print every received frame and error\n"
"frame as candump -L does, with the chip's variant (or NAME) in place of\n"
"the interface:  (1700000000.123456) mcp2510 123#DEADBEEF\n"
"Stops after N frames (exit 1 if fewer came), or when none came for MS\n"
"milliseconds (default: wait forever; on a simulated bus where no node\n"
"sends, nothing can ever come, so it says so and stops at once).\n"
"Filters set with the filter command stay; --filter NAME=VALUE changes\n"
"settings on top of them, with the names and values of the filter command.\n",
	.run = dump_run,
	.needs_device = true,
	.options = dump_options,
};

/* ---- selftest ---- */

/* Frames of every kind: both id formats, all lengths, remote frames. */
static unsigned int selftest_frames(struct can_frame *f, unsigned int max)
{
	static const canid_t std_ids[] = { 0x000, 0x7ff, 0x555, 0x2aa };
	static const canid_t ext_ids[] = { 0x00000000, 0x1fffffff, 0x15555555,
					   0x0aaaaaaa };
	unsigned int n = 0, len, i, k;

	for (len = 0; len <= CAN_MAX_DLEN && n + 2 <= max; len++) {
		for (k = 0; k < 2; k++) {
			memset(&f[n], 0, sizeof(f[n]));
			f[n].can_id = k ? ext_ids[len % 4] | CAN_EFF_FLAG :
					  std_ids[len % 4];
			f[n].len = (__u8)len;
			for (i = 0; i < len; i++)
				f[n].data[i] = (__u8)(0x11 * (i + 1) ^ (k ? 0xff : 0));
			n++;
		}
	}
	for (k = 0; k < 4 && n < max; k++, n++) {
		memset(&f[n], 0, sizeof(f[n]));
		f[n].can_id = (k & 1 ? ext_ids[k] | CAN_EFF_FLAG : std_ids[k]) |
			      CAN_RTR_FLAG;
		f[n].len = (__u8)(k * 2 + 1);
	}
	return n;
}

static int loop_one(struct ctl *c, struct mcp2510 *h,
		    const struct can_frame *sent, int timeout_ms)
{
	char want[FRAME_TEXT_MAX], got[FRAME_TEXT_MAX];
	struct mcp2510_event ev;

	frame_format(sent, want, sizeof(want));
	if (mcp2510_send(h, sent, 0)) {
		fprintf(c->out, "selftest: sending %s: %s\n", want, strerror(errno));
		return -1;
	}
	do {
		if (mcp2510_recv(h, &ev, timeout_ms)) {
			fprintf(c->out, "selftest: %s did not come back\n", want);
			return -1;
		}
	} while (ev.type != MCP2510_EVENT_RX);
	if (ctl_same_frame(sent, &ev.frame))
		return 0;
	frame_format(&ev.frame, got, sizeof(got));
	fprintf(c->out, "selftest: sent %s, got %s\n", want, got);
	return -1;
}

static int selftest_loop(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	const struct traffic_opts *t = ctx;
	struct can_frame frames[32];
	unsigned int i, n = selftest_frames(frames, 32), good = 0;

	for (i = 0; i < n; i++)
		if (!loop_one(c, h, &frames[i], t->timeout_ms))
			good++;
	fprintf(c->out, "selftest: %u of %u frames came back identical\n%s\n",
		good, n, good == n ? "PASS" : "FAIL");
	return good == n ? 0 : EXIT_FAIL;
}

static int selftest_run(struct ctl *c)
{
	struct traffic_opts t;
	bool done;
	int ret;

	traffic_defaults(&t);
	ret = ctl_parse(c, &ctl_selftest, timeout_options, traffic_option, &t,
			0, 0, &done);
	if (done)
		return ret;
	c->dev.ctrlmode |= CAN_CTRLMODE_LOOPBACK;
	t.accept_all = true;
	return ctl_on_chip(c, open_up(c, &t), selftest_loop, &t);
}

const struct ctl_command ctl_selftest = {
	.name = "selftest",
	.summary = "loop frames of every kind through the chip (PASS/FAIL)",
	.help =
"Usage: mcp2510ctl --device DEV selftest [--timeout MS]\n"
"Bring the chip up in loopback mode (nothing reaches the bus), send\n"
"standard and extended data frames of every length and remote frames,\n"
"and check each comes back identical.  Prints PASS or FAIL; exit 0 or 1.\n"
"Filters set with the filter command are reset to accept every frame\n"
"(with a note saying so).\n",
	.run = selftest_run,
	.needs_device = true,
	.options = timeout_options,
};
