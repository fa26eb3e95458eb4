// SPDX-License-Identifier: GPL-2.0
/*
 * The simulated chip seen through its SPI port: reset values, start-up,
 * instruction framing, sequential access, write protection, BIT MODIFY,
 * the MCP2515-only instructions, pins and SPI faults.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim_helpers.h"

struct rig {
	struct sim_bus bus;
	struct sim_chip chip;
};

static struct rig *rig_new(enum sim_variant variant)
{
	struct rig *r = test_calloc(1, sizeof(*r));

	sim_bus_init(&r->bus);
	simh_node_setup_125k(&r->bus, &r->chip, variant);
	return r;
}

static int setup_2510(void **state)
{
	*state = rig_new(SIM_MCP2510);
	return 0;
}

static int setup_2515(void **state)
{
	*state = rig_new(SIM_MCP2515);
	return 0;
}

/* DS21291 register summary: values after power-on / RESET */
static void test_reset_values(void **state)
{
	struct sim_chip chip;
	struct sim_bus bus;
	unsigned int n;

	(void)state;
	sim_bus_init(&bus);
	assert_int_equal(sim_chip_init(&chip, SIM_MCP2510, SIMH_OSC_16MHZ), 0);
	assert_int_equal(sim_bus_attach(&bus, &chip), 0);
	sim_bus_advance(&bus, sim_chip_startup_ns(&chip));

	assert_int_equal(simh_read(&chip, MCP2510_REG_CANSTAT), MCP2510_RESET_CANSTAT);
	/* AN739: REQOP reads 111 after power-up */
	assert_int_equal(simh_read(&chip, MCP2510_REG_CANCTRL), MCP2510_RESET_CANCTRL);
	assert_int_equal(simh_opmode(&chip), MCP2510_MODE_CONFIG);
	assert_int_equal(simh_read(&chip, MCP2510_REG_CANINTE), 0);
	assert_int_equal(simh_read(&chip, MCP2510_REG_CANINTF), 0);
	assert_int_equal(simh_read(&chip, MCP2510_REG_EFLG), 0);
	assert_int_equal(simh_read(&chip, MCP2510_REG_TEC), 0);
	assert_int_equal(simh_read(&chip, MCP2510_REG_REC), 0);
	assert_int_equal(simh_read(&chip, MCP2510_REG_BFPCTRL), 0);
	/* TXnRTS pins idle high (pull-ups), input mode: BnRTS read 1 */
	assert_int_equal(simh_read(&chip, MCP2510_REG_TXRTSCTRL), 0x38);
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		assert_int_equal(simh_read(&chip, MCP2510_REG_TXBCTRL(n)), 0);
	for (n = 0; n < MCP2510_RXB_COUNT; n++)
		assert_int_equal(simh_read(&chip, MCP2510_REG_RXBCTRL(n)), 0);
	assert_true(sim_chip_pin(&chip, SIM_PIN_INT));
	assert_true(sim_chip_pin(&chip, SIM_PIN_RX0BF));
	assert_true(sim_chip_pin(&chip, SIM_PIN_RX1BF));

	/* the MCP2515 has OSM and resets REQOP to configuration */
	assert_int_equal(sim_chip_init(&chip, SIM_MCP2515, SIMH_OSC_16MHZ), 0);
	assert_int_equal(simh_read(&chip, MCP2510_REG_CANCTRL), MCP2515_RESET_CANCTRL);
	assert_int_equal(sim_chip_init(&chip, 7, SIMH_OSC_16MHZ), -EINVAL);
	assert_int_equal(sim_chip_init(&chip, SIM_MCP2510, 0), -EINVAL);
}

/* bytes of the register file that hold something other than 0 */
static unsigned int nonzero_bytes(const u8 *regs, unsigned int from,
				  unsigned int to)
{
	unsigned int n = 0;

	for (; from < to; from++)
		n += regs[from] != 0;
	return n;
}

/*
 * DS21801 / DS21291 register legends: the transmit buffers' SIDH..D7
 * ("R/W-x"), the receive buffers ("R-x"), the filters and the masks are
 * unknown at power-on, so the model fills them with garbage; their
 * unimplemented bits still read 0, and every control register has its
 * number.
 */
