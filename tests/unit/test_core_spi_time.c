// SPDX-License-Identifier: GPL-2.0
/*
 * The driver core against a 1 Mbit/s flood under fixed, simple SPI costs:
 * every message pays a host overhead, every CS period its setup and hold
 * and 8 SCK cycles a byte at the chip's top clock, and every interrupt a
 * constant delivery latency.  The figures are round ones, not a board's
 * (test_core_spi_gap.c runs the calibrated board profiles), so the
 * assertions below pin the core's message and period counts.  Time is
 * the model's only, so the outcome does not depend on the host running
 * the test.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

#define MS		1000000ULL
#define BITRATE		1000000
#define FLOOD_FRAMES	2000
/* bit times of a standard 8-byte frame with intermission: no stuff bits, the most */
#define FRAME_BITS_MIN	111
#define FRAME_BITS_MAX	135


struct flood_result {
	struct ch_order order;	/* the flood's frames as received */
	u64 overflows;		/* the chip's count */
	u64 core_overflows;	/* what the core reported */
	u64 busy_ns;		/* SPI time the chip's traffic took */
	u64 elapsed_ns;		/* bus time from the first frame to idle */
	u64 messages;		/* SPI messages during the flood */
	u64 status_reads;	/* of them, a READ STATUS alone */
	u64 transfers;		/* CS periods during the flood */
	u64 bytes;		/* SPI bytes during the flood */
	u64 handler_calls;	/* passes of the interrupt loop */
	u64 irq_calls;		/* interrupts serviced */
};

/* a slow host: 40 us a message, SCK at most 4 MHz, 60 us to the handler */
static const struct sim_spi_timing slow_board_timing = {
	.enabled = true,
	.msg_ns = 40000,
	.cs_setup_ns = 500,
	.cs_hold_ns = 500,
	.ctlr_max_hz = 4000000,
	.irq_latency_ns = 60000,
};

static struct flood_result *result;
static struct can_frame flood_tmpl;


static void count_rx(struct ch_node *node, const struct can_frame *cf)
{
	(void)node;
	/* frames may go missing, but the rest come in order */
	ch_order_frame(&result->order, cf);
}

static void flood_edge(enum mcp2510_model model, const struct sim_spi_timing *t,
		       bool edge, struct flood_result *res)
{
	struct ch_rig *rig = ch_rig_new(1, model);
	struct ch_node *node = &rig->node[0];
	u64 start;

	memset(res, 0, sizeof(*res));
	result = res;
	flood_tmpl = ch_frame(0x123, 8, 0);
	node->ev.on_rx = count_rx;
	/* start-up and mode changes at no SPI cost; the flood pays */
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	rig->spi.timing = *t;
	node->core.irq_edge = edge;
	start = sim_bus_now(&rig->bus);
	res->messages = node->messages;
	res->status_reads = node->status_reads;
	res->transfers = sim_chip_counters(&node->sim)->spi_transfers;
	res->bytes = sim_chip_counters(&node->sim)->spi_bytes;
	res->handler_calls = node->core.counters.irq_loops;
	res->irq_calls = node->irq_calls;
	assert_int_equal(sim_phantom_flood(&rig->bus, &flood_tmpl, FLOOD_FRAMES,
					   BITRATE), 0);
	ch_run_idle(rig, 10000 * MS);
	assert_int_equal(sim_phantom_pending(&rig->bus), 0);

	res->overflows = sim_chip_counters(&node->sim)->overflows;
	res->core_overflows = node->core.counters.rx_overflows;
	res->busy_ns = sim_chip_counters(&node->sim)->spi_busy_ns;
	res->elapsed_ns = sim_bus_now(&rig->bus) - start;
	res->messages = node->messages - res->messages;
	res->status_reads = node->status_reads - res->status_reads;
	res->transfers = sim_chip_counters(&node->sim)->spi_transfers -
			 res->transfers;
	res->bytes = sim_chip_counters(&node->sim)->spi_bytes - res->bytes;
	res->handler_calls = node->core.counters.irq_loops - res->handler_calls;
	res->irq_calls = node->irq_calls - res->irq_calls;
	print_message("%s: %u/%u frames, %llu overflows, SPI busy %llu us of %llu us, %llu messages (%llu READ STATUS alone), %llu periods, %llu bytes, %llu passes, %llu interrupts\n",
		      mcp2510_variant_get(model)->name, res->order.received,
		      FLOOD_FRAMES, (unsigned long long)res->overflows,
		      (unsigned long long)res->busy_ns / 1000,
		      (unsigned long long)res->elapsed_ns / 1000,
		      (unsigned long long)res->messages,
		      (unsigned long long)res->status_reads,
		      (unsigned long long)res->transfers,
		      (unsigned long long)res->bytes,
		      (unsigned long long)res->handler_calls,
		      (unsigned long long)res->irq_calls);
	result = NULL;
	ch_rig_free(rig);
}

