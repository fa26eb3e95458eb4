// SPDX-License-Identifier: GPL-2.0
/*
 * mcp2510d's bridge: frames both ways, what it ignores, a stop request
 * and a vanished interface; and as a service: bus-off handled as the kernel's can-dev
 * handles it (off the bus until a restart, by hand or after restart_ms,
 * reported with error frames), a socket that refuses frames (ENOBUFS)
 * served again later without losing them, the receive queue's drop count
 * taken in, and the statistics lines.  A datagram socket pair stands in
 * for the CAN_RAW socket; the bus-off comes from the simulator's
 * bus_errors fault (MCP2510_SIM_BUS_ERRORS).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <cmocka.h>
#include <linux/can/error.h>

#include "bridge.h"

struct rig {
	struct mcp2510 *chip, *peer;
	int sv[2];			/* sv[0]: the bridge's, sv[1]: ours */
	struct bridge b;
};

static struct mcp2510 *up(const char *bus)
{
	struct mcp2510 *h = mcp2510_open(bus, NULL);

	assert_non_null(h);
	assert_int_equal(mcp2510_set_bitrate(h, 500000, 0), 0);
	assert_int_equal(mcp2510_up(h), 0);
	return h;
}

/* Two chips on BUS, the first bridged; the bus destroys its first N frames. */
static struct rig *rig_new(const char *bus, unsigned int bus_errors)
{
	struct rig *r = calloc(1, sizeof(*r));
	char n[16];

	assert_non_null(r);
	snprintf(n, sizeof(n), "%u", bus_errors);
	assert_int_equal(setenv("MCP2510_SIM_BUS_ERRORS", n, 1), 0);
	r->chip = up(bus);
	r->peer = up(bus);
	unsetenv("MCP2510_SIM_BUS_ERRORS");
	assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK, 0,
				    r->sv), 0);
	bridge_init(&r->b, r->chip, r->sv[0]);
	return r;
}

static void rig_free(struct rig *r)
{
	mcp2510_close(r->chip);
	mcp2510_close(r->peer);
	close(r->sv[0]);
	close(r->sv[1]);
	free(r);
}

static void pump(struct rig *r, unsigned int rounds)
{
	while (rounds--)
		assert_int_equal(bridge_poll(&r->b, -1, 10), 0);
}

/* Pump until *COUNTER reaches WANT, for at most ROUNDS rounds. */
static bool pump_until(struct rig *r, const uint64_t *counter, uint64_t want,
		       unsigned int rounds)
{
	while (*counter < want && rounds--)
		assert_int_equal(bridge_poll(&r->b, -1, 10), 0);
	return *counter >= want;
}

static void send_to_bridge(struct rig *r, canid_t id)
{
	struct can_frame cf = { .can_id = id, .len = 1, .data = { 0x5a } };

	assert_int_equal(write(r->sv[1], &cf, sizeof(cf)), sizeof(cf));
}

/* Read what the bridge wrote; the error frames' classes OR-ed in *ERRS. */
static unsigned int drain_socket(struct rig *r, canid_t *errs)
{
	struct can_frame cf;
	unsigned int frames = 0;

	while (read(r->sv[1], &cf, sizeof(cf)) == sizeof(cf)) {
		if (cf.can_id & CAN_ERR_FLAG)
			*errs |= cf.can_id & CAN_ERR_MASK;
		else
			frames++;
	}
	return frames;
}

/* The peer receives a frame with @id within a second of simulated time. */
static bool peer_receives(struct rig *r, canid_t id)
{
	struct mcp2510_event ev;
	unsigned int n;

	for (n = 0; n < 100; n++) {
		pump(r, 1);
		while (!mcp2510_recv(r->peer, &ev, 10))
			if (ev.type == MCP2510_EVENT_RX && ev.frame.can_id == id)
				return true;
	}
	return false;
}

