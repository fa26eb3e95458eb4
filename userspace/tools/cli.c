// SPDX-License-Identifier: GPL-2.0
/* Option scanning and one-line errors, for both tools. */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <stdarg.h>
#include <string.h>

#include "cli.h"

/* Room for every option of both tools, long and short. */
#define CLI_MAX_OPTIONS		48
/* getopt_long's value for the option at index i of the scan's table */
#define CLI_LONG_BASE		0x100

void cli_error(FILE *err, const char *prog, const char *fmt, ...)
{
	va_list ap;

	fprintf(err, "%s: ", prog);
	va_start(ap, fmt);
	vfprintf(err, fmt, ap);
	va_end(ap);
	fputc('\n', err);
}

void cli_error_errno(struct cli_args *a, const char *what)
{
	cli_error(a->err, a->prog, "%s: %s", what, strerror(errno));
}

/* The short forms, for the options of these names wherever they appear. */
static const struct {
	char c;
	const char *name;
} short_names[] = {
	{ 'h', "help" }, { 'V', "version" }, { 'd', "device" }, { 'i', "int" },
	{ 'c', "clock" }, { 'b', "bitrate" }, { 'n', "count" },
	{ 't', "timeout" },
};

static char short_name(const char *name)
{
	size_t i;

	for (i = 0; i < sizeof(short_names) / sizeof(short_names[0]); i++)
		if (!strcmp(short_names[i].name, name))
			return short_names[i].c;
	return 0;
}

/* getopt_long's view of the option tables, the first of a name winning. */
struct scan {
	struct option longopts[CLI_MAX_OPTIONS + 1];
	const struct cli_option *opt[CLI_MAX_OPTIONS];
	char shorts[3 * CLI_MAX_OPTIONS + 3];
	int n;
};

static bool scan_has(const struct scan *s, const char *name)
{
	int i;

	for (i = 0; i < s->n; i++)
		if (!strcmp(s->opt[i]->name, name))
			return true;
	return false;
}

static void scan_add(struct scan *s, const struct cli_option *o, char **p)
{
	struct option *l = &s->longopts[s->n];

	l->name = o->name;
	l->has_arg = o->has_arg ? required_argument : no_argument;
	l->flag = NULL;
	l->val = CLI_LONG_BASE + s->n;
	s->opt[s->n++] = o;
	if (!short_name(o->name))
		return;
	*(*p)++ = short_name(o->name);
	if (o->has_arg)
		*(*p)++ = ':';
}

static void scan_build(const struct cli_option *const *tables, struct scan *s)
{
	const struct cli_option *o;
	char *p = s->shorts;

	memset(s, 0, sizeof(*s));
	/* '-': arguments come back in order; ':': a missing value says so */
	*p++ = '-';
	*p++ = ':';
	for (; *tables; tables++)
		for (o = *tables; o->name && s->n < CLI_MAX_OPTIONS; o++)
			if (!scan_has(s, o->name))
				scan_add(s, o, &p);
	*p = '\0';
}

static const struct cli_option *scan_find(const struct scan *s, int c)
{
	int i;

	if (c >= CLI_LONG_BASE && c < CLI_LONG_BASE + s->n)
		return s->opt[c - CLI_LONG_BASE];
	for (i = 0; i < s->n; i++)
		if (short_name(s->opt[i]->name) == c)
			return s->opt[i];
	return NULL;
}

/* How many options start with @name (an abbreviation matches several). */
static int scan_prefixed(const struct scan *s, const char *name, size_t len)
{
	int i, n = 0;

	for (i = 0; i < s->n; i++)
		n += !strncmp(s->opt[i]->name, name, len);
	return n;
}

/* getopt_long's '?' and ':' as one line naming the option. */
static enum cli_kind scan_error(struct cli_args *a, const struct scan *s,
				int c)
{
	const struct cli_option *o = optopt ? scan_find(s, optopt) : NULL;
	const char *arg = a->argv[optind - 1];
	size_t len = strcspn(arg, "=");

	if (c == ':' && o)
		cli_error(a->err, a->prog, "option --%s needs a value", o->name);
	else if (o && !o->has_arg)
		cli_error(a->err, a->prog, "option --%s takes no value", o->name);
	else if (arg[0] == '-' && arg[1] >= '0' && arg[1] <= '9')
		cli_error(a->err, a->prog,
			  "invalid argument '%s': numbers here are 0 or more (and no option starts with a digit)",
			  arg);
	else if (optopt && optopt < CLI_LONG_BASE)
		cli_error(a->err, a->prog, "unknown option -%c", optopt);
	else if (arg[0] == '-' && arg[1] == '-' &&
		 scan_prefixed(s, arg + 2, len - 2) > 1)
		cli_error(a->err, a->prog, "ambiguous option %.*s", (int)len,
			  arg);
	else
		cli_error(a->err, a->prog, "unknown option %.*s", (int)len, arg);
	return CLI_ERROR;
}

static const struct cli_option *last_option;

const struct cli_option *cli_last_option(void)
{
	return last_option;
}

enum cli_kind cli_next(struct cli_args *a,
		       const struct cli_option *const *tables,
		       int *id, const char **value)
{
	const struct cli_option *o;
	struct scan s;
	int c;

	if (a->no_more_options) {
		if (a->next >= a->argc)
			return CLI_END;
		*value = a->argv[a->next++];
		return CLI_ARG;
	}
	scan_build(tables, &s);
	if (a->next) {
		optind = 0;	/* glibc: start over, forgetting any other scan */
		a->next = 0;
	}
	opterr = 0;
	c = getopt_long(a->argc, a->argv, s.shorts, s.longopts, NULL);
	if (c == -1) {
		/* the end, or "--": what follows are arguments */
		a->no_more_options = true;
		a->next = optind;
		return cli_next(a, tables, id, value);
	}
	if (c == 1) {
		*value = optarg;
		return CLI_ARG;
	}
	o = c == '?' || c == ':' ? NULL : scan_find(&s, c);
	if (!o)
		return scan_error(a, &s, c);
	*id = o->id;
	*value = o->has_arg ? optarg : NULL;
	last_option = o;
	return CLI_OPTION;
}

