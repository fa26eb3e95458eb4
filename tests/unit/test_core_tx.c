// SPDX-License-Identifier: GPL-2.0
/*
 * The ordered three-buffer transmit scheduler against simulated chips:
 * frames leave, arrive and complete in queue order while all three
 * buffers stay busy (10,000-frame streams with mixed identifiers and
 * competing traffic), the share of the bus they keep busy against one
 * buffer at a time, the SPI cost per frame, transport errors leaving
 * the scheduler consistent, and the MCP2515's LOAD TX BUFFER.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <setjmp.h>
#include <cmocka.h>

#include "core_harness.h"

#define MS		1000000ULL
#define BITRATE		1000000
#define PHANTOM_ID	0x001	/* beats every stream frame in arbitration */

/* Frame @i of a stream: mixed formats, identifiers, lengths, some RTR. */
static struct can_frame stream_frame(u32 i, bool full_length)
{
	u32 h = i * 2654435761u;
	u8 len = full_length ? 8 : (h >> 7) % 9;
	canid_t id;

	if (h & 0x10000)
		id = CAN_EFF_FLAG | ((h >> 3) & CAN_EFF_MASK);
	else
		id = 0x010 + (h >> 5) % (0x7ff - 0x010);
	if (!full_length && i % 13 == 5)
		id |= CAN_RTR_FLAG;
	return ch_frame(id, len, i);
}

struct stream {
	u32 total;
	bool full_length;
	u32 fail_every;		/* inject a transport error every n attempts */
	bool fail_reaches_chip;
	u32 phantom_every;	/* competing frames every n frames */
	bool one_buffer;	/* a plain FIFO: one frame in the chip at a time */
	const struct sim_spi_timing *timing;	/* SPI time; NULL: none */
	bool alone;		/* no receiving chip: the phantom acknowledges */
	/* progress */
	u32 submitted, received, done, attempts, failed;
	u8 fifo[4];		/* slots in submission order */
	u32 fifo_head, fifo_len;
	/* SPI cost of submits that succeeded */
	u64 tx_bytes, tx_transfers, tx_max_bytes;
	u32 load_tx_buffer_submits;
	/* bus monitor */
	u32 frames_on_bus, gaps;
	u64 first_start_ns, last_end_ns, frames_ns;
	/* the sender's, at the end */
	u32 stages;
	u64 drain_waits;
};

static struct stream *current;

static void stream_on_rx(struct ch_node *node, const struct can_frame *cf)
{
	struct can_frame want;

	(void)node;
	/*
	 * With SPI time the receiving node, serviced after the sender, may
	 * lose frames: only the sender's side is checked then.
	 */
	if (cf->can_id == PHANTOM_ID || current->timing)
		return;
	want = stream_frame(current->received, current->full_length);
	if (!ch_frame_equal(cf, &want))
		fail_msg("frame %u arrived as %x/%u, want %x/%u",
			 current->received, cf->can_id, cf->len, want.can_id,
			 want.len);
	current->received++;
}

static void stream_on_tx_done(struct ch_node *node, unsigned int slot)
{
	struct stream *s = current;

	(void)node;
	assert_true(s->fifo_len > 0);
	if (s->fifo[s->fifo_head % 4] != slot)
		fail_msg("tx_done for slot %u, queue head is slot %u", slot,
			 s->fifo[s->fifo_head % 4]);
	s->fifo_head++;
	s->fifo_len--;
	s->done++;
}

static void stream_monitor(void *ctx, const struct sim_bus_record *rec)
{
	struct stream *s = ctx;

	if (rec->kind != SIM_REC_FRAME)
		return;
	if (s->frames_on_bus && rec->start_ns != s->last_end_ns &&
	    s->submitted > s->done + 1)
		s->gaps++;
	if (!s->frames_on_bus)
		s->first_start_ns = rec->start_ns;
	s->frames_on_bus++;
	s->frames_ns += rec->end_ns - rec->start_ns;
	s->last_end_ns = rec->end_ns;
}

