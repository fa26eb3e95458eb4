// SPDX-License-Identifier: GPL-2.0
/*
 * libmcp2510 through its public API on simulated chips: configuration,
 * traffic between two nodes, loopback, fault confinement seen as state
 * and TEC/REC, hardware filters, the register dump, the event ring and
 * the pollable descriptor.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <poll.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "mcp2510.h"
#include <linux/can/mcp2510.h>

static struct mcp2510 *open_sim(const char *bus, const char *variant)
{
	struct mcp2510_options o;
	struct mcp2510 *h;

	mcp2510_options_init(&o);
	o.variant = variant;
	h = mcp2510_open(bus, &o);
	if (!h)
		fail_msg("open %s: %s", bus, strerror(errno));
	return h;
}

static struct mcp2510 *open_up(const char *bus, uint32_t ctrlmode)
{
	struct mcp2510 *h = open_sim(bus, NULL);

	assert_int_equal(mcp2510_set_bitrate(h, 500000, 0), 0);
	assert_int_equal(mcp2510_set_ctrlmode(h, ctrlmode), 0);
	assert_int_equal(mcp2510_up(h), 0);
	return h;
}

static struct can_frame frame(canid_t id, uint8_t len, uint8_t seed)
{
	struct can_frame cf;
	uint8_t i;

	memset(&cf, 0, sizeof(cf));
	cf.can_id = id;
	cf.len = len;
	for (i = 0; i < len; i++)
		cf.data[i] = (uint8_t)(seed + i);
	return cf;
}

static void assert_same_frame(const struct can_frame *a, const struct can_frame *b)
{
	assert_int_equal(a->can_id, b->can_id);
	assert_int_equal(a->len, b->len);
	if (!(a->can_id & CAN_RTR_FLAG))
		assert_memory_equal(a->data, b->data, a->len);
}

/* The next event of @type, skipping others. */
static struct mcp2510_event next_event(struct mcp2510 *h,
				       enum mcp2510_event_type type)
{
	struct mcp2510_event ev;

	do {
		if (mcp2510_recv(h, &ev, 100))
			fail_msg("no event %d: %s", type, strerror(errno));
	} while (ev.type != type);
	return ev;
}

static void test_open_and_bittiming(void **state)
{
	struct mcp2510 *h = open_sim("sim", NULL);
	struct can_bittiming bt;

	(void)state;
	assert_string_equal(mcp2510_variant_name(h), "mcp2510");
	assert_int_equal(mcp2510_osc_hz(h), MCP2510_DEFAULT_OSC_HZ);
	assert_int_equal(mcp2510_get_bittiming(h, &bt), -1);
	assert_int_equal(errno, ENODATA);
	assert_int_equal(mcp2510_up(h), -1);
	assert_int_equal(errno, ENODATA);
	assert_int_equal(mcp2510_set_bitrate(h, 500000, 0), 0);
	assert_int_equal(mcp2510_get_bittiming(h, &bt), 0);
	assert_int_equal(bt.bitrate, 500000);
	assert_int_equal(bt.sample_point, 875);
	assert_int_equal(bt.tq, 125);
	assert_int_equal(bt.prop_seg + bt.phase_seg1 + bt.phase_seg2 + 1, 16);
	/* 16 MHz cannot make 3 Mbit/s */
	assert_int_equal(mcp2510_set_bitrate(h, 3000000, 0), -1);
	assert_int_not_equal(errno, 0);
	mcp2510_close(h);
}

static void test_explicit_bittiming(void **state)
{
	struct can_bittiming in = { .prop_seg = 6, .phase_seg1 = 7,
				    .phase_seg2 = 2, .sjw = 1, .brp = 2 };
	struct mcp2510 *h = open_sim("sim", NULL);
	struct can_bittiming bt;

	(void)state;
	assert_int_equal(mcp2510_set_bittiming(h, &in), 0);
	mcp2510_get_bittiming(h, &bt);
	assert_int_equal(bt.bitrate, 250000);
	assert_int_equal(bt.sample_point, 875);
	assert_int_equal(bt.tq, 250);
	/* the quantum instead of the prescaler */
	in.brp = 0;
	in.tq = 500;
	assert_int_equal(mcp2510_set_bittiming(h, &in), 0);
	mcp2510_get_bittiming(h, &bt);
	assert_int_equal(bt.brp, 4);
	assert_int_equal(bt.bitrate, 125000);
	/* no phase segment 2 */
	in.phase_seg2 = 0;
	assert_int_equal(mcp2510_set_bittiming(h, &in), -1);
	assert_int_equal(errno, EINVAL);
	mcp2510_close(h);
}

