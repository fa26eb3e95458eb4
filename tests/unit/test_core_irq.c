// SPDX-License-Identifier: GPL-2.0
/*
 * The interrupt loop against simulated chips: received frames in arrival
 * order, the SPI cost per received frame on the MCP2510 and the MCP2515,
 * overflow, error flags that READ STATUS cannot show under an RX flood,
 * level versus edge-triggered handling, the storm bound, and transport
 * errors that must neither lose nor duplicate a frame.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

#define MS		1000000ULL
#define BITRATE		1000000
#define FRAME_NS	200000ULL	/* more than any frame at 1 Mbit/s */

static struct ch_rig *rx_rig(enum mcp2510_model model, bool rollover)
{
	struct ch_rig *rig = ch_rig_new(1, model);
	struct mcp2510_filters f;

	mcp2510_filters_default(&f);
	f.rollover = rollover;
	assert_int_equal(mcp2510_filters_apply(&rig->node[0].core, &f), 0);
	assert_int_equal(ch_start(&rig->node[0], BITRATE, 0), 0);
	sim_phantom_attach(&rig->bus, 0);
	return rig;
}

/* Let the phantom send @n frames while nobody services the chip. */
static void arrive_unserviced(struct ch_rig *rig, canid_t first_id,
			      unsigned int n)
{
	unsigned int i;

	for (i = 0; i < n; i++) {
		struct can_frame cf = ch_frame(first_id + i, 8, i);

		assert_int_equal(sim_phantom_send(&rig->bus, &cf, 0), 0);
	}
	sim_bus_advance(&rig->bus, n * FRAME_NS);
}

static void set_errif(struct ch_node *node)
{
	const u8 tx[4] = { MCP2510_INSTR_BIT_MODIFY, MCP2510_REG_CANINTF,
			   MCP2510_INT_ERR, MCP2510_INT_ERR };

	sim_chip_spi(&node->sim, tx, NULL, sizeof(tx));
}

struct flood_check {
	u32 received;
	struct can_frame tmpl;
};

static struct flood_check *flood;

/* frame k of a flood: the template with its first 4 bytes + k */
static void flood_on_rx(struct ch_node *node, const struct can_frame *cf)
{
	struct can_frame want = flood->tmpl;
	u32 v = 0;
	unsigned int i;

	(void)node;
	for (i = 0; i < 4; i++)
		v |= (u32)want.data[i] << (8 * i);
	v += flood->received;
	for (i = 0; i < 4; i++)
		want.data[i] = v >> (8 * i);
	if (!ch_frame_equal(cf, &want))
		fail_msg("flood frame %u wrong", flood->received);
	flood->received++;
}

static void rx_cost(enum mcp2510_model model, u64 max_bytes_x100,
		    u64 max_transfers_x100)
{
	struct ch_rig *rig = rx_rig(model, true);
	struct ch_node *node = &rig->node[0];
	struct flood_check fc = { .tmpl = ch_frame(0x321, 8, 0) };
	const u32 n = 1000;
	struct ch_spi_mark m;

	flood = &fc;
	node->ev.on_rx = flood_on_rx;
	ch_spi_mark(node, &m);
	assert_int_equal(sim_phantom_flood(&rig->bus, &fc.tmpl, n, 0), 0);
	ch_run_idle(rig, 1000 * MS);
	m = ch_spi_since(node, &m);
	assert_int_equal(fc.received, n);
	assert_int_equal(sim_chip_counters(&node->sim)->overflows, 0);
	print_message("%s: RX 8-byte frame: %.2f SPI bytes, %.2f transfers\n",
		      mcp2510_variant_get(model)->name, (double)m.bytes / n,
		      (double)m.transfers / n);
	assert_true(m.bytes * 100 <= max_bytes_x100 * n);
	assert_true(m.transfers * 100 <= max_transfers_x100 * n);
	flood = NULL;
	ch_rig_free(rig);
}

/*
 * READ STATUS 2 + READ RXB 15 + BIT MODIFY 4 + READ STATUS 2 (the last
 * two in one message: the order check), CANINTF now and then
 */
static void test_rx_cost_mcp2510(void **state)
{
	(void)state;
	rx_cost(MCP2510_MODEL_MCP2510, 2400, 400);
}

