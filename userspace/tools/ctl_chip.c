// SPDX-License-Identifier: GPL-2.0
/* mcp2510ctl commands about the chip itself: info, reset, bittiming,
 * regs, filter, state. */
#include <inttypes.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "ctl.h"
#include <linux/can/mcp2510.h>

static int no_own_option(struct ctl *c, void *ctx, int id, const char *value)
{
	(void)c;
	(void)ctx;
	(void)id;
	(void)value;
	return -1;
}

/* Parse a command that takes only device options and @max_pos args. */
static int parse_plain(struct ctl *c, const struct ctl_command *cmd,
		       int min_pos, int max_pos, bool *done)
{
	return ctl_parse(c, cmd, NULL, no_own_option, NULL, min_pos, max_pos,
			 done);
}

/* A command with no arguments of its own: parse, then @job on the chip. */
static int run_plain(struct ctl *c, const struct ctl_command *cmd,
		     ctl_chip_fn job)
{
	bool done;
	int ret = parse_plain(c, cmd, 0, 0, &done);

	if (done)
		return ret;
	return ctl_on_chip(c, cli_device_open(&c->dev, &c->args, true), job,
			   NULL);
}

static const char *mode_name(uint8_t canstat)
{
	static const char *const names[] = {
		[MCP2510_MODE_NORMAL] = "normal",
		[MCP2510_MODE_SLEEP] = "sleep",
		[MCP2510_MODE_LOOPBACK] = "loopback",
		[MCP2510_MODE_LISTEN_ONLY] = "listen-only",
		[MCP2510_MODE_CONFIG] = "configuration",
	};
	unsigned int mode = (canstat & MCP2510_CANSTAT_OPMOD_MASK) >> 5;

	return mode < sizeof(names) / sizeof(names[0]) && names[mode] ?
		names[mode] : "unknown";
}

static void print_state(struct ctl *c, enum can_state st,
			const struct can_berr_counter *bec)
{
	fprintf(c->out, "state %s tec %u rec %u\n", mcp2510_state_name(st),
		bec->txerr, bec->rxerr);
}

/* ---- info ---- */

static int info_print(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	uint8_t regs[MCP2510_REGS_LEN];
	struct can_berr_counter bec;
	enum can_state st;

	(void)ctx;
	if (mcp2510_read_regs(h, regs) || mcp2510_state(h, &st, &bec)) {
		cli_error_errno(&c->args, "reading the chip");
		return EXIT_FAIL;
	}
	fprintf(c->out, "device %s\nvariant %s\noscillator %" PRIu32 "\n",
		c->dev.device, mcp2510_variant_name(h), mcp2510_osc_hz(h));
	fprintf(c->out, "mode %s\n", mode_name(regs[MCP2510_REG_CANSTAT]));
	print_state(c, st, &bec);
	fprintf(c->out, "cnf1 0x%02x cnf2 0x%02x cnf3 0x%02x\n",
		regs[MCP2510_REG_CNF1], regs[MCP2510_REG_CNF2],
		regs[MCP2510_REG_CNF3]);
	return 0;
}

static int info_run(struct ctl *c)
{
	return run_plain(c, &ctl_info, info_print);
}

const struct ctl_command ctl_info = {
	.name = "info",
	.summary = "variant, oscillator, operating mode, error state, CNF1-3",
	.help =
"Usage: mcp2510ctl --device DEV info\n"
"Show what the chip is doing without disturbing it: variant, oscillator,\n"
"operating mode (CANSTAT), error state with TEC/REC, and CNF1..CNF3.\n",
	.run = info_run,
	.needs_device = true,
};

/* ---- reset ---- */

static int reset_chip(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	(void)ctx;
	if (mcp2510_reset(h)) {
		cli_error_errno(&c->args, "reset");
		return EXIT_FAIL;
	}
	return 0;
}

static int reset_run(struct ctl *c)
{
	return run_plain(c, &ctl_reset, reset_chip);
}

const struct ctl_command ctl_reset = {
	.name = "reset",
	.summary = "reset the chip into configuration mode",
	.help =
"Usage: mcp2510ctl --device DEV reset\n"
"Send the RESET instruction: every register returns to its reset value\n"
"and the chip waits in configuration mode.\n",
	.run = reset_run,
	.needs_device = true,
};

/* ---- bittiming ---- */

static int bittiming_run(struct ctl *c)
{
	struct can_bittiming bt;
	uint8_t cnf[3];
	bool done;
	int ret = parse_plain(c, &ctl_bittiming, 0, 1, &done);

	if (done)
		return ret;
	if (c->npos && (cli_u32(c->pos[0], &c->dev.bitrate) || !c->dev.bitrate)) {
		ctl_bad(c, "bit rate", c->pos[0]);
		return EXIT_USAGE;
	}
	if (cli_bittiming(&c->args, c->dev.opts.osc_hz, c->dev.bitrate,
			  c->dev.sample_point, &bt, cnf))
		return EXIT_FAIL;
	fprintf(c->out,
		"bitrate %u sample-point %.3f tq %u prop-seg %u phase-seg1 %u phase-seg2 %u sjw %u brp %u\n",
		bt.bitrate, bt.sample_point / 1000.0, bt.tq, bt.prop_seg,
		bt.phase_seg1, bt.phase_seg2, bt.sjw, bt.brp);
	fprintf(c->out, "cnf1 0x%02x cnf2 0x%02x cnf3 0x%02x\n",
		cnf[0], cnf[1], cnf[2]);
	return 0;
}