static void test_unknown_at_power_on(void **state)
{
	static const enum sim_variant variants[] = { SIM_MCP2510, SIM_MCP2515 };
	struct sim_chip chip;
	struct sim_bus bus;
	u8 regs[MCP2510_REG_COUNT];
	unsigned int v, n;

	(void)state;
	for (v = 0; v < ARRAY_SIZE(variants); v++) {
		sim_bus_init(&bus);
		assert_int_equal(sim_chip_init(&chip, variants[v], SIMH_OSC_16MHZ), 0);
		assert_int_equal(sim_bus_attach(&bus, &chip), 0);
		sim_bus_advance(&bus, sim_chip_startup_ns(&chip));
		simh_read_seq(&chip, 0, regs, sizeof(regs));

		/* filters 0-2, 3-5 and the masks: 36 bytes, nearly all set */
		assert_true(nonzero_bytes(regs, 0x00, 0x0c) > 6);
		assert_true(nonzero_bytes(regs, 0x10, 0x1c) > 6);
		assert_true(nonzero_bytes(regs, 0x20, 0x28) > 4);
		for (n = 0; n < MCP2510_TXB_COUNT; n++) {
			u8 b = MCP2510_REG_TXB(n);

			assert_true(nonzero_bytes(regs, b + MCP2510_BUF_SIDH,
						  b + MCP2510_BUF_LEN) > 6);
			assert_int_equal(regs[b + MCP2510_BUF_CTRL], 0);
			assert_int_equal(regs[b + MCP2510_BUF_SIDL] & 0x14, 0);
			assert_int_equal(regs[b + MCP2510_BUF_DLC] & 0xb0, 0);
		}
		for (n = 0; n < MCP2510_RXB_COUNT; n++) {
			u8 b = MCP2510_REG_RXB(n);

			assert_true(nonzero_bytes(regs, b + MCP2510_BUF_SIDH,
						  b + MCP2510_BUF_LEN) > 6);
			assert_int_equal(regs[b + MCP2510_BUF_CTRL], 0);
			assert_int_equal(regs[b + MCP2510_BUF_SIDL] & 0x04, 0);
			assert_int_equal(regs[b + MCP2510_BUF_DLC] & 0x80, 0);
		}
		for (n = 0; n < 6; n++)
			assert_int_equal(regs[MCP2510_REG_RXF(n) + MCP2510_ID_SIDL] & 0x14, 0);
		for (n = 0; n < 2; n++)
			assert_int_equal(regs[MCP2510_REG_RXM(n) + MCP2510_ID_SIDL] & 0x1c, 0);
		/* BFPCTRL .. CANINTF, EFLG: numbers, not garbage */
		assert_int_equal(nonzero_bytes(regs, MCP2510_REG_CNF3,
					       MCP2510_REG_CANINTF + 1), 0);
		assert_int_equal(regs[MCP2510_REG_EFLG], 0);
		assert_int_equal(regs[MCP2510_REG_TEC], 0);
		assert_int_equal(regs[MCP2510_REG_REC], 0);
	}
}

/*
 * The garbage follows the seed: the same seed gives the same bytes (runs
 * repeat), another seed others.  RESET leaves new garbage by default;
 * reset_keeps_unknown takes the reading where it leaves them alone.
 */
static void test_unknown_seeds(void **state)
{
	struct sim_chip a, b;
	u8 ra[MCP2510_REG_COUNT], rb[MCP2510_REG_COUNT];

	(void)state;
	assert_int_equal(sim_chip_init_seeded(&a, SIM_MCP2515, SIMH_OSC_16MHZ, 1), 0);
	assert_int_equal(sim_chip_init_seeded(&b, SIM_MCP2515, SIMH_OSC_16MHZ, 1), 0);
	simh_read_seq(&a, 0, ra, sizeof(ra));
	simh_read_seq(&b, 0, rb, sizeof(rb));
	assert_memory_equal(ra, rb, sizeof(ra));
	assert_int_equal(sim_chip_init_seeded(&b, SIM_MCP2515, SIMH_OSC_16MHZ, 2), 0);
	simh_read_seq(&b, 0, rb, sizeof(rb));
	assert_memory_not_equal(ra + MCP2510_REG_TXB(0), rb + MCP2510_REG_TXB(0),
				MCP2510_BUF_LEN);

	/* RESET: new garbage (no bus: no start-up time) */
	simh_reset(&a);
	simh_read_seq(&a, 0, rb, sizeof(rb));
	assert_memory_not_equal(ra + MCP2510_REG_TXB(0), rb + MCP2510_REG_TXB(0),
				MCP2510_BUF_LEN);
	/* the other reading: RESET keeps them, power-on does not */
	sim_chip_faults(&a)->reset_keeps_unknown = true;
	simh_read_seq(&a, 0, ra, sizeof(ra));
	simh_reset(&a);
	sim_chip_reset_pin(&a);
	simh_read_seq(&a, 0, rb, sizeof(rb));
	assert_memory_equal(ra, rb, sizeof(ra));
	sim_chip_power(&a, false);
	sim_chip_power(&a, true);
	simh_read_seq(&a, 0, rb, sizeof(rb));
	assert_memory_not_equal(ra + MCP2510_REG_RXB(0), rb + MCP2510_REG_RXB(0),
				MCP2510_BUF_LEN);
}

/* AN739 "Resetting the MCP2510": held in reset for 128 oscillator cycles */
static void test_startup_after_reset(void **state)
{
	struct rig *r = *state;
	u8 tx[3] = { MCP2510_INSTR_READ, MCP2510_REG_CANSTAT, 0 }, rx[3];
	u64 ignored;

	assert_int_equal(sim_chip_startup_ns(&r->chip), 8000);	/* 128 / 16 MHz */
	simh_write(&r->chip, MCP2510_REG_CNF1, 0x3f);
	tx[0] = MCP2510_INSTR_RESET;
	sim_chip_spi(&r->chip, tx, NULL, 1);
	assert_false(sim_chip_ready(&r->chip));
	assert_int_equal(sim_bus_next_event(&r->bus), sim_bus_now(&r->bus) + 8000);

	/* during start-up the chip does not answer: SO floats high */
	ignored = sim_chip_counters(&r->chip)->spi_ignored;
	tx[0] = MCP2510_INSTR_READ;
	sim_chip_spi(&r->chip, tx, rx, sizeof(tx));
	assert_int_equal(rx[2], 0xff);
	simh_write(&r->chip, MCP2510_REG_CNF2, 0x12);	/* lost */
	assert_int_equal(sim_chip_counters(&r->chip)->spi_ignored, ignored + 2);

	sim_bus_advance(&r->bus, 7999);
	assert_false(sim_chip_ready(&r->chip));
	sim_bus_advance(&r->bus, 1);
	assert_true(sim_chip_ready(&r->chip));
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0x80);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CNF1), 0);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CNF2), 0);
}

