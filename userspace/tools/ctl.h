/* SPDX-License-Identifier: GPL-2.0 */
/* mcp2510ctl's subcommands and what they share. */
#ifndef MCP2510_CTL_H
#define MCP2510_CTL_H

#include "cli.h"

#define CTL_MAX_ARGS	32
#define CTL_MAX_ITEMS	96

/* An option (opt set) or an argument after the command, in order. */
struct ctl_item {
	const struct cli_option *opt;
	const char *value;
};

struct ctl {
	FILE *out;
	struct cli_args args;
	struct cli_device dev;
	struct ctl_item items[CTL_MAX_ITEMS];	/* the whole command line */
	int nitems;
	const char *pos[CTL_MAX_ARGS];	/* positional arguments */
	int npos;
};

/* What a subcommand does with the opened chip; @ctx is its own state. */
typedef int (*ctl_chip_fn)(struct ctl *c, struct mcp2510 *h, void *ctx);

/* A subcommand's own option, handed to its parser. */
typedef int (*ctl_option_fn)(struct ctl *c, void *ctx, int id,
			     const char *value);

struct ctl_command {
	const char *name;
	const char *summary;		/* one line for the command list */
	const char *help;		/* the whole "CMD --help" text */
	bool needs_device;		/* --device is required */
	const struct cli_option *options;	/* its own, or NULL */
	int (*run)(struct ctl *c);
};

/*
 * Take the command line, options before or after the command alike:
 * device options, @own options (handled by @fn; @own is the command's
 * .options) and between @min_pos and @max_pos positional arguments into
 * c->pos.  Returns 0, or an exit status to end with: 0 after --help,
 * EXIT_USAGE after an error it reported.
 */
int ctl_parse(struct ctl *c, const struct ctl_command *cmd,
	      const struct cli_option *own, ctl_option_fn fn, void *ctx,
	      int min_pos, int max_pos, bool *done);

/*
 * Run @job on @h and close it.  A NULL @h means its opener failed and
 * already said why: EXIT_FAIL without running @job.
 */
int ctl_on_chip(struct ctl *c, struct mcp2510 *h, ctl_chip_fn job, void *ctx);

/* "bad VALUE for WHAT" as a usage error; returns -1. */
int ctl_bad(struct ctl *c, const char *what, const char *value);
/* Identifier, length and (unless remote) the data bytes are the same. */
bool ctl_same_frame(const struct can_frame *a, const struct can_frame *b);
/* Print an event's frame in candump -L form with @label. */
void ctl_print_frame(struct ctl *c, const struct mcp2510_event *ev,
		     const char *label);

extern const struct ctl_command ctl_info, ctl_reset, ctl_bittiming, ctl_regs,
	ctl_filter, ctl_state, ctl_send, ctl_dump, ctl_selftest, ctl_exchange,
	ctl_bench;

/* The whole tool, testable: arguments in, exit status out. */
int ctl_main(int argc, char **argv, FILE *out, FILE *err);

#endif /* MCP2510_CTL_H */
