// SPDX-License-Identifier: GPL-2.0
/* Option scanning and the chip-selection options of both tools. */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"

#define DEFAULT_BITRATE		500000u
/* Room for every option of both tools, long and short. */
#define CLI_MAX_OPTIONS		48
/* getopt_long's value for the option at index i of the scan's table */
#define CLI_LONG_BASE		0x100
/* SCK limits: DS21291 (MCP2510) 5 MHz, MCP2515 and MCP25625 10 MHz. */
#define SPI_MAX_HZ_MCP2510	5000000u
#define SPI_MAX_HZ_MCP2515	10000000u

const struct cli_option cli_device_options[] = {
	{ "help", false, CLI_OPT_HELP },
	{ "version", false, CLI_OPT_VERSION },
	{ "device", true, CLI_OPT_DEVICE },
	{ "int", true, CLI_OPT_INT },
	{ "clock", true, CLI_OPT_CLOCK },
	{ "variant", true, CLI_OPT_VARIANT },
	{ "bitrate", true, CLI_OPT_BITRATE },
	{ "sample-point", true, CLI_OPT_SAMPLE_POINT },
	{ "spi-hz", true, CLI_OPT_SPI_HZ },
	{ "spi-mode", true, CLI_OPT_SPI_MODE },
	{ "loopback", false, CLI_OPT_LOOPBACK },
	{ "listen-only", false, CLI_OPT_LISTEN_ONLY },
	{ "triple-sampling", false, CLI_OPT_TRIPLE },
	{ "one-shot", false, CLI_OPT_ONE_SHOT },
	{ "berr-reporting", false, CLI_OPT_BERR },
	{ NULL, false, 0 },
};

const char cli_device_help[] =
"  -d, --device DEV    spidev:/dev/spidevB.C (or just the path), sim (a\n"
"                      simulated chip with an always-acknowledging peer) or\n"
"                      sim:NAME (a simulated bus shared inside this process)\n"
"  -i, --int CHIP:LINE INT pin as a GPIO line, e.g. gpiochip0:25, or a line\n"
"                      name alone (GPIO25); without it the chip is polled\n"
"                      every 2 ms\n"
"  -c, --clock HZ      oscillator, 1M to 25M (default 16M, also 16MHz); the\n"
"                      CAN clock is half\n"
"  --variant NAME      mcp2510 (default), mcp2515 or mcp25625\n"
"  -b, --bitrate B     bit rate in bit/s (default 500k)\n"
"  --sample-point SP   sample point, 0.875 style (default: CiA recommendation)\n"
"  --spi-hz HZ         SPI clock (default and limit: 5M for MCP2510, 10M\n"
"                      for MCP2515/MCP25625)\n"
"  --spi-mode 0|3      SPI mode (default 0)\n"
"  --loopback, --listen-only, --triple-sampling, --one-shot, --berr-reporting\n"
"                      control modes, as in \"ip link set ... type can\"\n"
"                      (--one-shot: MCP2515/MCP25625 only)\n"
"  -V, --version       the version\n";

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

int cli_u32(const char *s, uint32_t *out)
{
	unsigned long long v, scale = 1;
	char *end;

	if (!s[0] || s[0] < '0' || s[0] > '9')
		return -1;
	errno = 0;
	v = strtoull(s, &end, 10);
	if (errno)
		return -1;
	if (*end == 'k' || *end == 'K')
		scale = 1000;
	else if (*end == 'M')
		scale = 1000000;
	if (scale != 1)
		end++;
	/* "16MHz", "500kHz", "16000000Hz" */
	if (!strcasecmp(end, "hz"))
		end += 2;
	if (*end || v > UINT32_MAX / scale)
		return -1;
	*out = (uint32_t)(v * scale);
	return 0;
}