/* AN739 "SPI Read": the address pointer increments; it has 7 bits and wraps */
static void test_sequential_read_wraps(void **state)
{
	struct rig *r = *state;
	u8 out[4];

	simh_write(&r->chip, MCP2510_REG_RXFSIDH(0), 0x5a);
	simh_write(&r->chip, MCP2510_REG_RXFSIDL(0), 0xff);
	simh_read_seq(&r->chip, 0x7e, out, sizeof(out));
	assert_int_equal(out[0], 0x80);		/* CANSTAT mirror at 7e */
	assert_int_equal(out[1], MCP2510_RESET_CANCTRL);	/* CANCTRL at 7f */
	assert_int_equal(out[2], 0x5a);		/* wrapped to 00 */
	assert_int_equal(out[3], 0xeb);		/* SIDL: bits 4 and 2 unimplemented */

	/* sequential WRITE wraps the same way */
	{
		/* rewrite CANCTRL unchanged, then filter 0 */
		u8 data[3] = { MCP2510_RESET_CANCTRL, 0x11, 0x22 };

		simh_write_seq(&r->chip, 0x7f, data, sizeof(data));
		assert_int_equal(simh_read(&r->chip, 0x00), 0x11);
		assert_int_equal(simh_read(&r->chip, 0x01), 0x22 & 0xeb);
	}
}

/* DS21291 register map: CANSTAT and CANCTRL at 0xXE / 0xXF of every row */
static void test_canstat_canctrl_mirrors(void **state)
{
	struct rig *r = *state;
	unsigned int row;

	for (row = 0; row < 8; row++) {
		assert_int_equal(simh_read(&r->chip, row << 4 | 0x0e), 0x80);
		assert_int_equal(simh_read(&r->chip, row << 4 | 0x0f),
				 MCP2510_RESET_CANCTRL);
	}
	/* a write through a mirror is a write to CANCTRL: request loopback */
	simh_write(&r->chip, 0x3f, FIELD_PREP(MCP2510_CANCTRL_REQOP_MASK,
					      MCP2510_MODE_LOOPBACK));
	assert_int_equal(simh_opmode(&r->chip), MCP2510_MODE_LOOPBACK);
	assert_int_equal(simh_read(&r->chip, 0x5e) >> 5, MCP2510_MODE_LOOPBACK);
	/* CANSTAT is read only */
	simh_write(&r->chip, MCP2510_REG_CANSTAT, 0x00);
	assert_int_equal(simh_opmode(&r->chip), MCP2510_MODE_LOOPBACK);
}

/*
 * AN739 "Set Bit Timing" / DS21801 10.1: CNF1-3, TXRTSCTRL, filters and
 * masks can only be modified in configuration mode.
 */
static void test_write_protection(void **state)
{
	struct rig *r = *state;
	static const u8 protected_regs[] = {
		MCP2510_REG_CNF1, MCP2510_REG_CNF2, MCP2510_REG_CNF3,
		MCP2510_REG_TXRTSCTRL, MCP2510_REG_RXFSIDH(0),
		MCP2510_REG_RXFEID0(5), MCP2510_REG_RXMSIDH(0),
		MCP2510_REG_RXMEID0(1),
	};
	u8 before[sizeof(protected_regs)];
	unsigned int i;

	simh_write(&r->chip, MCP2510_REG_RXFSIDH(0), 0x12);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_RXFSIDH(0)), 0x12);
	assert_int_equal(simh_set_mode(&r->chip, MCP2510_MODE_NORMAL), 0);
	for (i = 0; i < sizeof(protected_regs); i++) {
		before[i] = simh_read(&r->chip, protected_regs[i]);
		simh_write(&r->chip, protected_regs[i], 0x05);
		simh_bit_modify(&r->chip, protected_regs[i], 0xff, 0x06);
		assert_int_equal(simh_read(&r->chip, protected_regs[i]), before[i]);
	}
	/* registers that stay writable in normal mode */
	simh_write(&r->chip, MCP2510_REG_CANINTE, 0xa5);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTE), 0xa5);
	simh_write(&r->chip, MCP2510_REG_BFPCTRL, 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_BFPCTRL), 0x3f);
	simh_write(&r->chip, MCP2510_REG_TXBD(1, 7), 0x77);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBD(1, 7)), 0x77);
	/* read-only registers in any mode (RXB0 D0 holds its power-up garbage) */
	before[0] = simh_read(&r->chip, MCP2510_REG_RXBD(0, 0));
	simh_write(&r->chip, MCP2510_REG_TEC, 9);
	simh_write(&r->chip, MCP2510_REG_REC, 9);
	simh_write(&r->chip, MCP2510_REG_RXBD(0, 0), 9);
	simh_write(&r->chip, MCP2510_REG_EFLG, 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TEC), 0);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_REC), 0);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_RXBD(0, 0)), before[0]);
	/* only RXnOVR of EFLG is writable */
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_EFLG), 0xc0);

	/* back in configuration mode everything is writable again */
	assert_int_equal(simh_set_mode(&r->chip, MCP2510_MODE_CONFIG), 0);
	simh_write(&r->chip, MCP2510_REG_CNF1, 0x41);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CNF1), 0x41);
	/* CNF3 bit 7 (SOF) exists only on the MCP2515 */
	simh_write(&r->chip, MCP2510_REG_CNF3, 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CNF3), 0x47);
	/* RXB0CTRL: RXM and BUKT are writable; BUKT1 mirrors BUKT */
	simh_write(&r->chip, MCP2510_REG_RXBCTRL(0), 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_RXBCTRL(0)), 0x66);
	simh_write(&r->chip, MCP2510_REG_RXBCTRL(1), 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_RXBCTRL(1)), 0x60);
}

