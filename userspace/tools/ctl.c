// SPDX-License-Identifier: GPL-2.0
/* mcp2510ctl: global options, the subcommand table and --help. */
#include <string.h>

#include "ctl.h"
#include "frame_text.h"

static const struct ctl_command *const commands[] = {
	&ctl_info, &ctl_reset, &ctl_bittiming, &ctl_regs, &ctl_filter,
	&ctl_state, &ctl_send, &ctl_dump, &ctl_selftest, &ctl_exchange,
	&ctl_bench,
};

#define NCOMMANDS (sizeof(commands) / sizeof(commands[0]))

static void usage(struct ctl *c)
{
	size_t i;

	fprintf(c->out,
		"Usage: mcp2510ctl [OPTIONS] COMMAND [ARGS]\n"
		"Drive an MCP2510/MCP2515/MCP25625 CAN controller from userspace,\n"
		"on spidev or simulated.\n\nOptions (before or after COMMAND):\n");
	fputs(cli_device_help, c->out);
	fputs("  -h, --help          this text; COMMAND --help (or help COMMAND)\n"
	      "                      for a command's\n\n"
	      "Commands:\n", c->out);
	for (i = 0; i < NCOMMANDS; i++)
		fprintf(c->out, "  %-10s  %s\n", commands[i]->name,
			commands[i]->summary);
	fprintf(c->out, "  %-10s  %s\n", "help", "this text, or help COMMAND for a command's");
	fputs("\nTry it without hardware:\n"
	      "  mcp2510ctl --device sim exchange\n"
	      "  mcp2510ctl --device sim selftest\n"
	      "  mcp2510ctl bittiming 500000 --clock 16M\n"
	      "Exit status: 0 success, 1 failure, 2 bad command line.\n",
	      c->out);
}

static const struct ctl_command *find_command(const char *name)
{
	size_t i;

	for (i = 0; i < NCOMMANDS; i++)
		if (!strcmp(commands[i]->name, name))
			return commands[i];
	return NULL;
}

int ctl_on_chip(struct ctl *c, struct mcp2510 *h, ctl_chip_fn job, void *ctx)
{
	int ret;

	if (!h)
		return EXIT_FAIL;
	ret = job(c, h, ctx);
	mcp2510_close(h);
	return ret;
}

int ctl_bad(struct ctl *c, const char *what, const char *value)
{
	cli_error(c->args.err, c->args.prog, "invalid %s '%s'", what, value);
	return -1;
}

void ctl_print_frame(struct ctl *c, const struct mcp2510_event *ev,
		     const char *label)
{
	char line[FRAME_LOG_MAX(64)];

	if (frame_format_log(&ev->frame, &ev->ts, label, line, sizeof(line)) < 0)
		return;
	fprintf(c->out, "%s\n", line);
	fflush(c->out);
}

bool ctl_same_frame(const struct can_frame *a, const struct can_frame *b)
{
	if (a->can_id != b->can_id || a->len != b->len)
		return false;
	if (a->can_id & CAN_RTR_FLAG)
		return true;
	return !memcmp(a->data, b->data, a->len);
}

static int take_positional(struct ctl *c, const struct ctl_command *cmd,
			   const char *value, int max_pos)
{
	if (c->npos >= max_pos) {
		cli_error(c->args.err, c->args.prog,
			  "%s: unexpected argument '%s'", cmd->name, value);
		return -1;
	}
	c->pos[c->npos++] = value;
	return 0;
}

static const struct cli_option *own_option(const struct cli_option *own,
					   const char *name)
{
	for (; own && own->name; own++)
		if (!strcmp(own->name, name))
			return own;
	return NULL;
}

/* 1 after --help, 0, or -1 after reporting. */
static int take_option(struct ctl *c, const struct ctl_command *cmd,
		       const struct cli_option *own, ctl_option_fn fn,
		       void *ctx, const struct ctl_item *it)
{
	const struct cli_option *o;

	if (it->opt->id == CLI_OPT_HELP) {
		fputs(cmd->help, c->out);
		return 1;
	}
	if (it->opt->id < CLI_OPT_FIRST_OWN)
		return cli_device_set(&c->dev, &c->args, it->opt->id, it->value);
	o = own_option(own, it->opt->name);
	if (!o) {
		cli_error(c->args.err, c->args.prog,
			  "%s takes no --%s (see %s --help)", cmd->name,
			  it->opt->name, cmd->name);
		return -1;
	}
	return fn(c, ctx, o->id, it->value);
}