int cli_int(const char *s, bool allow_forever, int *out)
{
	uint32_t v;

	if (allow_forever && !strcmp(s, "-1")) {
		*out = -1;
		return 0;
	}
	if (cli_u32(s, &v) || v > INT32_MAX)
		return -1;
	*out = (int)v;
	return 0;
}

/* "0.875" -> 875, "87.5%" -> 875, "875" -> 875 */
int cli_sample_point(const char *s, uint32_t *out)
{
	double v;
	char *end;

	errno = 0;
	v = strtod(s, &end);
	if (errno || end == s)
		return -1;
	if (!strcmp(end, "%"))
		v *= 10;
	else if (*end)
		return -1;
	else if (v < 1)
		v *= 1000;
	else if (strchr(s, '.'))
		return -1;	/* tenths of a percent are whole numbers */
	if (v <= 0 || v >= 1000)
		return -1;
	*out = (uint32_t)(v + 0.5);
	return 0;
}

void cli_device_init(struct cli_device *d)
{
	memset(d, 0, sizeof(*d));
	mcp2510_options_init(&d->opts);
	d->bitrate = DEFAULT_BITRATE;
}

static int bad_value(struct cli_args *a, const char *opt, const char *value)
{
	cli_error(a->err, a->prog, "invalid value '%s' for --%s", value, opt);
	return -1;
}

static int set_variant(struct cli_device *d, struct cli_args *a,
		       const char *value)
{
	if (strcmp(value, "mcp2510") && strcmp(value, "mcp2515") &&
	    strcmp(value, "mcp25625"))
		return bad_value(a, "variant", value);
	d->opts.variant = value;
	return 0;
}

static int set_spi_mode(struct cli_device *d, struct cli_args *a,
			const char *value)
{
	if (strcmp(value, "0") && strcmp(value, "3"))
		return bad_value(a, "spi-mode", value);
	d->opts.spi_mode = (uint8_t)(value[0] - '0');
	return 0;
}

static int set_number(struct cli_args *a, const char *opt, const char *value,
		      uint32_t *dst)
{
	if (cli_u32(value, dst) || !*dst)
		return bad_value(a, opt, value);
	return 0;
}

/* A bare "/dev/spidev0.0" means the spidev transport. */
static int set_device(struct cli_device *d, struct cli_args *a,
		      const char *value)
{
	int n;

	if (value[0] != '/') {
		d->device = value;
		return 0;
	}
	n = snprintf(d->device_buf, sizeof(d->device_buf), "spidev:%s", value);
	if (n < 0 || (size_t)n >= sizeof(d->device_buf))
		return bad_value(a, "device", value);
	d->device = d->device_buf;
	return 0;
}

/*
 * "CHIP:LINE" with both parts, or a line name alone (looked up on every
 * chip); a bare number is an offset without its chip.  The library finds
 * them.
 */
static int set_int_line(struct cli_device *d, struct cli_args *a,
			const char *value)
{
	const char *colon = strrchr(value, ':');
	bool bare_number = !colon && value[0] &&
			   strspn(value, "0123456789") == strlen(value);

	if (!value[0] || bare_number ||
	    (colon && (colon == value || !colon[1]))) {
		cli_error(a->err, a->prog,
			  "--int %s: give the INT pin as CHIP:LINE, e.g. gpiochip0:25 (a GPIO chip, then a line offset or name), or a line name alone, e.g. GPIO25",
			  value);
		return -1;
	}
	d->opts.int_line = value;
	return 0;
}

static int set_clock(struct cli_device *d, struct cli_args *a,
		     const char *value)
{
	uint32_t hz;

	if (set_number(a, "clock", value, &hz))
		return -1;
	if (hz < MCP2510_OSC_HZ_MIN || hz > MCP2510_OSC_HZ_MAX) {
		cli_error(a->err, a->prog,
			  "--clock %s: the oscillator must be 1 to 25 MHz (%" PRIu32 " Hz given)",
			  value, hz);
		return -1;
	}
	d->opts.osc_hz = hz;
	return 0;
}