/*
 * DS21801 12.10: BIT MODIFY changes only the bits set in the mask; on a
 * register that is not bit-modifiable the mask is forced to FFh.
 */
static void test_bit_modify(void **state)
{
	struct rig *r = *state;
	u8 tx[4] = { MCP2510_INSTR_BIT_MODIFY, MCP2510_REG_CANINTE, 0xff, 0xff };

	simh_write(&r->chip, MCP2510_REG_CANINTE, 0x0f);
	simh_bit_modify(&r->chip, MCP2510_REG_CANINTE, 0x3c, 0xf0);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTE), 0x33);

	/* TXB0SIDH is not bit-modifiable: a plain write of the data byte */
	simh_write(&r->chip, MCP2510_REG_TXBSIDH(0), 0xf0);
	simh_bit_modify(&r->chip, MCP2510_REG_TXBSIDH(0), 0x01, 0x0f);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBSIDH(0)), 0x0f);
	/* nor are filters */
	simh_write(&r->chip, MCP2510_REG_RXFSIDH(2), 0xff);
	simh_bit_modify(&r->chip, MCP2510_REG_RXFSIDH(2), 0x80, 0x00);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_RXFSIDH(2)), 0x00);

	/* CS raised before the data byte: nothing changes */
	sim_chip_spi(&r->chip, tx, NULL, 3);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTE), 0x33);
	/* bit-modifiable everywhere it should be: TXBnCTRL, RXBnCTRL, CNF */
	simh_bit_modify(&r->chip, MCP2510_REG_TXBCTRL(2), 0x03, 0x02);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBCTRL(2)), 0x02);
	simh_bit_modify(&r->chip, MCP2510_REG_RXBCTRL(1), 0x60, 0x20);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_RXBCTRL(1)), 0x20);
	simh_write(&r->chip, MCP2510_REG_CNF2, 0x90);
	simh_bit_modify(&r->chip, MCP2510_REG_CNF2, 0x07, 0x05);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CNF2), 0x95);
}

/* DS21801 12.8 / AN739 "SPI Read Status": one byte, repeated while clocked */
static void test_read_status_repeats(void **state)
{
	struct rig *r = *state;
	u8 tx[5] = { MCP2510_INSTR_READ_STATUS }, rx[5];
	unsigned int i;

	/* TXREQ may be set in configuration mode; nothing is sent there */
	simh_rts(&r->chip, MCP2510_RTS_TXB(0) | MCP2510_RTS_TXB(2));
	simh_write(&r->chip, MCP2510_REG_CANINTF, MCP2510_INT_RX1 | MCP2510_INT_TX1);
	sim_chip_spi(&r->chip, tx, rx, sizeof(tx));
	assert_int_equal(rx[0], 0xff);
	for (i = 1; i < sizeof(rx); i++)
		assert_int_equal(rx[i], MCP2510_STATUS_TX0REQ | MCP2510_STATUS_TX2REQ |
					MCP2510_STATUS_RX1IF | MCP2510_STATUS_TX1IF);
	/* AN739 example 4 polls "& 0x54" for pending buffers */
	assert_int_equal(simh_read_status(&r->chip) & 0x54, 0x44);
}

/*
 * READ RX BUFFER, LOAD TX BUFFER and RX STATUS do not exist on the
 * MCP2510 (DS21291 instruction table): no effect, SO stays high-Z (0xff).
 */
static void test_mcp2515_instructions_on_mcp2510(void **state)
{
	struct rig *r = *state;
	u8 tx[6] = { 0 }, rx[6];
	u64 ignored = sim_chip_counters(&r->chip)->spi_ignored;
	unsigned int i;

	simh_write(&r->chip, MCP2510_REG_CANINTF, MCP2510_INT_RX0);
	tx[0] = MCP2515_INSTR_READ_RX_BUFFER;
	sim_chip_spi(&r->chip, tx, rx, sizeof(rx));
	for (i = 0; i < sizeof(rx); i++)
		assert_int_equal(rx[i], 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTF), MCP2510_INT_RX0);

	tx[0] = MCP2515_INSTR_LOAD_TX_BUFFER | MCP2515_LOAD_TXB_D0(0);
	tx[1] = simh_read(&r->chip, MCP2510_REG_TXBD(0, 0)) ^ 0xff;
	sim_chip_spi(&r->chip, tx, rx, 2);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBD(0, 0)), tx[1] ^ 0xff);

	tx[0] = MCP2515_INSTR_RX_STATUS;
	sim_chip_spi(&r->chip, tx, rx, 2);
	assert_int_equal(rx[1], 0xff);
	assert_int_equal(sim_chip_counters(&r->chip)->spi_ignored, ignored + 3);
}

