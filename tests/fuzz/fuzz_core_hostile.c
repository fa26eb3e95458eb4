// SPDX-License-Identifier: GPL-2.0
/*
 * The portable core against a hostile chip.
 *
 * Every transfer is answered from the input (fuzz_input.h) in one of
 * three ways the input picks: with bytes from its front and, once they
 * run out, one fill byte; with the fill byte only (a MISO line stuck at
 * 0x00, 0xff or anything); or with the answer of a simulated chip, of
 * which a decision can garble the next few transfers by XORing them with
 * bytes from the front, so that a working chip with a bit rotten here
 * and there is explored as well as plain garbage.  That way a chip
 * can claim DLC 15, an impossible CANSTAT, INT flags that never clear,
 * or read as all 0x00 or all 0xff.  Every N-th transfer can fail.
 * Decisions from the back of the input call the core's public functions
 * in any order and, with the simulated chip, have a peer send frames.
 *
 * Besides crashes, overruns and hangs, the harness holds the core to its
 * contract (mcp2510_core.h): transfers are well formed for the variant,
 * every call ends after a bounded number of transfers and a bounded
 * delay, results are among the documented ones, the interrupt loop stops
 * after MCP2510_IRQ_MAX_PASSES and counts the storm, received and error
 * frames are valid SocketCAN frames, and every submitted frame is
 * reported exactly once, tx_done in queue order.
 */
#include <stdlib.h>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "mcp2510_core.h"
#include "mcp2510_sim.h"

/* The longest transfer: a READ of the whole register file. */
#define LONGEST_XFER		(2 + MCP2510_REGDUMP_LEN)
/* Generous bounds that only a runaway loop can exceed. */
#define MAX_XFERS_PER_CALL	4096
#define MAX_DELAY_PER_CALL_US	10000000ULL
/*
 * No single wait comes near this: the longest is the last RESET retry,
 * the 1 MHz start-up time doubled seven times (17 ms).
 */
#define MAX_WAIT_US		1000000U
#define SLOTS			MCP2510_TXB_COUNT

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

enum miso {
	MISO_INPUT,		/* the front of the input, then the fill byte */
	MISO_STUCK,		/* the fill byte */
	MISO_MODEL,		/* the simulated chip's answer, maybe garbled */
	MISO_COUNT
};

static const u32 osc_table[] = { MCP2510_OSC_MIN_HZ, 8000000, 16000000,
				 20000000, MCP2510_OSC_MAX_HZ };

struct hostile {
	struct fuzz_input in;
	struct mcp2510_chip chip;
	enum miso miso;
	u8 fill;			/* MISO once the input ran out */
	struct sim_bus bus;		/* MISO_MODEL: the chip and a peer */
	struct sim_chip sim;
	unsigned int garble;		/* MISO_MODEL: transfers to XOR */
	unsigned int fail_every;	/* every N-th transfer fails; 0: never */
	unsigned long xfers;		/* all transfers */
	unsigned long call_xfers;	/* during the current call */
	unsigned long long call_delay_us;
	/* submitted frames not yet reported, oldest first */
	unsigned int queue[SLOTS];
	unsigned int queued;
};

/* Instructions the core may send to this variant, with their lengths. */
static void check_instruction(const struct hostile *h, const u8 *tx,
			      unsigned int len)
{
	bool buffer_instrs = h->chip.variant->has_buffer_instrs;
	u8 instr = tx[0];

	switch (instr) {
	case MCP2510_INSTR_RESET:
		FUZZ_CHECK(len == 1);
		return;
	case MCP2510_INSTR_READ:
	case MCP2510_INSTR_WRITE:
		FUZZ_CHECK(len >= 3);
		FUZZ_CHECK(tx[1] + len - 2 <= MCP2510_REG_COUNT);
		return;
	case MCP2510_INSTR_BIT_MODIFY:
		FUZZ_CHECK(len == 4);
		return;
	case MCP2510_INSTR_READ_STATUS:
		FUZZ_CHECK(len == 2);
		return;
	case MCP2515_INSTR_RX_STATUS:
		FUZZ_CHECK(buffer_instrs && len == 2);
		return;
	}
	if ((instr & ~MCP2510_RTS_ALL) == MCP2510_INSTR_RTS) {
		FUZZ_CHECK(instr != MCP2510_INSTR_RTS && len == 1);
		return;
	}
	FUZZ_CHECK(buffer_instrs);
	if ((instr & ~0x06) == MCP2515_INSTR_READ_RX_BUFFER) {
		FUZZ_CHECK(len >= 2 && len <= 1 + MCP2510_FRAME_REGS);
		return;
	}
	FUZZ_CHECK((instr & ~0x07) == MCP2515_INSTR_LOAD_TX_BUFFER &&
		   (instr & 0x07) < 6);
	FUZZ_CHECK(len >= 2 && len <= 1 + MCP2510_FRAME_REGS);
}

static int hostile_xfer(void *ctx, const u8 *tx, u8 *rx, unsigned int len)
{
	struct hostile *h = ctx;
	size_t got = 0;

	FUZZ_CHECK(tx && len >= 1 && len <= LONGEST_XFER);
	check_instruction(h, tx, len);
	h->xfers++;
	FUZZ_CHECK(++h->call_xfers <= MAX_XFERS_PER_CALL);
	if (h->fail_every && h->xfers % h->fail_every == 0)
		return -EIO;
	if (h->miso == MISO_MODEL) {
		u8 flip[LONGEST_XFER] = { 0 };
		unsigned int i;

		sim_chip_spi(&h->sim, tx, rx, len);
		if (!rx || !h->garble)
			return 0;
		h->garble--;
		fuzz_front_bytes(&h->in, flip, len);
		for (i = 0; i < len; i++)
			rx[i] ^= flip[i];
		return 0;
	}
	if (rx) {
		if (h->miso == MISO_INPUT)
			got = fuzz_front_bytes(&h->in, rx, len);
		memset(rx + got, h->fill, len - got);
	}
	return 0;
}

