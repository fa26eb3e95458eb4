// SPDX-License-Identifier: GPL-2.0
/*
 * The portable core against a hostile chip.
 *
 * The chip (fuzz_hostile_chip.c) answers every transfer from the input
 * (fuzz_input.h), as bytes, a stuck MISO line or a simulated chip whose
 * answers the input may garble, and can fail every N-th transfer.
 * Decisions from the back of the input call the core's public functions
 * in any order and, with the simulated chip, have a peer send frames.
 *
 * Besides crashes, overruns and hangs, the harness holds the core to its
 * contract (mcp2510_core.h): transfers are well formed for the variant,
 * every call ends after a bounded number of transfers and a bounded
 * delay, results are among the documented ones, the interrupt loop stops
 * after MCP2510_IRQ_MAX_PASSES and counts the storm (a level-triggered
 * call after MCP2510_IRQ_RX_PASSES at most), received and error
 * frames are valid SocketCAN frames, and every submitted frame is
 * reported exactly once, tx_done in queue order.
 */
#include <stdlib.h>

#include "fuzz_check.h"
#include "fuzz_hostile.h"

enum op {
	OP_HW_RESET,
	OP_SET_MODE,
	OP_START,
	OP_STOP,
	OP_RESTART,
	OP_IRQ,
	OP_IRQ_AGAIN,		/* weight: the interrupt loop is the main job */
	OP_TX_SUBMIT,
	OP_SLEEP,
	OP_BERR_COUNTER,
	OP_REGS_DUMP,
	OP_PIN_BF,
	OP_PIN_RTS,
	OP_FILTERS,
	OP_PEER_FRAME,
	OP_WAKE_ARM,
	OP_WAKE_ACK,
	OP_GARBLE,
	OP_COUNT
};

static bool one_of(int ret, const int *allowed, size_t n)
{
	size_t i;

	for (i = 0; i < n; i++)
		if (ret == allowed[i])
			return true;
	return false;
}

#define CHECK_RESULT(ret, ...)						\
	do {								\
		static const int allowed_[] = { __VA_ARGS__ };		\
		FUZZ_CHECK(one_of(ret, allowed_, ARRAY_SIZE(allowed_))); \
	} while (0)

/* Any timing, valid or not: the encoder sorts them out. */
static void take_bittiming(struct fuzz_input *in, struct can_bittiming *bt)
{
	memset(bt, 0, sizeof(*bt));
	bt->brp = fuzz_back_u8(in) % 66;
	bt->prop_seg = fuzz_back_u8(in) % 10;
	bt->phase_seg1 = fuzz_back_u8(in) % 10;
	bt->phase_seg2 = fuzz_back_u8(in) % 10;
	bt->sjw = fuzz_back_u8(in) % 6;
}

static void do_start(struct hostile *h)
{
	struct can_bittiming bt;
	u32 ctrlmode = fuzz_back_u8(&h->in);
	bool was_started = h->chip.started;
	int ret;

	take_bittiming(&h->in, &bt);
	ret = mcp2510_start(&h->chip, &bt, ctrlmode);
	CHECK_RESULT(ret, 0, -EBUSY, -EOPNOTSUPP, -EINVAL, -EIO, -ENODEV,
		     -ETIMEDOUT);
	FUZZ_CHECK(ret != -EBUSY || was_started);
}

static void do_irq(struct hostile *h)
{
	u32 loops = h->chip.counters.irq_loops;
	u32 bounds = h->chip.counters.irq_loop_bound;
	int ret = mcp2510_irq_handle(&h->chip);
	u32 passes = h->chip.counters.irq_loops - loops;

	FUZZ_CHECK(ret >= 0 || ret == -EAGAIN || ret == -EIO);
	FUZZ_CHECK(passes >= 1 && passes <= MCP2510_IRQ_MAX_PASSES);
	/* level-triggered: one pass, more only while frames keep coming */
	FUZZ_CHECK(h->chip.irq_edge || passes <= MCP2510_IRQ_RX_PASSES);
	/* a storm is reported and counted, and only a storm */
	FUZZ_CHECK((ret == -EAGAIN) ==
		   (h->chip.counters.irq_loop_bound == bounds + 1));
	FUZZ_CHECK(ret != -EAGAIN || passes == MCP2510_IRQ_MAX_PASSES);
}

static void do_tx_submit(struct hostile *h)
{
	struct can_frame cf = { 0 };
	unsigned int free_before = mcp2510_tx_free(&h->chip);
	unsigned int i;
	int ret;

	cf.can_id = fuzz_back_u32(&h->in) &
		    (CAN_EFF_FLAG | CAN_RTR_FLAG | CAN_EFF_MASK);
	if (!(cf.can_id & CAN_EFF_FLAG))
		cf.can_id &= CAN_RTR_FLAG | CAN_SFF_MASK;
	cf.len = fuzz_back_below(&h->in, CAN_MAX_DLEN + 2);	/* 9: invalid */
	for (i = 0; i < CAN_MAX_DLEN; i++)
		cf.data[i] = fuzz_back_u8(&h->in);
	FUZZ_CHECK(free_before == SLOTS - h->queued);

	ret = mcp2510_tx_submit(&h->chip, &cf);
	CHECK_RESULT(ret, 0, 1, 2, -EBUSY, -ENETDOWN, -EIO, -EINVAL);
	FUZZ_CHECK(ret != -EBUSY || !free_before);
	FUZZ_CHECK(ret != -EINVAL || cf.len > CAN_MAX_DLEN);
	if (ret < 0)
		return;
	FUZZ_CHECK(queue_pos(h, (unsigned int)ret) == SLOTS);
	h->queue[h->queued++] = (unsigned int)ret;
}