static void test_ctrlmodes_by_variant(void **state)
{
	struct mcp2510 *a = open_sim("sim", "mcp2510");
	struct mcp2510 *b = open_sim("sim", "mcp25625");

	(void)state;
	assert_int_equal(mcp2510_set_ctrlmode(a, CAN_CTRLMODE_ONE_SHOT), -1);
	assert_int_equal(errno, EOPNOTSUPP);
	assert_int_equal(mcp2510_set_ctrlmode(b, CAN_CTRLMODE_ONE_SHOT |
					      CAN_CTRLMODE_3_SAMPLES), 0);
	assert_int_equal(mcp2510_get_ctrlmode(b), CAN_CTRLMODE_ONE_SHOT |
						  CAN_CTRLMODE_3_SAMPLES);
	assert_int_equal(mcp2510_set_ctrlmode(a, CAN_CTRLMODE_FD), -1);
	assert_int_equal(errno, EOPNOTSUPP);
	mcp2510_close(a);
	mcp2510_close(b);
}

/* cc-len8-dlc: a DLC of 9..15 goes out as written and comes back. */
static void test_raw_dlc(void **state)
{
	struct mcp2510 *a = open_up("sim:dlc", CAN_CTRLMODE_CC_LEN8_DLC);
	struct mcp2510 *b = open_up("sim:dlc", CAN_CTRLMODE_CC_LEN8_DLC);
	struct mcp2510 *c = open_up("sim:dlc", 0);
	struct can_frame cf = frame(0x123, 8, 1), got;

	(void)state;
	cf.len8_dlc = 14;
	assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	got = next_event(b, MCP2510_EVENT_RX).frame;
	assert_same_frame(&got, &cf);
	assert_int_equal(got.len8_dlc, 14);
	/* without the mode the DLC reads as 8 */
	got = next_event(c, MCP2510_EVENT_RX).frame;
	assert_same_frame(&got, &cf);
	assert_int_equal(got.len8_dlc, 0);
	/* and a sender without it sends 8 */
	assert_int_equal(mcp2510_send(c, &cf, 0), 0);
	got = next_event(b, MCP2510_EVENT_RX).frame;
	assert_int_equal(got.len, 8);
	assert_int_equal(got.len8_dlc, 0);
	mcp2510_close(a);
	mcp2510_close(b);
	mcp2510_close(c);
}

static void test_running_rules(void **state)
{
	struct can_frame cf = frame(0x10, 1, 0);
	struct mcp2510_hw_filters f;
	struct mcp2510 *h = open_sim("sim", NULL);

	(void)state;
	assert_int_equal(mcp2510_send(h, &cf, 0), -1);
	assert_int_equal(errno, ENETDOWN);
	assert_int_equal(mcp2510_tx_room(h), 0);
	mcp2510_set_bitrate(h, 125000, 0);
	assert_int_equal(mcp2510_up(h), 0);
	assert_true(mcp2510_is_up(h));
	assert_int_equal(mcp2510_tx_room(h), 3);
	assert_int_equal(mcp2510_set_bitrate(h, 250000, 0), -1);
	assert_int_equal(errno, EBUSY);
	mcp2510_hw_filters_default(&f);
	assert_int_equal(mcp2510_set_filters(h, &f), -1);
	assert_int_equal(errno, EBUSY);
	assert_int_equal(mcp2510_up(h), -1);
	assert_int_equal(errno, EBUSY);
	/* frames the chip cannot carry */
	cf.len = 9;
	assert_int_equal(mcp2510_send(h, &cf, 0), -1);
	assert_int_equal(errno, EINVAL);
	cf = frame(0x800, 0, 0);
	assert_int_equal(mcp2510_send(h, &cf, 0), -1);
	assert_int_equal(errno, EINVAL);
	assert_int_equal(mcp2510_down(h), 0);
	assert_false(mcp2510_is_up(h));
	mcp2510_close(h);
}