static void stream_submit_one(struct stream *s, struct ch_node *tx)
{
	struct can_frame cf = stream_frame(s->submitted, s->full_length);
	u32 stages = tx->core.tx.stages;
	struct ch_spi_mark m;
	int ret;

	s->attempts++;
	if (s->fail_every && s->attempts % s->fail_every == 0) {
		tx->xfer_count = 0;
		tx->fail_at = 1;
		tx->fail_reaches_chip = s->fail_reaches_chip;
	}
	ch_spi_mark(tx, &m);
	ret = mcp2510_tx_submit(&tx->core, &cf);
	m = ch_spi_since(tx, &m);
	if (tx->fail_at) {
		tx->fail_at = 0;
		assert_int_equal(ret, -EIO);
		s->failed++;
		return;
	}
	assert_in_range(ret, 0, 2);
	/*
	 * A submit is one load and one RTS; a staged frame is only loaded
	 * (its RTS comes with a completion), unless nothing is pending.
	 */
	stages = tx->core.tx.stages - stages;
	if (stages)
		assert_in_range(m.transfers, 1, 2);
	else
		assert_int_equal(m.transfers, 2);
	if (cf.len == 8 && !(cf.can_id & CAN_RTR_FLAG))
		assert_true(m.bytes <= 17);
	if (!stages && m.bytes == 1 + 5 + cf.len + 1u &&
	    !(cf.can_id & CAN_RTR_FLAG))
		s->load_tx_buffer_submits++;
	s->tx_bytes += m.bytes;
	s->tx_transfers += m.transfers;
	if (m.bytes > s->tx_max_bytes)
		s->tx_max_bytes = m.bytes;
	s->fifo[(s->fifo_head + s->fifo_len) % 4] = ret;
	s->fifo_len++;
	s->submitted++;
}

static void stream_run(struct stream *s, enum mcp2510_model model)
{
	struct ch_rig *rig = ch_rig_new(2, model);
	struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];
	struct can_frame phantom = ch_frame(PHANTOM_ID, 1, 0);
	struct ch_spi_mark irq_start;
	u64 steps = 0;

	current = s;
	rx->ev.on_rx = stream_on_rx;
	tx->ev.on_tx_done = stream_on_tx_done;
	sim_bus_set_monitor(&rig->bus, stream_monitor, s);
	assert_int_equal(ch_start(tx, BITRATE, 0), 0);
	if (s->alone)
		sim_phantom_attach(&rig->bus, BITRATE);
	else
		assert_int_equal(ch_start(rx, BITRATE, 0), 0);
	/* start-up at no SPI cost; the stream pays */
	if (s->timing)
		rig->spi.timing = *s->timing;

	ch_spi_mark(tx, &irq_start);
	while (s->done < s->total) {
		while (s->submitted < s->total &&
		       mcp2510_tx_free(&tx->core) > (s->one_buffer ? 2 : 0)) {
			stream_submit_one(s, tx);
			if (s->phantom_every &&
			    s->submitted % s->phantom_every == 0)
				sim_phantom_send(&rig->bus, &phantom, 0);
		}
		/*
		 * INT asserted during the submits: serviced before the bus
		 * goes on, as the driver's handler runs once they release
		 * the chip.
		 */
		if (ch_int_asserted(tx)) {
			int ret;

			ch_service(tx, 16, &ret);
			assert_true(ret >= 0);
			continue;
		}
		/* with SPI time the last completion may come after the bus idles */
		if (!ch_step(rig)) {
			assert_non_null(s->timing);
			ch_run(rig, MS);
		}
		assert_true(++steps < 100ULL * s->total);
	}
	ch_run_idle(rig, 10 * MS);

	if (!s->timing && !s->alone)
		assert_int_equal(s->received, s->total);
	/* the competing frames really went in between */
	if (s->phantom_every && !s->alone)
		assert_int_equal(rx->ev.rx_count - s->received,
				 s->total / s->phantom_every);
	assert_int_equal(s->done, s->total);
	assert_int_equal(tx->ev.tx_aborted_count, 0);
	/* never a write into a buffer with TXREQ set (but to abort) */
	assert_int_equal(sim_chip_counters(&tx->sim)->tx_pending_writes, 0);
	/* the bus idles only while staged frames wait for their RTS */
	if (!s->timing)
		assert_true(s->gaps <= tx->core.tx.stages);
	assert_int_equal(mcp2510_tx_free(&tx->core), 3);
	/* the rest of the node's SPI traffic went on completions */
	irq_start = ch_spi_since(tx, &irq_start);
	print_message("%s: %u frames, submit %.2f bytes %.2f transfers/frame "
		      "(max %llu), %u staged, %u bus gaps, %u via LOAD TX "
		      "BUFFER, completion %.2f bytes %.2f transfers/frame, "
		      "%u injected errors\n",
		      mcp2510_variant_get(model)->name, s->total,
		      (double)s->tx_bytes / s->total,
		      (double)s->tx_transfers / s->total,
		      (unsigned long long)s->tx_max_bytes,
		      tx->core.tx.stages, s->gaps, s->load_tx_buffer_submits,
		      (double)(irq_start.bytes - s->tx_bytes) / s->total,
		      (double)(irq_start.transfers - s->tx_transfers) /
		      s->total, s->failed);
	s->stages = tx->core.tx.stages;
	s->drain_waits = tx->drain_waits;
	/* keys walk down one per frame: a restart about every nine */
	assert_true(tx->core.tx.stages <= 2 * (s->total / 9 + 1) +
		    2 * s->failed);
	ch_rig_free(rig);
	current = NULL;
}

