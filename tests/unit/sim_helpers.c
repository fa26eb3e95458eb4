// SPDX-License-Identifier: GPL-2.0
#include <string.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim_helpers.h"

#define SIMH_MAX_XFER	(2 + MCP2510_REG_COUNT * 2)

u8 simh_read(struct sim_chip *chip, u8 addr)
{
	u8 v;

	simh_read_seq(chip, addr, &v, 1);
	return v;
}

void simh_read_seq(struct sim_chip *chip, u8 addr, u8 *out, size_t n)
{
	u8 tx[SIMH_MAX_XFER] = { MCP2510_INSTR_READ, addr };
	u8 rx[SIMH_MAX_XFER];

	if (n > SIMH_MAX_XFER - 2)
		n = SIMH_MAX_XFER - 2;
	sim_chip_spi(chip, tx, rx, n + 2);
	memcpy(out, rx + 2, n);
}

void simh_write(struct sim_chip *chip, u8 addr, u8 val)
{
	simh_write_seq(chip, addr, &val, 1);
}

void simh_write_seq(struct sim_chip *chip, u8 addr, const u8 *data, size_t n)
{
	u8 tx[SIMH_MAX_XFER] = { MCP2510_INSTR_WRITE, addr };

	if (n > SIMH_MAX_XFER - 2)
		n = SIMH_MAX_XFER - 2;
	memcpy(tx + 2, data, n);
	sim_chip_spi(chip, tx, NULL, n + 2);
}

void simh_bit_modify(struct sim_chip *chip, u8 addr, u8 mask, u8 val)
{
	u8 tx[4] = { MCP2510_INSTR_BIT_MODIFY, addr, mask, val };

	sim_chip_spi(chip, tx, NULL, sizeof(tx));
}

void simh_reset(struct sim_chip *chip)
{
	u8 tx = MCP2510_INSTR_RESET;

	sim_chip_spi(chip, &tx, NULL, 1);
	if (chip->bus)
		sim_bus_advance(chip->bus, sim_chip_startup_ns(chip));
}

u8 simh_read_status(struct sim_chip *chip)
{
	u8 tx[2] = { MCP2510_INSTR_READ_STATUS, 0 }, rx[2];

	sim_chip_spi(chip, tx, rx, sizeof(tx));
	return rx[1];
}

void simh_rts(struct sim_chip *chip, u8 buffers)
{
	u8 tx = MCP2510_INSTR_RTS | (buffers & MCP2510_RTS_ALL);

	sim_chip_spi(chip, &tx, NULL, 1);
}

u8 simh_opmode(struct sim_chip *chip)
{
	return FIELD_GET(MCP2510_CANSTAT_OPMOD_MASK,
			 simh_read(chip, MCP2510_REG_CANSTAT));
}

int simh_set_mode(struct sim_chip *chip, unsigned int mode)
{
	unsigned int tries;

	simh_bit_modify(chip, MCP2510_REG_CANCTRL, MCP2510_CANCTRL_REQOP_MASK,
			FIELD_PREP(MCP2510_CANCTRL_REQOP_MASK, mode));
	for (tries = 0; tries < 1000; tries++) {
		if (simh_opmode(chip) == mode)
			return 0;
		if (!chip->bus)
			break;
		sim_bus_advance(chip->bus, 10000);	/* poll every 10 us */
	}
	return -ETIMEDOUT;
}

void simh_load_tx(struct sim_chip *chip, unsigned int n, const struct can_frame *cf)
{
	u8 b[MCP2510_BUF_LEN] = { 0 };	/* indexed by MCP2510_BUF_* */
	bool ext = cf->can_id & CAN_EFF_FLAG;
	u32 id = ext ? cf->can_id & CAN_EFF_MASK : cf->can_id & CAN_SFF_MASK;
	u32 sid = ext ? id >> MCP2510_EID_BITS : id;

	b[MCP2510_BUF_SIDH] = sid >> 3;
	b[MCP2510_BUF_SIDL] = (sid & 7) << 5;
	if (ext) {
		b[MCP2510_BUF_SIDL] |= MCP2510_SIDL_EXIDE | ((id >> 16) & 3);
		b[MCP2510_BUF_EID8] = id >> 8;
		b[MCP2510_BUF_EID0] = id;
	}
	b[MCP2510_BUF_DLC] = cf->len;
	if (cf->can_id & CAN_RTR_FLAG)
		b[MCP2510_BUF_DLC] |= MCP2510_DLC_RTR;
	memcpy(&b[MCP2510_BUF_D0], cf->data, cf->len);
	/* one sequential WRITE from SIDH to D7, as a driver would */
	simh_write_seq(chip, MCP2510_REG_TXBSIDH(n), &b[MCP2510_BUF_SIDH],
		       MCP2510_BUF_LEN - MCP2510_BUF_SIDH);
}

