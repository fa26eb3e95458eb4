// SPDX-License-Identifier: GPL-2.0
/*
 * The simulated bus that processes share ("sim:NAME@BUS"): chips of two
 * processes exchange frames through one broker, the broker goes when its
 * last user closes, two first users at once start one broker, and a
 * socket left by a crashed broker is replaced.
 * Every test has an XDG_RUNTIME_DIR of its own.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <cmocka.h>

#include "mcp2510.h"

#define WAIT_MS		5000	/* a bound for waits that end much sooner */

static char run_dir[64];

static int make_run_dir(void **state)
{
	(void)state;
	snprintf(run_dir, sizeof(run_dir), "/tmp/simbus-test-XXXXXX");
	if (!mkdtemp(run_dir))
		return -1;
	return setenv("XDG_RUNTIME_DIR", run_dir, 1);
}

static int remove_run_dir(void **state)
{
	char cmd[96];

	(void)state;
	snprintf(cmd, sizeof(cmd), "rm -rf '%s'", run_dir);
	return system(cmd) ? -1 : 0;
}

static void socket_path(char *buf, size_t len, const char *bus)
{
	snprintf(buf, len, "%s/mcp2510-sim/%s", run_dir, bus);
}

static struct mcp2510 *open_up(const char *dev)
{
	struct mcp2510_options o;
	struct mcp2510 *h;

	mcp2510_options_init(&o);
	h = mcp2510_open(dev, &o);
	if (!h)
		return NULL;
	if (mcp2510_set_bitrate(h, 500000, 0) || mcp2510_up(h)) {
		mcp2510_close(h);
		return NULL;
	}
	return h;
}

static struct can_frame frame(canid_t id, uint8_t byte)
{
	struct can_frame cf = { .can_id = id, .len = 1 };

	cf.data[0] = byte;
	return cf;
}

static bool same_frame(const struct can_frame *a, const struct can_frame *b)
{
	return a->can_id == b->can_id && a->len == b->len &&
	       a->data[0] == b->data[0];
}

/* Wait for an event of @type; its frame must be @want. */
static bool await(struct mcp2510 *h, enum mcp2510_event_type type,
		  const struct can_frame *want)
{
	struct mcp2510_event ev;

	do
		if (mcp2510_recv(h, &ev, WAIT_MS))
			return false;
	while (ev.type != type);
	return same_frame(&ev.frame, want);
}

/*
 * Wait for @sent's TX_DONE and @reply's RX in either order: one interrupt
 * pass may find the reply already in a receive buffer when it reports the
 * end of the transmission.
 */
static bool await_sent_and_reply(struct mcp2510 *h,
				 const struct can_frame *sent,
				 const struct can_frame *reply)
{
	bool done = false, received = false;
	struct mcp2510_event ev;

	while (!done || !received) {
		if (mcp2510_recv(h, &ev, WAIT_MS))
			return false;
		if (ev.type == MCP2510_EVENT_TX_DONE)
			done = same_frame(&ev.frame, sent);
		else if (ev.type == MCP2510_EVENT_RX)
			received = same_frame(&ev.frame, reply);
	}
	return true;
}

/* The other process: send 0x123, then expect 0x321 back. */
static int peer(const char *dev)
{
	struct can_frame out = frame(0x123, 0x11), in = frame(0x321, 0x22);
	struct mcp2510 *h = open_up(dev);
	bool ok;

	if (!h)
		return 2;
	ok = !mcp2510_send(h, &out, 0) && await_sent_and_reply(h, &out, &in);
	mcp2510_close(h);
	return ok ? 0 : 1;
}

static void two_processes_exchange_frames(void **state)
{
	struct can_frame in = frame(0x123, 0x11), out = frame(0x321, 0x22);
	struct mcp2510 *h = open_up("sim:a@pair");
	int status;
	pid_t pid;

	(void)state;
	assert_non_null(h);
	pid = fork();
	assert_true(pid >= 0);
	if (!pid)
		_exit(peer("sim:b@pair"));
	assert_true(await(h, MCP2510_EVENT_RX, &in));
	assert_int_equal(mcp2510_send(h, &out, 0), 0);
	assert_true(await(h, MCP2510_EVENT_TX_DONE, &out));
	assert_int_equal(waitpid(pid, &status, 0), pid);
	assert_true(WIFEXITED(status));
	assert_int_equal(WEXITSTATUS(status), 0);
	mcp2510_close(h);
}

