// SPDX-License-Identifier: GPL-2.0
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

static void ch_corrupt_start(struct ch_node *node)
{
	struct sim_chip_faults *f = sim_chip_faults(&node->sim);

	if (!node->corrupt_periods || node->xfer_count != node->corrupt_after)
		return;
	f->spi_corrupt_kind = node->corrupt_kind;
	f->spi_corrupt_byte = 0x00;
	f->spi_corrupt = node->corrupt_periods;
	node->corrupt_periods = 0;
}

void ch_corrupt_after(struct ch_node *node, u64 after,
		      enum sim_corrupt_kind kind, u32 periods)
{
	node->corrupt_after = node->xfer_count + after;
	node->corrupt_kind = kind;
	node->corrupt_periods = periods;
	ch_corrupt_start(node);
}

/*
 * One CS-low period of message @m reaching the chip.  With SPI time on,
 * bus time runs to the moment CS rises and the chip acts then.
 */
static void ch_chip_spi(struct ch_node *node, struct sim_spi_msg *m,
			const u8 *tx, u8 *rx, unsigned int len)
{
	struct sim_spi_bus *sb = &node->rig->spi;
	u32 max_hz = sim_chip_sck_max_hz(&node->sim);
	unsigned int first;
	u64 xfer_ns;

	if (sb->timing.enabled) {
		/* in transfers as the driver's transport splits it */
		first = mcp2510_xfer_first_len(len, node->spi_hz ? node->spi_hz :
							 max_hz);
		xfer_ns = sim_spi_xfer_ns(sb, first, node->spi_hz, max_hz) +
			  sim_spi_xfer_ns(sb, len - first, node->spi_hz,
					  max_hz);
		sim_bus_advance_to(&node->rig->bus,
				   sim_spi_msg_period(sb, m, xfer_ns));
	}
	sim_chip_spi(&node->sim, tx, rx, len);
}

static int ch_period(struct ch_node *node, struct sim_spi_msg *m,
		     const u8 *tx, u8 *rx, unsigned int len)
{
	ch_corrupt_start(node);
	node->xfer_count++;
	if (node->miso_stuck >= 0) {
		if (rx)
			memset(rx, node->miso_stuck, len);
		return 0;
	}
	if (node->fail_at && node->xfer_count == node->fail_at) {
		node->failed_instr = tx[0];
		if (node->fail_reaches_chip)
			ch_chip_spi(node, m, tx, rx, len);
		return -EREMOTEIO;
	}
	ch_chip_spi(node, m, tx, rx, len);
	if (node->after_xfer)
		node->after_xfer(node);
	return 0;
}

/*
 * A message takes its place on the SPI bus once, pays the host overhead
 * once, then each of its periods; after_xfer learns after each period how
 * many are still to come.
 */
static int ch_xfer_msg(void *ctx, const struct mcp2510_xfer *x, unsigned int n)
{
	struct ch_node *node = ctx;
	struct sim_spi_msg m;
	unsigned int i;
	int err = 0;

	sim_spi_msg_begin(&node->rig->spi, &m, sim_bus_now(&node->rig->bus));
	for (i = 0; i < n && !err; i++) {
		node->msg_left = n - 1 - i;
		err = ch_period(node, &m, x[i].tx, x[i].rx, x[i].len);
	}
	sim_spi_msg_end(&node->rig->spi, &m, &node->sim);
	node->msg_left = 0;
	node->messages++;
	if (n == 1 && x[0].len <= 2 && x[0].tx[0] == MCP2510_INSTR_READ_STATUS)
		node->status_reads++;
	return err;
}

static int ch_xfer(void *ctx, const u8 *tx, u8 *rx, unsigned int len)
{
	const struct mcp2510_xfer x = { .tx = tx, .rx = rx, .len = len };

	return ch_xfer_msg(ctx, &x, 1);
}

static void ch_delay_us(void *ctx, unsigned int us)
{
	struct ch_node *node = ctx;

	sim_bus_advance(&node->rig->bus, (u64)us * 1000);
}

static const struct mcp2510_ops ch_ops = {
	.xfer = ch_xfer,
	.xfer_msg = ch_xfer_msg,
	.delay_us = ch_delay_us,
};

