// SPDX-License-Identifier: LGPL-2.1-or-later
/*
 * The simulated chip of tests/sim as a transport.
 *
 * Buses live in this process.  "sim" gets a bus of its own with the
 * model's phantom node attached, which acknowledges every frame, so a lone
 * chip can transmit.  "sim:NAME" joins the bus NAME, shared by every
 * handle that names it, without a phantom: the chips acknowledge each
 * other as on a real bus.
 *
 * Simulated time is virtual and only moves while a handle waits: a wait
 * jumps from one scheduled change on the bus to the next until this
 * chip's INT pin falls or the wait's time is used up.  A wait of 0 also
 * runs what is pending (up to SIM_LOOK_NS ahead), so an event loop that
 * polls with timeout 0 still sees frames go by.  While one handle waits,
 * the other chips on its bus have their interrupts handled as they
 * happen (through the library's irq hook), as their own interrupt
 * threads would on a real system: one waiting handle cannot make another
 * chip's receive buffers overflow.  So every handle on one bus must be
 * used from the same thread.
 *
 * SPI takes no time unless MCP2510_SIM_SPI_TIME is set when a bus is
 * created, to "key=value,...": profile (none, pi, pi-rt, slow) at
 * scale_pct (100 unless named) sets every cost at once, seed starts the
 * latency draws, and the fields of struct sim_spi_timing by name (msg_ns,
 * cs_setup_ns, ..., irq_latency_ns) set or override single costs (those
 * neither named nor from a profile are 0).  Each transfer then ends, and
 * the chip acts, when CS rises at the modelled time, at the handle's
 * spi_hz clamped to the chip's limit, and an interrupt reaches its
 * handler the drawn latency after INT fell.
 *
 * MCP2510_SIM_MISO=low or =high, read when a handle takes its chip,
 * sticks that chip's MISO line at 0x00 or 0xff (the model's spi_corrupt
 * fault), as a chip that is not there or not powered reads: for trying
 * how the library and the tools report a missing chip.
 * MCP2510_SIM_BUS_ERRORS=N, set when a bus is created, destroys its first
 * N frames with an error frame (the model's bus_errors fault): 32 of one
 * transmitter's frames put it bus-off, for tests of what follows.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/eventfd.h>

#include "mcp2510_sim.h"
#include "sim_env.h"
#include "transport.h"

#define SIM_BUS_NAME_MAX	32
#define SIM_LOOK_NS		100000000ull	/* what a wait of 0 may run */
#define NS_PER_MS		1000000ull
#define MISO_ENV		"MCP2510_SIM_MISO"

struct sim_transport;

struct shared_bus {
	char name[SIM_BUS_NAME_MAX];	/* "" for a private bus */
	struct sim_bus bus;
	struct sim_spi_bus spi;		/* what SPI costs: see the top */
	struct sim_chip chips[SIM_MAX_NODES];
	struct sim_transport *users[SIM_MAX_NODES];	/* NULL: chip free */
	enum sim_variant variant[SIM_MAX_NODES];
	uint32_t osc_hz[SIM_MAX_NODES];
	unsigned int nchips;		/* chips attached, used or not */
	unsigned int refs;
	struct shared_bus *next;
};

struct sim_transport {
	struct mcp2510_transport base;
	struct shared_bus *shared;
	struct sim_chip *chip;
	unsigned int slot;
	uint32_t spi_hz;
	int event_fd;
	bool signalled;
	void (*irq_hook)(void *ctx);
	void *irq_ctx;
};

static struct shared_bus *shared_buses;

static struct sim_transport *to_sim(struct mcp2510_transport *t)
{
	return (struct sim_transport *)t;
}

static const struct sim_transport *to_sim_const(const struct mcp2510_transport *t)
{
	return (const struct sim_transport *)t;
}

static bool int_asserted(const struct sim_transport *s)
{
	return !sim_chip_pin(s->chip, SIM_PIN_INT);
}

/* Keep every user's descriptor readable exactly while it has work. */
static void update_fds(struct shared_bus *sb)
{
	bool pending = sim_bus_next_event(&sb->bus) != U64_MAX;
	uint64_t v = 1;
	unsigned int i;

	for (i = 0; i < sb->nchips; i++) {
		struct sim_transport *s = sb->users[i];
		bool want;

		if (!s)
			continue;
		want = pending || int_asserted(s);
		if (want && !s->signalled)
			s->signalled = write(s->event_fd, &v, sizeof(v)) == sizeof(v);
		else if (!want && s->signalled)
			s->signalled = read(s->event_fd, &v, sizeof(v)) != sizeof(v);
	}
}