/* The bridged chip goes bus-off: 32 destroyed frames, 8 each in TEC. */
static void go_bus_off(struct rig *r)
{
	canid_t errs = 0;

	send_to_bridge(r, 0x100);
	if (!pump_until(r, &r->b.counts.bus_offs, 1, 2000))
		fail_msg("no bus-off; tec/rec left as the chip says");
	drain_socket(r, &errs);
	assert_true(errs & CAN_ERR_BUSOFF);
	assert_true(errs & CAN_ERR_CRTL);	/* warning and passive on the way */
	assert_false(mcp2510_is_up(r->chip));
	assert_int_equal(r->b.counts.restarts, 0);
	/* the frame that never made it is an aborted one */
	assert_int_equal(r->b.counts.chip_drops, 1);
}

static void test_bridge_socket_to_bus(void **state)
{
	struct rig *r = rig_new("sim:bridge", 0);
	struct can_frame cf = { .can_id = 0x321, .len = 2, .data = { 7, 8 } };
	struct can_frame err = { .can_id = CAN_ERR_FLAG | CAN_ERR_BUSERROR,
				 .len = CAN_ERR_DLC };
	struct mcp2510_event ev;

	(void)state;
	assert_int_equal(write(r->sv[1], &err, sizeof(err)), sizeof(err));
	assert_int_equal(write(r->sv[1], &cf, sizeof(cf)), sizeof(cf));
	pump(r, 3);
	assert_int_equal(r->b.counts.ignored, 1);
	assert_int_equal(r->b.counts.to_chip, 1);
	do
		assert_int_equal(mcp2510_recv(r->peer, &ev, 100), 0);
	while (ev.type != MCP2510_EVENT_RX);
	assert_int_equal(ev.frame.can_id, 0x321);
	assert_memory_equal(ev.frame.data, cf.data, 2);
	rig_free(r);
}

static void test_bridge_bus_to_socket(void **state)
{
	struct rig *r = rig_new("sim:bridge", 0);
	struct can_frame cf = { .can_id = 0x1234 | CAN_EFF_FLAG, .len = 1,
				.data = { 9 } }, got;

	(void)state;
	assert_int_equal(mcp2510_send(r->peer, &cf, 0), 0);
	pump(r, 3);
	assert_int_equal(read(r->sv[1], &got, sizeof(got)), sizeof(got));
	assert_int_equal(got.can_id, cf.can_id);
	assert_int_equal(got.data[0], 9);
	assert_int_equal(r->b.counts.to_socket, 1);
	/* what the bridge sent itself does not come back */
	assert_int_equal(read(r->sv[1], &got, sizeof(got)), -1);
	assert_int_equal(errno, EAGAIN);
	rig_free(r);
}

static void test_bridge_stops_and_fails(void **state)
{
	struct rig *r = rig_new("sim:bridge", 0);
	uint64_t one = 1;
	int stop = eventfd(0, EFD_CLOEXEC);

	(void)state;
	assert_int_equal(bridge_poll(&r->b, stop, 0), 0);
	assert_int_equal(write(stop, &one, sizeof(one)), sizeof(one));
	assert_int_equal(bridge_poll(&r->b, stop, 1000), 1);
	close(stop);
	/* the interface went away */
	close(r->sv[1]);
	r->sv[1] = eventfd(0, EFD_CLOEXEC);
	assert_int_equal(bridge_poll(&r->b, -1, 100), -1);
	assert_int_equal(errno, ECONNRESET);
	rig_free(r);
}

