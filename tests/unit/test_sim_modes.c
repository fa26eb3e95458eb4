// SPDX-License-Identifier: GPL-2.0
/*
 * Operating modes of the simulated chip (DS21801 section 10, AN739
 * "Modes of Operation"), sleep and wake-up, the "slow mode change" and
 * "slow wake" faults, and acceptance filtering details (RXM, EXIDE,
 * extended masks, MCP2515 data byte filtering).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim_helpers.h"

#define US		1000ULL
#define MS		1000000ULL

struct rig {
	struct sim_bus bus;
	struct sim_chip a, b;
};

static struct rig *rig_new(enum sim_variant variant)
{
	struct rig *r = test_calloc(1, sizeof(*r));

	sim_bus_init(&r->bus);
	simh_node_setup_125k(&r->bus, &r->a, variant);
	simh_node_up(&r->bus, &r->b, SIM_MCP2510);
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

static void request_mode(struct sim_chip *chip, unsigned int mode)
{
	simh_bit_modify(chip, MCP2510_REG_CANCTRL, MCP2510_CANCTRL_REQOP_MASK,
			FIELD_PREP(MCP2510_CANCTRL_REQOP_MASK, mode));
}

/* AN739 "Set Normal Mode": the mode must be confirmed in CANSTAT.OPMOD */
static void test_slow_mode_change(void **state)
{
	struct rig *r = *state;
	u64 t0 = sim_bus_now(&r->bus);

	sim_chip_faults(&r->a)->mode_delay_ns = 2 * MS;
	request_mode(&r->a, MCP2510_MODE_NORMAL);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_CONFIG);
	assert_int_equal(sim_chip_opmode(&r->a), MCP2510_MODE_CONFIG);
	assert_int_equal(sim_bus_next_event(&r->bus), t0 + 2 * MS);
	sim_bus_advance(&r->bus, 2 * MS - 1);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_CONFIG);
	/* configuration registers stay writable until the change happens */
	simh_write(&r->a, MCP2510_REG_CNF1, SIMH_CNF1_125K);
	sim_bus_advance(&r->bus, 1);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_NORMAL);

	/* a request taken back before it happens is no request */
	request_mode(&r->a, MCP2510_MODE_LISTEN_ONLY);
	request_mode(&r->a, MCP2510_MODE_NORMAL);
	sim_bus_advance(&r->bus, 5 * MS);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_NORMAL);
	/* the helper polls as a driver would */
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_LOOPBACK), 0);
	sim_chip_faults(&r->a)->mode_delay_ns = 100 * MS;
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_CONFIG), -ETIMEDOUT);
}

/*
 * DS21801 10.0: the mode does not change until all pending transmissions
 * are complete, which a lone sender's never are (no ACK, retried for
 * ever): only an abort lets the request through.  DS21801 10.1: entering
 * configuration mode clears TEC and REC.
 */
static void test_mode_change_waits_for_pending(void **state)
{
	struct rig *r = *state;
	struct can_frame cf = simh_frame(0x10, 8, (const u8[8]){ 0 });

	assert_int_equal(simh_set_mode(&r->b, MCP2510_MODE_CONFIG), 0);
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_NORMAL), 0);
	simh_send(&r->a, 0, &cf);		/* alone: ACK errors */
	sim_bus_advance(&r->bus, 0);
	sim_bus_advance(&r->bus, 1);
	assert_false(sim_bus_idle(&r->bus));
	request_mode(&r->a, MCP2510_MODE_CONFIG);
	sim_bus_advance(&r->bus, 20 * MS);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_NORMAL);
	assert_true(simh_read(&r->a, MCP2510_REG_TXBCTRL(0)) & MCP2510_TXBCTRL_TXREQ);
	assert_true(sim_chip_tec(&r->a) >= 128);
	/* the driver polling for the mode times out */
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_CONFIG), -ETIMEDOUT);

	/* abort: the attempt on the bus ends, not retried, then the mode changes */
	simh_bit_modify(&r->a, MCP2510_REG_TXBCTRL(0), MCP2510_TXBCTRL_TXREQ, 0);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_CONFIG);
	assert_int_equal(simh_read(&r->a, MCP2510_REG_TEC), 0);
	assert_false(simh_read(&r->a, MCP2510_REG_TXBCTRL(0)) & MCP2510_TXBCTRL_TXREQ);
	assert_true(sim_bus_idle(&r->bus));
	assert_int_equal(sim_bus_next_event(&r->bus), U64_MAX);
}

/*
 * DS21801 10.0 again: buffers waiting for the bus count as pending, not
 * only the frame on it.  ABAT (3.4) ends the wait for the waiting ones;
 * the mode then follows the frame in flight.
 */
