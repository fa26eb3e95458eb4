// SPDX-License-Identifier: GPL-2.0
/* The options that say which chip to use and how, and bringing it up. */
#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define DEFAULT_BITRATE		500000u
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
"                      simulated chip with an always-acknowledging peer),\n"
"                      sim:NAME (a simulated bus shared inside this process)\n"
"                      or sim:CHIP@BUS (the chip CHIP on a simulated bus\n"
"                      that processes share)\n"
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

/* The control-mode switches, as "ip link set ... type can" names them. */
static int set_ctrlmode(struct cli_device *d, struct cli_args *a, int id)
{
	static const struct {
		int id;
		uint32_t mode;
	} modes[] = {
		{ CLI_OPT_LOOPBACK, CAN_CTRLMODE_LOOPBACK },
		{ CLI_OPT_LISTEN_ONLY, CAN_CTRLMODE_LISTENONLY },
		{ CLI_OPT_TRIPLE, CAN_CTRLMODE_3_SAMPLES },
		{ CLI_OPT_ONE_SHOT, CAN_CTRLMODE_ONE_SHOT },
		{ CLI_OPT_BERR, CAN_CTRLMODE_BERR_REPORTING },
	};
	size_t i;

	for (i = 0; i < sizeof(modes) / sizeof(modes[0]); i++) {
		if (modes[i].id == id) {
			d->ctrlmode |= modes[i].mode;
			return 0;
		}
	}
	cli_error(a->err, a->prog, "option not handled here");
	return -1;
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
	default:
		return set_ctrlmode(d, a, id);
	}
}

static bool is_mcp2510(const struct cli_device *d)
{
	return !d->opts.variant || !strcmp(d->opts.variant, "mcp2510");
}

static bool is_sim(const char *device)
{
	return !strcmp(device, "sim") || !strncmp(device, "sim:", 4);
}

/*
 * The simulator's settings from the environment that are set, as
 * "NAME=VALUE" and what each takes, when a well-formed "sim" device was
 * refused: one of them is malformed.
 */
static void sim_env_failed(struct cli_args *a, const char *device)
{
	static const struct {
		const char *name, *takes;
	} vars[] = {
		{ "MCP2510_SIM_MISO", "low or high" },
		{ "MCP2510_SIM_BUS_ERRORS", "a count" },
		{ "MCP2510_SIM_SPI_TIME", "KEY=NS,... (msg_ns, cs_setup_ns, cs_hold_ns, ctlr_max_hz, irq_latency_ns)" },
	};
	char set[512] = "";
	size_t i, n = 0;

	for (i = 0; i < sizeof(vars) / sizeof(vars[0]); i++) {
		const char *v = getenv(vars[i].name);

		if (v && *v && n < sizeof(set))
			n += (size_t)snprintf(set + n, sizeof(set) - n, "%s%s=%s (%s takes %s)",
					      n ? ", " : "", vars[i].name, v,
					      vars[i].name, vars[i].takes);
	}
	cli_error(a->err, a->prog, "cannot open %s: the simulator refused its settings: %s",
		  device, n ? set : "none is set");
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
	if (d->opts.int_line && d->device && is_sim(d->device)) {
		cli_error(a->err, a->prog,
			  "--int %s: a simulated chip (--device %s) has no INT pin to wire; --int is for spidev",
			  d->opts.int_line, d->device);
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

static const char *spidev_path(const char *device)
{
	return strncmp(device, "spidev:", 7) ? NULL : device + 7;
}

/* The shared bus's own refusals (sim:CHIP@BUS); false for the others. */
static bool simbus_failed(const char *device, struct cli_args *a, int err)
{
	const char *miso = getenv("MCP2510_SIM_MISO");
	const char *why;

	if (strncmp(device, "sim:", 4) || !strchr(device, '@'))
		return false;
	if (err == EINVAL && miso && *miso && strcmp(miso, "low") &&
	    strcmp(miso, "high"))
		return false;
	if (err == EINVAL || err == ENAMETOOLONG)
		why = "CHIP and BUS are 1 to 31 letters, digits, '.', '_' or '-', not starting with '.'";
	else if (err == EBUSY)
		why = "another handle has that chip";
	else if (err == EEXIST)
		why = "a chip of that name with another --variant or --clock is on the bus";
	else if (err == ENOSPC)
		why = "the bus has its 8 chips";
	else if (err == EACCES)
		why = "the socket directory is not the user's alone (mode 0700)";
	else
		return false;
	cli_error(a->err, a->prog, "cannot open %s: %s", device, why);
	return true;
}

/* What errno says about opening @d->device, as one line. */
static void open_failed(const struct cli_device *d, struct cli_args *a,
			int err)
{
	const char *path = spidev_path(d->device);

	if (simbus_failed(d->device, a, err))
		return;
	if (err == ENODEV)
		cli_error(a->err, a->prog,
			  "no chip answers on %s: wrong reset values or a register that does not keep what is written (MISO stuck low or high? no power? no oscillator?)",
			  d->device);
	else if (err == ENOTTY && path)
		cli_error(a->err, a->prog, "%s is not a spidev device", path);
	else if (err == EINVAL && is_sim(d->device))
		sim_env_failed(a, d->device);
	else if (err == EINVAL)
		cli_error(a->err, a->prog,
			  "cannot open %s: not spidev:/dev/spidevB.C, sim, sim:NAME or sim:CHIP@BUS",
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

int cli_device_timing(const struct cli_device *d, struct cli_args *a)
{
	struct can_bittiming bt;
	uint8_t cnf[3];

	return cli_bittiming(a, d->opts.osc_hz, d->bitrate, d->sample_point,
			     &bt, cnf);
}

int cli_device_up(const struct cli_device *d, struct mcp2510 *h,
		  struct cli_args *a)
{
	if (cli_device_apply_filters(d, h, a))
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