static void test_two_nodes_exchange_in_order(void **state)
{
	struct mcp2510 *a = open_up("sim:pair", 0), *b = open_up("sim:pair", 0);
	struct can_frame sent[3] = {
		frame(0x123, 8, 0x10),
		frame(0x1abcdef | CAN_EFF_FLAG, 3, 0x20),
		frame(0x7ff | CAN_RTR_FLAG, 2, 0),
	};
	struct mcp2510_stats s;
	struct mcp2510_event ev;
	unsigned int i;

	(void)state;
	for (i = 0; i < 3; i++)
		assert_int_equal(mcp2510_send(a, &sent[i], 0), 0);
	for (i = 0; i < 3; i++) {
		ev = next_event(b, MCP2510_EVENT_RX);
		assert_same_frame(&ev.frame, &sent[i]);
		assert_true(ev.ts.tv_sec > 0);
	}
	for (i = 0; i < 3; i++) {
		ev = next_event(a, MCP2510_EVENT_TX_DONE);
		assert_same_frame(&ev.frame, &sent[i]);
	}
	/* and back */
	assert_int_equal(mcp2510_send(b, &sent[0], 0), 0);
	ev = next_event(a, MCP2510_EVENT_RX);
	assert_same_frame(&ev.frame, &sent[0]);
	mcp2510_stats(a, &s);
	assert_int_equal(s.tx_frames, 3);
	assert_int_equal(s.rx_frames, 1);
	assert_true(s.spi_transfers > 0 && s.spi_bytes > s.spi_transfers);
	assert_true(s.interrupts > 0);
	mcp2510_close(a);
	mcp2510_close(b);
}

static void test_loopback_returns_frames(void **state)
{
	struct mcp2510 *h = open_up("sim:loop", CAN_CTRLMODE_LOOPBACK);
	struct can_frame cf = frame(0x1fffffff | CAN_EFF_FLAG, 8, 0xf0);
	struct mcp2510_event ev;

	(void)state;
	assert_int_equal(mcp2510_send(h, &cf, 0), 0);
	ev = next_event(h, MCP2510_EVENT_RX);
	assert_same_frame(&ev.frame, &cf);
	mcp2510_close(h);
}

static void test_lone_node_becomes_error_passive(void **state)
{
	struct mcp2510 *h = open_up("sim:alone", 0);
	struct can_frame cf = frame(0x55, 1, 1);
	struct can_berr_counter bec;
	struct mcp2510_event ev;
	enum can_state st;

	(void)state;
	assert_int_equal(mcp2510_state(h, &st, &bec), 0);
	assert_int_equal(st, CAN_STATE_ERROR_ACTIVE);
	assert_int_equal(bec.txerr, 0);
	assert_int_equal(mcp2510_send(h, &cf, 0), 0);
	ev = next_event(h, MCP2510_EVENT_STATE);
	assert_int_equal(ev.state, CAN_STATE_ERROR_WARNING);
	assert_true(ev.bec.txerr >= 96);
	ev = next_event(h, MCP2510_EVENT_STATE);
	assert_int_equal(ev.state, CAN_STATE_ERROR_PASSIVE);
	assert_int_equal(mcp2510_state(h, &st, &bec), 0);
	assert_int_equal(st, CAN_STATE_ERROR_PASSIVE);
	/* nobody acknowledges: a passive transmitter stops counting at 128 */
	assert_int_equal(bec.txerr, 128);
	assert_int_equal(bec.rxerr, 0);
	assert_string_equal(mcp2510_state_name(st), "ERROR-PASSIVE");
	mcp2510_close(h);
}

static void test_full_buffers_nonblock_and_timeout(void **state)
{
	struct mcp2510_options o;
	struct can_frame cf = frame(0x66, 2, 2);
	struct mcp2510 *h;
	unsigned int i;

	(void)state;
	mcp2510_options_init(&o);
	o.tx_timeout_ms = 50;
	h = mcp2510_open("sim:unacked", &o);
	assert_non_null(h);
	mcp2510_set_bitrate(h, 500000, 0);
	assert_int_equal(mcp2510_up(h), 0);
	for (i = 0; i < 3; i++)
		assert_int_equal(mcp2510_send(h, &cf, MCP2510_SEND_NONBLOCK), 0);
	assert_int_equal(mcp2510_tx_room(h), 0);
	assert_int_equal(mcp2510_send(h, &cf, MCP2510_SEND_NONBLOCK), -1);
	assert_int_equal(errno, EAGAIN);
	assert_int_equal(mcp2510_send(h, &cf, 0), -1);
	assert_int_equal(errno, ETIMEDOUT);
	/* going down drops the three, each reported */
	assert_int_equal(mcp2510_down(h), 0);
	for (i = 0; i < 3; i++)
		assert_int_equal(next_event(h, MCP2510_EVENT_TX_ABORTED).frame.can_id,
				 0x66);
	mcp2510_close(h);
}