static void test_mode_change_waits_for_queued(void **state)
{
	struct rig *r = *state;
	struct can_frame cf = simh_frame(0x20, 2, (const u8[]){ 1, 2 });
	unsigned int n;

	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_NORMAL), 0);
	for (n = 0; n < 3; n++)
		simh_load_tx(&r->a, n, &cf);
	simh_rts(&r->a, MCP2510_RTS_ALL);
	request_mode(&r->a, MCP2510_MODE_CONFIG);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_NORMAL);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(sim_chip_counters(&r->a)->frames_tx, 3);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_CONFIG);

	/* the same in loopback mode: the frames go round first */
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_LOOPBACK), 0);
	simh_rts(&r->a, MCP2510_RTS_ALL);
	request_mode(&r->a, MCP2510_MODE_NORMAL);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_LOOPBACK);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(sim_chip_counters(&r->a)->frames_tx, 6);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_NORMAL);

	/* ABAT: the waiting buffers go at once, the mode after the frame in flight */
	simh_rts(&r->a, MCP2510_RTS_ALL);
	/* the start-of-frame bit: the arbitration window closes */
	sim_bus_advance(&r->bus, 1000000000u / sim_chip_bitrate(&r->a));
	assert_false(sim_bus_idle(&r->bus));
	request_mode(&r->a, MCP2510_MODE_LISTEN_ONLY);
	simh_bit_modify(&r->a, MCP2510_REG_CANCTRL, MCP2510_CANCTRL_ABAT, 0xff);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_NORMAL);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(sim_chip_counters(&r->a)->frames_tx, 7);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_LISTEN_ONLY);
	for (n = 0; n < 2; n++)
		assert_int_equal(simh_read(&r->a, MCP2510_REG_TXBCTRL(n)),
				 MCP2510_TXBCTRL_ABTF);
	assert_int_equal(simh_read(&r->a, MCP2510_REG_TXBCTRL(2)), 0);

	/* no transmissions in listen-only mode: nothing holds a request there */
	simh_bit_modify(&r->a, MCP2510_REG_CANCTRL, MCP2510_CANCTRL_ABAT, 0);
	simh_rts(&r->a, MCP2510_RTS_TXB(0));
	request_mode(&r->a, MCP2510_MODE_CONFIG);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_CONFIG);
}

/*
 * AN739 "Sleep Mode": the SPI interface stays active.  DS21801 10.2:
 * bus activity wakes the chip (WAKIF, and INT with WAKIE) into
 * listen-only mode after the oscillator start-up; the waking frame is
 * lost.  AN739: with WAKIE clear the chip sleeps through bus activity.
 */
static void test_sleep_and_wake_on_bus(void **state)
{
	struct rig *r = *state;
	struct can_frame cf = simh_frame(0x77, 1, (const u8[]){ 0x5a }), got;
	u64 woke;

	simh_write(&r->a, MCP2510_REG_RXBCTRL(0),
		   FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_ANY));
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_SLEEP), 0);
	sim_phantom_attach(&r->bus, 0);

	/* WAKIE clear: b's frame does not wake a */
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_SLEEP);
	assert_int_equal(simh_read(&r->a, MCP2510_REG_CANINTF), 0);

	/* SPI works in sleep: set WAKIE */
	simh_write(&r->a, MCP2510_REG_CANINTE, MCP2510_INT_WAK);
	assert_int_equal(simh_read(&r->a, MCP2510_REG_CANINTE), MCP2510_INT_WAK);
	simh_send(&r->b, 0, &cf);
	sim_bus_advance(&r->bus, 0);
	woke = sim_bus_now(&r->bus);
	assert_true(simh_read(&r->a, MCP2510_REG_CANINTF) & MCP2510_INT_WAK);
	assert_false(sim_chip_pin(&r->a, SIM_PIN_INT));
	assert_int_equal(FIELD_GET(MCP2510_CANSTAT_ICOD_MASK,
				   simh_read(&r->a, MCP2510_REG_CANSTAT)),
			 MCP2510_ICOD_WAKE);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_SLEEP);
	sim_bus_advance_to(&r->bus, woke + sim_chip_startup_ns(&r->a) - 1);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_SLEEP);
	sim_bus_advance_to(&r->bus, woke + sim_chip_startup_ns(&r->a));
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_LISTEN_ONLY);
	assert_int_equal(FIELD_GET(MCP2510_CANCTRL_REQOP_MASK,
				   simh_read(&r->a, MCP2510_REG_CANCTRL)),
			 MCP2510_MODE_LISTEN_ONLY);
	simh_run_idle(&r->bus, 10 * MS);
	assert_false(simh_read(&r->a, MCP2510_REG_CANINTF) & MCP2510_INT_RX0);

	/* listening now: the next frame arrives */
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	simh_read_rx(&r->a, 0, &got, true);
	assert_true(simh_frame_equal(&cf, &got));
}