static void ch_ev_rx(void *ctx, const struct can_frame *cf)
{
	struct ch_node *node = ctx;

	node->ev.rx[node->ev.rx_count++ % CH_LOG_MAX] = *cf;
	if (node->ev.on_rx)
		node->ev.on_rx(node, cf);
}

static void ch_ev_tx_done(void *ctx, unsigned int slot)
{
	struct ch_node *node = ctx;

	node->ev.tx_done[node->ev.tx_done_count++ % CH_LOG_MAX] = slot;
	if (node->ev.on_tx_done)
		node->ev.on_tx_done(node, slot);
}

static void ch_ev_tx_aborted(void *ctx, unsigned int slot)
{
	struct ch_node *node = ctx;

	node->ev.tx_aborted[node->ev.tx_aborted_count++ % CH_LOG_MAX] = slot;
}

static void ch_ev_state(void *ctx, enum can_state state,
			const struct can_berr_counter *bec)
{
	struct ch_node *node = ctx;

	(void)bec;
	node->ev.state[node->ev.state_count++ % CH_LOG_MAX] = state;
}

static void ch_ev_error(void *ctx, const struct can_frame *cf)
{
	struct ch_node *node = ctx;

	node->ev.error[node->ev.error_count++ % CH_LOG_MAX] = *cf;
}

static void ch_ev_rx_pass(void *ctx, bool first_waited)
{
	struct ch_node *node = ctx;
	unsigned int n = node->ev.pass_count++ % CH_LOG_MAX;

	node->ev.pass[n].rx_before = node->ev.rx_count;
	node->ev.pass[n].first_waited = first_waited;
}

static const struct mcp2510_events ch_events = {
	.rx = ch_ev_rx,
	.tx_done = ch_ev_tx_done,
	.tx_aborted = ch_ev_tx_aborted,
	.state = ch_ev_state,
	.error = ch_ev_error,
	.rx_pass = ch_ev_rx_pass,
};

struct ch_rig *ch_rig_new(unsigned int n, enum mcp2510_model model)
{
	struct ch_rig *rig = test_calloc(1, sizeof(*rig));
	enum sim_variant sv = model == MCP2510_MODEL_MCP2510 ? SIM_MCP2510 :
							       SIM_MCP2515;
	unsigned int i;

	assert_true(n <= CH_MAX_NODES);
	sim_bus_init(&rig->bus);
	sim_spi_bus_init(&rig->spi);
	rig->nnodes = n;
	for (i = 0; i < n; i++) {
		struct ch_node *node = &rig->node[i];

		node->rig = rig;
		node->miso_stuck = -1;
		/* every node its own power-up garbage, the same on every run */
		assert_int_equal(sim_chip_init_seeded(&node->sim, sv, CH_OSC_HZ,
						      CH_SEED_BASE + i), 0);
		assert_int_equal(sim_bus_attach(&rig->bus, &node->sim), 0);
		assert_int_equal(mcp2510_init(&node->core,
					      mcp2510_variant_get(model),
					      CH_OSC_HZ, &ch_ops, &ch_events,
					      node), 0);
	}
	return rig;
}

void ch_rig_free(struct ch_rig *rig)
{
	test_free(rig);
}

struct can_bittiming ch_bittiming(u32 bitrate)
{
	struct can_bittiming bt = { .bitrate = bitrate };

	assert_int_equal(mcp2510_bittiming_calc(CH_OSC_HZ / 2, &bt), 0);
	return bt;
}

int ch_start(struct ch_node *node, u32 bitrate, u32 ctrlmode)
{
	struct can_bittiming bt = ch_bittiming(bitrate);

	return mcp2510_start(&node->core, &bt, ctrlmode);
}

bool ch_int_asserted(const struct ch_node *node)
{
	return !sim_chip_pin(&node->sim, SIM_PIN_INT);
}

/* With SPI time on, the handler starts the interrupt latency after INT fell. */
static void ch_irq_latency(struct ch_node *node)
{
	struct sim_bus *bus = &node->rig->bus;

	if (node->rig->spi.timing.enabled)
		sim_bus_advance_to(bus, sim_spi_irq_due(&node->rig->spi,
							sim_bus_now(bus)));
}