/*
 * READ STATUS 2 + READ RX BUFFER 14 (clears RXnIF itself) + READ STATUS
 * 2 in the same message
 */
static void test_rx_cost_mcp2515(void **state)
{
	(void)state;
	rx_cost(MCP2510_MODEL_MCP2515, 1850, 300);
}

/* The chips the tests that cover both run on. */
static const enum mcp2510_model both_models[] = {
	MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
};

static void test_both_buffers_oldest_first(void **state)
{
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(both_models); i++) {
		struct ch_rig *rig = rx_rig(both_models[i], true);
		struct ch_node *node = &rig->node[0];
		int ret;

		arrive_unserviced(rig, 0x100, 2);
		/* level-triggered: one pass takes both */
		assert_int_equal(ch_service(node, 1, &ret), 1);
		assert_true(ret >= 2);
		assert_int_equal(node->ev.rx_count, 2);
		assert_int_equal(node->ev.rx[0].can_id, 0x100);
		assert_int_equal(node->ev.rx[1].can_id, 0x101);
		ch_service(node, 4, NULL);
		assert_false(ch_int_asserted(node));
		assert_int_equal(node->ev.error_count, 0);
		ch_rig_free(rig);
	}
}

static void test_overflow_is_reported(void **state)
{
	static const struct {
		bool rollover;
		unsigned int frames, delivered;
		u8 ovr;
	} cases[] = {
		{ true, 3, 2, MCP2510_EFLG_RX1OVR },
		{ false, 2, 1, MCP2510_EFLG_RX0OVR },
	};
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(cases); i++) {
		struct ch_rig *rig = rx_rig(MCP2510_MODEL_MCP2510,
					    cases[i].rollover);
		struct ch_node *node = &rig->node[0];
		const struct can_frame *err;

		arrive_unserviced(rig, 0x200, cases[i].frames);
		assert_true(sim_chip_peek(&node->sim, MCP2510_REG_EFLG) &
			    cases[i].ovr);
		ch_service(node, 8, NULL);
		assert_false(ch_int_asserted(node));
		assert_int_equal(node->ev.rx_count, cases[i].delivered);
		assert_int_equal(node->ev.rx[0].can_id, 0x200);
		assert_int_equal(node->core.counters.rx_overflows, 1);
		assert_int_equal(node->ev.error_count, 1);
		err = &node->ev.error[0];
		assert_int_equal(err->can_id,
				 CAN_ERR_FLAG | CAN_ERR_CRTL | CAN_ERR_CNT);
		assert_int_equal(err->len, CAN_ERR_DLC);
		assert_int_equal(err->data[1], CAN_ERR_CRTL_RX_OVERFLOW);
		/* RXnOVR cleared, so the next overflow shows again */
		assert_false(sim_chip_peek(&node->sim, MCP2510_REG_EFLG) &
			     (MCP2510_EFLG_RX0OVR | MCP2510_EFLG_RX1OVR));
		ch_rig_free(rig);
	}
}

/*
 * Under an RX flood every overflow raises ERRIF, and its handling is time
 * during which both buffers stay full and the next frame is lost.  The
 * clear of RXnOVR and ERRIF and the reads of EFLG and TEC/REC it takes go
 * in one message: three frames on an unserviced chip (both buffers full,
 * one overflow) cost READ STATUS, the two buffers (each read and released
 * in one message), the CANINTF/EFLG read that finds ERRIF, and that one
 * message: five.  The overflow is still reported once and cleared.
 */
static void test_overflow_handling_is_one_message(void **state)
{
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(both_models); i++) {
		struct ch_rig *rig = rx_rig(both_models[i], true);
		struct ch_node *node = &rig->node[0];
		u64 messages;

		/* the periodic full read is not due: READ STATUS starts */
		ch_service(node, 8, NULL);
		arrive_unserviced(rig, 0x300, 3);
		messages = node->messages;
		ch_service(node, 8, NULL);
		messages = node->messages - messages;
		print_message("%s: %llu messages for 2 frames and an overflow\n",
			      mcp2510_variant_get(both_models[i])->name,
			      (unsigned long long)messages);
		assert_false(ch_int_asserted(node));
		assert_int_equal(node->ev.rx_count, 2);
		assert_int_equal(node->core.counters.rx_overflows, 1);
		assert_false(sim_chip_peek(&node->sim, MCP2510_REG_EFLG) &
			     (MCP2510_EFLG_RX0OVR | MCP2510_EFLG_RX1OVR));
		assert_int_equal(messages, 5);
		ch_rig_free(rig);
	}
}