static void hostile_delay(void *ctx, unsigned int us)
{
	struct hostile *h = ctx;

	FUZZ_CHECK(us > 0 && us <= MAX_WAIT_US);
	h->call_delay_us += us;
	FUZZ_CHECK(h->call_delay_us <= MAX_DELAY_PER_CALL_US);
	if (h->miso == MISO_MODEL)
		sim_bus_advance(&h->bus, (u64)us * 1000);
}

static void check_frame(const struct can_frame *cf)
{
	canid_t id = cf->can_id & ~(CAN_EFF_FLAG | CAN_RTR_FLAG);
	unsigned int i;

	FUZZ_CHECK(!(cf->can_id & CAN_ERR_FLAG));
	FUZZ_CHECK(id <= (cf->can_id & CAN_EFF_FLAG ? CAN_EFF_MASK :
			  CAN_SFF_MASK));
	FUZZ_CHECK(cf->len <= CAN_MAX_DLEN);
	/* a remote frame carries a length but no data */
	for (i = 0; i < CAN_MAX_DLEN; i++)
		FUZZ_CHECK(cf->data[i] == 0 ||
			   (!(cf->can_id & CAN_RTR_FLAG) && i < cf->len));
}

static void on_rx(void *ctx, const struct can_frame *cf)
{
	(void)ctx;
	check_frame(cf);
}

static void tx_forget(struct hostile *h, unsigned int pos)
{
	for (; pos + 1 < h->queued; pos++)
		h->queue[pos] = h->queue[pos + 1];
	h->queued--;
}

static unsigned int queue_pos(const struct hostile *h, unsigned int slot)
{
	unsigned int pos;

	for (pos = 0; pos < h->queued; pos++)
		if (h->queue[pos] == slot)
			return pos;
	return SLOTS;
}

static void on_tx_done(void *ctx, unsigned int slot)
{
	struct hostile *h = ctx;

	/* in queue order: the oldest outstanding frame */
	FUZZ_CHECK(h->queued && h->queue[0] == slot);
	tx_forget(h, 0);
}

static void on_tx_aborted(void *ctx, unsigned int slot)
{
	struct hostile *h = ctx;
	unsigned int pos = queue_pos(h, slot);

	FUZZ_CHECK(pos < h->queued);
	tx_forget(h, pos);
}

static void on_state(void *ctx, enum can_state state,
		     const struct can_berr_counter *bec)
{
	(void)ctx;
	(void)bec;
	FUZZ_CHECK(state == CAN_STATE_ERROR_ACTIVE ||
		   state == CAN_STATE_ERROR_WARNING ||
		   state == CAN_STATE_ERROR_PASSIVE ||
		   state == CAN_STATE_BUS_OFF);
}

static void on_error(void *ctx, const struct can_frame *cf)
{
	(void)ctx;
	FUZZ_CHECK(cf->can_id & CAN_ERR_FLAG);
	FUZZ_CHECK(!(cf->can_id & ~(CAN_ERR_FLAG | CAN_ERR_MASK)));
	FUZZ_CHECK(cf->len == CAN_ERR_DLC);
}

static const struct mcp2510_ops hostile_ops = {
	.xfer = hostile_xfer,
	.delay_us = hostile_delay,
};

static const struct mcp2510_events hostile_events = {
	.rx = on_rx,
	.tx_done = on_tx_done,
	.tx_aborted = on_tx_aborted,
	.state = on_state,
	.error = on_error,
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
	FUZZ_CHECK(h->chip.irq_edge || passes == 1);
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

static void hostile_init(struct hostile *h, const uint8_t *data, size_t size)
{
	enum mcp2510_model model;
	u32 osc;

	memset(h, 0, sizeof(*h));
	fuzz_input_init(&h->in, data, size);
	model = fuzz_back_below(&h->in, MCP2510_MODEL_MCP25625 + 1);
	osc = osc_table[fuzz_back_below(&h->in, ARRAY_SIZE(osc_table))];
	h->miso = fuzz_back_below(&h->in, MISO_COUNT);
	h->fill = fuzz_back_u8(&h->in);
	h->fail_every = fuzz_back_u8(&h->in) % 16;
	FUZZ_CHECK(mcp2510_init(&h->chip, mcp2510_variant_get(model), osc,
				&hostile_ops, &hostile_events, h) == 0);
	h->chip.irq_edge = fuzz_back_bool(&h->in);
	if (h->miso != MISO_MODEL)
		return;
	sim_bus_init(&h->bus);
	FUZZ_CHECK(sim_chip_init(&h->sim, model == MCP2510_MODEL_MCP2510 ?
				 SIM_MCP2510 : SIM_MCP2515, osc) == 0);
	FUZZ_CHECK(sim_bus_attach(&h->bus, &h->sim) == 0);
	/* the peer acknowledges: a lone node would retry for ever */
	sim_phantom_attach(&h->bus, 0);
	sim_bus_advance(&h->bus, sim_chip_startup_ns(&h->sim));
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