static void test_bus_off_waits_for_a_manual_restart(void **state)
{
	struct rig *r = rig_new("sim:boff0", 32);
	struct timespec t = { 0, 50 * 1000000L };
	canid_t errs = 0;
	unsigned int i;

	(void)state;
	go_bus_off(r);
	/*
	 * Longer than the chip's own recovery (128 x 11 bits: 2.8 ms at
	 * 500 kbit/s) in both clocks: with restart_ms 0 it stays off.
	 */
	for (i = 0; i < 5; i++) {
		nanosleep(&t, NULL);
		pump(r, 2);
	}
	assert_false(mcp2510_is_up(r->chip));
	assert_int_equal(r->b.counts.bus_offs, 1);
	assert_int_equal(r->b.counts.restarts, 0);
	/* a bus-off interface drops what it is given, counted */
	send_to_bridge(r, 0x101);
	pump(r, 2);
	assert_int_equal(r->b.counts.bus_off_drops, 1);
	assert_int_equal(r->b.counts.to_chip, 1);

	assert_int_equal(bridge_restart(&r->b), 0);
	assert_true(mcp2510_is_up(r->chip));
	assert_int_equal(r->b.counts.restarts, 1);
	assert_int_equal(drain_socket(r, &errs), 0);
	assert_int_equal(errs, CAN_ERR_RESTARTED);
	/* only a bus-off chip restarts, as can_restart_now() says */
	assert_int_equal(bridge_restart(&r->b), -1);
	assert_int_equal(errno, EBUSY);
	send_to_bridge(r, 0x102);
	assert_true(peer_receives(r, 0x102));
	assert_int_equal(r->b.counts.to_chip, 2);
	rig_free(r);
}

static void test_bus_off_restarts_after_restart_ms(void **state)
{
	struct rig *r = rig_new("sim:boff1", 32);
	struct timespec start, now;
	canid_t errs = 0;
	long ms;

	(void)state;
	r->b.restart_ms = 200;
	go_bus_off(r);
	clock_gettime(CLOCK_MONOTONIC, &start);
	if (!pump_until(r, &r->b.counts.restarts, 1, 1000))
		fail_msg("no restart after restart_ms");
	clock_gettime(CLOCK_MONOTONIC, &now);
	ms = (now.tv_sec - start.tv_sec) * 1000 +
	     (now.tv_nsec - start.tv_nsec) / 1000000;
	assert_in_range(ms, 150, 2000);
	assert_true(mcp2510_is_up(r->chip));
	drain_socket(r, &errs);
	assert_int_equal(errs, CAN_ERR_RESTARTED);
	assert_int_equal(r->b.counts.bus_offs, 1);
	send_to_bridge(r, 0x103);
	assert_true(peer_receives(r, 0x103));
	rig_free(r);
}

/* A socket that refuses frames gets all of them later, in order. */
static void test_refused_writes_are_retried(void **state)
{
	struct rig *r = rig_new("sim:enobufs", 0);
	int small = 1, sent = 60, got = 0, next = 0x200;
	struct can_frame cf = { .len = 0 };
	struct mcp2510_stats s;
	canid_t errs = 0;
	int i;

	(void)state;
	assert_int_equal(setsockopt(r->sv[0], SOL_SOCKET, SO_SNDBUF, &small,
				    sizeof(small)), 0);
	for (i = 0; i < sent; i++) {
		cf.can_id = 0x200 + i;
		assert_int_equal(mcp2510_send(r->peer, &cf, 0), 0);
		pump(r, 1);
	}
	assert_true(r->b.counts.enobufs > 0);
	while (got < sent && pump_until(r, &r->b.counts.to_socket, sent, 10)) {
		while (read(r->sv[1], &cf, sizeof(cf)) == sizeof(cf)) {
			assert_false(cf.can_id & CAN_ERR_FLAG);
			assert_int_equal(cf.can_id, next);
			next++;
			got++;
		}
	}
	for (i = 0; i < 100 && got < sent; i++) {
		pump(r, 1);
		while (read(r->sv[1], &cf, sizeof(cf)) == sizeof(cf)) {
			assert_int_equal(cf.can_id, next);
			next++;
			got++;
		}
	}
	assert_int_equal(mcp2510_stats(r->chip, &s), 0);
	assert_int_equal(s.rx_overflows, 0);
	assert_int_equal(r->b.counts.socket_drops, 0);
	assert_int_equal(got, sent);
	assert_int_equal(r->b.counts.to_socket, sent);
	assert_int_equal(drain_socket(r, &errs), 0);
	rig_free(r);
}