/*
 * READ STATUS shows no ERRIF.  A host too slow for a flood finds a new
 * frame every time it looks; the periodic CANINTF read must still find
 * the error flag within a few frames.
 */
static void test_error_flags_not_starved_by_rx(void **state)
{
	struct ch_rig *rig = rx_rig(MCP2510_MODEL_MCP2510, true);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x300, 8, 0);
	unsigned int passes = 0;

	(void)state;
	assert_int_equal(sim_phantom_flood(&rig->bus, &cf, 100, 0), 0);
	ch_run(rig, 20 * FRAME_NS);
	set_errif(node);
	while (sim_chip_peek(&node->sim, MCP2510_REG_CANINTF) &
	       MCP2510_INT_ERR) {
		/* look only when a frame waits: READ STATUS always shows RX */
		sim_bus_advance_to(&rig->bus, sim_bus_next_event(&rig->bus));
		if (!(sim_chip_peek(&node->sim, MCP2510_REG_CANINTF) &
		      MCP2510_INT_RX_ALL))
			continue;
		assert_true(mcp2510_irq_handle(&node->core) > 0);
		assert_true(++passes <= MCP2510_IRQ_FULL_READ_EVERY);
	}
	assert_true(sim_phantom_pending(&rig->bus) > 0);
	ch_run_idle(rig, 100 * MS);
	assert_int_equal(node->ev.rx_count, 100);
	ch_rig_free(rig);
}

/* Two frames, a sent frame and an ERRIF waiting at once. */
static struct ch_rig *busy_chip(bool edge)
{
	struct ch_rig *rig = rx_rig(MCP2510_MODEL_MCP2510, true);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x7f0, 2, 0);

	node->core.irq_edge = edge;
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	sim_bus_advance(&rig->bus, FRAME_NS);
	arrive_unserviced(rig, 0x400, 2);
	set_errif(node);
	return rig;
}

static void test_level_triggered_one_pass(void **state)
{
	struct ch_rig *rig = busy_chip(false);
	struct ch_node *node = &rig->node[0];
	u32 loops = node->core.counters.irq_loops;

	(void)state;
	assert_int_equal(mcp2510_irq_handle(&node->core), 3);
	assert_int_equal(node->core.counters.irq_loops - loops, 1);
	assert_int_equal(node->ev.rx_count, 2);
	assert_int_equal(node->ev.tx_done_count, 1);
	/* ERRIF is left for the next interrupt: the line stays low */
	assert_true(ch_int_asserted(node));
	assert_int_equal(mcp2510_irq_handle(&node->core), 1);
	assert_false(ch_int_asserted(node));
	ch_rig_free(rig);
}

static void test_edge_triggered_loops_until_clear(void **state)
{
	struct ch_rig *rig = busy_chip(true);
	struct ch_node *node = &rig->node[0];

	(void)state;
	assert_int_equal(mcp2510_irq_handle(&node->core), 4);
	assert_false(ch_int_asserted(node));
	assert_int_equal(node->ev.rx_count, 2);
	assert_int_equal(node->ev.tx_done_count, 1);
	assert_int_equal(node->core.counters.irq_loop_bound, 0);
	ch_rig_free(rig);
}

static void test_storm_is_bounded(void **state)
{
	struct ch_rig *rig = rx_rig(MCP2510_MODEL_MCP2510, true);
	struct ch_node *node = &rig->node[0];
	u32 loops = node->core.counters.irq_loops;

	(void)state;
	/* a chip that raises ERRIF again as soon as it is cleared */
	node->after_xfer = set_errif;
	set_errif(node);
	assert_int_equal(mcp2510_irq_handle(&node->core), 1);
	assert_int_equal(node->core.counters.irq_loop_bound, 0);

	node->core.irq_edge = true;
	loops = node->core.counters.irq_loops;
	assert_int_equal(mcp2510_irq_handle(&node->core), -EAGAIN);
	assert_int_equal(node->core.counters.irq_loop_bound, 1);
	assert_int_equal(node->core.counters.irq_loops - loops,
			 MCP2510_IRQ_MAX_PASSES);

	node->after_xfer = NULL;
	assert_int_equal(mcp2510_irq_handle(&node->core), 1);
	assert_false(ch_int_asserted(node));
	ch_rig_free(rig);
}

