// SPDX-License-Identifier: GPL-2.0
/*
 * The tools' text formats: cansend syntax in, candump -L out, and the
 * numbers of the command line.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <string.h>
#include <cmocka.h>
#include <linux/can/error.h>

#include "cli.h"
#include "frame_text.h"

static struct can_frame parse_ok(const char *text)
{
	struct can_frame cf;
	const char *why = NULL;

	if (frame_parse(text, &cf, &why))
		fail_msg("'%s' refused: %s", text, why);
	return cf;
}

static void test_parse_standard_data(void **state)
{
	struct can_frame cf = parse_ok("123#DEADBEEF");
	const uint8_t data[] = { 0xde, 0xad, 0xbe, 0xef };

	(void)state;
	assert_int_equal(cf.can_id, 0x123);
	assert_int_equal(cf.len, 4);
	assert_memory_equal(cf.data, data, sizeof(data));
}

static void test_parse_extended_and_lowercase(void **state)
{
	struct can_frame cf = parse_ok("1abcdef0#0a");

	(void)state;
	assert_int_equal(cf.can_id, 0x1abcdef0 | CAN_EFF_FLAG);
	assert_int_equal(cf.len, 1);
	assert_int_equal(cf.data[0], 0x0a);
	/* an 8-digit id is extended even when it would fit 11 bits */
	assert_int_equal(parse_ok("00000123#").can_id, 0x123 | CAN_EFF_FLAG);
}

static void test_parse_empty_dots_and_eight_bytes(void **state)
{
	struct can_frame cf = parse_ok("7FF#");

	(void)state;
	assert_int_equal(cf.can_id, 0x7ff);
	assert_int_equal(cf.len, 0);
	cf = parse_ok("001#11.22.33");
	assert_int_equal(cf.len, 3);
	assert_int_equal(cf.data[2], 0x33);
	cf = parse_ok("001#0102030405060708");
	assert_int_equal(cf.len, 8);
	assert_int_equal(cf.data[7], 8);
}

static void test_parse_remote(void **state)
{
	struct can_frame cf = parse_ok("123#R");

	(void)state;
	assert_int_equal(cf.can_id, 0x123 | CAN_RTR_FLAG);
	assert_int_equal(cf.len, 0);
	cf = parse_ok("12345678#R8");
	assert_int_equal(cf.can_id, 0x12345678 | CAN_EFF_FLAG | CAN_RTR_FLAG);
	assert_int_equal(cf.len, 8);
}

/* cansend's (can-utils lib.c) forms: a dot before any byte, raw DLC. */
static void test_parse_cansend_extras(void **state)
{
	struct can_frame cf = parse_ok("123#.11");

	(void)state;
	assert_int_equal(cf.len, 1);
	assert_int_equal(cf.data[0], 0x11);
	assert_int_equal(parse_ok("123#11.").len, 1);
	cf = parse_ok("123#1122334455667788_9");
	assert_int_equal(cf.len, 8);
	assert_int_equal(cf.len8_dlc, 9);
	cf = parse_ok("123#11.22.33.44.55.66.77.88_f");
	assert_int_equal(cf.len8_dlc, 15);
	cf = parse_ok("123#R8_A");
	assert_int_equal(cf.can_id, 0x123 | CAN_RTR_FLAG);
	assert_int_equal(cf.len, 8);
	assert_int_equal(cf.len8_dlc, 10);
}

static void assert_refused(const char *text, const char *reason_part)
{
	struct can_frame cf;
	const char *why = NULL;

	if (!frame_parse(text, &cf, &why))
		fail_msg("'%s' was accepted", text);
	assert_non_null(why);
	if (!strstr(why, reason_part))
		fail_msg("'%s': reason '%s' lacks '%s'", text, why, reason_part);
}

static void test_parse_refuses_bad_frames(void **state)
{
	(void)state;
	assert_refused("123", "missing '#'");
	assert_refused("12#11", "3 (standard) or 8");
	assert_refused("1234#11", "3 (standard) or 8");
	assert_refused("12G#11", "not hexadecimal");
	assert_refused("800#", "above 7FF");
	assert_refused("40000000#", "above 1FFFFFFF");
	assert_refused("20000001#", "error frames");
	assert_refused("123#1", "pairs of hex digits");
	assert_refused("123#1G", "pairs of hex digits");
	assert_refused("123#11..22", "one dot");
	assert_refused("123#11223344556677_9", "after 8 data bytes");
	assert_refused("123#1122334455667788_8", "9 to F");
	assert_refused("123#1122334455667788_9A", "one hex digit");
	assert_refused("123#R7_9", "or R8");
	assert_refused("123#010203040506070809", "more than 8");
	assert_refused("123#R9", "0-8");
	assert_refused("123#R12", "0-8");
	assert_refused("123##1", "CAN FD");
}

static void assert_formats(const struct can_frame *cf, const char *want)
{
	char buf[FRAME_TEXT_MAX];

	assert_int_equal(frame_format(cf, buf, sizeof(buf)), strlen(want));
	assert_string_equal(buf, want);
}

static void test_format_like_candump(void **state)
{
	struct can_frame cf = { .can_id = 0x12, .len = 2, .data = { 0xab, 1 } };

	(void)state;
	assert_formats(&cf, "012#AB01");
	cf.can_id = 0x12 | CAN_EFF_FLAG;
	assert_formats(&cf, "00000012#AB01");
	cf.can_id = 0x7ff | CAN_RTR_FLAG;
	cf.len = 3;
	assert_formats(&cf, "7FF#R3");
	cf.len = 0;
	assert_formats(&cf, "7FF#R");
	/* error frames: flag in the id, all eight data bytes */
	memset(&cf, 0, sizeof(cf));
	cf.can_id = CAN_ERR_FLAG | CAN_ERR_ACK;
	cf.len = CAN_ERR_DLC;
	cf.data[6] = 0x80;
	assert_formats(&cf, "20000020#0000000000008000");
}