static void flood(enum mcp2510_model model, const struct sim_spi_timing *t,
		  struct flood_result *res)
{
	flood_edge(model, t, false, res);
}

/* The flood ran at bus speed and SPI really took time. */
static void assert_flood_was_real(const struct flood_result *res)
{
	/* FLOOD_FRAMES frames back to back at 1 us a bit */
	assert_true(res->elapsed_ns >= (u64)FLOOD_FRAMES * FRAME_BITS_MIN * 1000);
	assert_true(res->elapsed_ns <= (u64)FLOOD_FRAMES * FRAME_BITS_MAX * 1000);
	/* at least the message overhead of one transfer per frame */
	assert_true(res->busy_ns >= (u64)FLOOD_FRAMES * ch_pi_like.msg_ns);
}

static void zero_loss(enum mcp2510_model model)
{
	struct flood_result res;

	flood(model, &ch_pi_like, &res);
	assert_flood_was_real(&res);
	assert_int_equal(res.order.received, FLOOD_FRAMES);
	assert_int_equal(res.order.out_of_order, 0);
	assert_int_equal(res.overflows, 0);
	assert_int_equal(res.core_overflows, 0);
}

static void test_flood_zero_loss_mcp2510(void **state)
{
	(void)state;
	zero_loss(MCP2510_MODEL_MCP2510);
}

static void test_flood_zero_loss_mcp2515(void **state)
{
	(void)state;
	zero_loss(MCP2510_MODEL_MCP2515);
}

/*
 * The same flood with a host ten times slower per message, slower than
 * the bus even without interrupts: the chip must overflow and the core
 * must say so (so the zero above is a measurement, not a harness that
 * cannot lose frames).  Order is not checked: with both buffers full no
 * register says which frame is older.
 */
static void test_slow_host_loses_frames(void **state)
{
	struct sim_spi_timing slow = ch_pi_like;
	struct flood_result res;

	(void)state;
	slow.msg_ns = 100000;
	flood(MCP2510_MODEL_MCP2510, &slow, &res);
	assert_true(res.overflows > 0);
	/* one overflow flag may stand for several frames lost */
	assert_true(res.core_overflows > 0);
	assert_true(res.core_overflows <= res.overflows);
	assert_int_equal(res.order.received + res.overflows, FLOOD_FRAMES);
}

/*
 * driver-stream.sh's first half in simulated time: node 0 streams to node
 * 1 as fast as its three buffers allow, both chips on the one SPI
 * controller.  Returns the frames node 1 received out of order; *lost
 * gets those that never arrived.
 */
static u32 stream(enum mcp2510_model model, u32 bitrate, u32 n, u32 *lost)
{
	struct ch_rig *rig = ch_rig_new(2, model);
	struct flood_result res;
	u32 submitted = 0;
	unsigned int i;

	memset(&res, 0, sizeof(res));
	result = &res;
	rig->node[1].ev.on_rx = count_rx;
	for (i = 0; i < 2; i++)
		assert_int_equal(ch_start(&rig->node[i], bitrate, 0), 0);
	rig->spi.timing = ch_pi_like;
	while (rig->node[0].ev.tx_done_count < n) {
		while (submitted < n && mcp2510_tx_free(&rig->node[0].core)) {
			struct can_frame cf = ch_frame(0x100, 8, submitted);

			assert_true(mcp2510_tx_submit(&rig->node[0].core, &cf) >= 0);
			submitted++;
		}
		ch_run(rig, 100000);
	}
	ch_run_idle(rig, 100 * MS);
	*lost = n - res.order.received;
	print_message("%s at %u bit/s: %u of %u received, %u out of order\n",
		      mcp2510_variant_get(model)->name, bitrate, res.order.received,
		      n, res.order.out_of_order);
	result = NULL;
	ch_rig_free(rig);
	return res.order.out_of_order;
}