void simh_send(struct sim_chip *chip, unsigned int n, const struct can_frame *cf)
{
	simh_load_tx(chip, n, cf);
	simh_rts(chip, MCP2510_RTS_TXB(n));
}

void simh_read_rx(struct sim_chip *chip, unsigned int n, struct can_frame *cf,
		  bool clear)
{
	u8 buf[MCP2510_BUF_LEN];
	u8 *b = buf;
	u32 sid;

	simh_read_seq(chip, MCP2510_REG_RXB(n), buf, sizeof(buf));
	memset(cf, 0, sizeof(*cf));
	sid = (u32)b[MCP2510_BUF_SIDH] << 3 | b[MCP2510_BUF_SIDL] >> 5;
	if (b[MCP2510_BUF_SIDL] & MCP2510_SIDL_EXIDE) {
		cf->can_id = CAN_EFF_FLAG | sid << MCP2510_EID_BITS |
			     (u32)(b[MCP2510_BUF_SIDL] & 3) << 16 |
			     (u32)b[MCP2510_BUF_EID8] << 8 | b[MCP2510_BUF_EID0];
		if (b[MCP2510_BUF_DLC] & MCP2510_DLC_RTR)
			cf->can_id |= CAN_RTR_FLAG;
	} else {
		cf->can_id = sid;
		if (b[MCP2510_BUF_SIDL] & MCP2510_SIDL_SRR)
			cf->can_id |= CAN_RTR_FLAG;
	}
	cf->len = b[MCP2510_BUF_DLC] & MCP2510_DLC_MASK;
	if (cf->len > CAN_MAX_DLEN)
		cf->len = CAN_MAX_DLEN;
	if (!(cf->can_id & CAN_RTR_FLAG))
		memcpy(cf->data, &b[MCP2510_BUF_D0], cf->len);
	if (clear)
		simh_bit_modify(chip, MCP2510_REG_CANINTF, MCP2510_INT_RX(n), 0);
}

void simh_node_setup(struct sim_bus *bus, struct sim_chip *chip,
		     enum sim_variant variant, u8 cnf1, u8 cnf2, u8 cnf3)
{
	/* its own power-up garbage: the seed is the node's index */
	sim_chip_init_seeded(chip, variant, SIMH_OSC_16MHZ, bus->nchips);
	sim_bus_attach(bus, chip);
	sim_bus_advance(bus, sim_chip_startup_ns(chip));
	simh_reset(chip);
	simh_write(chip, MCP2510_REG_CNF1, cnf1);
	simh_write(chip, MCP2510_REG_CNF2, cnf2);
	simh_write(chip, MCP2510_REG_CNF3, cnf3);
}

void simh_node_setup_125k(struct sim_bus *bus, struct sim_chip *chip,
			  enum sim_variant variant)
{
	simh_node_setup(bus, chip, variant, SIMH_CNF1_125K, SIMH_CNF2_125K,
			SIMH_CNF3_125K);
}

void simh_node_up(struct sim_bus *bus, struct sim_chip *chip,
		  enum sim_variant variant)
{
	simh_node_setup_125k(bus, chip, variant);
	simh_set_mode(chip, MCP2510_MODE_NORMAL);
}

int simh_teardown(void **state)
{
	test_free(*state);
	return 0;
}

void simh_run_idle(struct sim_bus *bus, u64 max_ns)
{
	u64 end = sim_bus_now(bus) + max_ns;

	while (sim_bus_now(bus) < end) {
		u64 next = sim_bus_next_event(bus);

		if (next == U64_MAX)
			break;
		sim_bus_advance_to(bus, next < end ? next : end);
		if (next >= end)
			break;
	}
}

struct can_frame simh_frame(canid_t id, u8 len, const u8 *data)
{
	struct can_frame cf;

	memset(&cf, 0, sizeof(cf));
	cf.can_id = id;
	cf.len = len;
	if (data && !(id & CAN_RTR_FLAG))
		memcpy(cf.data, data, len);
	return cf;
}

bool simh_frame_equal(const struct can_frame *a, const struct can_frame *b)
{
	if (a->can_id != b->can_id || a->len != b->len)
		return false;
	if (a->can_id & CAN_RTR_FLAG)
		return true;
	return !memcmp(a->data, b->data, a->len);
}

static void simh_log_record(void *ctx, const struct sim_bus_record *rec)
{
	struct simh_log *log = ctx;

	log->rec[log->count % SIMH_LOG_MAX] = *rec;
	log->count++;
}

void simh_log_attach(struct sim_bus *bus, struct simh_log *log)
{
	memset(log, 0, sizeof(*log));
	sim_bus_set_monitor(bus, simh_log_record, log);
}

const struct sim_bus_record *simh_log_get(const struct simh_log *log,
					  unsigned int i)
{
	return &log->rec[i % SIMH_LOG_MAX];
}
