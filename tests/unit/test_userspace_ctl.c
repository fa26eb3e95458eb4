// SPDX-License-Identifier: GPL-2.0
/*
 * mcp2510ctl through its testable main (arguments in, exit status and
 * both output streams out).
 */
#define _GNU_SOURCE
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>

#include "ctl.h"

struct run {
	int status;
	char *out;
	char *err;
};

static struct run ctl(const char *first, ...)
{
	char *argv[CTL_MAX_ARGS + 2] = { "mcp2510ctl" };
	struct run r = { 0, NULL, NULL };
	size_t out_len, err_len;
	FILE *out, *err;
	const char *arg;
	va_list ap;
	int argc = 1;

	va_start(ap, first);
	for (arg = first; arg; arg = va_arg(ap, const char *))
		argv[argc++] = (char *)arg;
	va_end(ap);
	out = open_memstream(&r.out, &out_len);
	err = open_memstream(&r.err, &err_len);
	r.status = ctl_main(argc, argv, out, err);
	fclose(out);
	fclose(err);
	return r;
}

static void run_free(struct run *r)
{
	free(r->out);
	free(r->err);
}

/* Failed with @status and exactly one line "mcp2510ctl: ...@part...". */
static void assert_one_line_error(struct run r, int status, const char *part)
{
	if (r.status != status || strncmp(r.err, "mcp2510ctl: ", 12) ||
	    !strstr(r.err, part) || strchr(r.err, '\n') != r.err + strlen(r.err) - 1)
		fail_msg("status %d (want %d), stderr '%s' (want one line with '%s')",
			 r.status, status, r.err, part);
	run_free(&r);
}

static unsigned int lines(const char *s)
{
	unsigned int n = 0;

	for (; *s; s++)
		n += *s == '\n';
	return n;
}

static void test_usage_errors(void **state)
{
	(void)state;
	assert_one_line_error(ctl(NULL), EXIT_USAGE, "no command given");
	assert_one_line_error(ctl("frob", NULL), EXIT_USAGE, "unknown command 'frob'");
	assert_one_line_error(ctl("--frob", "info", NULL), EXIT_USAGE,
			      "unknown option --frob");
	assert_one_line_error(ctl("-x", NULL), EXIT_USAGE, "unknown option -x");
	assert_one_line_error(ctl("bittiming", "--clock", NULL), EXIT_USAGE,
			      "option --clock needs a value");
	assert_one_line_error(ctl("bittiming", "--clock", "16Q", NULL), EXIT_USAGE,
			      "invalid value '16Q' for --clock");
	assert_one_line_error(ctl("bittiming", "fast", NULL), EXIT_USAGE,
			      "invalid bit rate 'fast'");
	assert_one_line_error(ctl("bittiming", "1", "2", NULL), EXIT_USAGE,
			      "unexpected argument '2'");
	assert_one_line_error(ctl("--variant", "mcp9", "info", NULL), EXIT_USAGE,
			      "invalid value 'mcp9' for --variant");
	assert_one_line_error(ctl("--loopback=1", "info", NULL), EXIT_USAGE,
			      "takes no value");
	assert_one_line_error(ctl("info", NULL), EXIT_USAGE, "no --device");
	assert_one_line_error(ctl("--device", "sim", "send", NULL), EXIT_USAGE,
			      "missing argument");
	assert_one_line_error(ctl("--device", "sim", "dump", "--count", "x", NULL),
			      EXIT_USAGE, "invalid --count 'x'");
	assert_one_line_error(ctl("--device", "sim", "filter", "rxm0=bogus", NULL),
			      EXIT_USAGE, "'rxm0=bogus': a receive mode is filtered, std, ext or any");
	assert_one_line_error(ctl("--device", "spidev:/dev/spidev0.0", "exchange",
				  NULL), EXIT_USAGE, "needs --device sim");
}

