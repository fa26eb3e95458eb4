// SPDX-License-Identifier: GPL-2.0
/*
 * The hostile chip below the core in the core_hostile target, and the
 * events the core raises.
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
 *
 * Each transfer and delay is checked to be well formed for the variant
 * and within its call's bounds; each event to be a valid SocketCAN frame
 * or state, and every submitted frame to be reported exactly once,
 * tx_done in queue order.
 */
#include <string.h>

#include "fuzz_check.h"
#include "fuzz_hostile.h"

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

static const u32 osc_table[] = { MCP2510_OSC_MIN_HZ, 8000000, 16000000,
				 20000000, MCP2510_OSC_MAX_HZ };

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

static void on_rx(void *ctx, const struct can_frame *cf)
{
	(void)ctx;
	FUZZ_CHECK(!(cf->can_id & CAN_ERR_FLAG));
	fuzz_check_frame(cf);
}

static void tx_forget(struct hostile *h, unsigned int pos)
{
	for (; pos + 1 < h->queued; pos++)
		h->queue[pos] = h->queue[pos + 1];
	h->queued--;
}

unsigned int queue_pos(const struct hostile *h, unsigned int slot)
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

void hostile_init(struct hostile *h, const uint8_t *data, size_t size)
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

