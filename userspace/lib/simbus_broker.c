// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * The broker of a shared simulated bus (simbus.h): one bus of tests/sim
 * whose time follows CLOCK_MONOTONIC from the broker's start, a chip per
 * name, a client per connection.  It sleeps until the next change the
 * model has scheduled or a packet, runs the bus to the present, answers,
 * and tells every client whose INT pin changed.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <poll.h>
#include <stdbool.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sys/socket.h>

#include "mcp2510_sim.h"
#include "simbus.h"

#define NO_CHIP		(-1)
/* one more than chips, so that a user too many is told ENOSPC */
#define MAX_CLIENTS	(SIM_MAX_NODES + 1)

struct chip_slot {
	struct sim_chip chip;
	char name[SIMBUS_NAME_MAX];
	bool mcp2515;
	uint32_t osc_hz;
	bool taken;
};

struct client {
	int fd;				/* -1: free */
	int chip;			/* index in chips, NO_CHIP before HELLO */
	bool int_low;			/* as last told */
};

struct broker {
	int listen_fd;
	const char *path;
	uint64_t t0;
	struct sim_bus bus;
	struct chip_slot chips[SIM_MAX_NODES];
	unsigned int nchips;
	struct client clients[MAX_CLIENTS];
	unsigned int nclients;
};

static uint64_t mono_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC, &ts);
	return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void catch_up(struct broker *b)
{
	sim_bus_advance_to(&b->bus, mono_ns() - b->t0);
}

static bool int_low(const struct broker *b, const struct client *c)
{
	return c->chip != NO_CHIP &&
	       !sim_chip_pin(&b->chips[c->chip].chip, SIM_PIN_INT);
}

/* An INT packet to every client whose pin changed since it was told. */
static void tell_int(struct broker *b)
{
	struct simbus_msg m = { .op = SIMBUS_INT };
	unsigned int i;

	for (i = 0; i < MAX_CLIENTS; i++) {
		struct client *c = &b->clients[i];

		if (c->fd < 0 || int_low(b, c) == c->int_low)
			continue;
		c->int_low = int_low(b, c);
		m.int_low = c->int_low;
		simbus_send(c->fd, &m);
	}
}

/* The chip named in a HELLO: the one of that name, or a new one. */
static int take_chip(struct broker *b, const struct simbus_msg *m)
{
	struct chip_slot *s;
	unsigned int i;
	int ret;

	for (i = 0; i < b->nchips; i++) {
		s = &b->chips[i];
		if (strcmp(s->name, m->name))
			continue;
		if (s->taken)
			return -EBUSY;
		if (s->mcp2515 != !!m->mcp2515 || s->osc_hz != m->osc_hz)
			return -EEXIST;
		return (int)i;
	}
	if (b->nchips == SIM_MAX_NODES)
		return -ENOSPC;
	s = &b->chips[b->nchips];
	ret = sim_chip_init_seeded(&s->chip, m->mcp2515 ? SIM_MCP2515 : SIM_MCP2510,
				   m->osc_hz, SIM_DEFAULT_SEED + b->nchips);
	if (!ret)
		ret = sim_bus_attach(&b->bus, &s->chip);
	if (ret)
		return ret;
	memcpy(s->name, m->name, sizeof(s->name));
	s->mcp2515 = m->mcp2515;
	s->osc_hz = m->osc_hz;
	return (int)b->nchips++;
}

static int hello(struct broker *b, struct client *c, const struct simbus_msg *m)
{
	struct sim_chip_faults *f;
	int ret;

	if (c->chip != NO_CHIP || simbus_check_name(m->name) ||
	    m->miso > SIMBUS_MISO_HIGH)
		return -EINVAL;
	ret = take_chip(b, m);
	if (ret < 0)
		return ret;
	c->chip = ret;
	b->chips[ret].taken = true;
	f = sim_chip_faults(&b->chips[ret].chip);
	f->spi_corrupt = m->miso ? SIM_CORRUPT_FOREVER : 0;
	f->spi_corrupt_kind = SIM_CORRUPT_FIXED;
	f->spi_corrupt_byte = m->miso == SIMBUS_MISO_LOW ? 0x00 : 0xff;
	return 0;
}