static void test_bad_frames_named_verbatim(void **state)
{
	(void)state;
	assert_one_line_error(ctl("--device", "sim", "send", "123#1", NULL),
			      EXIT_USAGE,
			      "bad frame '123#1': data must be pairs of hex digits");
	/* user text is data, never a format */
	assert_one_line_error(ctl("--device", "sim", "send", "%s%n#", NULL),
			      EXIT_USAGE, "bad frame '%s%n#'");
}

static void test_help_texts(void **state)
{
	struct run r = ctl("--help", NULL);
	static const char *const cmds[] = {
		"info", "reset", "bittiming", "regs", "filter", "state", "send",
		"dump", "selftest", "exchange", "bench",
	};
	size_t i;

	(void)state;
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "Usage: mcp2510ctl"));
	assert_string_equal(r.err, "");
	run_free(&r);
	for (i = 0; i < sizeof(cmds) / sizeof(cmds[0]); i++) {
		char want[64];

		r = ctl(cmds[i], "--help", NULL);
		snprintf(want, sizeof(want), "mcp2510ctl ");
		assert_int_equal(r.status, 0);
		if (!strstr(r.out, want) || !strstr(r.out, cmds[i]))
			fail_msg("%s --help: '%s'", cmds[i], r.out);
		run_free(&r);
	}
}

static void test_bittiming_contract(void **state)
{
	struct run r = ctl("bittiming", "500000", "--clock", "16000000", NULL);

	(void)state;
	assert_int_equal(r.status, 0);
	assert_string_equal(r.out,
		"bitrate 500000 sample-point 0.875 tq 125 prop-seg 6 phase-seg1 7 phase-seg2 2 sjw 1 brp 1\n"
		"cnf1 0x00 cnf2 0xb5 cnf3 0x01\n");
	run_free(&r);
	r = ctl("--clock", "8M", "bittiming", "125k", "--sample-point", "0.75", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "bitrate 125000 sample-point 0.750 "));
	run_free(&r);
	assert_one_line_error(ctl("bittiming", "1000000", "--clock", "4M", NULL),
			      EXIT_FAIL, "bit rate 1000000 cannot be made from a 4000000 Hz oscillator");
}

/* Stderr of @r is exactly @n lines, each containing its part, in order. */
static void assert_stderr_lines(const struct run *r, unsigned int n, ...)
{
	const char *p = r->err, *part;
	va_list ap;

	if (lines(r->err) != n)
		fail_msg("stderr '%s': want %u lines", r->err, n);
	va_start(ap, n);
	while (n--) {
		part = va_arg(ap, const char *);
		p = strstr(p, part);
		if (!p)
			fail_msg("stderr '%s' lacks '%s'", r->err, part);
	}
	va_end(ap);
}

/*
 * The bit-rate error as can-calc-bit-timing shows it (in %, one decimal):
 * a warning when not exact, refused beyond CAN's 1.58 % oscillator
 * tolerance; the sample point warned about when it misses the CiA one by
 * more than 5 %.
 */
static void test_bittiming_errors_reported(void **state)
{
	struct run r = ctl("bittiming", "95000", NULL);

	(void)state;
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "bitrate 95238 "));
	assert_stderr_lines(&r, 1, "warning: bit rate 95238 is 0.3% off the 95000 asked for");
	run_free(&r);
	assert_one_line_error(ctl("bittiming", "1040000", NULL), EXIT_FAIL,
			      "bit rate 1040000: the nearest a 16000000 Hz oscillator makes is 1000000, 3.8% off");
	assert_one_line_error(ctl("bittiming", "300000", "--clock", "10M", NULL),
			      EXIT_FAIL, "2.0% off, beyond the 1.58%");
	r = ctl("bittiming", "500000", "--clock", "8M", NULL);
	assert_int_equal(r.status, 0);
	assert_stderr_lines(&r, 1, "warning: the CiA sample point 0.875 cannot be made at 500000 bit/s from a 8000000 Hz oscillator; using 0.750 (14.3% off)");
	run_free(&r);
	r = ctl("bittiming", "470000", NULL);
	assert_int_equal(r.status, 0);
	assert_stderr_lines(&r, 2, "0.1% off", "using 0.823 (5.9% off)");
	run_free(&r);
	/* the tools that bring the chip up say the same */
	assert_one_line_error(ctl("--device", "sim", "-b", "1040000", "send", "123#",
				  NULL), EXIT_FAIL, "3.8% off");
}

