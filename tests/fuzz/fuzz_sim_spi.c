// SPDX-License-Identifier: GPL-2.0
/*
 * The chip model's SPI decoder under arbitrary byte streams.
 *
 * Two chips share a bus with the phantom node.  The input is a script:
 * decisions from its back (fuzz_input.h) pick chip-select periods of any
 * length, time steps, peer frames, power cuts, RTS pin edges and faults;
 * the MOSI bytes come from its front.  Every transfer gets buffers of
 * exactly its length, so ASan sees any access past them.
 *
 * Beyond "no crash, no overrun, no hang", after every step the model must
 * keep the promises mcp2510_sim.h makes: INT follows CANINTE & CANINTF,
 * CANSTAT shows the operating mode, counters count every transfer, an
 * unready chip answers 0xff, time only moves forward and by exactly the
 * step asked for, callbacks may transfer but not advance time, and frames
 * on the bus never overlap.
 */
#include <stdlib.h>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "mcp2510_sim.h"

#define NCHIPS		2
/* One step never runs the bus for more than ~1 ms: bounded work per input. */
#define STEP_NS_UNIT	16
#define JUMP_MAX_NS	1000000ULL
#define MAX_FLOOD	64

enum op {
	OP_SPI,
	OP_SPI_AGAIN,		/* weight: transfers are what this target is about */
	OP_ADVANCE,
	OP_ADVANCE_NEXT,
	OP_PHANTOM_SEND,
	OP_PHANTOM_FLOOD,
	OP_PHANTOM_DETACH,
	OP_POWER,
	OP_RTS,
	OP_BUS_FAULTS,
	OP_CHIP_FAULTS,
	OP_COUNT
};

static const u32 osc_table[] = { 4000000, 8000000, 10000000, 16000000,
				 20000000, 25000000 };
static const u32 phantom_rates[] = { 0, 125000, 250000, 500000, 1000000 };

struct rig {
	struct sim_bus bus;
	struct sim_chip chip[NCHIPS];
	bool powered[NCHIPS];		/* as the harness switched them */
	bool service_in_callback;	/* pin callbacks read CANINTF */
	bool advancing;			/* inside sim_bus_advance*() */
	u32 callback_xfers[NCHIPS];	/* transfers made from callbacks */
	u64 bytes_in_callbacks[NCHIPS];
	bool have_record;
	u64 last_end_ns;
};

static unsigned int chip_index(const struct rig *rig, const struct sim_chip *chip)
{
	return (unsigned int)(chip - rig->chip);
}

/*
 * A driver services INT from its interrupt handler, which may run while
 * the bus is advancing: read the flags, and from inside an advance try
 * to advance time, which the model must refuse.
 */
static void pin_changed(void *ctx, struct sim_chip *chip, enum sim_pin pin,
			bool level)
{
	static const u8 read_flags[] = { MCP2510_INSTR_READ,
					 MCP2510_REG_CANINTF, 0, 0 };
	struct rig *rig = ctx;
	u8 rx[sizeof(read_flags)];
	u64 now = sim_bus_now(&rig->bus);

	FUZZ_CHECK(pin < SIM_PIN_COUNT);
	if (pin != SIM_PIN_INT || level || !rig->service_in_callback)
		return;
	rig->callback_xfers[chip_index(rig, chip)]++;
	rig->bytes_in_callbacks[chip_index(rig, chip)] += sizeof(read_flags);
	sim_chip_spi(chip, read_flags, rx, sizeof(read_flags));
	if (!rig->advancing)
		return;
	sim_bus_advance(&rig->bus, 1000);
	FUZZ_CHECK(sim_bus_now(&rig->bus) == now);
}

static void bus_record(void *ctx, const struct sim_bus_record *rec)
{
	struct rig *rig = ctx;

	FUZZ_CHECK(rec->kind == SIM_REC_FRAME || rec->kind == SIM_REC_ERROR);
	FUZZ_CHECK(rec->sender == SIM_NODE_PHANTOM ||
		   (rec->sender >= 0 && rec->sender < NCHIPS));
	FUZZ_CHECK(rec->frame.len <= CAN_MAX_DLEN);
	FUZZ_CHECK(rec->end_ns > rec->start_ns);
	FUZZ_CHECK(rec->bits > 0);
	/* one bus: a frame starts after the previous one ended */
	FUZZ_CHECK(!rig->have_record || rec->start_ns >= rig->last_end_ns);
	rig->have_record = true;
	rig->last_end_ns = rec->end_ns;
}