static void test_three_frames_keep_their_order(void **state)
{
	struct ch_rig *rig = ch_rig_new(2, MCP2510_MODEL_MCP2510);
	struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];
	/* identifiers that the bus would reorder if all were pending */
	static const canid_t ids[] = { 0x700, 0x300, 0x100 };
	struct can_frame extra = ch_frame(0x1, 1, 0);
	unsigned int i;

	(void)state;
	assert_int_equal(ch_start(tx, BITRATE, 0), 0);
	assert_int_equal(ch_start(rx, BITRATE, 0), 0);
	for (i = 0; i < 3; i++) {
		struct can_frame cf = ch_frame(ids[i], 8, i);

		assert_true(mcp2510_tx_submit(&tx->core, &cf) >= 0);
	}
	assert_int_equal(mcp2510_tx_free(&tx->core), 0);
	assert_int_equal(mcp2510_tx_submit(&tx->core, &extra), -EBUSY);
	ch_run_idle(rig, 10 * MS);
	assert_int_equal(rx->ev.rx_count, 3);
	for (i = 0; i < 3; i++)
		assert_int_equal(rx->ev.rx[i].can_id, ids[i]);
	assert_int_equal(tx->ev.tx_done_count, 3);
	/* first frame into the top key: buffer 2 at TXP 3, then 1 and 0 */
	assert_int_equal(tx->ev.tx_done[0], 2);
	assert_int_equal(tx->ev.tx_done[1], 1);
	assert_int_equal(tx->ev.tx_done[2], 0);
	assert_int_equal(mcp2510_tx_free(&tx->core), 3);
	ch_rig_free(rig);
}

/*
 * cc-len8-dlc through two chips, on both models (plain READ and READ RX
 * BUFFER): the sender's mode decides the DLC on the wire, the receiver's
 * whether a DLC above 8 reaches it as len8_dlc.
 */