int cli_device_set(struct cli_device *d, struct cli_args *a, int id,
		   const char *value)
{
	switch (id) {
	case CLI_OPT_DEVICE:
		return set_device(d, a, value);
	case CLI_OPT_INT:
		return set_int_line(d, a, value);
	case CLI_OPT_CLOCK:
		return set_clock(d, a, value);
	case CLI_OPT_VARIANT:
		return set_variant(d, a, value);
	case CLI_OPT_BITRATE:
		return set_number(a, "bitrate", value, &d->bitrate);
	case CLI_OPT_SAMPLE_POINT:
		if (cli_sample_point(value, &d->sample_point))
			return bad_value(a, "sample-point", value);
		return 0;
	case CLI_OPT_SPI_HZ:
		return set_number(a, "spi-hz", value, &d->opts.spi_hz);
	case CLI_OPT_SPI_MODE:
		return set_spi_mode(d, a, value);
	case CLI_OPT_LOOPBACK:
		d->ctrlmode |= CAN_CTRLMODE_LOOPBACK;
		return 0;
	case CLI_OPT_LISTEN_ONLY:
		d->ctrlmode |= CAN_CTRLMODE_LISTENONLY;
		return 0;
	case CLI_OPT_TRIPLE:
		d->ctrlmode |= CAN_CTRLMODE_3_SAMPLES;
		return 0;
	case CLI_OPT_ONE_SHOT:
		d->ctrlmode |= CAN_CTRLMODE_ONE_SHOT;
		return 0;
	case CLI_OPT_BERR:
		d->ctrlmode |= CAN_CTRLMODE_BERR_REPORTING;
		return 0;
	default:
		cli_error(a->err, a->prog, "option not handled here");
		return -1;
	}
}

static bool is_mcp2510(const struct cli_device *d)
{
	return !d->opts.variant || !strcmp(d->opts.variant, "mcp2510");
}

int cli_device_check(const struct cli_device *d, struct cli_args *a)
{
	uint32_t limit = is_mcp2510(d) ? SPI_MAX_HZ_MCP2510 : SPI_MAX_HZ_MCP2515;
	const char *name = d->opts.variant ? d->opts.variant : "mcp2510";

	if (d->opts.spi_hz > limit) {
		cli_error(a->err, a->prog,
			  "--spi-hz %" PRIu32 ": above the %s's SPI clock limit of %" PRIu32 " MHz",
			  d->opts.spi_hz, name, limit / 1000000);
		return -1;
	}
	if ((d->ctrlmode & CAN_CTRLMODE_ONE_SHOT) && is_mcp2510(d)) {
		cli_error(a->err, a->prog,
			  "--one-shot needs an MCP2515 or MCP25625 (--variant mcp2515): the MCP2510 has no one-shot mode");
		return -1;
	}
	return 0;
}

void cli_version(FILE *out, const char *prog)
{
	fprintf(out, "%s %s\n", prog, mcp2510_version());
}

static bool filter_setting_is_id(const char *name)
{
	struct mcp2510_hw_filters scratch;

	mcp2510_hw_filters_default(&scratch);
	return (!strncmp(name, "mask", 4) || !strncmp(name, "filter", 6)) &&
	       !mcp2510_hw_filters_set(&scratch, name, "0");
}

static bool filter_setting_known(const char *name)
{
	struct mcp2510_hw_filters scratch;

	mcp2510_hw_filters_default(&scratch);
	return !mcp2510_hw_filters_set(&scratch, name, "0") ||
	       !mcp2510_hw_filters_set(&scratch, name, "any");
}

