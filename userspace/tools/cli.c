// SPDX-License-Identifier: GPL-2.0
/* Option scanning and the chip-selection options of both tools. */
#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define DEFAULT_BITRATE		500000u

const struct cli_option cli_device_options[] = {
	{ "help", false, CLI_OPT_HELP },
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
"  --device DEV        spidev:/dev/spidevB.C, sim (a simulated chip with an\n"
"                      always-acknowledging peer) or sim:NAME (a simulated\n"
"                      bus shared inside this process)\n"
"  --int CHIP:LINE     INT pin as a GPIO line, e.g. gpiochip0:25; without it\n"
"                      the chip is polled every 2 ms\n"
"  --clock HZ          oscillator frequency (default 16M); the CAN clock is half\n"
"  --variant NAME      mcp2510 (default), mcp2515 or mcp25625\n"
"  --bitrate B         bit rate in bit/s (default 500k)\n"
"  --sample-point SP   sample point, 0.875 style (default: CiA recommendation)\n"
"  --spi-hz HZ         SPI clock (default 5M for MCP2510, 10M otherwise)\n"
"  --spi-mode 0|3      SPI mode (default 0)\n"
"  --loopback, --listen-only, --triple-sampling, --one-shot, --berr-reporting\n"
"                      control modes, as in \"ip link set ... type can\"\n";

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

static const struct cli_option *find_option(const struct cli_option *const *tables,
					    const char *name, size_t len)
{
	const struct cli_option *o;

	for (; *tables; tables++)
		for (o = *tables; o->name; o++)
			if (strlen(o->name) == len && !strncmp(o->name, name, len))
				return o;
	return NULL;
}

static enum cli_kind take_option(struct cli_args *a, const char *arg,
				 const struct cli_option *const *tables,
				 int *id, const char **value)
{
	const char *name = arg + 2, *eq = strchr(name, '=');
	size_t len = eq ? (size_t)(eq - name) : strlen(name);
	const struct cli_option *o = find_option(tables, name, len);

	if (!o) {
		cli_error(a->err, a->prog, "unknown option --%.*s", (int)len, name);
		return CLI_ERROR;
	}
	*id = o->id;
	*value = NULL;
	if (!o->has_arg) {
		if (!eq)
			return CLI_OPTION;
		cli_error(a->err, a->prog, "option --%s takes no value", o->name);
		return CLI_ERROR;
	}
	if (eq) {
		*value = eq + 1;
		return CLI_OPTION;
	}
	if (a->next >= a->argc) {
		cli_error(a->err, a->prog, "option --%s needs a value", o->name);
		return CLI_ERROR;
	}
	*value = a->argv[a->next++];
	return CLI_OPTION;
}

enum cli_kind cli_next(struct cli_args *a,
		       const struct cli_option *const *tables,
		       int *id, const char **value)
{
	const char *arg;

	if (a->next >= a->argc)
		return CLI_END;
	arg = a->argv[a->next++];
	if (!a->no_more_options && !strcmp(arg, "--")) {
		a->no_more_options = true;
		return cli_next(a, tables, id, value);
	}
	if (a->no_more_options || arg[0] != '-' || !arg[1]) {
		*value = arg;
		return CLI_ARG;
	}
	if (!strcmp(arg, "-h")) {
		*id = CLI_OPT_HELP;
		*value = NULL;
		return CLI_OPTION;
	}
	if (arg[1] != '-') {
		/* "-1" and such are values, not options */
		if (arg[1] >= '0' && arg[1] <= '9') {
			*value = arg;
			return CLI_ARG;
		}
		cli_error(a->err, a->prog, "unknown option %s", arg);
		return CLI_ERROR;
	}
	return take_option(a, arg, tables, id, value);
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

int cli_device_set(struct cli_device *d, struct cli_args *a, int id,
		   const char *value)
{
	switch (id) {
	case CLI_OPT_DEVICE:
		d->device = value;
		return 0;
	case CLI_OPT_INT:
		d->opts.int_line = value;
		return 0;
	case CLI_OPT_CLOCK:
		return set_number(a, "clock", value, &d->opts.osc_hz);
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

struct mcp2510 *cli_device_open(const struct cli_device *d,
				struct cli_args *a, bool no_reset)
{
	struct mcp2510_options o = d->opts;
	struct mcp2510 *h;

	if (!d->device) {
		cli_error(a->err, a->prog,
			  "no --device given (spidev:/dev/spidevB.C or sim)");
		return NULL;
	}
	o.no_reset = no_reset;
	h = mcp2510_open(d->device, &o);
	if (!h)
		cli_error(a->err, a->prog, "cannot open %s: %s", d->device,
			  errno == EINVAL ? "invalid device or options" :
			  strerror(errno));
	return h;
}

int cli_device_up(const struct cli_device *d, struct mcp2510 *h,
		  struct cli_args *a)
{
	if (mcp2510_set_bitrate(h, d->bitrate, d->sample_point)) {
		cli_error(a->err, a->prog,
			  "bit rate %" PRIu32 " cannot be made from a %" PRIu32 " Hz oscillator",
			  d->bitrate, mcp2510_osc_hz(h));
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