static void test_raw_dlc_through_chips(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	static const struct {
		u32 tx_mode, rx_mode;
		u8 len8_dlc;	/* what the receiver gets */
	} cases[] = {
		{ CAN_CTRLMODE_CC_LEN8_DLC, CAN_CTRLMODE_CC_LEN8_DLC, 14 },
		{ CAN_CTRLMODE_CC_LEN8_DLC, 0, 0 },
		{ 0, CAN_CTRLMODE_CC_LEN8_DLC, 0 },
	};
	unsigned int m, c;

	(void)state;
	for (m = 0; m < ARRAY_SIZE(models); m++) {
		for (c = 0; c < ARRAY_SIZE(cases); c++) {
			struct ch_rig *rig = ch_rig_new(2, models[m]);
			struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];
			struct can_frame cf = ch_frame(0x123, 8, c);

			cf.len8_dlc = 14;
			assert_int_equal(ch_start(tx, BITRATE, cases[c].tx_mode), 0);
			assert_int_equal(ch_start(rx, BITRATE, cases[c].rx_mode), 0);
			assert_true(mcp2510_tx_submit(&tx->core, &cf) >= 0);
			ch_run_idle(rig, 10 * MS);
			assert_int_equal(tx->ev.tx_done_count, 1);
			assert_int_equal(rx->ev.rx_count, 1);
			assert_int_equal(rx->ev.rx[0].len, 8);
			assert_int_equal(rx->ev.rx[0].len8_dlc, cases[c].len8_dlc);
			assert_memory_equal(rx->ev.rx[0].data, cf.data, 8);
			ch_rig_free(rig);
		}
	}
}

/*
 * Requests made within one bit of a start of frame contend together
 * (tests/sim/README.md): three frames submitted back to back over a timed
 * SPI bus, all within the first bit of the first one's start of frame,
 * still leave in queue order, since each new frame's buffer and TXP rank
 * below the pending ones.
 */
static void test_frames_within_a_bit_keep_their_order(void **state)
{
	struct ch_rig *rig = ch_rig_new(2, MCP2510_MODEL_MCP2515);
	struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];
	static const canid_t ids[] = { 0x700, 0x300, 0x100 };
	const struct sim_spi_timing fast = { .enabled = true };
	const u32 bit_ns = 1000000000U / 20000;
	u64 first;
	unsigned int i;

	(void)state;
	assert_int_equal(ch_start(tx, 20000, 0), 0);
	assert_int_equal(ch_start(rx, 20000, 0), 0);
	rig->spi.timing = fast;
	first = sim_bus_now(&rig->bus);
	for (i = 0; i < 3; i++) {
		struct can_frame cf = ch_frame(ids[i], 0, i);

		assert_true(mcp2510_tx_submit(&tx->core, &cf) >= 0);
	}
	/* every request came while the first start of frame was on the bus */
	assert_true(sim_bus_now(&rig->bus) > first);
	assert_true(sim_bus_now(&rig->bus) - first < bit_ns);
	assert_false(sim_bus_idle(&rig->bus));
	ch_run_idle(rig, 100 * MS);
	assert_int_equal(rx->ev.rx_count, 3);
	for (i = 0; i < 3; i++)
		assert_int_equal(rx->ev.rx[i].can_id, ids[i]);
	ch_rig_free(rig);
}

/*
 * The transmit buffers' SIDH..D7 power up unknown (DS21801 registers
 * 3-3..3-8, "x") and the model fills them with garbage.  The first frame
 * of every buffer, of every kind, goes out exactly as submitted: the core
 * writes the identifier and DLC whole and the data bytes the DLC covers
 * (bytes past the DLC are never sent), whatever a buffer held.
 */
static void test_first_frames_ignore_power_up_garbage(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	struct can_frame frames[3];
	unsigned int m, i;

	(void)state;
	frames[0] = ch_frame(0x0, 0, 0);			/* SIDL EXIDE must go */
	frames[1] = ch_frame(0x7ff | CAN_RTR_FLAG, 0, 0);
	frames[2] = ch_frame(CAN_EFF_FLAG | 0x12345, 8, 7);
	for (m = 0; m < ARRAY_SIZE(models); m++) {
		struct ch_rig *rig = ch_rig_new(2, models[m]);
		struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];

		assert_int_equal(ch_start(tx, BITRATE, 0), 0);
		assert_int_equal(ch_start(rx, BITRATE, 0), 0);
		for (i = 0; i < 3; i++)
			assert_true(mcp2510_tx_submit(&tx->core, &frames[i]) >= 0);
		ch_run_idle(rig, 10 * MS);
		assert_int_equal(rx->ev.rx_count, 3);
		for (i = 0; i < 3; i++)
			assert_true(ch_frame_equal(&rx->ev.rx[i], &frames[i]));
		ch_rig_free(rig);
	}
}