/* Why mcp2510_hw_filters_set() refused NAME=VALUE, as one line. */
static void filter_why(struct cli_args *a, const char *arg, const char *name,
		       const char *value)
{
	if (!filter_setting_known(name))
		cli_error(a->err, a->prog,
			  "unknown filter setting '%s' in '%s' (mask0-1, filter0-5, rxm0-1, rollover)",
			  name, arg);
	else if (filter_setting_is_id(name) && !strncasecmp(value, "0x", 2) &&
		 value[2])
		cli_error(a->err, a->prog,
			  "'%s': write the id in hex without 0x, an x after it for a 29-bit id (%s=123, %s=1fffffffx)",
			  arg, name, name);
	else if (filter_setting_is_id(name))
		cli_error(a->err, a->prog,
			  "'%s': the id must be hex, up to 7ff (11 bit) or up to 1fffffff followed by x (29 bit)",
			  arg);
	else if (!strncmp(name, "rxm", 3))
		cli_error(a->err, a->prog,
			  "'%s': a receive mode is filtered, std, ext or any", arg);
	else
		cli_error(a->err, a->prog, "'%s': rollover is 0 or 1", arg);
}

int cli_filter_assign(struct cli_args *a, struct mcp2510_hw_filters *f,
		      const char *arg)
{
	const char *eq = strchr(arg, '=');
	size_t n = eq ? (size_t)(eq - arg) : 0;
	char name[16];

	if (!eq || !n || n >= sizeof(name)) {
		cli_error(a->err, a->prog,
			  "filter setting '%s' is not NAME=VALUE (e.g. mask0=7ff filter0=123)",
			  arg);
		return -1;
	}
	memcpy(name, arg, n);
	name[n] = '\0';
	if (!mcp2510_hw_filters_set(f, name, eq + 1))
		return 0;
	filter_why(a, arg, name, eq + 1);
	return -1;
}

int cli_device_add_filter(struct cli_device *d, struct cli_args *a,
			  const char *arg)
{
	struct mcp2510_hw_filters scratch;

	mcp2510_hw_filters_default(&scratch);
	if (cli_filter_assign(a, &scratch, arg))
		return -1;
	if (d->nfilters == CLI_MAX_FILTERS) {
		cli_error(a->err, a->prog, "more than %d --filter settings",
			  CLI_MAX_FILTERS);
		return -1;
	}
	d->filters[d->nfilters++] = arg;
	return 0;
}

static int apply_filters(const struct cli_device *d, struct mcp2510 *h,
			 struct cli_args *a)
{
	struct mcp2510_hw_filters f;
	unsigned int i;

	if (!d->nfilters)
		return 0;
	mcp2510_get_filters(h, &f);
	for (i = 0; i < d->nfilters; i++)
		if (cli_filter_assign(a, &f, d->filters[i]))
			return -1;
	if (mcp2510_set_filters(h, &f)) {
		cli_error_errno(a, "setting the filters");
		return -1;
	}
	return 0;
}

static const char *spidev_path(const char *device)
{
	return strncmp(device, "spidev:", 7) ? NULL : device + 7;
}

/* What errno says about opening @d->device, as one line. */
static void open_failed(const struct cli_device *d, struct cli_args *a,
			int err)
{
	const char *path = spidev_path(d->device);

	if (err == ENODEV)
		cli_error(a->err, a->prog,
			  "no chip answers on %s: wrong reset values or a register that does not keep what is written (MISO stuck low or high? no power? no oscillator?)",
			  d->device);
	else if (err == ENOTTY && path)
		cli_error(a->err, a->prog, "%s is not a spidev device", path);
	else if (err == EINVAL)
		cli_error(a->err, a->prog,
			  "cannot open %s: not spidev:/dev/spidevB.C, sim or sim:NAME",
			  d->device);
	else
		cli_error(a->err, a->prog, "cannot open %s: %s", d->device,
			  strerror(err));
}

/*
 * The library opens the spidev device before the INT line: when the
 * open fails with --int, trying again without it tells whose fault it
 * was (a missing gpiochip is ENOENT too).
 */