/* DS21801 12.4, 12.6, 12.9 on the MCP2515 */
static void test_mcp2515_instructions(void **state)
{
	struct rig *r = *state;
	u8 d[8] = { 1, 2, 3, 4, 5, 6, 7, 8 };
	struct can_frame cf = simh_frame(0x123, 8, d);
	u8 tx[14] = { 0 }, rx[14];
	unsigned int i;

	/* LOAD TX BUFFER at TXB1 D0, then RTS for TXB1 in loopback */
	tx[0] = MCP2515_INSTR_LOAD_TX_BUFFER | MCP2515_LOAD_TXB_SIDH(1);
	tx[1] = 0x24;		/* 0x123 >> 3 */
	tx[2] = 0x60;		/* (0x123 & 7) << 5 */
	tx[5] = 8;
	memcpy(&tx[6], d, 8);
	sim_chip_spi(&r->chip, tx, NULL, sizeof(tx));
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBSIDH(1)), 0x24);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBD(1, 7)), 8);
	tx[0] = MCP2515_INSTR_LOAD_TX_BUFFER | MCP2515_LOAD_TXB_D0(1);
	tx[1] = 0xaa;
	sim_chip_spi(&r->chip, tx, NULL, 2);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBD(1, 0)), 0xaa);
	cf.data[0] = 0xaa;

	simh_write(&r->chip, MCP2510_REG_RXBCTRL(0),
		   FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_ANY));
	assert_int_equal(simh_set_mode(&r->chip, MCP2510_MODE_LOOPBACK), 0);
	simh_rts(&r->chip, MCP2510_RTS_TXB(1));
	simh_run_idle(&r->bus, 10000000);

	/* RX STATUS: message in RXB0, standard data frame, filter 0 */
	memset(tx, 0, sizeof(tx));
	tx[0] = MCP2515_INSTR_RX_STATUS;
	sim_chip_spi(&r->chip, tx, rx, 3);
	assert_int_equal(rx[1], MCP2515_RXSTATUS_RXB0);
	assert_int_equal(rx[2], rx[1]);

	/* READ RX BUFFER from D0: data, and RXB0IF clears when CS rises */
	tx[0] = MCP2515_INSTR_READ_RX_BUFFER | MCP2515_READ_RXB_D0(0);
	sim_chip_spi(&r->chip, tx, rx, 9);
	for (i = 0; i < 8; i++)
		assert_int_equal(rx[1 + i], cf.data[i]);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTF) & MCP2510_INT_RX0, 0);

	/* an invalid LOAD TX BUFFER address (abc = 110) is not an instruction */
	{
		u64 ignored = sim_chip_counters(&r->chip)->spi_ignored;

		tx[0] = MCP2515_INSTR_LOAD_TX_BUFFER | 0x06;
		tx[1] = 0x99;
		sim_chip_spi(&r->chip, tx, NULL, 2);
		assert_int_equal(sim_chip_counters(&r->chip)->spi_ignored,
				 ignored + 1);
	}
}

/* Unknown instructions, zero-length and truncated transfers never break the chip. */
static void test_malformed_spi(void **state)
{
	struct rig *r = *state;
	u8 tx[4] = { 0x55, 0x0f, 0x00, 0x00 }, rx[4];
	u8 before[MCP2510_REG_COUNT], after[MCP2510_REG_COUNT];
	unsigned int instr;

	simh_read_seq(&r->chip, 0, before, sizeof(before));
	/* every byte that is not an instruction of this chip */
	for (instr = 0; instr < 256; instr++) {
		tx[0] = instr;
		if (instr == MCP2510_INSTR_RESET || instr == MCP2510_INSTR_WRITE ||
		    instr == MCP2510_INSTR_BIT_MODIFY ||
		    (instr & ~MCP2510_RTS_ALL) == MCP2510_INSTR_RTS)
			continue;
		sim_chip_spi(&r->chip, tx, rx, sizeof(tx));
	}
	sim_chip_spi(&r->chip, tx, rx, 0);
	sim_chip_spi(&r->chip, NULL, rx, 0);
	sim_chip_spi(&r->chip, tx, NULL, 4);
	/* WRITE with CS raised after the address: nothing written */
	tx[0] = MCP2510_INSTR_WRITE;
	sim_chip_spi(&r->chip, tx, NULL, 2);
	/* READ with CS raised after the address: nothing read, no harm */
	tx[0] = MCP2510_INSTR_READ;
	sim_chip_spi(&r->chip, tx, rx, 2);
	assert_int_equal(rx[1], 0xff);
	simh_read_seq(&r->chip, 0, after, sizeof(after));
	assert_memory_equal(before, after, sizeof(before));
	assert_true(sim_chip_ready(&r->chip));
}

