// SPDX-License-Identifier: GPL-2.0
/*
 * Messages are not atomic: under the calibrated board profiles
 * (sim_spi_profile.c) bus time runs on between the chip-select periods of
 * one SPI message, as on a board, so frames land between the release of
 * a receive buffer and the READ STATUS that follows it in the same
 * message.  The receive order must hold all the same, on both chips, at
 * every profile and cost scale; the floods also report what a frame costs
 * in SPI time, periods and bytes.  Time is the model's only.
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

struct gap_result {
	struct ch_order order;	/* the flood's frames as received */
	u64 gap_frames;		/* frames stored between two periods of one message */
	u64 prev_rx;
	unsigned int prev_left;
};

static struct gap_result *result;


static void count_rx(struct ch_node *node, const struct can_frame *cf)
{
	(void)node;
	ch_order_frame(&result->order, cf);
}

/* after every period: did a frame reach a buffer since the message's last one? */
static void watch_gap(struct ch_node *node)
{
	u64 rx = sim_chip_counters(&node->sim)->frames_rx;

	if (result->prev_left && rx > result->prev_rx)
		result->gap_frames++;
	result->prev_rx = rx;
	result->prev_left = node->msg_left;
}

/*
 * A 1 Mbit/s flood of 8-byte frames under profile p at scale_pct: every
 * frame received or counted lost, none out of order.  Returns the frames
 * received.
 */
static u32 flood(enum mcp2510_model model, unsigned int p, u32 scale_pct,
		 struct gap_result *res)
{
	struct ch_rig *rig = ch_rig_new(1, model);
	struct ch_node *node = &rig->node[0];
	const struct sim_counters *c = sim_chip_counters(&node->sim);
	struct can_frame cf = ch_frame(0x123, 8, 0);
	u64 busy, periods, bytes, msgs;

	memset(res, 0, sizeof(*res));
	result = res;
	node->ev.on_rx = count_rx;
	node->after_xfer = watch_gap;
	assert_int_equal(ch_start(node, BITRATE, 0), 0);
	assert_int_equal(sim_spi_profile_timing(p, scale_pct, &rig->spi.timing), 0);
	sim_spi_seed(&rig->spi, 1);
	busy = c->spi_busy_ns;
	periods = c->spi_transfers;
	bytes = c->spi_bytes;
	msgs = node->messages;
	assert_int_equal(sim_phantom_flood(&rig->bus, &cf, FLOOD_FRAMES, BITRATE), 0);
	ch_run_idle(rig, 10000 * MS);
	assert_int_equal(sim_phantom_pending(&rig->bus), 0);

	assert_int_equal(res->order.out_of_order, 0);
	assert_int_equal(res->order.received + c->overflows, FLOOD_FRAMES);
	print_message("%s %s x%u.%02u: %u/%u received, %llu in a gap; per frame received %llu.%llu us SPI, %llu.%02llu messages, %llu.%02llu periods, %llu.%llu bytes\n",
		      mcp2510_variant_get(model)->name, sim_spi_profile_name(p),
		      scale_pct / 100, scale_pct % 100, res->order.received,
		      FLOOD_FRAMES, (unsigned long long)res->gap_frames,
		      (unsigned long long)(c->spi_busy_ns - busy) / res->order.received / 1000,
		      (unsigned long long)(c->spi_busy_ns - busy) / res->order.received / 100 % 10,
		      (unsigned long long)(node->messages - msgs) / res->order.received,
		      (unsigned long long)(node->messages - msgs) * 100 / res->order.received % 100,
		      (unsigned long long)(c->spi_transfers - periods) / res->order.received,
		      (unsigned long long)(c->spi_transfers - periods) * 100 / res->order.received % 100,
		      (unsigned long long)(c->spi_bytes - bytes) / res->order.received,
		      (unsigned long long)(c->spi_bytes - bytes) * 10 / res->order.received % 10);
	result = NULL;
	ch_rig_free(rig);
	return res->order.received;
}

/* Frames land between the periods of one message, and order holds. */
static void test_frames_land_between_periods(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	struct gap_result res;
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		flood(models[i], SIM_SPI_PROFILE_PI, 100, &res);
		assert_true(res.gap_frames > 0);
	}
}

/* Every profile at 0.5x, 1x and 2x of its costs, both chips. */
static void test_order_under_every_profile(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	static const u32 scales[] = { 50, 100, 200 };
	struct gap_result res;
	unsigned int i, p, s;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++)
		for (p = SIM_SPI_PROFILE_PI; p < SIM_SPI_PROFILE_COUNT; p++)
			for (s = 0; s < ARRAY_SIZE(scales); s++)
				flood(models[i], p, scales[s], &res);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_frames_land_between_periods),
		cmocka_unit_test(test_order_under_every_profile),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