/* The simulator's environment, not the device string, is at fault. */
static struct run ctl_with_env(const char *name, const char *value)
{
	struct run r;

	setenv(name, value, 1);
	r = ctl("--device", "sim", "info", NULL);
	unsetenv(name);
	return r;
}

static void test_sim_environment_named(void **state)
{
	(void)state;
	assert_one_line_error(ctl_with_env("MCP2510_SIM_MISO", "bogus"), EXIT_FAIL,
			      "MCP2510_SIM_MISO=bogus");
	assert_one_line_error(ctl_with_env("MCP2510_SIM_BUS_ERRORS", "abc"),
			      EXIT_FAIL, "MCP2510_SIM_BUS_ERRORS=abc");
}

/* What was taken without a word before, or meant something else. */
static void test_inconsistencies(void **state)
{
	struct run r;

	(void)state;
	/* -1 (forever) is dump's; send would spin on a lone node */
	assert_one_line_error(ctl("--device", "sim:alone", "send", "-t", "-1", "123#",
				  NULL), EXIT_USAGE, "--timeout -1");
	assert_one_line_error(ctl("--device", "sim", "dump", "-n", "0", NULL),
			      EXIT_USAGE, "--count");
	assert_one_line_error(ctl("--device", "sim", "--int", "gpiochip0:25", "info",
				  NULL), EXIT_USAGE, "--int");
	assert_one_line_error(ctl("bittiming", "-1", NULL), EXIT_USAGE,
			      "'-1'");
	assert_one_line_error(ctl("bittiming", "--sample-point", "1", NULL),
			      EXIT_USAGE, "invalid value '1' for --sample-point");
	r = ctl("help", "help", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "Usage: mcp2510ctl"));
	run_free(&r);
	r = ctl("--clock", "16mhz", "bittiming", NULL);
	assert_int_equal(r.status, 0);
	run_free(&r);
}

static void test_chip_commands_on_sim(void **state)
{
	struct run r = ctl("--device", "sim", "selftest", NULL);

	(void)state;
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "PASS\n"));
	run_free(&r);
	r = ctl("--device", "sim", "exchange", "--count", "2", NULL);
	assert_int_equal(r.status, 0);
	assert_int_equal(lines(r.out), 4);
	assert_non_null(strstr(r.out, ") mcp2510.1 100#00\n"));
	assert_non_null(strstr(r.out, ") mcp2510.0 201#1011\n"));
	run_free(&r);
	r = ctl("--device", "sim", "send", "123#11", "1FFFFFFF#R", NULL);
	assert_int_equal(r.status, 0);
	assert_string_equal(r.out, "");
	run_free(&r);
	r = ctl("--device", "sim", "regs", NULL);
	assert_int_equal(r.status, 0);
	assert_int_equal(lines(r.out), 128);
	assert_non_null(strstr(r.out, "0x2a CNF1       0x"));
	run_free(&r);
	r = ctl("--device", "sim", "filter", "mask0=7ff", "filter0=123x", NULL);
	assert_int_equal(r.status, 0);
	assert_int_equal(lines(r.out), MCP2510_HW_FILTER_SETTINGS);
	assert_non_null(strstr(r.out, "mask0 7ff\nmask1 0\nfilter0 00000123x\n"));
	run_free(&r);
	r = ctl("--device", "sim", "dump", "--count", "1", "--timeout", "5", NULL);
	assert_int_equal(r.status, EXIT_FAIL);
	assert_string_equal(r.out, "");
	run_free(&r);
	r = ctl("--device", "sim", "info", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "variant mcp2510\n"));
	assert_non_null(strstr(r.out, "mode configuration\n"));
	run_free(&r);
}