/* AN739 "The Transmit Buffers": no writes to TXBn while TXREQ is set */
static void test_tx_buffer_locked(void **state)
{
	struct rig *r = *state;
	u8 sidh = simh_read(&r->chip, MCP2510_REG_TXBSIDH(0));

	simh_write(&r->chip, MCP2510_REG_TXBD(0, 0), 0x11);
	simh_rts(&r->chip, MCP2510_RTS_TXB(0));
	simh_write(&r->chip, MCP2510_REG_TXBD(0, 0), 0x22);
	simh_write(&r->chip, MCP2510_REG_TXBSIDH(0), sidh ^ 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBD(0, 0)), 0x11);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBSIDH(0)), sidh);
	assert_int_equal(sim_chip_counters(&r->chip)->tx_pending_writes, 2);
	/* the harsher reading (default): TXP is locked too */
	simh_bit_modify(&r->chip, MCP2510_REG_TXBCTRL(0), 0x03, 0x03);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBCTRL(0)), 0x08);
	assert_int_equal(sim_chip_counters(&r->chip)->tx_pending_writes, 3);
	/* the other reading: TXP stays writable */
	sim_chip_faults(&r->chip)->txp_writable_while_pending = true;
	simh_bit_modify(&r->chip, MCP2510_REG_TXBCTRL(0), 0x03, 0x03);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBCTRL(0)), 0x0b);
	assert_int_equal(sim_chip_counters(&r->chip)->tx_pending_writes, 4);
	/*
	 * clearing TXREQ aborts and unlocks, and is no violation; DS21801
	 * 3.4: ABTF only for ABAT, not for this
	 */
	simh_bit_modify(&r->chip, MCP2510_REG_TXBCTRL(0), MCP2510_TXBCTRL_TXREQ, 0);
	assert_int_equal(sim_chip_counters(&r->chip)->tx_pending_writes, 4);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBCTRL(0)), 0x03);
	simh_write(&r->chip, MCP2510_REG_TXBD(0, 0), 0x22);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBD(0, 0)), 0x22);
	/* setting TXREQ again clears ABTF, MLOA and TXERR */
	simh_bit_modify(&r->chip, MCP2510_REG_TXBCTRL(0), MCP2510_TXBCTRL_TXREQ, 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBCTRL(0)), 0x0b);
}

/* DS21291 register 3-2 TXRTSCTRL and AN739 "Transmitting a Message" (pins) */
static void test_txrts_pins(void **state)
{
	struct rig *r = *state;

	sim_chip_set_rts(&r->chip, 1, false);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXRTSCTRL), 0x28);
	/* input mode: an edge requests nothing */
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBCTRL(1)), 0);
	sim_chip_set_rts(&r->chip, 1, true);

	/* request-to-send mode for TXB1: BnRTS reads 0, a falling edge sets TXREQ */
	simh_write(&r->chip, MCP2510_REG_TXRTSCTRL, 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXRTSCTRL), 0x07);
	simh_write(&r->chip, MCP2510_REG_TXRTSCTRL, MCP2510_TXRTSCTRL_B1RTSM);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXRTSCTRL), 0x2a);
	sim_chip_set_rts(&r->chip, 1, false);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXBCTRL(1)),
			 MCP2510_TXBCTRL_TXREQ);
	sim_chip_set_rts(&r->chip, 1, false);	/* no edge, no change */
	sim_chip_set_rts(&r->chip, 7, false);	/* no such pin */
	/* the mode bits are frozen outside configuration mode */
	assert_int_equal(simh_set_mode(&r->chip, MCP2510_MODE_NORMAL), 0);
	simh_bit_modify(&r->chip, MCP2510_REG_TXRTSCTRL, 0x07, 0x00);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_TXRTSCTRL) & 0x07, 0x02);
}

static unsigned int pin_events;
static bool pin_last[SIM_PIN_COUNT];

static void count_pins(void *ctx, struct sim_chip *chip, enum sim_pin pin,
		       bool level)
{
	(void)ctx;
	(void)chip;
	pin_events++;
	pin_last[pin] = level;
}

