// SPDX-License-Identifier: GPL-2.0
/*
 * One chip's SPI slave: instruction decoding (RESET, READ, WRITE, RTS,
 * READ STATUS, BIT MODIFY, and on the MCP2515 RX STATUS, READ RX BUFFER and
 * LOAD TX BUFFER), the sequential address pointer, and the corrupted MISO
 * answers a fault may ask for.  What a transfer costs in time is
 * sim_spi_time.c's.
 *
 * References: DS21291 section 11 (SPI interface, table 11-1, figures
 * 11-2..11-7); DS21801 section 12 (table 12-1, figures 12-2..12-9).
 */
#include "sim_private.h"

#define SIM_MISO_IDLE		0xff	/* SO high impedance, pulled up */
#define SIM_DEFAULT_CORRUPT	0xa5
#define SIM_CORRUPT_SEED	0x2545f491u	/* any non-zero xorshift state */

/* ---- SPI ------------------------------------------------------------------------ */

static u8 sim_read_status(const struct sim_chip *chip)
{
	u8 intf = chip->regs[MCP2510_REG_CANINTF], s = 0;
	unsigned int n;

	if (intf & MCP2510_INT_RX0)
		s |= MCP2510_STATUS_RX0IF;
	if (intf & MCP2510_INT_RX1)
		s |= MCP2510_STATUS_RX1IF;
	for (n = 0; n < MCP2510_TXB_COUNT; n++) {
		if (chip->regs[MCP2510_REG_TXBCTRL(n)] & MCP2510_TXBCTRL_TXREQ)
			s |= MCP2510_STATUS_TXREQ(n);
		if (intf & MCP2510_INT_TX(n))
			s |= MCP2510_STATUS_TXIF(n);
	}
	return s;
}

/* DS21801 figure 12-9 */
static u8 sim_rx_status(const struct sim_chip *chip)
{
	u8 rxif = chip->regs[MCP2510_REG_CANINTF] & MCP2510_INT_RX_ALL;
	u8 s = rxif << 6;

	if (rxif & MCP2510_INT_RX0)
		s |= chip->rx_status[0];
	else if (rxif & MCP2510_INT_RX1)
		s |= chip->rx_status[1];
	return s;
}

/* Sequential READ / WRITE through the 7-bit address pointer (wraps 7f -> 00). */
static void sim_spi_read_seq(struct sim_chip *chip, unsigned int addr,
			     u8 *rx, size_t from, size_t len)
{
	size_t i;

	for (i = from; i < len; i++, addr++)
		if (rx)
			rx[i] = sim_reg_read(chip, addr);
}

static void sim_spi_write_seq(struct sim_chip *chip, unsigned int addr,
			      const u8 *tx, size_t from, size_t len)
{
	size_t i;

	for (i = from; i < len; i++, addr++)
		sim_reg_write(chip, addr, tx[i], 0xff);
}

static void sim_spi_repeat(u8 *rx, size_t len, u8 val)
{
	size_t i;

	for (i = 1; rx && i < len; i++)
		rx[i] = val;
}

/* One instruction; returns false when the chip does not know it. */
static bool sim_spi_execute(struct sim_chip *chip, const u8 *tx, u8 *rx,
			    size_t len)
{
	bool mcp2515 = chip->variant == SIM_MCP2515;
	u8 instr = tx[0];
	unsigned int n;

	switch (instr) {
	case MCP2510_INSTR_RESET:
		sim_chip_reset(chip, false);
		return true;
	case MCP2510_INSTR_READ:
		if (len > 2)
			sim_spi_read_seq(chip, tx[1], rx, 2, len);
		return true;
	case MCP2510_INSTR_WRITE:
		if (len > 2)
			sim_spi_write_seq(chip, tx[1], tx, 2, len);
		return true;
	case MCP2510_INSTR_BIT_MODIFY:
		/* CS raised before the data byte is complete: nothing changes */
		if (len >= 4)
			sim_reg_write(chip, tx[1] & SIM_ADDR_MASK, tx[3],
				      sim_reg_bit_modifiable(tx[1] & SIM_ADDR_MASK) ?
				      tx[2] : 0xff);
		return true;
	case MCP2510_INSTR_READ_STATUS:
		sim_spi_repeat(rx, len, sim_read_status(chip));
		return true;
	case MCP2515_INSTR_RX_STATUS:
		if (!mcp2515)
			return false;
		sim_spi_repeat(rx, len, sim_rx_status(chip));
		return true;
	}
	if ((instr & ~MCP2510_RTS_ALL) == MCP2510_INSTR_RTS) {
		for (n = 0; n < MCP2510_TXB_COUNT; n++)
			if (instr & MCP2510_RTS_TXB(n))
				sim_chip_request(chip, n);
		return true;
	}
	if (mcp2515 && (instr & ~0x06) == MCP2515_INSTR_READ_RX_BUFFER) {
		n = (instr >> 2) & 1;
		sim_spi_read_seq(chip, MCP2510_REG_RXB(n) +
				 ((instr & 0x02) ? MCP2510_BUF_D0 : MCP2510_BUF_SIDH),
				 rx, 1, len);
		/* RXnIF clears when CS goes high */
		*sim_reg(chip, MCP2510_REG_CANINTF) &= ~MCP2510_INT_RX(n);
		return true;
	}
	if (mcp2515 && (instr & ~0x07) == MCP2515_INSTR_LOAD_TX_BUFFER &&
	    (instr & 0x07) < 6) {
		n = (instr & 0x07) >> 1;
		sim_spi_write_seq(chip, MCP2510_REG_TXB(n) +
				  ((instr & 1) ? MCP2510_BUF_D0 : MCP2510_BUF_SIDH),
				  tx, 1, len);
		return true;
	}
	return false;
}

/* xorshift32 (Marsaglia): cheap, and the same bytes on every run */
static u8 sim_corrupt_random(struct sim_chip_faults *f)
{
	u32 x = f->spi_corrupt_seed ? f->spi_corrupt_seed : SIM_CORRUPT_SEED;

	x ^= x << 13;
	x ^= x >> 17;
	x ^= x << 5;
	f->spi_corrupt_seed = x;
	return x >> 24;
}

static u8 sim_corrupt_byte(struct sim_chip_faults *f, u8 answer)
{
	switch (f->spi_corrupt_kind) {
	case SIM_CORRUPT_FIXED:
		return f->spi_corrupt_byte;
	case SIM_CORRUPT_RANDOM:
		return sim_corrupt_random(f);
	default:
		return answer ^ (f->spi_corrupt_xor ? f->spi_corrupt_xor :
				 SIM_DEFAULT_CORRUPT);
	}
}

static void sim_spi_corrupt(struct sim_chip *chip, u8 *rx, size_t len)
{
	struct sim_chip_faults *f = &chip->faults;
	size_t i;

	if (!f->spi_corrupt)
		return;
	if (f->spi_corrupt != SIM_CORRUPT_FOREVER)
		f->spi_corrupt--;
	for (i = 0; rx && i < len; i++)
		rx[i] = sim_corrupt_byte(f, rx[i]);
}

void sim_chip_spi(struct sim_chip *chip, const u8 *tx, u8 *rx, size_t len)
{
	chip->counters.spi_transfers++;
	chip->counters.spi_bytes += len;
	if (rx)
		memset(rx, SIM_MISO_IDLE, len);
	if (!len || !tx || !sim_chip_ready(chip) ||
	    !sim_spi_execute(chip, tx, rx, len))
		chip->counters.spi_ignored++;
	if (len && chip->powered)
		sim_spi_corrupt(chip, rx, len);
	sim_chip_update_pins(chip);
}