/*
 * Fail each transfer of the pass in turn, once as a transfer that never
 * reached the chip and once as one that did (only the host saw the
 * error): each of two frames comes exactly once, in order.  A READ RX
 * BUFFER that reached the chip has released its buffer, and so has an
 * MCP2510 BIT MODIFY of RXnIF.
 */
static void test_transport_error_neither_loses_nor_duplicates(void **state)
{
	unsigned int i, fail, reaches, bad = 0;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(both_models); i++) {
		for (reaches = 0; reaches < 2; reaches++) {
			for (fail = 1; fail <= 8; fail++) {
				struct ch_rig *rig = rx_rig(both_models[i], true);
				struct ch_node *node = &rig->node[0];

				arrive_unserviced(rig, 0x500, 2);
				node->xfer_count = 0;
				node->fail_at = fail;
				node->fail_reaches_chip = reaches;
				mcp2510_irq_handle(&node->core);
				node->fail_at = 0;
				ch_service(node, 8, NULL);
				if (node->ev.rx_count != 2 ||
				    node->ev.rx[0].can_id != 0x500 ||
				    node->ev.rx[1].can_id != 0x501) {
					print_message("%s, transfer %u %s: %u frames\n",
						      node->core.variant->name,
						      fail,
						      reaches ? "reached the chip" :
								"lost",
						      node->ev.rx_count);
					bad++;
				}
				assert_false(ch_int_asserted(node));
				ch_rig_free(rig);
			}
		}
	}
	assert_int_equal(bad, 0);
}

/* ---- the receive order, with frames arriving at the worst moments ---- */

struct order_run {
	u32 total, sent, received, inversions, rx1_first_seen;
	u32 last_seq;
	u32 rng;
};

static struct order_run *orun;

static u32 order_rand(void)
{
	u32 x = orun->rng;

	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	orun->rng = x;
	return x;
}

/* One frame from the phantom, complete now, with nobody servicing INT. */
static void arrive_now(struct ch_node *node)
{
	struct sim_bus *bus = &node->rig->bus;
	const struct sim_counters *c = sim_chip_counters(&node->sim);
	u64 before = c->frames_rx + c->overflows;
	struct can_frame cf = ch_frame(0x321, 8, orun->sent++);

	assert_int_equal(sim_phantom_send(bus, &cf, 0), 0);
	while (c->frames_rx + c->overflows == before)
		sim_bus_advance_to(bus, sim_bus_next_event(bus));
}

/*
 * After any transfer: up to two frames between messages (a host can be
 * held up there for as long as it likes), at most one between the
 * chip-select periods of one message (they are microseconds apart,
 * frames at least 47 bit times).
 */
static void order_after_xfer(struct ch_node *node)
{
	unsigned int n = order_rand() % (node->msg_left ? 2 : 3);

	if (node->core.irq.rx1_first)
		orun->rx1_first_seen++;
	while (n-- && orun->sent < orun->total)
		arrive_now(node);
}

static void order_on_rx(struct ch_node *node, const struct can_frame *cf)
{
	u32 seq = cf->data[0] | cf->data[1] << 8 | cf->data[2] << 16 |
		  (u32)cf->data[3] << 24;

	(void)node;
	if (orun->received && seq <= orun->last_seq)
		orun->inversions++;
	orun->last_seq = seq;
	orun->received++;
}