/* AN739 register 11: INT is low while an enabled flag is set; ICOD priority */
static void test_int_pin_and_icod(void **state)
{
	struct rig *r = *state;
	u64 irqs = sim_chip_counters(&r->chip)->interrupts;

	pin_events = 0;
	sim_chip_set_pin_cb(&r->chip, count_pins, NULL);
	/* flags without enables: no interrupt, ICOD none */
	simh_write(&r->chip, MCP2510_REG_CANINTF, 0xff);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_INT));
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT) & 0x0e, 0);
	/* ICOD follows the highest-priority enabled flag */
	simh_write(&r->chip, MCP2510_REG_CANINTE, MCP2510_INT_RX1 | MCP2510_INT_TX2);
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_INT));
	assert_int_equal(pin_events, 1);
	assert_false(pin_last[SIM_PIN_INT]);
	assert_int_equal(sim_chip_counters(&r->chip)->interrupts, irqs + 1);
	assert_int_equal(FIELD_GET(MCP2510_CANSTAT_ICOD_MASK,
				   simh_read(&r->chip, MCP2510_REG_CANSTAT)),
			 MCP2510_ICOD_TXB2);
	simh_write(&r->chip, MCP2510_REG_CANINTE, 0xff);
	assert_int_equal(FIELD_GET(MCP2510_CANSTAT_ICOD_MASK,
				   simh_read(&r->chip, MCP2510_REG_CANSTAT)),
			 MCP2510_ICOD_ERR);
	simh_bit_modify(&r->chip, MCP2510_REG_CANINTF, MCP2510_INT_ERR, 0);
	assert_int_equal(FIELD_GET(MCP2510_CANSTAT_ICOD_MASK,
				   simh_read(&r->chip, MCP2510_REG_CANSTAT)),
			 MCP2510_ICOD_WAKE);
	simh_bit_modify(&r->chip, MCP2510_REG_CANINTF, 0x7c, 0);
	assert_int_equal(FIELD_GET(MCP2510_CANSTAT_ICOD_MASK,
				   simh_read(&r->chip, MCP2510_REG_CANSTAT)),
			 MCP2510_ICOD_RXB0);
	/* MERRF alone keeps INT low but has no ICOD */
	simh_bit_modify(&r->chip, MCP2510_REG_CANINTF, 0x03, 0);
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_INT));
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT) & 0x0e, 0);
	simh_write(&r->chip, MCP2510_REG_CANINTF, 0);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_INT));
	assert_true(pin_last[SIM_PIN_INT]);
	sim_chip_set_pin_cb(&r->chip, NULL, NULL);
}

/* DS21291 register 4-? BFPCTRL: RXnBF as digital outputs or buffer-full interrupts */
static void test_rxbf_pins(void **state)
{
	struct rig *r = *state;

	/* enabled, digital output: the pin follows BnBFS */
	simh_write(&r->chip, MCP2510_REG_BFPCTRL, MCP2510_BFPCTRL_B0BFE);
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_RX0BF));
	simh_bit_modify(&r->chip, MCP2510_REG_BFPCTRL, MCP2510_BFPCTRL_B0BFS, 0xff);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_RX0BF));
	/* interrupt mode: low while RX1IF is set */
	simh_write(&r->chip, MCP2510_REG_BFPCTRL,
		   MCP2510_BFPCTRL_B1BFE | MCP2510_BFPCTRL_B1BFM);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_RX1BF));
	simh_write(&r->chip, MCP2510_REG_CANINTF, MCP2510_INT_RX1);
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_RX1BF));
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_RX0BF));	/* disabled: high-Z */
	simh_write(&r->chip, MCP2510_REG_CANINTF, 0);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_RX1BF));
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_COUNT));
}

/* Fault hooks: power loss and MISO corruption */
static void test_power_loss(void **state)
{
	struct rig *r = *state;

	simh_write(&r->chip, MCP2510_REG_CANINTE, 0xff);
	simh_write(&r->chip, MCP2510_REG_CANINTF, 0x01);
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_INT));
	sim_chip_power(&r->chip, false);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_INT));	/* floats high */
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0xff);
	assert_false(sim_chip_ready(&r->chip));
	sim_chip_power(&r->chip, false);
	sim_chip_power(&r->chip, true);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0xff);
	sim_bus_advance(&r->bus, sim_chip_startup_ns(&r->chip));
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0x80);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTE), 0);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_INT));
}

static void test_spi_corruption(void **state)
{
	struct rig *r = *state;
	struct sim_chip_faults *f = sim_chip_faults(&r->chip);

	f->spi_corrupt = 2;
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0x80 ^ 0xa5);
	f->spi_corrupt_xor = 0x01;
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0x81);
	assert_int_equal(f->spi_corrupt, 0);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0x80);
	/* MOSI is not corrupted: the register file is intact */
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANCTRL), MCP2510_RESET_CANCTRL);
}

static void test_spi_garbage_kinds(void **state)
{
	struct rig *r = *state;
	struct sim_chip_faults *f = sim_chip_faults(&r->chip);
	u8 a[8], b[8];

	f->spi_corrupt = 1;
	f->spi_corrupt_kind = SIM_CORRUPT_FIXED;
	f->spi_corrupt_byte = 0x00;
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANCTRL), 0x00);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANCTRL), MCP2510_RESET_CANCTRL);

	/* random bytes differ from each other and from one period to the next */
	f->spi_corrupt = 2;
	f->spi_corrupt_kind = SIM_CORRUPT_RANDOM;
	simh_read_seq(&r->chip, MCP2510_REG_CNF3, a, sizeof(a));
	simh_read_seq(&r->chip, MCP2510_REG_CNF3, b, sizeof(b));
	assert_memory_not_equal(a, b, sizeof(a));
	assert_int_not_equal(a[0], a[1]);
	assert_int_equal(f->spi_corrupt, 0);

	/* until cleared: the count stays */
	f->spi_corrupt = SIM_CORRUPT_FOREVER;
	f->spi_corrupt_kind = SIM_CORRUPT_FIXED;
	f->spi_corrupt_byte = 0xff;
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0xff);
	assert_int_equal(f->spi_corrupt, SIM_CORRUPT_FOREVER);
	f->spi_corrupt = 0;
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0x80);
}