const struct ctl_command ctl_bittiming = {
	.name = "bittiming",
	.summary = "bit timing and CNF1-3 for a bit rate (needs no chip)",
	.help =
"Usage: mcp2510ctl bittiming [BITRATE] [--clock HZ] [--sample-point SP]\n"
"Print the timing the Linux kernel would choose for BITRATE (default: the\n"
"--bitrate option) with an oscillator of HZ (the device tree's clock; the\n"
"CAN clock is half of it), in iproute2's words, then the CNF1..CNF3 values\n"
"that program it:\n"
"  bitrate B sample-point S tq T prop-seg P phase-seg1 A phase-seg2 B sjw J brp R\n"
"  cnf1 0xNN cnf2 0xNN cnf3 0xNN\n"
"tq is in nanoseconds.  A bit rate the chip cannot make exits with 1.\n",
	.run = bittiming_run,
};

/* ---- regs ---- */

static int regs_print(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	uint8_t regs[MCP2510_REGS_LEN];
	char name[MCP2510_REG_NAME_MAX];
	unsigned int i;

	(void)ctx;
	if (mcp2510_read_regs(h, regs)) {
		cli_error_errno(&c->args, "reading the registers");
		return EXIT_FAIL;
	}
	for (i = 0; i < MCP2510_REGS_LEN; i++) {
		mcp2510_reg_name(i, name, sizeof(name));
		fprintf(c->out, "0x%02x %-10s 0x%02x\n", i, name, regs[i]);
	}
	return 0;
}

static int regs_run(struct ctl *c)
{
	return run_plain(c, &ctl_regs, regs_print);
}

const struct ctl_command ctl_regs = {
	.name = "regs",
	.summary = "dump the 128 registers with their names",
	.help =
"Usage: mcp2510ctl --device DEV regs\n"
"Read the whole register file in one sequential READ, without resetting\n"
"the chip, and print one register a line: address, name, value.\n"
"CANSTAT and CANCTRL appear at the end of every row, as the chip maps them.\n",
	.run = regs_run,
	.needs_device = true,
};

/* ---- filter ---- */

static void filters_print(struct ctl *c, const struct mcp2510_hw_filters *f)
{
	char line[64];
	unsigned int i;

	for (i = 0; i < MCP2510_HW_FILTER_SETTINGS; i++)
		if (mcp2510_hw_filters_format(f, i, line, sizeof(line)) >= 0)
			fprintf(c->out, "%s\n", line);
}

/* Program @ctx's filters, then print what the chip holds. */
static int filters_apply(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	struct mcp2510_hw_filters *f = ctx;

	if (mcp2510_set_filters(h, f) || mcp2510_get_filters(h, f)) {
		cli_error_errno(&c->args, "setting the filters");
		return EXIT_FAIL;
	}
	filters_print(c, f);
	return 0;
}

static int filter_run(struct ctl *c)
{
	struct mcp2510_hw_filters f;
	bool done;
	int i, ret = parse_plain(c, &ctl_filter, 0, CTL_MAX_ARGS, &done);

	if (done)
		return ret;
	mcp2510_hw_filters_default(&f);
	for (i = 0; i < c->npos; i++)
		if (cli_filter_assign(&c->args, &f, c->pos[i]))
			return EXIT_USAGE;
	return ctl_on_chip(c, cli_device_open(&c->dev, &c->args, false),
			   filters_apply, &f);
}

const struct ctl_command ctl_filter = {
	.name = "filter",
	.summary = "set and show masks, filters and receive modes",
	.help =
"Usage: mcp2510ctl --device DEV filter [NAME=VALUE ...]\n"
"Program the acceptance filters, starting from the default (accept all),\n"
"and print every setting.  NAME and VALUE as in the driver's sysfs files\n"
"(hex ids without 0x; an x after a 29-bit one):\n"
"  mask0 mask1         7ff (standard, 11 bit) or 1fffffffx (extended)\n"
"  filter0 .. filter5  RXB0 uses filters 0-1, RXB1 filters 2-5\n"
"  rxm0 rxm1           filtered, std, ext or any (filters off)\n"
"  rollover            1: a frame for a full RXB0 goes to RXB1\n"
"They stay in the chip for what comes next (send, dump, mcp2510d) until\n"
"its power goes or filter runs again; filter alone accepts every frame\n"
"again.  selftest replaces them, saying so; dump --filter NAME=VALUE\n"
"changes settings on top of them for one capture.\n",
	.run = filter_run,
	.needs_device = true,
};

/* ---- state ---- */

static int state_read(struct ctl *c, struct mcp2510 *h, void *ctx)
{
	struct can_berr_counter bec;
	enum can_state st;

	(void)ctx;
	if (mcp2510_state(h, &st, &bec)) {
		cli_error_errno(&c->args, "reading the state");
		return EXIT_FAIL;
	}
	print_state(c, st, &bec);
	return 0;
}

static int state_run(struct ctl *c)
{
	return run_plain(c, &ctl_state, state_read);
}

const struct ctl_command ctl_state = {
	.name = "state",
	.summary = "error state and TEC/REC",
	.help =
"Usage: mcp2510ctl --device DEV state\n"
"Print the error state (ERROR-ACTIVE, ERROR-WARNING, ERROR-PASSIVE,\n"
"BUS-OFF, or STOPPED/SLEEPING when the chip is not on the bus) and the\n"
"transmit and receive error counters, without disturbing the chip.\n",
	.run = state_run,
	.needs_device = true,
};