static void rx_order(enum mcp2510_model model, u32 seed)
{
	struct order_run run = { .total = 3000, .rng = seed };
	struct ch_rig *rig = rx_rig(model, true);
	struct ch_node *node = &rig->node[0];
	const struct sim_counters *c = sim_chip_counters(&node->sim);

	orun = &run;
	node->ev.on_rx = order_on_rx;
	node->after_xfer = order_after_xfer;
	while (run.sent < run.total) {
		if (ch_int_asserted(node))
			assert_true(mcp2510_irq_handle(&node->core) >= 0);
		else
			arrive_now(node);
	}
	node->after_xfer = NULL;
	ch_service(node, 16, NULL);
	assert_false(ch_int_asserted(node));
	if (run.inversions)
		fail_msg("%s: %u of %u frames came after a newer one",
			 node->core.variant->name, run.inversions,
			 run.received);
	assert_int_equal(run.received + c->overflows, run.sent);
	assert_true(c->overflows > 0);		/* both buffers were full ... */
	assert_true(run.rx1_first_seen > 0);	/* ... with RXB1 the older */
	ch_rig_free(rig);
}

static void test_rx_order_exact_mcp2510(void **state)
{
	(void)state;
	rx_order(MCP2510_MODEL_MCP2510, 12345);
}

static void test_rx_order_exact_mcp2515(void **state)
{
	(void)state;
	rx_order(MCP2510_MODEL_MCP2515, 54321);
}

/*
 * Receive timestamps (rx_pass): what the pass that takes the next frames
 * says of the first of them.  The first pass after start follows the
 * reset that cleared the flags, so it says nothing: serve one frame
 * first.
 */
static bool next_pass_waited(struct ch_node *node)
{
	unsigned int before = node->ev.pass_count;

	assert_true(mcp2510_irq_handle(&node->core) > 0);
	assert_true(node->ev.pass_count > before);
	return node->ev.pass[before % CH_LOG_MAX].first_waited;
}

static struct ch_rig *stamp_rig(enum mcp2510_model model, bool rollover)
{
	struct ch_rig *rig = rx_rig(model, rollover);
	struct ch_node *node = &rig->node[0];

	arrive_unserviced(rig, 0x080, 1);
	assert_false(next_pass_waited(node));	/* after the reset */
	assert_int_equal(node->ev.rx_count, 1);
	return rig;
}

static void test_rx_stamp_frames_alone(void **state)
{
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(both_models); i++) {
		struct ch_rig *rig = stamp_rig(both_models[i], true);
		struct ch_node *node = &rig->node[0];
		unsigned int last;

		arrive_unserviced(rig, 0x100, 1);
		assert_true(next_pass_waited(node));
		/* both buffers, the older known: rollover, RXB0 takes all */
		arrive_unserviced(rig, 0x200, 2);
		assert_true(next_pass_waited(node));
		last = (node->ev.pass_count - 1) % CH_LOG_MAX;
		assert_int_equal(node->ev.pass[last].rx_before, 2);
		assert_int_equal(node->ev.rx[2].can_id, 0x200);
		ch_rig_free(rig);
	}
}

/*
 * RXB0 taking only 0x100 and RXB1 everything: 0x200 goes straight to
 * RXB1 while RXB0 is free, so either buffer may hold the older frame.
 */
static void test_rx_stamp_order_unknown(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2515);
	struct ch_node *node = &rig->node[0];
	struct mcp2510_filters f;

	(void)state;
	mcp2510_filters_default(&f);
	f.mask[0].id = 0x7ff;
	f.filter[0].id = 0x100;
	assert_int_equal(mcp2510_filters_apply(&node->core, &f), 0);
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	sim_phantom_attach(&rig->bus, 0);
	arrive_unserviced(rig, 0x100, 1);
	assert_false(next_pass_waited(node));	/* after the reset */
	arrive_unserviced(rig, 0x200, 1);
	assert_true(next_pass_waited(node));	/* one frame: no order */
	arrive_unserviced(rig, 0x200, 1);
	arrive_unserviced(rig, 0x100, 1);
	assert_false(next_pass_waited(node));
	assert_int_equal(node->ev.rx_count, 4);
	ch_rig_free(rig);
}

/* A sent frame may have asserted INT before the received one came. */
static void test_rx_stamp_not_with_tx(void **state)
{
	struct ch_rig *rig = stamp_rig(MCP2510_MODEL_MCP2510, true);
	struct ch_node *node = &rig->node[0];
	struct can_frame cf = ch_frame(0x7f0, 2, 0);

	(void)state;
	assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
	sim_bus_advance(&rig->bus, FRAME_NS);
	arrive_unserviced(rig, 0x400, 1);
	assert_false(next_pass_waited(node));
	assert_int_equal(node->ev.tx_done_count, 1);
	ch_rig_free(rig);
}

