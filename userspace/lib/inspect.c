// SPDX-License-Identifier: LGPL-2.1-or-later
/* Looking at the chip: error state and counters, registers, statistics. */
#include <stdio.h>

#include "handle.h"

/*
 * A chip this handle did not start (another program may drive it): the
 * state as its EFLG and operating mode show it now.
 */
static int state_from_chip(struct mcp2510 *h, enum can_state *state)
{
	u8 eflg, canstat;
	int ret;

	ret = mcp2510_reg_read(&h->chip, MCP2510_REG_EFLG, &eflg, 1);
	if (!ret)
		ret = mcp2510_reg_read(&h->chip, MCP2510_REG_CANSTAT, &canstat, 1);
	if (ret)
		return ret;
	switch (FIELD_GET(MCP2510_CANSTAT_OPMOD_MASK, canstat)) {
	case MCP2510_MODE_CONFIG:
		*state = CAN_STATE_STOPPED;
		return 0;
	case MCP2510_MODE_SLEEP:
		*state = CAN_STATE_SLEEPING;
		return 0;
	}
	if (eflg & MCP2510_EFLG_TXBO)
		*state = CAN_STATE_BUS_OFF;
	else if (eflg & (MCP2510_EFLG_TXEP | MCP2510_EFLG_RXEP))
		*state = CAN_STATE_ERROR_PASSIVE;
	else if (eflg & MCP2510_EFLG_EWARN)
		*state = CAN_STATE_ERROR_WARNING;
	else
		*state = CAN_STATE_ERROR_ACTIVE;
	return 0;
}

int mcp2510_state(struct mcp2510 *h, enum can_state *state,
		  struct can_berr_counter *bec)
{
	struct can_berr_counter b;
	enum can_state st = h->state;
	int ret = mcp2510_berr_counter(&h->chip, &b);

	if (!ret && !h->running)
		ret = state_from_chip(h, &st);
	if (ret)
		return mcp2510_fail(ret);
	if (state)
		*state = st;
	if (bec)
		*bec = b;
	return 0;
}

const char *mcp2510_version(void)
{
	return MCP2510_VERSION;
}

/* The words "ip -details link show" uses. */
const char *mcp2510_state_name(enum can_state state)
{
	switch (state) {
	case CAN_STATE_ERROR_ACTIVE:
		return "ERROR-ACTIVE";
	case CAN_STATE_ERROR_WARNING:
		return "ERROR-WARNING";
	case CAN_STATE_ERROR_PASSIVE:
		return "ERROR-PASSIVE";
	case CAN_STATE_BUS_OFF:
		return "BUS-OFF";
	case CAN_STATE_STOPPED:
		return "STOPPED";
	case CAN_STATE_SLEEPING:
		return "SLEEPING";
	default:
		return "UNKNOWN";
	}
}

int mcp2510_read_regs(struct mcp2510 *h, uint8_t *regs)
{
	return mcp2510_fail(mcp2510_regs_dump(&h->chip, regs));
}

static const char *const buf_field[MCP2510_BUF_LEN] = {
	"CTRL", "SIDH", "SIDL", "EID8", "EID0", "DLC",
	"D0", "D1", "D2", "D3", "D4", "D5", "D6", "D7",
};

static const char *const id_field[MCP2510_ID_LEN] = {
	"SIDH", "SIDL", "EID8", "EID0",
};

/* Registers outside the buffers and the filter blocks, by address. */
static const char *control_reg(unsigned int addr)
{
	switch (addr) {
	case MCP2510_REG_BFPCTRL:	return "BFPCTRL";
	case MCP2510_REG_TXRTSCTRL:	return "TXRTSCTRL";
	case MCP2510_REG_TEC:		return "TEC";
	case MCP2510_REG_REC:		return "REC";
	case MCP2510_REG_CNF3:		return "CNF3";
	case MCP2510_REG_CNF2:		return "CNF2";
	case MCP2510_REG_CNF1:		return "CNF1";
	case MCP2510_REG_CANINTE:	return "CANINTE";
	case MCP2510_REG_CANINTF:	return "CANINTF";
	case MCP2510_REG_EFLG:		return "EFLG";
	default:			return NULL;
	}
}

static void name_reg(unsigned int addr, char *buf, size_t len)
{
	const char *ctl = control_reg(addr);
	unsigned int row = addr >> 4, col = addr & 0xf;

	if ((addr & 0xf) == (MCP2510_REG_CANSTAT & 0xf))
		snprintf(buf, len, "CANSTAT");
	else if ((addr & 0xf) == (MCP2510_REG_CANCTRL & 0xf))
		snprintf(buf, len, "CANCTRL");
	else if (ctl)
		snprintf(buf, len, "%s", ctl);
	else if (row >= 3 && row < 3 + MCP2510_TXB_COUNT)
		snprintf(buf, len, "TXB%u%s", row - 3, buf_field[col]);
	else if (row >= 6 && row < 6 + MCP2510_RXB_COUNT)
		snprintf(buf, len, "RXB%u%s", row - 6, buf_field[col]);
	else if (addr < MCP2510_REG_RXF(3))
		snprintf(buf, len, "RXF%u%s", addr / 4, id_field[addr % 4]);
	else if (addr < MCP2510_REG_TEC)
		snprintf(buf, len, "RXF%u%s", 3 + (addr - MCP2510_REG_RXF(3)) / 4,
			 id_field[addr % 4]);
	else if (addr >= MCP2510_REG_RXM(0) && addr < MCP2510_REG_CNF3)
		snprintf(buf, len, "RXM%u%s", (addr - MCP2510_REG_RXM(0)) / 4,
			 id_field[addr % 4]);
	else
		snprintf(buf, len, "-");
}

int mcp2510_reg_name(unsigned int addr, char *buf, size_t len)
{
	if (addr >= MCP2510_REG_COUNT || !len)
		return mcp2510_fail(-EINVAL);
	name_reg(addr, buf, len);
	return 0;
}

MCP2510_ABI_LAYOUT(struct mcp2510_stats, 144);

int mcp2510_stats(const struct mcp2510 *h, struct mcp2510_stats *s)
{
	const struct mcp2510_counters *c = &h->chip.counters;
	struct mcp2510_transport_counts tc;

	h->transport->ops->counts(h->transport, &tc);
	memset(s, 0, sizeof(*s));
	s->spi_transfers = tc.spi_transfers;
	s->spi_bytes = tc.spi_bytes;
	s->interrupts = tc.interrupts;
	s->rx_frames = h->rx_frames;
	s->tx_frames = h->tx_frames_done;
	s->ring_overflows = h->ring.overflows;
	s->rx_overflows = c->rx_overflows;
	s->bus_errors = c->bus_errors;
	s->arbitration_lost = c->arbitration_lost;
	s->tx_errors = c->tx_errors;
	s->warnings = c->warnings;
	s->passives = c->passives;
	s->bus_offs = c->bus_offs;
	s->restarts = c->restarts;
	return 0;
}
