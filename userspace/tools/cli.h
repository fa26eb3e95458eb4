/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Command-line handling shared by mcp2510ctl and mcp2510d: an option
 * scanner and one-line error messages (cli.c), the number grammar
 * (cli_number.c), the options that say which chip to use and how
 * (--device, --int, --clock, --variant, --bitrate, ...: cli_device.c),
 * the filter settings (cli_filter.c) and the bit timing they ask for
 * (cli_timing.c).
 */
#ifndef MCP2510_CLI_H
#define MCP2510_CLI_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "mcp2510.h"

/* Exit statuses of both tools. */
#define EXIT_FAIL	1	/* the operation failed */
#define EXIT_USAGE	2	/* the command line is wrong */

struct cli_option {
	const char *name;	/* without the leading "--"; NULL ends a table */
	bool has_arg;
	int id;
};

struct cli_args {
	int argc;
	char **argv;
	int next;		/* 1 to start; 0 while getopt_long scans; after
				 * "--", index of the next argument */
	bool no_more_options;	/* after "--" */
	const char *prog;
	FILE *err;
};

enum cli_kind { CLI_END, CLI_OPTION, CLI_ARG, CLI_ERROR };

/*
 * The next option (its id and value) or positional argument, in command
 * line order, from the NULL-terminated list of NULL-terminated option
 * tables (the same list at every call), through getopt_long: "--name
 * value", "--name=value", unambiguous abbreviations, "--" and the short
 * forms -h -V -d -i -c -b -n -t of help, version, device, int, clock,
 * bitrate, count and timeout, where a table has them ("-d sim", "-dsim").  The first call starts the scan
 * at argv[1].  CLI_ERROR has already been reported on @a->err.
 */
enum cli_kind cli_next(struct cli_args *a,
		       const struct cli_option *const *tables,
		       int *id, const char **value);
/* The table entry of the last CLI_OPTION cli_next() returned. */
const struct cli_option *cli_last_option(void);

/* Report "PROG: MESSAGE" as one line on @err. */
void cli_error(FILE *err, const char *prog, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* ---- the number grammar (cli_number.c) ---- */

/*
 * Decimal digits, then optionally k or M (either case: thousand,
 * million), then optionally Hz (any case): "500000", "500k", "16M",
 * "16MHz", "16mhz"; -1 if bad.
 */
int cli_u32(const char *s, uint32_t *out);
/* A non-negative int, or -1 when @allow_forever and @s is "-1". */
int cli_int(const char *s, bool allow_forever, int *out);
/*
 * A sample point, "0.875", "87.5%" or "875" (whole tenths of a percent),
 * 10.0 % to 99.9 %, to tenths of a percent; -1 if bad.
 */
int cli_sample_point(const char *s, uint32_t *out);

/* ---- which chip, and how ---- */

enum cli_device_opt {
	CLI_OPT_HELP = 1,
	CLI_OPT_DEVICE,
	CLI_OPT_INT,
	CLI_OPT_CLOCK,
	CLI_OPT_VARIANT,
	CLI_OPT_BITRATE,
	CLI_OPT_SAMPLE_POINT,
	CLI_OPT_SPI_HZ,
	CLI_OPT_SPI_MODE,
	CLI_OPT_LOOPBACK,
	CLI_OPT_LISTEN_ONLY,
	CLI_OPT_TRIPLE,
	CLI_OPT_ONE_SHOT,
	CLI_OPT_BERR,
	CLI_OPT_VERSION,
	CLI_OPT_FIRST_OWN = 100,	/* ids of a tool's own options */
};

extern const struct cli_option cli_device_options[];
/* The device options' lines for a --help text. */
extern const char cli_device_help[];

#define CLI_MAX_FILTERS	16

struct cli_device {
	const char *device;		/* transport string */
	char device_buf[256];		/* "spidev:" + a bare path */
	/* --filter NAME=VALUE, applied in order on top of the chip's */
	const char *filters[CLI_MAX_FILTERS];
	unsigned int nfilters;
	struct mcp2510_options opts;
	uint32_t bitrate;
	uint32_t sample_point;
	uint32_t ctrlmode;
};

void cli_device_init(struct cli_device *d);
/* Take a device option's value; -1 after reporting a bad one. */
int cli_device_set(struct cli_device *d, struct cli_args *a, int id,
		   const char *value);
/*
 * After the last option: what options say only together (--one-shot and
 * the variant, --spi-hz and the variant's SPI clock limit, --int and a
 * simulated chip).  -1 after reporting, for exit status EXIT_USAGE.
 */
int cli_device_check(const struct cli_device *d, struct cli_args *a);
/* Print "PROG VERSION". */
void cli_version(FILE *out, const char *prog);
/*
 * "NAME=VALUE" of the filter command and --filter into @f, or -1 after
 * saying what is wrong with it.
 */
int cli_filter_assign(struct cli_args *a, struct mcp2510_hw_filters *f,
		      const char *arg);
/* Take a --filter NAME=VALUE for cli_device_up(), or say what is wrong. */
int cli_device_add_filter(struct cli_device *d, struct cli_args *a,
			  const char *arg);
/*
 * The --filter settings on top of the filters @h holds, written to the
 * chip; -1 after reporting.
 */
int cli_device_apply_filters(const struct cli_device *d, struct mcp2510 *h,
			     struct cli_args *a);
/* Open the chip, or report why not. */
struct mcp2510 *cli_device_open(const struct cli_device *d,
				struct cli_args *a, bool no_reset);
/*
 * mcp2510_bittiming_for(), saying why not (the oscillator, or which data
 * sheet rule a sample point breaks).  The bit-rate error is told as
 * can-calc-bit-timing shows it, in % with one decimal: a warning when the
 * rate is not exact, a refusal beyond CAN's oscillator tolerance of
 * 1.58 %.  A warning too when the sample point misses the one asked for,
 * or the CiA recommendation by more than 5 %.  0 or -1.
 */
int cli_bittiming(struct cli_args *a, uint32_t osc_hz, uint32_t bitrate,
		  uint32_t sp, struct can_bittiming *bt, uint8_t cnf[3]);
/* cli_bittiming() for the options' bit rate and sample point. */
int cli_device_timing(const struct cli_device *d, struct cli_args *a);
/*
 * Apply the --filter settings on top of the filters the handle holds
 * (those the chip kept, see mcp2510_open()), program bit rate and
 * control modes and join the bus, or report.  The timing is not told
 * about again: cli_device_timing() comes first.
 */
int cli_device_up(const struct cli_device *d, struct mcp2510 *h,
		  struct cli_args *a);
/* Report a failed library call: "PROG: WHAT: strerror(errno)". */
void cli_error_errno(struct cli_args *a, const char *what);

#endif /* MCP2510_CLI_H */