static void test_rxq_drops_follow_the_kernel_total(void **state)
{
	struct bridge b;

	(void)state;
	bridge_init(&b, NULL, -1);
	bridge_rxq_total(&b, 5);
	bridge_rxq_total(&b, 5);
	bridge_rxq_total(&b, 12);
	assert_int_equal(b.counts.rxq_drops, 12);
	/* a frame queued before the last look carries an older total */
	bridge_rxq_total(&b, 9);
	assert_int_equal(b.counts.rxq_drops, 12);
	/* the kernel's count is 32 bits and wraps */
	b.rxq_seen = 0xfffffffeu;
	bridge_rxq_total(&b, 3);
	assert_int_equal(b.counts.rxq_drops, 17);
}

/* msg with one control message LEVEL/TYPE carrying @v in @len bytes */
static void one_cmsg(struct msghdr *msg, char *buf, size_t size, int level,
		     int type, uint32_t v, size_t len)
{
	struct cmsghdr *c;

	memset(msg, 0, sizeof(*msg));
	memset(buf, 0, size);
	msg->msg_control = buf;
	msg->msg_controllen = CMSG_SPACE(sizeof(v));
	c = CMSG_FIRSTHDR(msg);
	c->cmsg_level = level;
	c->cmsg_type = type;
	c->cmsg_len = CMSG_LEN(len);
	memcpy(CMSG_DATA(c), &v, len < sizeof(v) ? len : sizeof(v));
}

static void test_rxq_drops_from_the_cmsg(void **state)
{
	union {
		char buf[CMSG_SPACE(sizeof(uint32_t))];
		struct cmsghdr align;
	} u;
	struct msghdr msg;
	struct bridge b;

	(void)state;
	bridge_init(&b, NULL, -1);
	one_cmsg(&msg, u.buf, sizeof(u.buf), SOL_SOCKET, SO_RXQ_OVFL, 7, 4);
	bridge_take_cmsgs(&b, &msg);
	assert_int_equal(b.counts.rxq_drops, 7);
	/* another option's message, or one too short, is no drop count */
	one_cmsg(&msg, u.buf, sizeof(u.buf), SOL_SOCKET, SO_TIMESTAMP, 50, 4);
	bridge_take_cmsgs(&b, &msg);
	one_cmsg(&msg, u.buf, sizeof(u.buf), SOL_CAN_BASE, SO_RXQ_OVFL, 50, 4);
	bridge_take_cmsgs(&b, &msg);
	one_cmsg(&msg, u.buf, sizeof(u.buf), SOL_SOCKET, SO_RXQ_OVFL, 50, 2);
	bridge_take_cmsgs(&b, &msg);
	assert_int_equal(b.counts.rxq_drops, 7);
	/* none at all */
	memset(&msg, 0, sizeof(msg));
	bridge_take_cmsgs(&b, &msg);
	assert_int_equal(b.counts.rxq_drops, 7);
}

/* One chip alone on BUS, bridged, with control modes @ctrlmode. */
static struct rig *lone_rig(const char *bus, uint32_t ctrlmode)
{
	struct rig *r = calloc(1, sizeof(*r));

	assert_non_null(r);
	r->chip = mcp2510_open(bus, NULL);
	assert_non_null(r->chip);
	assert_int_equal(mcp2510_set_bitrate(r->chip, 500000, 0), 0);
	assert_int_equal(mcp2510_set_ctrlmode(r->chip, ctrlmode), 0);
	assert_int_equal(mcp2510_up(r->chip), 0);
	r->peer = mcp2510_open("sim", NULL);	/* elsewhere: rig_free closes it */
	assert_non_null(r->peer);
	assert_int_equal(socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK, 0,
				    r->sv), 0);
	bridge_init(&r->b, r->chip, r->sv[0]);
	return r;
}

/* Five frames from @base up written to the bridge, and taken in. */
static void send_five(struct rig *r, canid_t base)
{
	canid_t i;

	for (i = 0; i < 5; i++)
		send_to_bridge(r, base + i);
	pump(r, 5);
}