/* With SPI time on, bus time runs to when CS rises; the chip acts then. */
static void timed_spi(struct sim_transport *s, const uint8_t *tx, uint8_t *rx,
		      unsigned int len)
{
	struct shared_bus *sb = s->shared;
	struct sim_spi_msg m;
	uint64_t xfer_ns;

	if (sb->spi.timing.enabled) {
		sim_spi_msg_begin(&sb->spi, &m, sim_bus_now(&sb->bus));
		xfer_ns = sim_spi_xfer_ns(&sb->spi, len, s->spi_hz,
					  sim_chip_sck_max_hz(s->chip));
		sim_bus_advance_to(&sb->bus,
				   sim_spi_msg_period(&sb->spi, &m, xfer_ns));
	}
	sim_chip_spi(s->chip, tx, rx, len);
	if (sb->spi.timing.enabled)
		sim_spi_msg_end(&sb->spi, &m, s->chip);
}

/* With SPI time on, a handler starts the interrupt latency after INT fell. */
static void irq_latency(struct shared_bus *sb)
{
	if (sb->spi.timing.enabled)
		sim_bus_advance_to(&sb->bus,
				   sim_spi_irq_due(&sb->spi, sim_bus_now(&sb->bus)));
}

static int sim_xfer(struct mcp2510_transport *t, const uint8_t *tx,
		    uint8_t *rx, unsigned int len)
{
	struct sim_transport *s = to_sim(t);

	timed_spi(s, tx, rx, len);
	update_fds(s->shared);
	return 0;
}

static void sim_delay_us(struct mcp2510_transport *t, unsigned int us)
{
	struct sim_transport *s = to_sim(t);

	sim_bus_advance(&s->shared->bus, (uint64_t)us * 1000u);
	update_fds(s->shared);
}

/* The other chips' interrupt handlers, run as soon as their INT is low. */
static void service_others(struct sim_transport *s)
{
	struct shared_bus *sb = s->shared;
	unsigned int i;

	for (i = 0; i < sb->nchips; i++) {
		struct sim_transport *u = sb->users[i];

		if (u && u != s && u->irq_hook && int_asserted(u)) {
			irq_latency(sb);
			u->irq_hook(u->irq_ctx);
		}
	}
}

/* Run the bus from event to event until INT falls or @deadline. */
static int run_until(struct sim_transport *s, uint64_t deadline)
{
	struct sim_bus *bus = &s->shared->bus;

	while (!int_asserted(s)) {
		uint64_t next = sim_bus_next_event(bus);
		uint64_t now = sim_bus_now(bus);

		if (next == U64_MAX || next > deadline) {
			if (deadline != U64_MAX)
				sim_bus_advance_to(bus, deadline);
			return 0;
		}
		/* never stand still, whatever the model reports */
		sim_bus_advance_to(bus, next > now ? next : now + 1);
		service_others(s);
	}
	return 1;
}

static int sim_wait_irq(struct mcp2510_transport *t, int timeout_ms)
{
	struct sim_transport *s = to_sim(t);
	uint64_t now = sim_bus_now(&s->shared->bus);
	uint64_t deadline;
	int ret;

	if (timeout_ms < 0)
		deadline = U64_MAX;
	else if (timeout_ms == 0)
		deadline = now + SIM_LOOK_NS;
	else
		deadline = now + (uint64_t)timeout_ms * NS_PER_MS;
	ret = run_until(s, deadline);
	if (ret)
		irq_latency(s->shared);
	update_fds(s->shared);
	return ret;
}

static int sim_fd(const struct mcp2510_transport *t)
{
	return to_sim_const(t)->event_fd;
}

static void sim_counts(const struct mcp2510_transport *t,
		       struct mcp2510_transport_counts *c)
{
	const struct sim_counters *sc = sim_chip_counters(to_sim_const(t)->chip);

	c->spi_transfers = sc->spi_transfers;
	c->spi_bytes = sc->spi_bytes;
	c->interrupts = sc->interrupts;
}

static void shared_bus_put(struct shared_bus *sb)
{
	struct shared_bus **pp;

	if (--sb->refs)
		return;
	for (pp = &shared_buses; *pp; pp = &(*pp)->next) {
		if (*pp == sb) {
			*pp = sb->next;
			break;
		}
	}
	free(sb);
}

/*
 * The model has no way to take a chip off a bus, so a closed handle's
 * chip stays attached, unpowered (silent, as if unplugged), until the
 * bus goes away or a later handle powers it up again.
 */
static void sim_close(struct mcp2510_transport *t)
{
	struct sim_transport *s = to_sim(t);
	struct shared_bus *sb = s->shared;

	sim_chip_power(s->chip, false);
	sb->users[s->slot] = NULL;
	close(s->event_fd);
	free(s);
	update_fds(sb);
	shared_bus_put(sb);
}

static void sim_set_irq_hook(struct mcp2510_transport *t,
			     void (*fn)(void *ctx), void *ctx)
{
	struct sim_transport *s = to_sim(t);

	s->irq_hook = fn;
	s->irq_ctx = ctx;
}