static bool int_line_at_fault(const struct mcp2510_options *o,
			      const char *device)
{
	struct mcp2510_options polled = *o;
	struct mcp2510 *h;

	if (!o->int_line || !spidev_path(device))
		return false;
	polled.int_line = NULL;
	h = mcp2510_open(device, &polled);
	if (!h)
		return false;
	mcp2510_close(h);
	return true;
}

struct mcp2510 *cli_device_open(const struct cli_device *d,
				struct cli_args *a, bool no_reset)
{
	struct mcp2510_options o = d->opts;
	struct mcp2510 *h;
	int err;

	if (!d->device) {
		cli_error(a->err, a->prog,
			  "no --device given (spidev:/dev/spidevB.C or sim)");
		return NULL;
	}
	o.no_reset = no_reset;
	h = mcp2510_open(d->device, &o);
	if (h)
		return h;
	err = errno;
	if (int_line_at_fault(&o, d->device))
		cli_error(a->err, a->prog, "INT line %s: %s (%s itself opens fine)",
			  o.int_line, strerror(err), d->device);
	else
		open_failed(d, a, err);
	return NULL;
}

/* Why @bitrate at @sp cannot be made, when without @sp it can. */
static void sample_point_why(struct cli_args *a, uint32_t osc_hz,
			     uint32_t bitrate, uint32_t sp)
{
	struct can_bittiming bt;
	uint8_t cnf[3];
	uint32_t later;
	char earliest[48] = "";

	for (later = sp + 1; later < 1000; later++)
		if (!mcp2510_bittiming_for(osc_hz, bitrate, later, &bt, cnf))
			break;
	if (later < 1000)
		snprintf(earliest, sizeof(earliest), "; the earliest here is %.3f",
			 bt.sample_point / 1000.0);
	cli_error(a->err, a->prog,
		  "sample point %.3f at %" PRIu32 " bit/s breaks the data sheet's PRSEG + PS1 >= PS2 (the sample point must come after the middle of the bit)%s",
		  sp / 1000.0, bitrate, earliest);
}

int cli_bittiming(struct cli_args *a, uint32_t osc_hz, uint32_t bitrate,
		  uint32_t sp, struct can_bittiming *bt, uint8_t cnf[3])
{
	if (mcp2510_bittiming_for(osc_hz, bitrate, sp, bt, cnf)) {
		if (sp && !mcp2510_bittiming_for(osc_hz, bitrate, 0, bt, cnf)) {
			sample_point_why(a, osc_hz, bitrate, sp);
			return -1;
		}
		cli_error(a->err, a->prog,
			  "bit rate %" PRIu32 " cannot be made from a %" PRIu32 " Hz oscillator (none within 5%% with 6 to 25 quanta of 2 to 128 oscillator periods)",
			  bitrate, osc_hz);
		return -1;
	}
	if (sp && bt->sample_point != sp)
		cli_error(a->err, a->prog,
			  "warning: sample point %.3f cannot be made at %" PRIu32 " bit/s from a %" PRIu32 " Hz oscillator; using %.3f",
			  sp / 1000.0, bitrate, osc_hz, bt->sample_point / 1000.0);
	return 0;
}

int cli_device_up(const struct cli_device *d, struct mcp2510 *h,
		  struct cli_args *a)
{
	struct can_bittiming bt;
	uint8_t cnf[3];

	if (apply_filters(d, h, a) ||
	    cli_bittiming(a, mcp2510_osc_hz(h), d->bitrate, d->sample_point,
			  &bt, cnf))
		return -1;
	if (mcp2510_set_bitrate(h, d->bitrate, d->sample_point)) {
		cli_error_errno(a, "bit rate");
		return -1;
	}
	if (mcp2510_set_ctrlmode(h, d->ctrlmode)) {
		cli_error_errno(a, "control mode");
		return -1;
	}
	if (mcp2510_up(h)) {
		cli_error_errno(a, "starting the chip");
		return -1;
	}
	return 0;
}