static void test_hardware_filters(void **state)
{
	struct mcp2510 *a = open_up("sim:filters", 0);
	struct mcp2510 *b = open_sim("sim:filters", NULL);
	struct mcp2510_hw_filters f;
	struct can_frame cf;
	char line[32];
	canid_t id;

	(void)state;
	mcp2510_hw_filters_default(&f);
	assert_int_equal(mcp2510_hw_filters_set(&f, "mask0", "7ff"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "filter0", "123"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "filter1", "123"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "mask1", "1fffffffx"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "filter2", "1234567x"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "rollover", "0"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "filter6", "1"), -1);
	assert_int_equal(mcp2510_hw_filters_set(&f, "mask0", "800"), -1);
	assert_int_equal(mcp2510_hw_filters_set(&f, "rxm0", "some"), -1);
	assert_int_equal(mcp2510_hw_filters_set(&f, "rollover", "2"), -1);
	assert_int_equal(errno, EINVAL);
	assert_int_equal(mcp2510_set_filters(b, &f), 0);
	mcp2510_hw_filters_format(&f, 1, line, sizeof(line));
	assert_string_equal(line, "mask1 1fffffffx");
	mcp2510_hw_filters_format(&f, 10, line, sizeof(line));
	assert_string_equal(line, "rollover 0");
	mcp2510_set_bitrate(b, 500000, 0);
	assert_int_equal(mcp2510_up(b), 0);
	/* only 123 and 1234567x pass */
	for (id = 0x120; id < 0x126; id++) {
		cf = frame(id, 1, 0);
		assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	}
	cf = frame(0x1234567 | CAN_EFF_FLAG, 1, 0);
	assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	assert_int_equal(next_event(b, MCP2510_EVENT_RX).frame.can_id, 0x123);
	assert_int_equal(next_event(b, MCP2510_EVENT_RX).frame.can_id,
			 0x1234567 | CAN_EFF_FLAG);
	mcp2510_close(a);
	mcp2510_close(b);
}

/* #17: a missing chip is refused at open, with or without a reset. */
static void test_missing_chip_refused(void **state)
{
	static const char *const miso[] = { "low", "high" };
	uint8_t regs[MCP2510_REGS_LEN];
	struct mcp2510_options o;
	struct mcp2510 *h;
	size_t m;
	int no_reset;

	(void)state;
	mcp2510_options_init(&o);
	for (m = 0; m < 2; m++) {
		setenv("MCP2510_SIM_MISO", miso[m], 1);
		for (no_reset = 0; no_reset <= 1; no_reset++) {
			o.no_reset = no_reset;
			errno = 0;
			h = mcp2510_open("sim", &o);
			if (h || errno != ENODEV) {
				unsetenv("MCP2510_SIM_MISO");
				fail_msg("MISO %s, no_reset %d: handle %p, errno %d",
					 miso[m], no_reset, (void *)h, errno);
			}
		}
	}
	assert_int_equal(setenv("MCP2510_SIM_MISO", "sideways", 1), 0);
	assert_null(mcp2510_open("sim", &o));
	assert_int_equal(errno, EINVAL);
	unsetenv("MCP2510_SIM_MISO");
	/* a chip that is there passes, and the look leaves nothing behind */
	o.no_reset = true;
	h = mcp2510_open("sim", &o);
	assert_non_null(h);
	assert_int_equal(mcp2510_read_regs(h, regs), 0);
	/* the byte holds its power-up garbage again, not the last pattern */
	assert_int_not_equal(regs[MCP2510_REG_TXBD(2, 7)], 0x5a);
	mcp2510_close(h);
	o.no_reset = false;
	h = mcp2510_open("sim", &o);
	assert_non_null(h);
	assert_int_equal(mcp2510_read_regs(h, regs), 0);
	assert_int_equal(regs[MCP2510_REG_CNF1], 0);	/* its reset value again */
	mcp2510_close(h);
}