/* #17: a chip that is not there answers nothing, whatever the command. */
static void test_no_chip_no_answer(void **state)
{
	static const char *const cmds[][3] = {
		{ "info" }, { "state" }, { "regs" }, { "reset" }, { "filter" },
		{ "selftest" }, { "dump", "--timeout", "5" },
		{ "send", "123#11" },
	};
	static const char *const miso[] = { "low", "high" };
	size_t i, m;

	(void)state;
	for (m = 0; m < 2; m++) {
		setenv("MCP2510_SIM_MISO", miso[m], 1);
		for (i = 0; i < sizeof(cmds) / sizeof(cmds[0]); i++) {
			struct run r = ctl("--device", "sim", cmds[i][0],
					   cmds[i][1], cmds[i][2], NULL);

			if (r.status != EXIT_FAIL || r.out[0] ||
			    !strstr(r.err, "mcp2510ctl: no chip answers on sim: ") ||
			    lines(r.err) != 1) {
				unsetenv("MCP2510_SIM_MISO");
				fail_msg("MISO %s, %s: status %d, out '%s', err '%s'",
					 miso[m], cmds[i][0], r.status, r.out, r.err);
			}
			run_free(&r);
		}
	}
	unsetenv("MCP2510_SIM_MISO");
	assert_one_line_error(ctl("--device", "/dev/null", "info", NULL),
			      EXIT_FAIL, "/dev/null is not a spidev device");
}

/* #17: each message names the real cause. */
static void test_messages_name_the_cause(void **state)
{
	struct run r;

	(void)state;
	assert_one_line_error(ctl("--device", "sim", "--int", "25", "info", NULL),
			      EXIT_USAGE, "--int 25: give the INT pin as CHIP:LINE, e.g. gpiochip0:25");
	assert_one_line_error(ctl("--device", "sim", "--int", "gpiochip0:", "info",
				  NULL), EXIT_USAGE,
			      "--int gpiochip0:: give the INT pin as CHIP:LINE");
	/* a line name alone is taken, but a simulated chip has no pin */
	assert_one_line_error(ctl("--device", "sim", "--int", "GPIO25", "info", NULL),
			      EXIT_USAGE, "--int GPIO25: a simulated chip");
	/* a bare path is a spidev path */
	assert_one_line_error(ctl("--device", "/nonexistent/spidev0.0", "info",
				  NULL), EXIT_FAIL,
			      "cannot open spidev:/nonexistent/spidev0.0: No such file or directory");
	assert_one_line_error(ctl("bittiming", "500000", "--clock", "40M", NULL),
			      EXIT_USAGE, "--clock 40M: the oscillator must be 1 to 25 MHz");
	assert_one_line_error(ctl("bittiming", "500000", "--sample-point", "0.5",
				  NULL), EXIT_FAIL,
			      "sample point 0.500 at 500000 bit/s breaks the data sheet's PRSEG + PS1 >= PS2 (the sample point must come after the middle of the bit); the earliest here is 0.562");
	r = ctl("bittiming", "125000", "--sample-point", "0.99", NULL);
	assert_int_equal(r.status, 0);
	assert_string_equal(r.err, "mcp2510ctl: warning: sample point 0.990 cannot be made at 125000 bit/s from a 16000000 Hz oscillator; using 0.875 (11.6% off)\n");
	assert_non_null(strstr(r.out, "sample-point 0.875 "));
	run_free(&r);
	r = ctl("--device", "sim", "--sample-point", "0.99", "--bitrate", "125k",
		"send", "123#", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.err, "warning: sample point 0.990 cannot be made"));
	run_free(&r);
	assert_one_line_error(ctl("--device", "sim", "--one-shot", "send", "001#", NULL),
			      EXIT_USAGE, "--one-shot needs an MCP2515 or MCP25625");
	r = ctl("--device", "sim", "--variant", "mcp2515", "--one-shot", "send",
		"001#", NULL);
	assert_int_equal(r.status, 0);
	run_free(&r);
	assert_one_line_error(ctl("--device", "sim", "--listen-only", "send", "001#",
				  NULL), EXIT_USAGE, "send: --listen-only never transmits");
	/* nothing can ever arrive on a private simulated bus: say so */
	r = ctl("--device", "sim", "dump", NULL);
	assert_int_equal(r.status, 0);
	assert_string_equal(r.err, "mcp2510ctl: dump: the simulated bus has gone quiet for good (no node on it sends), stopping\n");
	run_free(&r);
	assert_one_line_error(ctl("--device", "sim", "dump", "-n", "2", "-t", "10",
				  NULL), EXIT_FAIL, "dump: 0 of 2 frames, then none for 10 ms");
	r = ctl("--device", "sim", "filter", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "filter1 00000000x\n"));
	assert_null(strstr(r.out, " 0x\n"));
	run_free(&r);
	assert_one_line_error(ctl("--device", "sim", "filter", "filter0=0x123", NULL),
			      EXIT_USAGE, "'filter0=0x123': write the id in hex without 0x");
	assert_one_line_error(ctl("--device", "sim", "filter", "filter0=800", NULL),
			      EXIT_USAGE, "up to 7ff (11 bit)");
	assert_one_line_error(ctl("--device", "sim", "filter", "filt0=1", NULL),
			      EXIT_USAGE, "unknown filter setting 'filt0'");
	assert_one_line_error(ctl("--device", "sim", "dump", "--filter", "mask0", NULL),
			      EXIT_USAGE, "filter setting 'mask0' is not NAME=VALUE");
	assert_one_line_error(ctl("--device", "sim", "--spi-hz", "6M", "info", NULL),
			      EXIT_USAGE, "--spi-hz 6000000: above the mcp2510's SPI clock limit of 5 MHz");
	assert_one_line_error(ctl("--device", "sim", "--variant", "mcp25625",
				  "--spi-hz", "11M", "info", NULL), EXIT_USAGE,
			      "above the mcp25625's SPI clock limit of 10 MHz");
	r = ctl("--device", "sim", "--variant", "mcp2515", "--spi-hz", "10MHz",
		"info", NULL);
	assert_int_equal(r.status, 0);
	run_free(&r);
}