static void do_filters(struct hostile *h)
{
	struct mcp2510_filters f;
	unsigned int i;
	int ret;

	mcp2510_filters_default(&f);
	for (i = 0; i < MCP2510_MASK_COUNT; i++)
		f.mask[i].id = fuzz_back_u32(&h->in) & CAN_EFF_MASK;
	for (i = 0; i < MCP2510_FILTER_COUNT; i++)
		f.filter[i].ext = fuzz_back_bool(&h->in);
	f.rxm[0] = fuzz_back_below(&h->in, 5);	/* 4: invalid */
	ret = mcp2510_filters_apply(&h->chip, &f);
	CHECK_RESULT(ret, 0, -EBUSY, -EINVAL);
	FUZZ_CHECK((ret == -EBUSY) == h->chip.started);
}

static void do_dump(struct hostile *h)
{
	/* exactly the documented size: ASan sees a write past it */
	u8 *buf = malloc(MCP2510_REGDUMP_LEN);

	FUZZ_CHECK(buf);
	CHECK_RESULT(mcp2510_regs_dump(&h->chip, buf), 0, -EIO);
	free(buf);
}

/* The peer sends a frame at the chip's bit rate (model only). */
static void do_peer_frame(struct hostile *h)
{
	struct can_frame cf = { 0 };
	unsigned int i;

	cf.can_id = fuzz_back_u32(&h->in) &
		    (CAN_EFF_FLAG | CAN_RTR_FLAG | CAN_EFF_MASK);
	cf.len = fuzz_back_below(&h->in, CAN_MAX_DLEN + 1);
	for (i = 0; i < cf.len; i++)
		cf.data[i] = fuzz_back_u8(&h->in);
	if (h->miso != MISO_MODEL)
		return;
	CHECK_RESULT(sim_phantom_send(&h->bus, &cf, 0), 0, -ENOSPC);
	sim_bus_advance(&h->bus, (u64)fuzz_back_u16(&h->in) * 1000);
}

static void run_op(struct hostile *h)
{
	struct can_berr_counter bec;
	int ret;

	switch (fuzz_back_below(&h->in, OP_COUNT)) {
	case OP_HW_RESET:
		/* probe's job: a started chip has frames to account for */
		if (h->chip.started)
			return;
		CHECK_RESULT(mcp2510_hw_reset(&h->chip), 0, -ENODEV, -EIO);
		return;
	case OP_SET_MODE:
		ret = mcp2510_set_mode(&h->chip, fuzz_back_u8(&h->in) % 9);
		CHECK_RESULT(ret, 0, -EINVAL, -ETIMEDOUT, -EIO);
		return;
	case OP_START:
		do_start(h);
		return;
	case OP_STOP:
		CHECK_RESULT(mcp2510_stop(&h->chip), 0, -ETIMEDOUT, -EIO);
		FUZZ_CHECK(!h->queued);
		return;
	case OP_RESTART:
		ret = mcp2510_restart(&h->chip);
		CHECK_RESULT(ret, 0, -ENETDOWN, -EIO, -ENODEV, -ETIMEDOUT);
		FUZZ_CHECK(ret == -ENETDOWN || !h->queued);
		return;
	case OP_IRQ:
	case OP_IRQ_AGAIN:
		do_irq(h);
		return;
	case OP_TX_SUBMIT:
		do_tx_submit(h);
		return;
	case OP_SLEEP:
		CHECK_RESULT(mcp2510_sleep(&h->chip), 0, -ETIMEDOUT, -EIO);
		return;
	case OP_BERR_COUNTER:
		CHECK_RESULT(mcp2510_berr_counter(&h->chip, &bec), 0, -EIO);
		return;
	case OP_REGS_DUMP:
		do_dump(h);
		return;
	case OP_PIN_BF:
		ret = mcp2510_pin_bf_set(&h->chip, fuzz_back_below(&h->in, 3),
					 fuzz_back_bool(&h->in));
		CHECK_RESULT(ret, 0, -EINVAL, -EIO);
		return;
	case OP_PIN_RTS:
		ret = mcp2510_pin_rts_get(&h->chip, fuzz_back_below(&h->in, 4));
		CHECK_RESULT(ret, 0, 1, -EINVAL, -EIO);
		return;
	case OP_FILTERS:
		do_filters(h);
		return;
	case OP_PEER_FRAME:
		do_peer_frame(h);
		return;
	case OP_WAKE_ARM:
		/* the filter bit only reaches the chip at the next start */
		mcp2510_wake_filter_set(&h->chip, fuzz_back_bool(&h->in));
		CHECK_RESULT(mcp2510_wake_arm(&h->chip), 0, -ETIMEDOUT, -EIO);
		return;
	case OP_WAKE_ACK:
		CHECK_RESULT(mcp2510_wake_ack(&h->chip), 0, 1, -EIO);
		return;
	default:
		h->garble = 1 + fuzz_back_below(&h->in, 4);
		return;
	}
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct hostile h;

	hostile_init(&h, data, size);
	while (fuzz_input_left(&h.in)) {
		h.call_xfers = 0;
		h.call_delay_us = 0;
		run_op(&h);
		FUZZ_CHECK(mcp2510_tx_free(&h.chip) == SLOTS - h.queued);
	}
	return 0;
}