static void test_stream_between_nodes(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	static const u32 rates[] = { 500000, 1000000 };
	unsigned int i, r;
	u32 lost;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		for (r = 0; r < ARRAY_SIZE(rates); r++) {
			assert_int_equal(stream(models[i], rates[r], 2000, &lost), 0);
			assert_int_equal(lost, 0);
		}
	}
}

/* Timing off: an SPI transfer takes no bus time, as before SPI time existed. */
static void test_off_is_instant(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *node = &rig->node[0];
	u64 before;

	(void)state;
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	before = sim_bus_now(&rig->bus);
	assert_int_equal(mcp2510_irq_handle(&node->core), 0);
	assert_int_equal(sim_bus_now(&rig->bus), before);
	assert_int_equal(sim_chip_counters(&node->sim)->spi_busy_ns, 0);

	rig->spi.timing = ch_pi_like;
	assert_int_equal(mcp2510_irq_handle(&node->core), 0);
	assert_true(sim_bus_now(&rig->bus) >= before + ch_pi_like.msg_ns);
	assert_true(sim_chip_counters(&node->sim)->spi_busy_ns >= ch_pi_like.msg_ns);
	ch_rig_free(rig);
}

/*
 * The slow host, a 1 Mbit/s flood.  A pass after an interrupt costs the
 * latency, the flags and the frame, 60 + 45 + 85 us, more than a frame
 * takes on the bus; but each pass takes the frame the previous one's
 * READ STATUS showed (irq_rx.c, irq_flags.c), in 85 us, so the backlog
 * drains between interrupts; once it has, a few READ STATUS polls wait
 * for the next frame instead of the interrupt, and the whole flood
 * arrives with far fewer interrupts than frames.  Per frame the MCP2510
 * costs READ 15 + BIT MODIFY 4 + READ STATUS 2 in three periods of one
 * message, the MCP2515 READ RX BUFFER 14 + READ STATUS 2 in two; each
 * interrupt, and the full read every MCP2510_IRQ_FULL_READ_EVERY passes,
 * add a message of one period that reads the flags (4 bytes at most);
 * the polls, a message of one READ STATUS each, fewer than the frames.
 */
static void slow_board(enum mcp2510_model model, u64 frame_bytes,
		       u64 frame_periods)
{
	struct flood_result res;
	u64 reads, polls;

	flood(model, &slow_board_timing, &res);
	assert_int_equal(res.order.received, FLOOD_FRAMES);
	assert_int_equal(res.order.out_of_order, 0);
	assert_int_equal(res.overflows, 0);
	assert_true(res.irq_calls * 8 <= FLOOD_FRAMES);
	reads = res.irq_calls + res.handler_calls / MCP2510_IRQ_FULL_READ_EVERY + 1;
	polls = res.status_reads;
	assert_true(polls < FLOOD_FRAMES);
	assert_true(res.messages - polls <= FLOOD_FRAMES + reads);
	assert_true(res.transfers - polls <= FLOOD_FRAMES * frame_periods + reads);
	assert_true(res.bytes - 2 * polls <= FLOOD_FRAMES * frame_bytes + 4 * reads);
}

static void test_slow_board_flood_mcp2510(void **state)
{
	(void)state;
	slow_board(MCP2510_MODEL_MCP2510, 21, 3);
}

static void test_slow_board_flood_mcp2515(void **state)
{
	(void)state;
	slow_board(MCP2510_MODEL_MCP2515, 16, 2);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_flood_zero_loss_mcp2510),
		cmocka_unit_test(test_flood_zero_loss_mcp2515),
		cmocka_unit_test(test_slow_host_loses_frames),
		cmocka_unit_test(test_stream_between_nodes),
		cmocka_unit_test(test_off_is_instant),
		cmocka_unit_test(test_slow_board_flood_mcp2510),
		cmocka_unit_test(test_slow_board_flood_mcp2515),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