static void check_chip(const struct rig *rig, const struct sim_chip *chip)
{
	u8 pending = sim_chip_peek(chip, MCP2510_REG_CANINTE) &
		     sim_chip_peek(chip, MCP2510_REG_CANINTF);
	u8 canstat = sim_chip_peek(chip, MCP2510_REG_CANSTAT);
	bool powered = rig->powered[chip_index(rig, chip)];

	FUZZ_CHECK(sim_chip_pin(chip, SIM_PIN_INT) == (!powered || !pending));
	FUZZ_CHECK(FIELD_GET(MCP2510_CANSTAT_OPMOD_MASK, canstat) ==
		   sim_chip_opmode(chip));
	FUZZ_CHECK(sim_chip_peek(chip, MCP2510_REG_TEC) ==
		   (sim_chip_tec(chip) > 255 ? 255 : sim_chip_tec(chip)));
	FUZZ_CHECK(sim_chip_peek(chip, MCP2510_REG_REC) ==
		   (sim_chip_rec(chip) > 255 ? 255 : sim_chip_rec(chip)));
	FUZZ_CHECK(sim_chip_bus_off(chip) ==
		   !!(sim_chip_peek(chip, MCP2510_REG_EFLG) & MCP2510_EFLG_TXBO));
	FUZZ_CHECK(!powered || !sim_chip_timing_valid(chip) ||
		   sim_chip_bitrate(chip) > 0);
	FUZZ_CHECK(sim_bus_next_event(&rig->bus) >= sim_bus_now(&rig->bus));
}

static bool all_bytes(const u8 *buf, size_t len, u8 val)
{
	size_t i;

	for (i = 0; i < len; i++)
		if (buf[i] != val)
			return false;
	return true;
}

/* One chip-select-low period of any length, to either chip. */
static void do_spi(struct rig *rig, struct fuzz_input *in)
{
	unsigned int n = fuzz_back_below(in, NCHIPS);
	struct sim_chip *chip = &rig->chip[n];
	bool want_rx = !fuzz_back_bool(in);
	size_t len = fuzz_back_u8(in);
	const struct sim_counters *cnt = sim_chip_counters(chip);
	u64 transfers = cnt->spi_transfers, bytes = cnt->spi_bytes;
	bool answers = sim_chip_ready(chip) || sim_chip_faults(chip)->spi_corrupt;
	u8 *tx = malloc(len ? len : 1);
	u8 *rx = want_rx ? malloc(len ? len : 1) : NULL;

	FUZZ_CHECK(tx && (rx || !want_rx));
	len = fuzz_front_bytes(in, tx, len);
	rig->callback_xfers[n] = 0;
	rig->bytes_in_callbacks[n] = 0;
	sim_chip_spi(chip, tx, rx, len);

	FUZZ_CHECK(cnt->spi_transfers == transfers + 1 + rig->callback_xfers[n]);
	FUZZ_CHECK(cnt->spi_bytes == bytes + len + rig->bytes_in_callbacks[n]);
	/* start-up, unpowered: MISO floats and the pull-up wins */
	if (rx && !answers)
		FUZZ_CHECK(all_bytes(rx, len, 0xff));
	free(tx);
	free(rx);
}

static void do_advance(struct rig *rig, struct fuzz_input *in)
{
	u64 ns = (u64)fuzz_back_u16(in) * STEP_NS_UNIT;
	u64 before = sim_bus_now(&rig->bus);

	rig->advancing = true;
	sim_bus_advance(&rig->bus, ns);
	rig->advancing = false;
	FUZZ_CHECK(sim_bus_now(&rig->bus) == before + ns);
}

static void do_advance_next(struct rig *rig)
{
	u64 now = sim_bus_now(&rig->bus);
	u64 next = sim_bus_next_event(&rig->bus);

	if (next == U64_MAX || next - now > JUMP_MAX_NS)
		return;
	rig->advancing = true;
	sim_bus_advance_to(&rig->bus, next);
	rig->advancing = false;
	FUZZ_CHECK(sim_bus_now(&rig->bus) == next);
}

static struct can_frame take_frame(struct fuzz_input *in)
{
	struct can_frame cf = { 0 };
	unsigned int i;

	cf.can_id = fuzz_back_u32(in);
	cf.len = fuzz_back_u8(in) % (CAN_MAX_DLEN + 2);	/* 9: invalid */
	for (i = 0; i < CAN_MAX_DLEN; i++)
		cf.data[i] = fuzz_back_u8(in);
	return cf;
}

static u32 take_phantom_rate(struct fuzz_input *in)
{
	unsigned int i = fuzz_back_below(in, ARRAY_SIZE(phantom_rates) + 1);

	/* one choice in six is any number at all, to try the validation */
	return i < ARRAY_SIZE(phantom_rates) ? phantom_rates[i] :
	       fuzz_back_u32(in);
}

static void do_phantom_send(struct rig *rig, struct fuzz_input *in)
{
	struct can_frame cf = take_frame(in);
	int ret = sim_phantom_send(&rig->bus, &cf, take_phantom_rate(in));

	FUZZ_CHECK(ret == 0 || ret == -ENOSPC || ret == -EINVAL);
	FUZZ_CHECK(ret != 0 || cf.len <= CAN_MAX_DLEN);
}