/* #17: filters set on a stopped handle are in the chip, for the next user. */
static void test_filters_reach_the_chip(void **state)
{
	struct mcp2510 *h = open_sim("sim", NULL);
	uint8_t regs[MCP2510_REGS_LEN];
	struct mcp2510_hw_filters f;

	(void)state;
	mcp2510_hw_filters_default(&f);
	assert_int_equal(mcp2510_hw_filters_set(&f, "mask0", "7ff"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "filter0", "123"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "filter2", "1234567x"), 0);
	assert_int_equal(mcp2510_hw_filters_set(&f, "rxm1", "any"), 0);
	assert_int_equal(mcp2510_set_filters(h, &f), 0);
	assert_int_equal(mcp2510_read_regs(h, regs), 0);
	assert_int_equal(regs[MCP2510_REG_RXMSIDH(0)], 0xff);
	assert_int_equal(regs[MCP2510_REG_RXMSIDL(0)], 0xe0);
	assert_int_equal(regs[MCP2510_REG_RXFSIDH(0)], 0x24);
	assert_int_equal(regs[MCP2510_REG_RXFSIDL(0)], 0x60);
	assert_int_equal(regs[MCP2510_REG_RXFSIDH(2)], 0x09);
	assert_int_equal(regs[MCP2510_REG_RXFSIDL(2)], 0x0b);
	assert_int_equal(regs[MCP2510_REG_RXFEID8(2)], 0x45);
	assert_int_equal(regs[MCP2510_REG_RXFEID0(2)], 0x67);
	assert_int_equal(regs[MCP2510_REG_RXBCTRL(0)] & MCP2510_RXB0CTRL_BUKT,
			 MCP2510_RXB0CTRL_BUKT);
	assert_int_equal(regs[MCP2510_REG_RXBCTRL(1)] & MCP2510_RXBCTRL_RXM_MASK,
			 MCP2510_RXBCTRL_RXM_MASK);
	mcp2510_close(h);
}

static void test_register_dump_and_names(void **state)
{
	struct mcp2510 *h = open_up("sim", 0);
	uint8_t regs[MCP2510_REGS_LEN], cnf[3];
	char name[MCP2510_REG_NAME_MAX];
	struct can_bittiming bt;

	(void)state;
	assert_int_equal(mcp2510_read_regs(h, regs), 0);
	assert_int_equal(mcp2510_bittiming_for(MCP2510_DEFAULT_OSC_HZ, 500000, 0,
					       &bt, cnf), 0);
	assert_int_equal(regs[MCP2510_REG_CNF1], cnf[0]);
	assert_int_equal(regs[MCP2510_REG_CNF2], cnf[1]);
	assert_int_equal(regs[MCP2510_REG_CNF3], cnf[2]);
	assert_int_equal(regs[MCP2510_REG_CANSTAT] & MCP2510_CANSTAT_OPMOD_MASK, 0);
	mcp2510_reg_name(0x2a, name, sizeof(name));
	assert_string_equal(name, "CNF1");
	mcp2510_reg_name(0x31, name, sizeof(name));
	assert_string_equal(name, "TXB0SIDH");
	mcp2510_reg_name(0x6d, name, sizeof(name));
	assert_string_equal(name, "RXB0D7");
	mcp2510_reg_name(0x7e, name, sizeof(name));
	assert_string_equal(name, "CANSTAT");
	mcp2510_reg_name(0x14, name, sizeof(name));
	assert_string_equal(name, "RXF4SIDH");
	mcp2510_reg_name(0x23, name, sizeof(name));
	assert_string_equal(name, "RXM0EID0");
	assert_int_equal(mcp2510_reg_name(0x80, name, sizeof(name)), -1);
	mcp2510_close(h);
}

/* A receiver that does not keep up loses events, and says how many. */
static void test_event_ring_overflow_counted(void **state)
{
	const unsigned int n = MCP2510_EVENT_RING_SIZE + 6;
	struct mcp2510 *a = open_up("sim:flood", 0), *b = open_up("sim:flood", 0);
	struct mcp2510_event ev;
	struct mcp2510_stats s;
	struct can_frame cf;
	unsigned int i, got = 0;

	(void)state;
	for (i = 0; i < n; i++) {
		cf = frame(0x200, 1, (uint8_t)i);
		assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	}
	while (!mcp2510_recv(a, &ev, 100))
		;
	mcp2510_stats(b, &s);
	assert_int_equal(s.rx_frames, n);
	assert_int_equal(s.ring_overflows, n - MCP2510_EVENT_RING_SIZE);
	while (!mcp2510_recv(b, &ev, 0)) {
		assert_int_equal(ev.frame.data[0], got);
		got++;
	}
	assert_int_equal(got, MCP2510_EVENT_RING_SIZE);
	mcp2510_close(a);
	mcp2510_close(b);
}