/*
 * An overflow's ERRIF outlives the full buffers: a pass that takes both
 * from READ STATUS leaves it set, INT stays asserted with both buffers
 * free, and frames that come next came after INT fired.  The pass that
 * finds them with the ERRIF cannot vouch for them.  Nor with an ERRIF
 * of a state change.
 */
static void test_rx_stamp_errif(void **state)
{
	struct ch_rig *rig = stamp_rig(MCP2510_MODEL_MCP2515, true);
	struct ch_node *node = &rig->node[0];

	(void)state;
	arrive_unserviced(rig, 0x100, 3);
	assert_true(next_pass_waited(node));	/* READ STATUS: both full */
	assert_int_equal(node->ev.rx_count, 3);
	assert_true(ch_int_asserted(node));	/* the overflow's ERRIF */
	arrive_unserviced(rig, 0x200, 1);
	assert_false(next_pass_waited(node));
	assert_int_equal(node->core.counters.rx_overflows, 1);
	assert_int_equal(node->ev.rx_count, 4);

	ch_service(node, 8, NULL);
	arrive_unserviced(rig, 0x300, 1);
	set_errif(node);
	node->core.irq.full_read_next = true;
	assert_false(next_pass_waited(node));
	ch_rig_free(rig);
}

/* Two frames arrive (the second overflowing) after the first transfer. */
static bool overflow_sent;

static void overflow_after_first_xfer(struct ch_node *node)
{
	unsigned int i;

	if (overflow_sent)
		return;
	overflow_sent = true;
	for (i = 0; i < 2; i++) {
		struct can_frame cf = ch_frame(0x200 + i, 8, i);

		assert_int_equal(sim_phantom_send(&node->rig->bus, &cf, 0), 0);
	}
	sim_bus_advance(&node->rig->bus, 2 * FRAME_NS);
}

/*
 * The overflow's ERRIF unseen by READ STATUS: a pass sees RXB0 alone,
 * then RXB1 fills and a frame overflows while it reads.  The READ STATUS
 * after RXB0's release shows RXB1, and a second pass takes it (not
 * stamped at INT: it came after) and leaves INT asserted by the ERRIF
 * alone; a frame arriving then came after INT fired, and the pass that
 * finds it must see the ERRIF.
 */
static void test_rx_stamp_unseen_overflow(void **state)
{
	struct ch_rig *rig = stamp_rig(MCP2510_MODEL_MCP2515, true);
	struct ch_node *node = &rig->node[0];
	unsigned int passes;

	(void)state;
	arrive_unserviced(rig, 0x100, 1);
	passes = node->ev.pass_count;
	overflow_sent = false;
	node->after_xfer = overflow_after_first_xfer;
	assert_true(next_pass_waited(node));
	node->after_xfer = NULL;
	assert_int_equal(node->ev.rx_count, 3);
	assert_int_equal(node->ev.pass_count - passes, 2);
	assert_false(node->ev.pass[(passes + 1) % CH_LOG_MAX].first_waited);
	assert_int_equal(sim_chip_counters(&node->sim)->overflows, 1);
	assert_true(ch_int_asserted(node));	/* ERRIF */
	arrive_unserviced(rig, 0x300, 1);
	assert_false(next_pass_waited(node));
	assert_int_equal(node->ev.rx_count, 4);
	ch_rig_free(rig);
}

/*
 * A drain's poll (irq_tx.c) that ends on a received frame: the frame came
 * while the handler ran, after INT fired for the completion before it,
 * so the pass that takes it on the polled status must not say it waited.
 * Each transfer costs 20 us of bus time while frames are staged; a frame
 * of higher priority, queued when the drain begins, wins the bus from the
 * last pending frame and arrives during the polls.
 */
#define POLLED_ID	0x001
static bool polled_sent, polled_taken, polled_waited, polled_in_call;
/* the handler call whose first transfer left no frame in the chip */
static u64 call_seen, rx_empty_call;