static void test_stream_mcp2510(void **state)
{
	struct stream s = { .total = 10000, .phantom_every = 97 };

	(void)state;
	stream_run(&s, MCP2510_MODEL_MCP2510);
}

static void test_stream_mcp2515(void **state)
{
	struct stream s = { .total = 10000, .phantom_every = 89 };

	(void)state;
	stream_run(&s, MCP2510_MODEL_MCP2515);
}

/*
 * What the scheduler is for: on a host with SPI and interrupt latency,
 * one frame in the chip at a time leaves the bus idle between frames
 * while the completion is read and the next frame loaded; three keep it
 * busy.  The share of bus time the stream's frames took, both ways.
 */
static void test_scheduler_against_one_buffer(void **state)
{
	struct stream three = { .total = 1000, .full_length = true,
				.timing = &ch_pi_like };
	struct stream one = three;
	double use_three, use_one;

	(void)state;
	one.one_buffer = true;
	stream_run(&three, MCP2510_MODEL_MCP2510);
	stream_run(&one, MCP2510_MODEL_MCP2510);
	use_three = (double)three.frames_ns /
		    (three.last_end_ns - three.first_start_ns);
	use_one = (double)one.frames_ns / (one.last_end_ns - one.first_start_ns);
	print_message("bus use at 1 Mbit/s: three buffers %.1f%%, one buffer %.1f%%\n",
		      100 * use_three, 100 * use_one);
	assert_true(use_three > use_one);
}

/*
 * A drain on a Raspberry Pi's costs (the calibrated `pi` profile at 1x,
 * 1 Mbit/s, the phantom acknowledging): once the last pending frame is
 * on its way, the handler polls for its end, so that the staged frames'
 * RTS follows it by a message rather than by an interrupt's latency and
 * a flags read.  Counted by the handler calls a drain waited for: most
 * drains are bridged by the polls.
 */
static void test_drain_does_not_wait_for_int(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	struct sim_spi_timing pi;
	unsigned int i;

	(void)state;
	assert_int_equal(sim_spi_profile_timing(SIM_SPI_PROFILE_PI, 100, &pi),
			 0);
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		struct stream s = { .total = 1000, .full_length = true,
				    .timing = &pi, .alone = true };

		stream_run(&s, models[i]);
		print_message("%s under pi 1x: bus use %.1f%%, %u frames staged, %llu drains waited for INT\n",
			      mcp2510_variant_get(models[i])->name,
			      100.0 * s.frames_ns /
			      (s.last_end_ns - s.first_start_ns),
			      s.stages, (unsigned long long)s.drain_waits);
		/* drains there were, most of them bridged */
		assert_true(s.stages >= 20);
		assert_true(s.drain_waits * 4 <= s.stages);
	}
}

/*
 * A period one byte too long to be polled by spi-bcm2835 (the load of a
 * frame at the MCP2510's 5 MHz) goes as two polled transfers; one that
 * is short enough, or too long for two, stays whole.
 */
static void test_load_split_for_polled_transfers(void **state)
{
	(void)state;
	assert_int_equal(mcp2510_xfer_first_len(16, 5000000), 8);
	assert_int_equal(mcp2510_xfer_first_len(15, 5000000), 15);
	assert_int_equal(mcp2510_xfer_first_len(30, 5000000), 15);
	assert_int_equal(mcp2510_xfer_first_len(31, 5000000), 31);
	assert_int_equal(mcp2510_xfer_first_len(16, 10000000), 16);
	assert_int_equal(mcp2510_xfer_first_len(33, 10000000), 16);
	assert_int_equal(mcp2510_xfer_first_len(130, 10000000), 130);
	/* too slow a clock to poll anything: nothing gained by splitting */
	assert_int_equal(mcp2510_xfer_first_len(2, 500000), 2);
	assert_int_equal(mcp2510_xfer_first_len(2, 0), 2);
}