/*
 * MCP2510_SIM_SPI_TIME makes SPI take time on buses created after it is
 * set: a receiver on a 1 kHz SPI clock cannot empty its buffers before a
 * burst of frames overflows them; at the chip's own clock it can.
 */
static unsigned int burst_received(const char *bus, uint32_t rx_spi_hz,
				   uint32_t *overflows)
{
	struct mcp2510 *a = open_up(bus, 0), *b;
	struct mcp2510_options o;
	struct mcp2510_event ev;
	struct mcp2510_stats s;
	struct can_frame cf;
	unsigned int i;

	mcp2510_options_init(&o);
	o.spi_hz = rx_spi_hz;
	b = mcp2510_open(bus, &o);
	assert_non_null(b);
	assert_int_equal(mcp2510_set_bitrate(b, 500000, 0), 0);
	assert_int_equal(mcp2510_up(b), 0);
	for (i = 0; i < 3; i++) {
		cf = frame(0x300, 8, (uint8_t)i);
		assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	}
	while (!mcp2510_recv(a, &ev, 1000))
		;
	while (!mcp2510_recv(b, &ev, 1000))
		;
	mcp2510_stats(b, &s);
	*overflows = s.rx_overflows;
	mcp2510_close(a);
	mcp2510_close(b);
	return (unsigned int)s.rx_frames;
}

static void test_spi_time_from_environment(void **state)
{
	uint32_t overflows;

	(void)state;
	assert_int_equal(setenv("MCP2510_SIM_SPI_TIME", "msg_ns=10,bogus=1", 1), 0);
	assert_null(mcp2510_open("sim:badtime", NULL));
	assert_int_equal(errno, EINVAL);

	assert_int_equal(setenv("MCP2510_SIM_SPI_TIME",
				"msg_ns=10000,cs_setup_ns=100,cs_hold_ns=100,irq_latency_ns=20000",
				1), 0);
	assert_int_equal(burst_received("sim:fastspi", 0, &overflows), 3);
	assert_int_equal(overflows, 0);
	assert_true(burst_received("sim:slowspi", 1000, &overflows) < 3);
	assert_true(overflows > 0);
	/* a board profile by name, at a scale, with a seed and an override */
	assert_int_equal(setenv("MCP2510_SIM_SPI_TIME", "profile=nosuch", 1), 0);
	assert_null(mcp2510_open("sim:badprofile", NULL));
	assert_int_equal(errno, EINVAL);
	assert_int_equal(setenv("MCP2510_SIM_SPI_TIME", "profile=pi,scale_pct=5", 1), 0);
	assert_null(mcp2510_open("sim:badscale", NULL));
	assert_int_equal(errno, EINVAL);
	assert_int_equal(setenv("MCP2510_SIM_SPI_TIME",
				"seed=3,profile=pi-rt,scale_pct=50,msg_ns=2000", 1), 0);
	assert_int_equal(burst_received("sim:rtspi", 0, &overflows), 3);
	assert_int_equal(overflows, 0);
	assert_int_equal(unsetenv("MCP2510_SIM_SPI_TIME"), 0);
	/* off: the slow clock costs nothing */
	assert_int_equal(burst_received("sim:offspi", 1000, &overflows), 3);
}

static bool readable(struct mcp2510 *h)
{
	struct pollfd p = { .fd = mcp2510_fd(h), .events = POLLIN };

	return poll(&p, 1, 0) == 1 && (p.revents & POLLIN);
}

static void test_fd_readable_while_work_waits(void **state)
{
	struct mcp2510 *a = open_up("sim:poll", 0), *b = open_up("sim:poll", 0);
	struct can_frame cf = frame(0x42, 4, 4);
	struct mcp2510_event ev;

	(void)state;
	assert_false(readable(b));
	assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	/* a frame in flight is work for both */
	assert_true(readable(a));
	next_event(a, MCP2510_EVENT_TX_DONE);
	assert_true(readable(b));
	ev = next_event(b, MCP2510_EVENT_RX);
	assert_same_frame(&ev.frame, &cf);
	assert_false(readable(b));
	assert_int_equal(mcp2510_recv(b, &ev, 0), -1);
	assert_int_equal(errno, EAGAIN);
	assert_int_equal(mcp2510_recv(b, &ev, 10), -1);
	assert_int_equal(errno, ETIMEDOUT);
	mcp2510_close(a);
	mcp2510_close(b);
}