int ctl_parse(struct ctl *c, const struct ctl_command *cmd,
	      const struct cli_option *own, ctl_option_fn fn, void *ctx,
	      int min_pos, int max_pos, bool *done)
{
	int i, ret;

	*done = true;
	if (max_pos > CTL_MAX_ARGS)
		max_pos = CTL_MAX_ARGS;
	for (i = 0; i < c->nitems; i++) {
		const struct ctl_item *it = &c->items[i];

		if (it->opt)
			ret = take_option(c, cmd, own, fn, ctx, it);
		else
			ret = take_positional(c, cmd, it->value, max_pos);
		if (ret)
			return ret > 0 ? 0 : EXIT_USAGE;
	}
	if (cli_device_check(&c->dev, &c->args))
		return EXIT_USAGE;
	if (cmd->needs_device && !c->dev.device) {
		cli_error(c->args.err, c->args.prog,
			  "%s: no --device given (spidev:/dev/spidevB.C or sim)",
			  cmd->name);
		return EXIT_USAGE;
	}
	if (c->npos < min_pos) {
		cli_error(c->args.err, c->args.prog, "%s: missing argument (see %s --help)",
			  cmd->name, cmd->name);
		return EXIT_USAGE;
	}
	*done = false;
	return 0;
}

/* Every option any command takes, so each may come before the command. */
static void all_tables(const struct cli_option **tables)
{
	size_t i, n = 0;

	tables[n++] = cli_device_options;
	for (i = 0; i < NCOMMANDS; i++)
		if (commands[i]->options)
			tables[n++] = commands[i]->options;
	tables[n] = NULL;
}

/*
 * The whole command line into c->items; the first argument is the
 * command.  Returns 0, or an exit status after --version or an error.
 */
static int scan(struct ctl *c, const char **name, bool *version)
{
	const struct cli_option *tables[NCOMMANDS + 2];
	const char *value;
	enum cli_kind kind;
	int id;

	all_tables(tables);
	while ((kind = cli_next(&c->args, tables, &id, &value)) != CLI_END) {
		if (kind == CLI_ERROR)
			return EXIT_USAGE;
		if (kind == CLI_ARG && !*name) {
			*name = value;
			continue;
		}
		if (kind == CLI_OPTION && id == CLI_OPT_VERSION) {
			*version = true;
			continue;
		}
		if (c->nitems == CTL_MAX_ITEMS) {
			cli_error(c->args.err, c->args.prog, "too many arguments");
			return EXIT_USAGE;
		}
		c->items[c->nitems].opt = kind == CLI_OPTION ? cli_last_option() : NULL;
		c->items[c->nitems++].value = value;
	}
	return 0;
}

static bool asks_help(const struct ctl *c)
{
	int i;

	for (i = 0; i < c->nitems; i++)
		if (c->items[i].opt && c->items[i].opt->id == CLI_OPT_HELP)
			return true;
	return false;
}

/* "help" and "help COMMAND". */
static int help_command(struct ctl *c)
{
	const struct ctl_command *cmd;
	int i;

	for (i = 0; i < c->nitems; i++) {
		if (c->items[i].opt)
			continue;
		/* "help help": help's own text is the usage */
		if (!strcmp(c->items[i].value, "help"))
			break;
		cmd = find_command(c->items[i].value);
		if (!cmd) {
			cli_error(c->args.err, c->args.prog,
				  "help: unknown command '%s'", c->items[i].value);
			return EXIT_USAGE;
		}
		fputs(cmd->help, c->out);
		return 0;
	}
	usage(c);
	return 0;
}

int ctl_main(int argc, char **argv, FILE *out, FILE *err)
{
	const struct ctl_command *cmd;
	const char *name = NULL;
	bool version = false;
	struct ctl c;
	int ret;

	memset(&c, 0, sizeof(c));
	c.out = out;
	c.args.argc = argc;
	c.args.argv = argv;
	c.args.next = 1;
	c.args.prog = "mcp2510ctl";
	c.args.err = err;
	cli_device_init(&c.dev);
	ret = scan(&c, &name, &version);
	if (ret)
		return ret;
	if (version) {
		cli_version(out, c.args.prog);
		return 0;
	}
	if (!name || !strcmp(name, "help")) {
		if (name || asks_help(&c))
			return help_command(&c);
		cli_error(err, c.args.prog, "no command given (try --help)");
		return EXIT_USAGE;
	}
	cmd = find_command(name);
	if (!cmd) {
		cli_error(err, c.args.prog, "unknown command '%s' (try --help)", name);
		return EXIT_USAGE;
	}
	return cmd->run(&c);
}