/* getopt_long: short forms, options anywhere, --version, help. */
static void test_command_line(void **state)
{
	struct run r;

	(void)state;
	r = ctl("--timeout", "100", "-d", "sim", "send", "123#11", NULL);
	assert_int_equal(r.status, 0);
	assert_string_equal(r.err, "");
	run_free(&r);
	r = ctl("-n", "1", "exchange", "-dsim", NULL);
	assert_int_equal(r.status, 0);
	assert_int_equal(lines(r.out), 2);
	run_free(&r);
	r = ctl("--version", NULL);
	assert_int_equal(r.status, 0);
	assert_string_equal(r.out, "mcp2510ctl " MCP2510_VERSION "\n");
	run_free(&r);
	r = ctl("-V", "info", NULL);
	assert_int_equal(r.status, 0);
	assert_string_equal(r.out, "mcp2510ctl " MCP2510_VERSION "\n");
	run_free(&r);
	r = ctl("help", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "Usage: mcp2510ctl"));
	run_free(&r);
	r = ctl("help", "dump", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "Usage: mcp2510ctl --device DEV dump"));
	run_free(&r);
	r = ctl("-h", "send", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "Usage: mcp2510ctl --device DEV send"));
	run_free(&r);
	assert_one_line_error(ctl("help", "frob", NULL), EXIT_USAGE,
			      "help: unknown command 'frob'");
	r = ctl("-c", "16MHz", "bittiming", "-b", "500kHz", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "bitrate 500000 "));
	run_free(&r);
	r = ctl("--clo=8M", "bittiming", "125k", NULL);
	assert_int_equal(r.status, 0);
	assert_non_null(strstr(r.out, "brp 2\n"));
	run_free(&r);
	assert_one_line_error(ctl("--c", "1", "bittiming", NULL), EXIT_USAGE,
			      "ambiguous option --c");
	assert_one_line_error(ctl("--device", "sim", "--count", "1", "send", "001#",
				  NULL), EXIT_USAGE, "send takes no --count");
	/* after "--" nothing is an option */
	assert_one_line_error(ctl("--device", "sim", "send", "--", "--timeout", NULL),
			      EXIT_USAGE, "bad frame '--timeout'");
}