static void test_spi_cost_per_8_byte_frame(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		struct stream s = { .total = 1000, .full_length = true };

		stream_run(&s, models[i]);
		/* at most the 17-byte, 2-transfer submit */
		assert_true(s.tx_bytes <= 17ULL * s.total);
		/*
		 * A busy stream changes every buffer's TXP at each reuse, so
		 * even the MCP2515 writes TXBnCTRL with the frame (see the
		 * idle case for LOAD TX BUFFER).
		 */
		assert_int_equal(s.load_tx_buffer_submits, 0);
	}
}

/*
 * One frame on an idle chip: the exact instruction sequence, the load and
 * its RTS in one message.
 */
static void test_idle_submit_and_completion_cost(void **state)
{
	static const struct {
		enum mcp2510_model model;
		u64 first, second;
	} cases[] = {
		/*
		 * WRITE TXBnCTRL..D7 (16) + RTS (1), then WRITE SIDH..D7
		 * (15): TXP already right, and one byte less is a transfer
		 * spi-bcm2835 polls at 5 MHz
		 */
		{ MCP2510_MODEL_MCP2510, 17, 16 },
		/* then LOAD TX BUFFER SIDH..D7 (14) + RTS: TXP already right */
		{ MCP2510_MODEL_MCP2515, 17, 15 },
	};
	unsigned int i, k;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(cases); i++) {
		struct ch_rig *rig = ch_rig_new(2, cases[i].model);
		struct ch_node *tx = &rig->node[0];

		assert_int_equal(ch_start(tx, BITRATE, 0), 0);
		assert_int_equal(ch_start(&rig->node[1], BITRATE, 0), 0);
		for (k = 0; k < 2; k++) {
			struct can_frame cf = ch_frame(0x123, 8, k);
			u64 messages = tx->messages;
			struct ch_spi_mark m;

			ch_spi_mark(tx, &m);
			assert_int_equal(mcp2510_tx_submit(&tx->core, &cf), 2);
			m = ch_spi_since(tx, &m);
			assert_int_equal(tx->messages - messages, 1);
			assert_int_equal(m.transfers, 2);
			assert_int_equal(m.bytes, k ? cases[i].second :
					 cases[i].first);

			/* completion: READ STATUS, BIT MODIFY CANINTF */
			sim_bus_advance(&rig->bus, MS);
			ch_spi_mark(tx, &m);
			assert_int_equal(ch_service(tx, 4, NULL), 1);
			m = ch_spi_since(tx, &m);
			assert_int_equal(m.transfers, 2);
			assert_int_equal(m.bytes, 6);
			assert_int_equal(tx->ev.tx_done_count, k + 1);
			ch_service(&rig->node[1], 4, NULL);
		}
		ch_rig_free(rig);
	}
}

static void test_stream_with_transport_errors(void **state)
{
	static const struct {
		enum mcp2510_model model;
		bool reaches_chip;
	} cases[] = {
		{ MCP2510_MODEL_MCP2510, false },
		{ MCP2510_MODEL_MCP2510, true },
		{ MCP2510_MODEL_MCP2515, false },
		{ MCP2510_MODEL_MCP2515, true },
	};
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(cases); i++) {
		struct stream s = {
			.total = 600, .fail_every = 7,
			.fail_reaches_chip = cases[i].reaches_chip,
		};

		stream_run(&s, cases[i].model);
		assert_true(s.failed >= 600 / 7);
	}
}