static void test_int_stuck(void **state)
{
	struct rig *r = *state;
	struct sim_chip_faults *f = sim_chip_faults(&r->chip);
	u64 edges = sim_chip_counters(&r->chip)->interrupts;

	assert_true(sim_chip_pin(&r->chip, SIM_PIN_INT));
	f->int_stuck = true;
	sim_chip_refresh_pins(&r->chip);
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_INT));
	assert_int_equal(sim_chip_counters(&r->chip)->interrupts, edges + 1);
	/* no flag to clear: it stays low, even without power */
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTF), 0);
	sim_chip_power(&r->chip, false);
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_INT));
	sim_chip_power(&r->chip, true);
	f->int_stuck = false;
	sim_chip_refresh_pins(&r->chip);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_INT));
}

static void test_reset_pin(void **state)
{
	struct rig *r = *state;

	simh_write(&r->chip, MCP2510_REG_CNF1, SIMH_CNF1_125K);
	simh_write(&r->chip, MCP2510_REG_CANINTE, 0xff);
	assert_int_equal(simh_set_mode(&r->chip, MCP2510_MODE_NORMAL), 0);
	simh_write(&r->chip, MCP2510_REG_CANINTF, MCP2510_INT_RX(0));
	assert_false(sim_chip_pin(&r->chip, SIM_PIN_INT));

	sim_chip_reset_pin(&r->chip);
	assert_true(sim_chip_pin(&r->chip, SIM_PIN_INT));	/* CANINTE is 0 */
	assert_false(sim_chip_ready(&r->chip));
	sim_bus_advance(&r->bus, sim_chip_startup_ns(&r->chip));
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0x80);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CNF1), 0);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANINTE), 0);

	/* an unpowered chip has nothing to reset */
	sim_chip_power(&r->chip, false);
	sim_chip_reset_pin(&r->chip);
	assert_false(sim_chip_ready(&r->chip));
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANSTAT), 0xff);
}

/* AN739 note on CANCTRL: REQOP 111 is only valid after power-up */
static void test_invalid_reqop_ignored(void **state)
{
	struct rig *r = *state;

	assert_int_equal(simh_set_mode(&r->chip, MCP2510_MODE_NORMAL), 0);
	simh_bit_modify(&r->chip, MCP2510_REG_CANCTRL, MCP2510_CANCTRL_REQOP_MASK, 0xe0);
	sim_bus_advance(&r->bus, 1000000);
	assert_int_equal(simh_opmode(&r->chip), MCP2510_MODE_NORMAL);
	simh_bit_modify(&r->chip, MCP2510_REG_CANCTRL, MCP2510_CANCTRL_REQOP_MASK, 0xa0);
	assert_int_equal(simh_opmode(&r->chip), MCP2510_MODE_NORMAL);
	/* OSM is not implemented on the MCP2510 */
	simh_bit_modify(&r->chip, MCP2510_REG_CANCTRL, MCP2515_CANCTRL_OSM, 0xff);
	assert_int_equal(simh_read(&r->chip, MCP2510_REG_CANCTRL) & MCP2515_CANCTRL_OSM, 0);
}

/* Bit timing as the chip derives it (AN739 example 2 and DS21291 section 5) */
static void test_bit_rate(void **state)
{
	struct rig *r = *state;

	assert_int_equal(sim_chip_bitrate(&r->chip), 125000);
	simh_write(&r->chip, MCP2510_REG_CNF1, SIMH_CNF1_1M);
	assert_int_equal(sim_chip_bitrate(&r->chip), 1000000);
	/* BTLMODE 0: PS2 = max(PS1, 2): PS1 = 3 -> 1 + 1 + 3 + 3 = 8 TQ */
	simh_write(&r->chip, MCP2510_REG_CNF2, 0x10);
	simh_write(&r->chip, MCP2510_REG_CNF3, 0x07);
	assert_int_equal(sim_chip_bitrate(&r->chip), 1000000);
	/* PS1 = 1 -> PS2 = IPT = 2: 1 + 1 + 1 + 2 = 5 TQ of 125 ns */
	simh_write(&r->chip, MCP2510_REG_CNF2, 0x00);
	assert_int_equal(sim_chip_bitrate(&r->chip), 1600000);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_reset_values),
		cmocka_unit_test(test_unknown_at_power_on),
		cmocka_unit_test(test_unknown_seeds),
		cmocka_unit_test_setup_teardown(test_startup_after_reset, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_sequential_read_wraps, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_canstat_canctrl_mirrors, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_write_protection, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_bit_modify, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_read_status_repeats, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_mcp2515_instructions_on_mcp2510, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_mcp2515_instructions, setup_2515, simh_teardown),
		cmocka_unit_test_setup_teardown(test_malformed_spi, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_tx_buffer_locked, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_txrts_pins, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_int_pin_and_icod, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_rxbf_pins, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_power_loss, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_spi_corruption, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_spi_garbage_kinds, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_int_stuck, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_reset_pin, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_invalid_reqop_ignored, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_bit_rate, setup_2510, simh_teardown),
	};

	return cmocka_run_group_tests_name("sim_spi", tests, NULL, NULL);
}