/* DS21801 10.2: the MCU wakes the chip by setting WAKIF; fault "slow wake" */
static void test_wake_by_spi_slow(void **state)
{
	struct rig *r = *state;
	u64 t0;

	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_SLEEP), 0);
	sim_chip_faults(&r->a)->wake_delay_ns = 3 * MS;
	t0 = sim_bus_now(&r->bus);
	simh_bit_modify(&r->a, MCP2510_REG_CANINTF, MCP2510_INT_WAK, 0xff);
	assert_int_equal(sim_bus_next_event(&r->bus),
			 t0 + sim_chip_startup_ns(&r->a) + 3 * MS);
	sim_bus_advance(&r->bus, 3 * MS);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_SLEEP);
	/* a second wake-up cause changes nothing */
	simh_write(&r->a, MCP2510_REG_CANINTF, 0);
	simh_write(&r->a, MCP2510_REG_CANINTF, MCP2510_INT_WAK);
	sim_bus_advance(&r->bus, sim_chip_startup_ns(&r->a));
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_LISTEN_ONLY);
	/* WAKIF was not enabled: no interrupt */
	assert_true(sim_chip_pin(&r->a, SIM_PIN_INT));

	/* a mode request also leaves sleep, after the oscillator start-up */
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_SLEEP), 0);
	request_mode(&r->a, MCP2510_MODE_CONFIG);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_SLEEP);
	sim_bus_advance(&r->bus, sim_chip_startup_ns(&r->a));
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_CONFIG);
}

/*
 * DS21801 4.5 and AN739 "Setting Masks and Filters": EXIDE picks the frame
 * type a filter takes; RXM narrows a buffer to standard or extended
 * frames; extended masks compare all 29 bits.
 */
static void test_filters_and_rxm(void **state)
{
	struct rig *r = *state;
	struct can_frame cf;
	u8 filt[4], mask[4] = { 0xff, 0xe3, 0xff, 0xf0 };	/* ignore EID3..0 */
	u32 id = 0x12345678 & CAN_EFF_MASK;

	/* RXF1: extended id, RXM0 compares all but the low 4 bits */
	filt[0] = id >> 21;
	filt[1] = ((id >> 18) & 7) << 5 | MCP2510_SIDL_EXIDE | ((id >> 16) & 3);
	filt[2] = id >> 8;
	filt[3] = id;
	simh_write_seq(&r->a, MCP2510_REG_RXF(1), filt, 4);
	simh_write_seq(&r->a, MCP2510_REG_RXM(0), mask, 4);
	/* RXB1: standard frames only, filter 5 = 0x7ff, all bits */
	simh_write(&r->a, MCP2510_REG_RXBCTRL(1),
		   FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_STD));
	simh_write(&r->a, MCP2510_REG_RXMSIDH(1), 0xff);
	simh_write(&r->a, MCP2510_REG_RXMSIDL(1), 0xe0);
	simh_write(&r->a, MCP2510_REG_RXFSIDH(5), 0xff);
	simh_write(&r->a, MCP2510_REG_RXFSIDL(5), 0xe0);
	/* RXF0 = standard 0x000 under RXM0: only 0x000 passes RXB0 as standard */
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_NORMAL), 0);

	cf = simh_frame(CAN_EFF_FLAG | (id ^ 0x0f), 0, NULL);	/* low bits differ */
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3, MCP2510_STATUS_RX0IF);
	assert_int_equal(simh_read(&r->a, MCP2510_REG_RXBCTRL(0)) &
			 MCP2510_RXB0CTRL_FILHIT0, 1);
	simh_write(&r->a, MCP2510_REG_CANINTF, 0);

	cf = simh_frame(CAN_EFF_FLAG | (id ^ 0x10), 0, NULL);	/* EID4 differs */
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3, 0);

	cf = simh_frame(0x7ff, 0, NULL);	/* RXB0 rejects, RXB1 filter 5 */
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3, MCP2510_STATUS_RX1IF);
	assert_int_equal(simh_read(&r->a, MCP2510_REG_RXBCTRL(1)) &
			 MCP2510_RXB1CTRL_FILHIT_MASK, 5);
	simh_write(&r->a, MCP2510_REG_CANINTF, 0);

	/* RXM "ext only" on RXB1 turns the same standard frame away */
	simh_write(&r->a, MCP2510_REG_RXBCTRL(1),
		   FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_EXT));
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3, 0);
	/* and RXM "std only" on RXB0 turns extended frames away */
	simh_write(&r->a, MCP2510_REG_RXBCTRL(0),
		   FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_STD));
	cf = simh_frame(CAN_EFF_FLAG | id, 0, NULL);
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3, 0);
}