/* A load that fails leaves the slot free; an RTS that fails sends nothing. */
static void test_failed_submit_sends_nothing(void **state)
{
	struct ch_rig *rig = ch_rig_new(2, MCP2510_MODEL_MCP2510);
	struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];
	struct can_frame lost = ch_frame(0x111, 8, 1);
	struct can_frame sent = ch_frame(0x222, 8, 2);
	unsigned int fail;

	(void)state;
	assert_int_equal(ch_start(tx, BITRATE, 0), 0);
	assert_int_equal(ch_start(rx, BITRATE, 0), 0);
	for (fail = 1; fail <= 2; fail++) {
		tx->xfer_count = 0;
		tx->fail_at = fail;	/* 1: the load, 2: the RTS */
		tx->fail_reaches_chip = false;
		assert_int_equal(mcp2510_tx_submit(&tx->core, &lost), -EIO);
		tx->fail_at = 0;
		assert_int_equal(mcp2510_tx_free(&tx->core), 3);
		ch_run_idle(rig, 5 * MS);
		assert_int_equal(rx->ev.rx_count, 0);
		assert_int_equal(tx->ev.tx_done_count, 0);
	}
	assert_true(mcp2510_tx_submit(&tx->core, &sent) >= 0);
	ch_run_idle(rig, 5 * MS);
	assert_int_equal(rx->ev.rx_count, 1);
	assert_true(ch_frame_equal(&rx->ev.rx[0], &sent));
	assert_int_equal(tx->ev.tx_done_count, 1);
	ch_rig_free(rig);
}

/*
 * An RTS whose transfer reached the chip although the host saw an error:
 * the chip latched the request and sends the frame.  The slot must not
 * be taken for free (loading a frame into it would write a buffer with
 * TXREQ set, and its frame would go instead of the new one), and the
 * frame is reported once, as sent.
 */
static void test_failed_rts_that_reached_the_chip(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	unsigned int i, k;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		struct ch_rig *rig = ch_rig_new(2, models[i]);
		struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];
		int ret;

		assert_int_equal(ch_start(tx, BITRATE, 0), 0);
		assert_int_equal(ch_start(rx, BITRATE, 0), 0);
		tx->xfer_count = 0;
		tx->fail_at = 2;	/* the RTS */
		tx->fail_reaches_chip = true;
		ret = mcp2510_tx_submit(&tx->core, &(struct can_frame){
			.can_id = 0x100, .len = 1 });
		tx->fail_at = 0;
		/* three more frames before anything could complete */
		for (k = 1; k <= 3; k++) {
			struct can_frame cf = ch_frame(0x100 + k, 8, k);

			if (!mcp2510_tx_free(&tx->core))
				break;
			assert_true(mcp2510_tx_submit(&tx->core, &cf) >= 0);
		}
		ch_run_idle(rig, 10 * MS);
		assert_int_equal(sim_chip_counters(&tx->sim)->tx_pending_writes,
				 0);
		/* what went on the bus is what was reported */
		assert_int_equal(rx->ev.rx_count,
				 tx->ev.tx_done_count);
		assert_int_equal(rx->ev.rx_count,
				 k - 1 + (ret >= 0));
		assert_int_equal(rx->ev.rx[0].can_id, 0x100);
		for (k = 1; k < rx->ev.rx_count; k++)
			assert_int_equal(rx->ev.rx[k].can_id, 0x100 + k);
		ch_rig_free(rig);
	}
}

static void test_restart_drops_queued_frames(void **state)
{
	struct ch_rig *rig = ch_rig_new(1, MCP2510_MODEL_MCP2510);
	struct ch_node *tx = &rig->node[0];
	struct can_frame cf = ch_frame(0x100, 8, 0);

	(void)state;
	assert_int_equal(ch_start(tx, BITRATE, 0), 0);
	assert_true(mcp2510_tx_submit(&tx->core, &cf) >= 0);
	assert_true(mcp2510_tx_submit(&tx->core, &cf) >= 0);
	ch_run(rig, MS);	/* no ACK: they stay pending */
	assert_int_equal(mcp2510_restart(&tx->core), 0);
	assert_int_equal(tx->ev.tx_aborted_count, 2);
	assert_int_equal(mcp2510_tx_free(&tx->core), 3);
	assert_int_equal(tx->core.counters.restarts, 1);
	/* the chip forgot them too */
	assert_false(sim_chip_peek(&tx->sim, MCP2510_REG_TXBCTRL(2)) &
		     MCP2510_TXBCTRL_TXREQ);
	ch_rig_free(rig);
}