static void test_bus_outlives_its_handles(void **state)
{
	struct mcp2510 *a = open_up("sim:again", 0), *b = open_up("sim:again", 0);
	struct can_frame cf = frame(0x77, 0, 0);

	(void)state;
	mcp2510_close(b);
	b = open_up("sim:again", 0);
	assert_int_equal(mcp2510_send(a, &cf, 0), 0);
	assert_int_equal(next_event(b, MCP2510_EVENT_RX).frame.can_id, 0x77);
	mcp2510_close(a);
	mcp2510_close(b);
	assert_null(mcp2510_open("sim:", NULL));
	assert_int_equal(errno, EINVAL);
}

/* The reserved space that lets the public structs grow (mcp2510.h). */
static bool all_zero(const void *p, size_t len)
{
	const unsigned char *b = p;

	while (len--)
		if (*b++)
			return false;
	return true;
}

static void test_structs_can_grow(void **state)
{
	struct mcp2510_options o;
	struct mcp2510_hw_filters f;
	struct mcp2510_stats st;
	struct mcp2510_event ev;
	struct can_frame cf = frame(0x55, 1, 9);
	struct mcp2510 *h;

	(void)state;
	/* a setting this library does not know is refused, not ignored */
	memset(&o, 0xa5, sizeof(o));
	mcp2510_options_init(&o);
	assert_true(all_zero(o.reserved, sizeof(o.reserved)));
	o.reserved[7] = 1;
	errno = 0;
	assert_null(mcp2510_open("sim", &o));
	assert_int_equal(errno, EINVAL);

	h = open_up("sim", 0);
	memset(&f, 0xa5, sizeof(f));
	assert_int_equal(mcp2510_get_filters(h, &f), 0);
	assert_true(all_zero(f.reserved, sizeof(f.reserved)));
	assert_int_equal(mcp2510_down(h), 0);
	f.reserved[0] = 1;
	assert_int_equal(mcp2510_set_filters(h, &f), -1);
	assert_int_equal(errno, EINVAL);
	f.reserved[0] = 0;
	assert_int_equal(mcp2510_set_filters(h, &f), 0);

	/* what the library fills in has the space zeroed */
	assert_int_equal(mcp2510_up(h), 0);
	assert_int_equal(mcp2510_send(h, &cf, 0), 0);
	memset(&ev, 0xa5, sizeof(ev));
	ev = next_event(h, MCP2510_EVENT_TX_DONE);
	assert_true(all_zero(ev.reserved, sizeof(ev.reserved)));
	memset(&st, 0xa5, sizeof(st));
	assert_int_equal(mcp2510_stats(h, &st), 0);
	assert_true(all_zero(st.reserved, sizeof(st.reserved)));
	assert_int_equal(st.tx_frames, 1);
	mcp2510_close(h);

	assert_string_equal(mcp2510_version(), MCP2510_VERSION);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_spi_time_from_environment),
		cmocka_unit_test(test_open_and_bittiming),
		cmocka_unit_test(test_explicit_bittiming),
		cmocka_unit_test(test_ctrlmodes_by_variant),
		cmocka_unit_test(test_raw_dlc),
		cmocka_unit_test(test_running_rules),
		cmocka_unit_test(test_two_nodes_exchange_in_order),
		cmocka_unit_test(test_loopback_returns_frames),
		cmocka_unit_test(test_lone_node_becomes_error_passive),
		cmocka_unit_test(test_full_buffers_nonblock_and_timeout),
		cmocka_unit_test(test_hardware_filters),
		cmocka_unit_test(test_register_dump_and_names),
		cmocka_unit_test(test_missing_chip_refused),
		cmocka_unit_test(test_filters_reach_the_chip),
		cmocka_unit_test(test_event_ring_overflow_counted),
		cmocka_unit_test(test_fd_readable_while_work_waits),
		cmocka_unit_test(test_bus_outlives_its_handles),
		cmocka_unit_test(test_structs_can_grow),
	};

	return cmocka_run_group_tests_name("userspace_lib", tests, NULL, NULL);
}