static char *stats_text(struct rig *r)
{
	char *text = NULL;
	size_t len = 0;
	FILE *out = open_memstream(&text, &len);

	bridge_print_stats(&r->b, out, "mcp2510d");
	fclose(out);
	return text;
}

/*
 * Frames that never went out are counted at shutdown: three in the
 * chip's buffers (no node acknowledges a lone one), one held, one still
 * in the socket.
 */
static void test_stop_counts_frames_given_up(void **state)
{
	struct rig *r = lone_rig("sim:lone", 0);
	char *text;

	(void)state;
	send_five(r, 0x100);
	assert_int_equal(r->b.counts.to_chip, 3);
	bridge_stop(&r->b);
	assert_false(mcp2510_is_up(r->chip));
	assert_int_equal(r->b.counts.chip_drops, 5);
	text = stats_text(r);
	assert_non_null(strstr(text, " to-chip 3 "));
	assert_non_null(strstr(text, " tx-aborted 5 "));
	/* the state is the bus's before shutdown, not the stopped chip's */
	assert_non_null(strstr(text, "stats bus: state ERROR-PASSIVE tec 128 "));
	free(text);
	rig_free(r);
}

/*
 * A listen-only chip never transmits: what programs send on the
 * interface is dropped and counted, as a listen-only CAN interface drops
 * it, and the bridge keeps reading.
 */
static void test_listen_only_drops_what_comes_to_send(void **state)
{
	struct rig *r = lone_rig("sim:listen", CAN_CTRLMODE_LISTENONLY);
	struct can_frame cf;

	(void)state;
	send_five(r, 0x200);
	assert_int_equal(r->b.counts.to_chip, 0);
	assert_int_equal(r->b.counts.ignored, 5);
	assert_false(r->b.holding);
	assert_int_equal(read(r->sv[0], &cf, sizeof(cf)), -1);
	assert_int_equal(errno, EAGAIN);
	rig_free(r);
}

static void test_stats_lines(void **state)
{
	struct rig *r = rig_new("sim:stats", 0);
	char *text = NULL;
	size_t len = 0;
	FILE *out = open_memstream(&text, &len);

	(void)state;
	r->b.counts.to_socket = 7;
	r->b.counts.to_chip = 3;
	r->b.counts.rxq_drops = 40;
	r->b.counts.enobufs = 2;
	r->b.counts.bus_offs = 1;
	r->b.counts.restarts = 1;
	bridge_print_stats(&r->b, out, "mcp2510d");
	fclose(out);
	assert_non_null(strstr(text,
		"mcp2510d: stats frames: to-iface 7 to-chip 3 error-frames 0 ignored 0\n"));
	assert_non_null(strstr(text,
		"mcp2510d: stats lost: rxq-overflow 40 enobufs-retries 2 iface-full 0 tx-aborted 0 bus-off-drops 0 chip-rx-overflow 0 event-overflow 0\n"));
	assert_non_null(strstr(text,
		"mcp2510d: stats bus: state ERROR-ACTIVE tec 0 rec 0 bus-errors 0 bus-off 1 restarts 1\n"));
	free(text);
	rig_free(r);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_bridge_socket_to_bus),
		cmocka_unit_test(test_bridge_bus_to_socket),
		cmocka_unit_test(test_bridge_stops_and_fails),
		cmocka_unit_test(test_bus_off_waits_for_a_manual_restart),
		cmocka_unit_test(test_bus_off_restarts_after_restart_ms),
		cmocka_unit_test(test_refused_writes_are_retried),
		cmocka_unit_test(test_rxq_drops_follow_the_kernel_total),
		cmocka_unit_test(test_rxq_drops_from_the_cmsg),
		cmocka_unit_test(test_stats_lines),
		cmocka_unit_test(test_stop_counts_frames_given_up),
		cmocka_unit_test(test_listen_only_drops_what_comes_to_send),
	};

	return cmocka_run_group_tests_name("userspace_bridge", tests, NULL, NULL);
}