static void drain_poll_costs(struct ch_node *node)
{
	const struct mcp2510_chip *c = &node->core;
	u8 pending = c->tx.busy & ~c->tx.done & ~c->tx.staged;
	struct can_frame cf = ch_frame(POLLED_ID, 8, 0);

	if (node->in_irq && call_seen != node->irq_calls) {
		call_seen = node->irq_calls;
		if (!(sim_chip_peek(&node->sim, MCP2510_REG_CANINTF) &
		      MCP2510_INT_RX_ALL))
			rx_empty_call = call_seen;
	}
	if (!c->tx.staged)
		return;
	if (!polled_sent && pending & (pending - 1)) {
		assert_int_equal(sim_phantom_send(&node->rig->bus, &cf, 0), 0);
		polled_sent = true;
	}
	sim_bus_advance(&node->rig->bus, 20000);
}

static void drain_poll_rx(struct ch_node *node, const struct can_frame *cf)
{
	if (cf->can_id != POLLED_ID)
		return;
	polled_taken = true;
	polled_waited =
		node->ev.pass[(node->ev.pass_count - 1) % CH_LOG_MAX].first_waited;
	/* the handler call taking it began before it came */
	polled_in_call = rx_empty_call == node->irq_calls;
}

static void test_rx_stamp_not_for_frame_polled_in_drain(void **state)
{
	unsigned int i, k;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(both_models); i++) {
		struct ch_rig *rig = stamp_rig(both_models[i], true);
		struct ch_node *node = &rig->node[0];

		polled_sent = false;
		polled_taken = false;
		call_seen = U64_MAX;
		rx_empty_call = U64_MAX;
		node->after_xfer = drain_poll_costs;
		node->ev.on_rx = drain_poll_rx;
		for (k = 0; !polled_taken && k < 100; k++) {
			struct can_frame cf = ch_frame(0x100, 8, k);

			while (!mcp2510_tx_free(&node->core))
				assert_true(ch_step(rig));
			assert_true(mcp2510_tx_submit(&node->core, &cf) >= 0);
		}
		assert_true(polled_taken);
		assert_true(polled_in_call);
		assert_false(polled_waited);
		ch_rig_free(rig);
	}
}

/* After a restart (a reset) the first pass cannot tell. */
static void test_rx_stamp_not_after_reset(void **state)
{
	struct ch_rig *rig = stamp_rig(MCP2510_MODEL_MCP2510, true);
	struct ch_node *node = &rig->node[0];

	(void)state;
	assert_int_equal(mcp2510_restart(&node->core), 0);
	arrive_unserviced(rig, 0x100, 1);
	assert_false(next_pass_waited(node));
	arrive_unserviced(rig, 0x101, 1);
	assert_true(next_pass_waited(node));
	ch_rig_free(rig);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_rx_cost_mcp2510),
		cmocka_unit_test(test_rx_cost_mcp2515),
		cmocka_unit_test(test_both_buffers_oldest_first),
		cmocka_unit_test(test_overflow_is_reported),
		cmocka_unit_test(test_overflow_handling_is_one_message),
		cmocka_unit_test(test_error_flags_not_starved_by_rx),
		cmocka_unit_test(test_level_triggered_one_pass),
		cmocka_unit_test(test_edge_triggered_loops_until_clear),
		cmocka_unit_test(test_storm_is_bounded),
		cmocka_unit_test(test_transport_error_neither_loses_nor_duplicates),
		cmocka_unit_test(test_rx_order_exact_mcp2510),
		cmocka_unit_test(test_rx_order_exact_mcp2515),
		cmocka_unit_test(test_rx_stamp_frames_alone),
		cmocka_unit_test(test_rx_stamp_order_unknown),
		cmocka_unit_test(test_rx_stamp_not_with_tx),
		cmocka_unit_test(test_rx_stamp_errif),
		cmocka_unit_test(test_rx_stamp_unseen_overflow),
		cmocka_unit_test(test_rx_stamp_not_for_frame_polled_in_drain),
		cmocka_unit_test(test_rx_stamp_not_after_reset),
	};

	return cmocka_run_group_tests_name("core_irq", tests, NULL, NULL);
}