/* One packet from @c; false when the client is to go. */
static bool serve(struct broker *b, struct client *c)
{
	struct simbus_msg m, r = { .op = SIMBUS_REPLY };

	if (simbus_recv(c->fd, &m))
		return false;
	catch_up(b);
	if (m.op == SIMBUS_HELLO) {
		r.status = hello(b, c, &m);
	} else if (m.op == SIMBUS_XFER && c->chip != NO_CHIP) {
		sim_chip_spi(&b->chips[c->chip].chip, m.data, r.data, m.len);
		r.len = m.len;
	} else {
		return false;
	}
	c->int_low = int_low(b, c);
	r.int_low = c->int_low;
	return !simbus_send(c->fd, &r);
}

/*
 * A client gone: its chip stays on the bus as it was left, as a board's
 * chip stays powered when a program ends (mcp2510_close() put it in
 * configuration mode, a killed program may leave it on the bus), until
 * the next user of its name.
 */
static void drop(struct broker *b, struct client *c)
{
	if (c->chip != NO_CHIP)
		b->chips[c->chip].taken = false;
	close(c->fd);
	c->fd = -1;
	b->nclients--;
}

static void accept_client(struct broker *b)
{
	int fd = accept4(b->listen_fd, NULL, NULL, SOCK_CLOEXEC);
	unsigned int i;

	if (fd < 0)
		return;
	for (i = 0; i < MAX_CLIENTS; i++) {
		if (b->clients[i].fd < 0) {
			b->clients[i] = (struct client){ fd, NO_CHIP, false };
			b->nclients++;
			return;
		}
	}
	/* all taken: only while one that sent no HELLO holds a place */
	close(fd);
}

static bool connection_waiting(const struct broker *b)
{
	struct pollfd p = { .fd = b->listen_fd, .events = POLLIN };

	return poll(&p, 1, 0) > 0;
}

/*
 * With no client left, go, unless one connected meanwhile: under the
 * bus's lock no new one can come between the look and the unlink.
 */
static void leave(struct broker *b)
{
	int lock_fd = simbus_lock(b->path);

	if (connection_waiting(b)) {
		if (lock_fd >= 0)
			close(lock_fd);
		return;
	}
	unlink(b->path);
	_exit(0);
}

/* How long poll may sleep: until the model's next change, or forever. */
static struct timespec *sleep_for(const struct broker *b, struct timespec *ts)
{
	uint64_t next = sim_bus_next_event(&b->bus);
	uint64_t now = sim_bus_now(&b->bus);
	uint64_t ns;

	if (next == U64_MAX)
		return NULL;
	ns = next > now ? next - now : 0;
	ts->tv_sec = (time_t)(ns / 1000000000u);
	ts->tv_nsec = (long)(ns % 1000000000u);
	return ts;
}

_Noreturn void simbus_broker_run(int listen_fd, const char *path)
{
	static struct broker b;
	struct pollfd p[MAX_CLIENTS + 1];
	struct timespec ts;
	unsigned int i;

	b.listen_fd = listen_fd;
	b.path = path;
	b.t0 = mono_ns();
	sim_bus_init(&b.bus);
	for (i = 0; i < MAX_CLIENTS; i++)
		b.clients[i].fd = -1;
	for (;;) {
		if (!b.nclients && !connection_waiting(&b))
			leave(&b);
		p[0] = (struct pollfd){ .fd = listen_fd, .events = POLLIN };
		for (i = 0; i < MAX_CLIENTS; i++)
			p[i + 1] = (struct pollfd){ .fd = b.clients[i].fd,
						    .events = POLLIN };
		if (ppoll(p, MAX_CLIENTS + 1, sleep_for(&b, &ts), NULL) < 0 &&
		    errno != EINTR)
			_exit(1);
		catch_up(&b);
		for (i = 0; i < MAX_CLIENTS; i++)
			if (p[i + 1].revents && b.clients[i].fd >= 0 &&
			    !serve(&b, &b.clients[i]))
				drop(&b, &b.clients[i]);
		if (p[0].revents & POLLIN)
			accept_client(&b);
		tell_int(&b);
	}
}