static void do_phantom_flood(struct rig *rig, struct fuzz_input *in)
{
	struct can_frame cf = take_frame(in);
	u32 count = fuzz_back_below(in, MAX_FLOOD + 1);
	int ret = sim_phantom_flood(&rig->bus, &cf, count, take_phantom_rate(in));

	FUZZ_CHECK(ret == 0 || ret == -EBUSY || ret == -EINVAL);
}

static void do_power(struct rig *rig, struct fuzz_input *in)
{
	unsigned int n = fuzz_back_below(in, NCHIPS);
	struct sim_chip *chip = &rig->chip[n];
	bool on = fuzz_back_bool(in);
	bool was_on = rig->powered[n];

	sim_chip_power(chip, on);
	rig->powered[n] = on;
	/* power-on is a reset: start-up begins again */
	FUZZ_CHECK(!on || was_on || !sim_chip_ready(chip));
	FUZZ_CHECK(on || !sim_chip_ready(chip));
}

static void do_rts(struct rig *rig, struct fuzz_input *in)
{
	struct sim_chip *chip = &rig->chip[fuzz_back_below(in, NCHIPS)];
	/* pin 3 does not exist: the model must ignore it */
	unsigned int pin = fuzz_back_below(in, MCP2510_TXB_COUNT + 1);

	sim_chip_set_rts(chip, pin, fuzz_back_bool(in));
}

static void do_bus_faults(struct rig *rig, struct fuzz_input *in)
{
	struct sim_bus_faults *f = sim_bus_faults(&rig->bus);

	f->bus_errors = fuzz_back_below(in, 4);
	f->no_ack = fuzz_back_bool(in);
}

static void do_chip_faults(struct rig *rig, struct fuzz_input *in)
{
	struct sim_chip_faults *f =
		sim_chip_faults(&rig->chip[fuzz_back_below(in, NCHIPS)]);

	f->spi_corrupt = fuzz_back_below(in, 3);
	f->spi_corrupt_xor = fuzz_back_u8(in);
	f->wake_delay_ns = (u64)fuzz_back_u16(in) * STEP_NS_UNIT;
	f->mode_delay_ns = (u64)fuzz_back_u16(in) * STEP_NS_UNIT;
}

static void run_op(struct rig *rig, struct fuzz_input *in)
{
	switch (fuzz_back_below(in, OP_COUNT)) {
	case OP_SPI:
	case OP_SPI_AGAIN:
		do_spi(rig, in);
		break;
	case OP_ADVANCE:
		do_advance(rig, in);
		break;
	case OP_ADVANCE_NEXT:
		do_advance_next(rig);
		break;
	case OP_PHANTOM_SEND:
		do_phantom_send(rig, in);
		break;
	case OP_PHANTOM_FLOOD:
		do_phantom_flood(rig, in);
		break;
	case OP_PHANTOM_DETACH:
		sim_phantom_detach(&rig->bus);
		break;
	case OP_POWER:
		do_power(rig, in);
		break;
	case OP_RTS:
		do_rts(rig, in);
		break;
	case OP_BUS_FAULTS:
		do_bus_faults(rig, in);
		break;
	default:
		do_chip_faults(rig, in);
		break;
	}
}

static void rig_init(struct rig *rig, struct fuzz_input *in)
{
	unsigned int n;

	memset(rig, 0, sizeof(*rig));
	sim_bus_init(&rig->bus);
	sim_bus_set_monitor(&rig->bus, bus_record, rig);
	rig->service_in_callback = fuzz_back_bool(in);
	for (n = 0; n < NCHIPS; n++) {
		enum sim_variant v = fuzz_back_bool(in) ? SIM_MCP2515 : SIM_MCP2510;
		u32 osc = osc_table[fuzz_back_below(in, ARRAY_SIZE(osc_table))];

		FUZZ_CHECK(sim_chip_init(&rig->chip[n], v, osc) == 0);
		rig->powered[n] = true;
		sim_chip_set_pin_cb(&rig->chip[n], pin_changed, rig);
		FUZZ_CHECK(sim_bus_attach(&rig->bus, &rig->chip[n]) == 0);
	}
	if (fuzz_back_bool(in))
		sim_phantom_attach(&rig->bus, 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static struct rig rig;
	struct fuzz_input in;
	unsigned int n;

	fuzz_input_init(&in, data, size);
	rig_init(&rig, &in);
	while (fuzz_input_left(&in)) {
		run_op(&rig, &in);
		for (n = 0; n < NCHIPS; n++)
			check_chip(&rig, &rig.chip[n]);
	}
	return 0;
}