/* --filter (dump's and mcp2510d's) applies on top of the handle's filters. */
static void test_filter_option_applies(void **state)
{
	struct cli_args a = { 0, NULL, 1, false, "mcp2510d", stderr };
	struct mcp2510_hw_filters f;
	struct mcp2510_event ev;
	struct cli_device d;
	struct can_frame cf;
	struct mcp2510 *rx, *tx;
	char line[64];
	canid_t id;

	(void)state;
	cli_device_init(&d);
	d.device = "sim:filters";
	assert_int_equal(cli_device_add_filter(&d, &a, "mask0=7ff"), 0);
	assert_int_equal(cli_device_add_filter(&d, &a, "filter0=123"), 0);
	assert_int_equal(cli_device_add_filter(&d, &a, "filter1=123"), 0);
	assert_int_equal(cli_device_add_filter(&d, &a, "rxm1=ext"), 0);
	assert_int_equal(cli_device_add_filter(&d, &a, "filter0=0x5"), -1);
	rx = cli_device_open(&d, &a, false);
	assert_non_null(rx);
	assert_int_equal(cli_device_up(&d, rx, &a), 0);
	assert_int_equal(mcp2510_get_filters(rx, &f), 0);
	mcp2510_hw_filters_format(&f, 2, line, sizeof(line));
	assert_string_equal(line, "filter0 123");
	d.nfilters = 0;
	tx = cli_device_open(&d, &a, false);
	assert_non_null(tx);
	assert_int_equal(cli_device_up(&d, tx, &a), 0);
	for (id = 0x121; id <= 0x124; id++) {
		memset(&cf, 0, sizeof(cf));
		cf.can_id = id;
		assert_int_equal(mcp2510_send(tx, &cf, 0), 0);
	}
	assert_int_equal(mcp2510_recv(rx, &ev, 100), 0);
	assert_int_equal(ev.type, MCP2510_EVENT_RX);
	assert_int_equal(ev.frame.can_id, 0x123);
	while (!mcp2510_recv(rx, &ev, 50))
		assert_int_not_equal(ev.type, MCP2510_EVENT_RX);
	mcp2510_close(tx);
	mcp2510_close(rx);
}

static void test_device_failures(void **state)
{
	(void)state;
	assert_one_line_error(ctl("--device", "spidev:/nonexistent/spidev0.0",
				  "info", NULL), EXIT_FAIL, "cannot open");
	assert_one_line_error(ctl("--device", "sim:alone", "send", "--timeout", "20",
				  "123#", NULL), EXIT_FAIL, "not acknowledged");
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_usage_errors),
		cmocka_unit_test(test_bad_frames_named_verbatim),
		cmocka_unit_test(test_help_texts),
		cmocka_unit_test(test_bittiming_contract),
		cmocka_unit_test(test_bittiming_errors_reported),
		cmocka_unit_test(test_sim_environment_named),
		cmocka_unit_test(test_inconsistencies),
		cmocka_unit_test(test_chip_commands_on_sim),
		cmocka_unit_test(test_device_failures),
		cmocka_unit_test(test_no_chip_no_answer),
		cmocka_unit_test(test_messages_name_the_cause),
		cmocka_unit_test(test_command_line),
		cmocka_unit_test(test_filter_option_applies),
	};

	return cmocka_run_group_tests_name("userspace_ctl", tests, NULL, NULL);
}