/*
 * DS21801 4.5.1: for standard data frames the MCP2515 applies the EID15..0
 * mask and filter bits to data bytes 0 and 1.  The MCP2510 does not.
 */
static void check_data_byte_filter(struct rig *r, bool expect_filtering)
{
	struct can_frame cf;

	simh_write(&r->a, MCP2510_REG_RXMSIDH(0), 0xff);
	simh_write(&r->a, MCP2510_REG_RXMSIDL(0), 0xe0);
	simh_write(&r->a, MCP2510_REG_RXMEID8(0), 0xff);	/* data byte 0 */
	simh_write(&r->a, MCP2510_REG_RXMEID0(0), 0);	/* powered up unknown */
	simh_write(&r->a, MCP2510_REG_RXFSIDH(0), 0x24);	/* id 0x123 */
	simh_write(&r->a, MCP2510_REG_RXFSIDL(0), 0x60);
	simh_write(&r->a, MCP2510_REG_RXFEID8(0), 0x55);
	simh_write(&r->a, MCP2510_REG_RXFSIDL(1), MCP2510_SIDL_EXIDE);
	/* RXB1 would take any standard frame (mask 0): keep it for extended */
	simh_write(&r->a, MCP2510_REG_RXBCTRL(1),
		   FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_EXT));
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_NORMAL), 0);

	cf = simh_frame(0x123, 2, (const u8[]){ 0x55, 0x99 });
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3, MCP2510_STATUS_RX0IF);
	simh_write(&r->a, MCP2510_REG_CANINTF, 0);

	cf = simh_frame(0x123, 2, (const u8[]){ 0x56, 0x99 });
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3,
			 expect_filtering ? 0 : MCP2510_STATUS_RX0IF);
	simh_write(&r->a, MCP2510_REG_CANINTF, 0);

	/* remote frames have no data to filter on */
	cf = simh_frame(0x123 | CAN_RTR_FLAG, 2, NULL);
	simh_send(&r->b, 0, &cf);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_read_status(&r->a) & 3, MCP2510_STATUS_RX0IF);
}

static void test_data_byte_filter_mcp2515(void **state)
{
	check_data_byte_filter(*state, true);
}

static void test_no_data_byte_filter_mcp2510(void **state)
{
	check_data_byte_filter(*state, false);
}

/* Loopback needs no other node and no ACK, and TEC stays untouched. */
static void test_loopback_alone(void **state)
{
	struct rig *r = *state;
	struct can_frame cf = simh_frame(0x10, 0, NULL);

	assert_int_equal(simh_set_mode(&r->b, MCP2510_MODE_CONFIG), 0);
	simh_write(&r->a, MCP2510_REG_RXBCTRL(0),
		   FIELD_PREP(MCP2510_RXBCTRL_RXM_MASK, MCP2510_RXM_ANY));
	assert_int_equal(simh_set_mode(&r->a, MCP2510_MODE_LOOPBACK), 0);
	simh_send(&r->a, 0, &cf);
	simh_send(&r->a, 1, &cf);
	/* a mode change waits for both frames (DS21801 10.0: all pending) */
	sim_bus_advance(&r->bus, 0);
	request_mode(&r->a, MCP2510_MODE_CONFIG);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_LOOPBACK);
	simh_run_idle(&r->bus, 10 * MS);
	assert_int_equal(simh_opmode(&r->a), MCP2510_MODE_CONFIG);
	assert_int_equal(simh_read(&r->a, MCP2510_REG_TEC), 0);
	assert_int_equal(sim_chip_counters(&r->a)->frames_tx, 2);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test_setup_teardown(test_slow_mode_change, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_mode_change_waits_for_pending, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_mode_change_waits_for_queued, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_sleep_and_wake_on_bus, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_wake_by_spi_slow, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_filters_and_rxm, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_data_byte_filter_mcp2515, setup_2515, simh_teardown),
		cmocka_unit_test_setup_teardown(test_no_data_byte_filter_mcp2510, setup_2510, simh_teardown),
		cmocka_unit_test_setup_teardown(test_loopback_alone, setup_2510, simh_teardown),
	};

	return cmocka_run_group_tests_name("sim_modes", tests, NULL, NULL);
}