/* Staged frames whose TXREQ was set after the first period of a message. */
static u8 drain_staged, drain_requested_first;

static void drain_after_xfer(struct ch_node *node)
{
	unsigned int n;

	if (node->msg_left != 1 || drain_requested_first)
		return;
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		if (drain_staged & BIT(n) &&
		    sim_chip_peek(&node->sim, MCP2510_REG_TXBCTRL(n)) &
		    MCP2510_TXBCTRL_TXREQ)
			drain_requested_first |= BIT(n);
}

/*
 * The drain: with the keys used up a frame is staged until the pending
 * ones are gone, and the pass that sees the last of them go clears their
 * TXnIF and requests the staged frame in one message, the RTS first, so
 * the bus waits one chip-select period for it rather than two or another
 * message.
 */
static void test_drain_clears_and_requests_in_one_message(void **state)
{
	static const enum mcp2510_model models[] = {
		MCP2510_MODEL_MCP2510, MCP2510_MODEL_MCP2515,
	};
	unsigned int i;

	(void)state;
	for (i = 0; i < ARRAY_SIZE(models); i++) {
		struct ch_rig *rig = ch_rig_new(2, models[i]);
		struct ch_node *tx = &rig->node[0], *rx = &rig->node[1];
		u64 messages;
		u32 k = 0;

		assert_int_equal(ch_start(tx, BITRATE, 0), 0);
		assert_int_equal(ch_start(rx, BITRATE, 0), 0);
		while (!tx->core.tx.staged) {
			struct can_frame cf = ch_frame(0x100, 8, k);

			if (!mcp2510_tx_free(&tx->core)) {
				assert_true(ch_step(rig));
				continue;
			}
			assert_true(mcp2510_tx_submit(&tx->core, &cf) >= 0);
			k++;
		}
		/* the pending frames go, nobody serves the sender meanwhile */
		sim_bus_advance(&rig->bus, MS);
		assert_true(ch_int_asserted(tx));
		messages = tx->messages;
		drain_staged = tx->core.tx.staged;
		drain_requested_first = 0;
		tx->after_xfer = drain_after_xfer;
		assert_int_equal(ch_service(tx, 4, NULL), 1);
		tx->after_xfer = NULL;
		/* the flags, then the RTS with the clear */
		assert_int_equal(tx->messages - messages, 2);
		assert_int_equal(drain_requested_first, drain_staged);
		assert_int_equal(tx->core.tx.staged, 0);
		ch_run_idle(rig, 10 * MS);
		assert_int_equal(tx->ev.tx_done_count, k);
		ch_rig_free(rig);
	}
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_three_frames_keep_their_order),
		cmocka_unit_test(test_raw_dlc_through_chips),
		cmocka_unit_test(test_frames_within_a_bit_keep_their_order),
		cmocka_unit_test(test_first_frames_ignore_power_up_garbage),
		cmocka_unit_test(test_idle_submit_and_completion_cost),
		cmocka_unit_test(test_stream_mcp2510),
		cmocka_unit_test(test_stream_mcp2515),
		cmocka_unit_test(test_scheduler_against_one_buffer),
		cmocka_unit_test(test_spi_cost_per_8_byte_frame),
		cmocka_unit_test(test_drain_does_not_wait_for_int),
		cmocka_unit_test(test_load_split_for_polled_transfers),
		cmocka_unit_test(test_stream_with_transport_errors),
		cmocka_unit_test(test_failed_submit_sends_nothing),
		cmocka_unit_test(test_failed_rts_that_reached_the_chip),
		cmocka_unit_test(test_restart_drops_queued_frames),
		cmocka_unit_test(test_drain_clears_and_requests_in_one_message),
	};

	return cmocka_run_group_tests_name("core_tx", tests, NULL, NULL);
}