/* The socket is gone within WAIT_MS: the broker left. */
static bool socket_goes(const char *bus)
{
	struct timespec tick = { .tv_nsec = 10000000 };
	char path[128];
	int i;

	socket_path(path, sizeof(path), bus);
	for (i = 0; i < WAIT_MS / 10; i++) {
		if (access(path, F_OK) && errno == ENOENT)
			return true;
		nanosleep(&tick, NULL);
	}
	return false;
}

static void broker_leaves_after_last_close(void **state)
{
	struct mcp2510 *a = open_up("sim:a@gone"), *b = open_up("sim:b@gone");
	char path[128];

	(void)state;
	assert_non_null(a);
	assert_non_null(b);
	socket_path(path, sizeof(path), "gone");
	mcp2510_close(a);
	assert_int_equal(access(path, F_OK), 0);
	mcp2510_close(b);
	assert_true(socket_goes("gone"));
}

/* A socket nobody listens on, as a killed broker leaves it. */
static void stale_socket_is_replaced(void **state)
{
	struct sockaddr_un sa = { .sun_family = AF_UNIX };
	struct can_frame cf = frame(0x7ff, 0x33);
	struct mcp2510 *a, *b;
	char dir[96];
	int fd;

	(void)state;
	snprintf(dir, sizeof(dir), "%s/mcp2510-sim", run_dir);
	assert_int_equal(mkdir(dir, 0700), 0);
	socket_path(sa.sun_path, sizeof(sa.sun_path), "stale");
	fd = socket(AF_UNIX, SOCK_SEQPACKET, 0);
	assert_true(fd >= 0);
	assert_int_equal(bind(fd, (struct sockaddr *)&sa, sizeof(sa)), 0);
	close(fd);

	a = open_up("sim:a@stale");
	assert_non_null(a);
	b = open_up("sim:b@stale");
	assert_non_null(b);
	assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	assert_true(await(b, MCP2510_EVENT_RX, &cf));
	mcp2510_close(a);
	mcp2510_close(b);
	assert_true(socket_goes("stale"));
}

/* Wait for the go, open @dev, then send or receive 0x100#44. */
static int racer(int go, const char *dev, bool sender)
{
	struct can_frame cf = frame(0x100, 0x44);
	struct mcp2510 *h;
	char c;
	bool ok;

	if (read(go, &c, 1) != 1)
		return 3;
	h = open_up(dev);
	if (!h)
		return 2;
	if (sender)
		ok = !mcp2510_send(h, &cf, 0) &&
		     await(h, MCP2510_EVENT_TX_DONE, &cf);
	else
		ok = await(h, MCP2510_EVENT_RX, &cf);
	mcp2510_close(h);
	return ok ? 0 : 1;
}

/* Two first users at once start one broker: their chips share a bus. */
static void first_users_at_once_share_one_bus(void **state)
{
	int go[2], status, i;
	pid_t pid[2];

	(void)state;
	assert_int_equal(pipe(go), 0);
	for (i = 0; i < 2; i++) {
		pid[i] = fork();
		assert_true(pid[i] >= 0);
		if (!pid[i])
			_exit(racer(go[0], i ? "sim:b@race" : "sim:a@race", i));
	}
	assert_int_equal(write(go[1], "gg", 2), 2);
	for (i = 0; i < 2; i++) {
		assert_int_equal(waitpid(pid[i], &status, 0), pid[i]);
		assert_true(WIFEXITED(status));
		assert_int_equal(WEXITSTATUS(status), 0);
	}
	close(go[0]);
	close(go[1]);
	assert_true(socket_goes("race"));
}