/* Frames staged, and every frame the core counts as pending sent. */
static bool ch_drain_waits(const struct ch_node *node)
{
	const struct mcp2510_chip *c = &node->core;
	u8 pending = c->tx.busy & ~c->tx.done & ~c->tx.staged;
	unsigned int n;

	if (!c->tx.staged)
		return false;
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (pending & BIT(n) &&
		    sim_chip_peek(&node->sim, MCP2510_REG_TXBCTRL(n)) &
		    MCP2510_TXBCTRL_TXREQ)
			return false;
	return true;
}

unsigned int ch_service(struct ch_node *node, unsigned int max, int *last_ret)
{
	unsigned int calls = 0;
	int ret = 0;

	while (calls < max && ch_int_asserted(node)) {
		ch_irq_latency(node);
		if (ch_drain_waits(node))
			node->drain_waits++;
		node->in_irq = true;
		ret = mcp2510_irq_handle(&node->core);
		node->in_irq = false;
		node->irq_calls++;
		calls++;
	}
	if (last_ret)
		*last_ret = ret;
	return calls;
}

static void ch_service_all(struct ch_rig *rig)
{
	unsigned int i;
	int ret;

	for (i = 0; i < rig->nnodes; i++) {
		if (!rig->node[i].core.started)
			continue;
		ch_service(&rig->node[i], 16, &ret);
		assert_true(ret >= 0);
	}
}

const struct sim_spi_timing ch_pi_like = {
	.enabled = true,
	.msg_ns = 10000,
	.cs_setup_ns = 100,
	.cs_hold_ns = 100,
	.irq_latency_ns = 20000,
};

bool ch_step(struct ch_rig *rig)
{
	u64 next = sim_bus_next_event(&rig->bus);

	if (next == U64_MAX)
		return false;
	sim_bus_advance_to(&rig->bus, next);
	ch_service_all(rig);
	return true;
}

void ch_run(struct ch_rig *rig, u64 ns)
{
	u64 end = sim_bus_now(&rig->bus) + ns;

	ch_service_all(rig);
	for (;;) {
		u64 next = sim_bus_next_event(&rig->bus);

		if (next > end) {
			sim_bus_advance_to(&rig->bus, end);
			ch_service_all(rig);
			return;
		}
		sim_bus_advance_to(&rig->bus, next);
		ch_service_all(rig);
	}
}

void ch_run_idle(struct ch_rig *rig, u64 max_ns)
{
	u64 end = sim_bus_now(&rig->bus) + max_ns;

	ch_service_all(rig);
	while (sim_bus_now(&rig->bus) < end) {
		u64 next = sim_bus_next_event(&rig->bus);

		if (next == U64_MAX)
			return;
		sim_bus_advance_to(&rig->bus, next < end ? next : end);
		ch_service_all(rig);
	}
}

void ch_spi_mark(const struct ch_node *node, struct ch_spi_mark *m)
{
	const struct sim_counters *c = sim_chip_counters(&node->sim);

	m->bytes = c->spi_bytes;
	m->transfers = c->spi_transfers;
}

struct ch_spi_mark ch_spi_since(const struct ch_node *node,
				const struct ch_spi_mark *m)
{
	struct ch_spi_mark now;

	ch_spi_mark(node, &now);
	now.bytes -= m->bytes;
	now.transfers -= m->transfers;
	return now;
}

/* A frame whose first four data bytes carry @seq (little endian). */
struct can_frame ch_frame(canid_t id, u8 len, u32 seq)
{
	struct can_frame cf;
	unsigned int i;

	memset(&cf, 0, sizeof(cf));
	cf.can_id = id;
	cf.len = len;
	for (i = 0; i < len && !(id & CAN_RTR_FLAG); i++)
		cf.data[i] = i < 4 ? (u8)(seq >> (8 * i)) : (u8)(0xa0 + i);
	return cf;
}

bool ch_frame_equal(const struct can_frame *a, const struct can_frame *b)
{
	return a->can_id == b->can_id && a->len == b->len &&
	       !memcmp(a->data, b->data, a->len);
}

void ch_order_frame(struct ch_order *o, const struct can_frame *cf)
{
	u32 seq = cf->data[0] | cf->data[1] << 8 | cf->data[2] << 16 |
		  (u32)cf->data[3] << 24;

	if (o->received && seq <= o->last_seq)
		o->out_of_order++;
	o->last_seq = seq;
	o->received++;
}