static void test_format_raw_dlc(void **state)
{
	struct can_frame cf = { .can_id = 0x123, .len = 8, .len8_dlc = 12 };
	char buf[FRAME_TEXT_MAX];

	(void)state;
	frame_format(&cf, buf, sizeof(buf));
	assert_string_equal(buf, "123#0000000000000000_C");
	cf.can_id |= CAN_RTR_FLAG;
	frame_format(&cf, buf, sizeof(buf));
	assert_string_equal(buf, "123#R8_C");
}

static void test_format_parse_round_trip(void **state)
{
	static const char *const texts[] = {
		"000#", "7FF#0102030405060708", "1FFFFFFF#FF", "123#R", "123#R8",
		"00000000#R1",
	};
	char buf[FRAME_TEXT_MAX];
	struct can_frame cf;
	size_t i;

	(void)state;
	for (i = 0; i < sizeof(texts) / sizeof(texts[0]); i++) {
		cf = parse_ok(texts[i]);
		frame_format(&cf, buf, sizeof(buf));
		assert_string_equal(buf, texts[i]);
	}
}

static void test_format_log_line(void **state)
{
	struct can_frame cf = { .can_id = 0x123, .len = 4,
				.data = { 0xde, 0xad, 0xbe, 0xef } };
	struct timespec ts = { .tv_sec = 1700000000, .tv_nsec = 123456789 };
	char buf[FRAME_LOG_MAX(8)];

	(void)state;
	assert_true(frame_format_log(&cf, &ts, "mcp2510", buf, sizeof(buf)) > 0);
	assert_string_equal(buf, "(1700000000.123456) mcp2510 123#DEADBEEF");
	ts.tv_sec = 5;
	ts.tv_nsec = 1000;
	frame_format_log(&cf, &ts, "x", buf, sizeof(buf));
	assert_string_equal(buf, "(0000000005.000001) x 123#DEADBEEF");
	/* too small a buffer is refused, not cut */
	assert_int_equal(frame_format_log(&cf, &ts, "x", buf, 10), -1);
}

/* One grammar: digits, k or M in either case, Hz in any case. */
static void test_numbers(void **state)
{
	static const struct {
		const char *text;
		uint32_t want;
	} good[] = {
		{ "500000", 500000 }, { "500k", 500000 }, { "500K", 500000 },
		{ "16M", 16000000 }, { "16mhz", 16000000 },
		{ "16MHZ", 16000000 }, { "500kHz", 500000 },
	};
	static const char *const bad[] = {
		"", "-5", "5x", "16G", "5000M", "4294967296",
	};
	uint32_t v;
	size_t n;
	int i;

	(void)state;
	for (n = 0; n < sizeof(good) / sizeof(good[0]); n++) {
		if (cli_u32(good[n].text, &v) || v != good[n].want)
			fail_msg("'%s' not read as %u", good[n].text, good[n].want);
	}
	for (n = 0; n < sizeof(bad) / sizeof(bad[0]); n++)
		if (!cli_u32(bad[n], &v))
			fail_msg("'%s' taken as %u", bad[n], v);
	assert_int_equal(cli_int("-1", true, &i), 0);
	assert_int_equal(i, -1);
	assert_int_equal(cli_int("-1", false, &i), -1);
}

static void test_sample_point(void **state)
{
	uint32_t sp;

	(void)state;
	assert_int_equal(cli_sample_point("0.875", &sp), 0);
	assert_int_equal(sp, 875);
	assert_int_equal(cli_sample_point("87.5%", &sp), 0);
	assert_int_equal(sp, 875);
	assert_int_equal(cli_sample_point("750", &sp), 0);
	assert_int_equal(sp, 750);
	/* a percentage needs its sign: 87.5 is none of the three forms */
	assert_int_equal(cli_sample_point("87.5", &sp), -1);
	/* tenths of a percent are 100 to 999, as can-calc-bit-timing -s */
	assert_int_equal(cli_sample_point("1", &sp), -1);
	assert_int_equal(cli_sample_point("99", &sp), -1);
	assert_int_equal(cli_sample_point("1000", &sp), -1);
	assert_int_equal(cli_sample_point("0.05", &sp), -1);
	assert_int_equal(cli_sample_point("100%", &sp), -1);
	assert_int_equal(cli_sample_point("0", &sp), -1);
	assert_int_equal(cli_sample_point("abc", &sp), -1);
	assert_int_equal(cli_sample_point("0.8x", &sp), -1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_parse_standard_data),
		cmocka_unit_test(test_parse_extended_and_lowercase),
		cmocka_unit_test(test_parse_empty_dots_and_eight_bytes),
		cmocka_unit_test(test_parse_remote),
		cmocka_unit_test(test_parse_cansend_extras),
		cmocka_unit_test(test_parse_refuses_bad_frames),
		cmocka_unit_test(test_format_raw_dlc),
		cmocka_unit_test(test_format_like_candump),
		cmocka_unit_test(test_format_parse_round_trip),
		cmocka_unit_test(test_format_log_line),
		cmocka_unit_test(test_numbers),
		cmocka_unit_test(test_sample_point),
	};

	return cmocka_run_group_tests_name("userspace_text", tests, NULL, NULL);
}