static const struct mcp2510_transport_ops sim_ops = {
	.xfer = sim_xfer,
	.delay_us = sim_delay_us,
	.wait_irq = sim_wait_irq,
	.fd = sim_fd,
	.counts = sim_counts,
	.close = sim_close,
	.set_irq_hook = sim_set_irq_hook,
};

static struct shared_bus *shared_bus_find(const char *name)
{
	struct shared_bus *sb;

	for (sb = shared_buses; sb; sb = sb->next)
		if (!strcmp(sb->name, name))
			return sb;
	return NULL;
}

static int shared_bus_get(const char *name, struct shared_bus **out)
{
	struct shared_bus *sb = name[0] ? shared_bus_find(name) : NULL;

	if (strlen(name) >= SIM_BUS_NAME_MAX)
		return -ENAMETOOLONG;
	if (!sb) {
		sb = calloc(1, sizeof(*sb));
		if (!sb)
			return -ENOMEM;
		strcpy(sb->name, name);
		sim_bus_init(&sb->bus);
		sim_spi_bus_init(&sb->spi);
		if (sim_env_spi_time(&sb->spi) ||
		    sim_env_bus_errors(&sb->bus)) {
			free(sb);
			return -EINVAL;
		}
		if (!name[0])
			sim_phantom_attach(&sb->bus, 0);
		else {
			sb->next = shared_buses;
			shared_buses = sb;
		}
	}
	sb->refs++;
	*out = sb;
	return 0;
}

/* MCP2510_SIM_MISO: 0, or -EINVAL for a value other than low or high. */
static int miso_from_env(struct sim_chip *chip)
{
	const char *p = getenv(MISO_ENV);
	struct sim_chip_faults *f = sim_chip_faults(chip);

	/* a chip unplugged and taken again must not keep a past fault */
	f->spi_corrupt = 0;
	if (!p || !*p)
		return 0;
	if (strcmp(p, "low") && strcmp(p, "high"))
		return -EINVAL;
	f->spi_corrupt = SIM_CORRUPT_FOREVER;
	f->spi_corrupt_kind = SIM_CORRUPT_FIXED;
	f->spi_corrupt_byte = strcmp(p, "low") ? 0xff : 0x00;
	return 0;
}

/* A chip for a new user: a fresh one, or an unplugged one of the same kind. */
static int shared_bus_take_chip(struct shared_bus *sb,
				const struct mcp2510_transport_params *p,
				struct sim_transport *s)
{
	enum sim_variant v = p->mcp2515 ? SIM_MCP2515 : SIM_MCP2510;
	struct sim_chip *chip;
	unsigned int i;
	int ret;

	for (i = 0; i < sb->nchips; i++) {
		chip = &sb->chips[i];
		if (!sb->users[i] && sb->variant[i] == v &&
		    sb->osc_hz[i] == p->osc_hz) {
			sim_chip_power(chip, true);
			goto out_take;
		}
	}
	if (sb->nchips == SIM_MAX_NODES)
		return -ENOSPC;
	i = sb->nchips;
	chip = &sb->chips[i];
	/* its own power-up garbage, the same on every run: seeded by its slot */
	ret = sim_chip_init_seeded(chip, v, p->osc_hz, SIM_DEFAULT_SEED + i);
	if (ret)
		return ret;
	ret = sim_bus_attach(&sb->bus, chip);
	if (ret)
		return ret;
	sb->variant[i] = v;
	sb->osc_hz[i] = p->osc_hz;
	sb->nchips++;

out_take:
	ret = miso_from_env(chip);
	if (ret)
		return ret;
	sb->users[i] = s;
	s->chip = chip;
	s->slot = i;
	return 0;
}

int mcp2510_sim_open(const char *bus_name,
		     const struct mcp2510_transport_params *p,
		     struct mcp2510_transport **out)
{
	struct sim_transport *s;
	int ret;

	s = calloc(1, sizeof(*s));
	if (!s)
		return -ENOMEM;
	s->base.ops = &sim_ops;
	s->spi_hz = p->spi_hz;
	s->event_fd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
	if (s->event_fd < 0) {
		ret = -errno;
		goto out_free;
	}
	ret = shared_bus_get(bus_name, &s->shared);
	if (ret)
		goto out_close_fd;
	ret = shared_bus_take_chip(s->shared, p, s);
	if (ret)
		goto out_put_bus;
	/* like a board powered long ago: past the start-up, even unreset */
	sim_bus_advance(&s->shared->bus, sim_chip_startup_ns(s->chip));
	update_fds(s->shared);
	*out = &s->base;
	return 0;

out_put_bus:
	shared_bus_put(s->shared);
out_close_fd:
	close(s->event_fd);
out_free:
	free(s);
	return ret;
}