static void a_name_is_one_chip(void **state)
{
	struct mcp2510 *a = open_up("sim:a@names");
	struct mcp2510_options o;

	(void)state;
	assert_non_null(a);
	mcp2510_options_init(&o);
	assert_null(mcp2510_open("sim:a@names", &o));
	assert_int_equal(errno, EBUSY);
	mcp2510_close(a);
}

/*
 * A chip keeps its registers between its users, as a board's chip does
 * between programs, while the bus lives: filters set by one handle are
 * what the next handle of that chip finds (and receives through).
 */
static void a_chip_keeps_its_filters(void **state)
{
	static const char *const only_123[][2] = {
		{ "mask0", "7ff" }, { "filter0", "123" },
		{ "mask1", "7ff" }, { "filter2", "123" },
	};
	struct can_frame miss = frame(0x124, 0x55), hit = frame(0x123, 0x66);
	struct mcp2510 *holder = open_up("sim:h@keep"), *c;
	struct mcp2510_hw_filters f, got;
	struct mcp2510_options o;
	struct mcp2510_event ev;
	size_t i;

	(void)state;
	assert_non_null(holder);
	mcp2510_options_init(&o);
	c = mcp2510_open("sim:c@keep", &o);
	assert_non_null(c);
	mcp2510_hw_filters_default(&f);
	for (i = 0; i < sizeof(only_123) / sizeof(only_123[0]); i++)
		assert_int_equal(mcp2510_hw_filters_set(&f, only_123[i][0],
							only_123[i][1]), 0);
	assert_int_equal(mcp2510_set_filters(c, &f), 0);
	mcp2510_close(c);

	c = open_up("sim:c@keep");
	assert_non_null(c);
	assert_int_equal(mcp2510_get_filters(c, &got), 0);
	assert_int_equal(got.filter[0].id, 0x123);
	assert_int_equal(got.mask[0].id, 0x7ff);
	assert_int_equal(mcp2510_send(holder, &miss, 0), 0);
	assert_int_equal(mcp2510_send(holder, &hit, 0), 0);
	assert_true(await(c, MCP2510_EVENT_RX, &hit));
	assert_int_equal(mcp2510_recv(c, &ev, 0), -1);
	mcp2510_close(c);
	mcp2510_close(holder);
}

static void a_bus_holds_eight_chips(void **state)
{
	struct mcp2510_options o;
	struct mcp2510 *h[8];
	char dev[32];
	int i;

	(void)state;
	mcp2510_options_init(&o);
	for (i = 0; i < 8; i++) {
		snprintf(dev, sizeof(dev), "sim:c%d@full", i);
		h[i] = mcp2510_open(dev, &o);
		assert_non_null(h[i]);
	}
	assert_null(mcp2510_open("sim:c8@full", &o));
	assert_int_equal(errno, ENOSPC);
	for (i = 0; i < 8; i++)
		mcp2510_close(h[i]);
}

static void bad_names_are_refused(void **state)
{
	static const char *const bad[] = {
		"sim:@bus", "sim:a@", "sim:a@../x", "sim:a@.x", "sim:a b@bus",
	};
	struct mcp2510_options o;
	size_t i;

	(void)state;
	mcp2510_options_init(&o);
	for (i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
		assert_null(mcp2510_open(bad[i], &o));
		assert_int_equal(errno, EINVAL);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(two_processes_exchange_frames,
						make_run_dir, remove_run_dir),
		cmocka_unit_test_setup_teardown(broker_leaves_after_last_close,
						make_run_dir, remove_run_dir),
		cmocka_unit_test_setup_teardown(stale_socket_is_replaced,
						make_run_dir, remove_run_dir),
		cmocka_unit_test_setup_teardown(first_users_at_once_share_one_bus,
						make_run_dir, remove_run_dir),
		cmocka_unit_test_setup_teardown(a_name_is_one_chip,
						make_run_dir, remove_run_dir),
		cmocka_unit_test_setup_teardown(a_chip_keeps_its_filters,
						make_run_dir, remove_run_dir),
		cmocka_unit_test_setup_teardown(a_bus_holds_eight_chips,
						make_run_dir, remove_run_dir),
		cmocka_unit_test_setup_teardown(bad_names_are_refused,
						make_run_dir, remove_run_dir),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
