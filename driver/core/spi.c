// SPDX-License-Identifier: GPL-2.0
/*
 * SPI instruction framing, register access and the table of chip variants.
 * Each function here is exactly one chip-select-low period, except
 * mcp2510_xfer_msg(), which puts several in one message.
 */
#include "mcp2510_core_priv.h"

static const struct mcp2510_variant mcp2510_variants[] = {
	[MCP2510_MODEL_MCP2510] = {
		.name = "mcp2510",
		.model = MCP2510_MODEL_MCP2510,
		.spi_default_hz = 5000000,
		.has_buffer_instrs = false,
		.has_one_shot = false,
		.reset_canctrl = MCP2510_RESET_CANCTRL,
	},
	[MCP2510_MODEL_MCP2515] = {
		.name = "mcp2515",
		.model = MCP2510_MODEL_MCP2515,
		.spi_default_hz = 10000000,
		.has_buffer_instrs = true,
		.has_one_shot = true,
		.reset_canctrl = MCP2515_RESET_CANCTRL,
	},
	[MCP2510_MODEL_MCP25625] = {
		.name = "mcp25625",
		.model = MCP2510_MODEL_MCP25625,
		.spi_default_hz = 10000000,
		.has_buffer_instrs = true,
		.has_one_shot = true,
		.reset_canctrl = MCP2515_RESET_CANCTRL,
	},
};

const struct mcp2510_variant *mcp2510_variant_get(enum mcp2510_model model)
{
	if ((unsigned int)model >= ARRAY_SIZE(mcp2510_variants))
		return NULL;
	return &mcp2510_variants[model];
}

/*
 * Whatever the transport says went wrong, the chip's view of the transfer
 * is unknown: callers only need to know that, so every failure is -EIO.
 */
int mcp2510_xfer(struct mcp2510_chip *chip, const u8 *tx, u8 *rx,
		 unsigned int len)
{
	return chip->ops->xfer(chip->ctx, tx, rx, len) ? -EIO : 0;
}

int mcp2510_xfer_msg(struct mcp2510_chip *chip, const struct mcp2510_xfer *x,
		     unsigned int n)
{
	unsigned int i;

	if (!n || n > MCP2510_XFER_MSG_MAX)
		return -EINVAL;
	if (chip->ops->xfer_msg)
		return chip->ops->xfer_msg(chip->ctx, x, n) ? -EIO : 0;
	for (i = 0; i < n; i++)
		if (chip->ops->xfer(chip->ctx, x[i].tx, x[i].rx, x[i].len))
			return -EIO;
	return 0;
}

/*
 * Controllers commonly poll short transfers and finish longer ones from
 * an interrupt, which then wakes the waiting thread.  spi-bcm2835, on
 * every Raspberry Pi, polls those shorter than speed / 300000 bytes (30
 * us at 9 clocks a byte): at the MCP2510's 5 MHz, 16 bytes, the load of
 * a frame, are one too many.  A period that fits in two polled transfers
 * goes as two, chip select held low between them, which the chip cannot
 * tell from one: a transfer's set-up costs the controller a few
 * microseconds, a wake-up 16 and, in its tail, hundreds.
 */
#define MCP2510_POLL_HZ_PER_BYTE	300000

unsigned int mcp2510_xfer_first_len(unsigned int len, u32 speed_hz)
{
	unsigned int poll_max = speed_hz / MCP2510_POLL_HZ_PER_BYTE;

	if (poll_max)
		poll_max--;
	if (len <= poll_max || len > 2 * poll_max)
		return len;
	return len / 2;
}

int mcp2510_reg_read(struct mcp2510_chip *chip, u8 addr, u8 *buf,
		     unsigned int len)
{
	u8 tx[MCP2510_XFER_MAX] = { MCP2510_INSTR_READ, addr };
	u8 rx[MCP2510_XFER_MAX];
	int err;

	if (!len || len > MCP2510_REG_COUNT)
		return -EINVAL;
	err = mcp2510_xfer(chip, tx, rx, 2 + len);
	if (err)
		return err;
	memcpy(buf, rx + 2, len);
	return 0;
}

int mcp2510_reg_write(struct mcp2510_chip *chip, u8 addr, const u8 *buf,
		      unsigned int len)
{
	u8 tx[MCP2510_XFER_MAX] = { MCP2510_INSTR_WRITE, addr };

	if (!len || len > MCP2510_REG_COUNT)
		return -EINVAL;
	memcpy(tx + 2, buf, len);
	return mcp2510_xfer(chip, tx, NULL, 2 + len);
}

int mcp2510_reg_modify(struct mcp2510_chip *chip, u8 addr, u8 mask, u8 val)
{
	const u8 tx[4] = { MCP2510_INSTR_BIT_MODIFY, addr, mask, val };

	return mcp2510_xfer(chip, tx, NULL, sizeof(tx));
}

int mcp2510_read_status(struct mcp2510_chip *chip, u8 *status)
{
	const u8 tx[2] = { MCP2510_INSTR_READ_STATUS, 0 };
	u8 rx[2];
	int err;

	err = mcp2510_xfer(chip, tx, rx, sizeof(tx));
	if (!err)
		*status = rx[1];
	return err;
}

int mcp2510_regs_dump(struct mcp2510_chip *chip, u8 *buf)
{
	return mcp2510_reg_read(chip, 0, buf, MCP2510_REGDUMP_LEN);
}
