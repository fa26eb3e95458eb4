// SPDX-License-Identifier: GPL-2.0
/*
 * The counting of can-flood (tests/vm/guest/flood_count.h): every frame
 * received is corrupted, duplicated, reordered or in order, and what
 * never came is lost; lossless means all four are zero.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "../vm/guest/flood_count.h"

#define COUNT 100

static const struct flood crc_flood = { .id = 0x123, .start = 7, .count = COUNT };

struct run {
	struct flood f;
	struct flood_count c;
};

static struct run *start_run(const struct flood *f)
{
	struct run *r = calloc(1, sizeof(*r));

	assert_non_null(r);
	r->f = *f;
	assert_int_equal(flood_count_init(&r->c, &r->f), 0);
	return r;
}

static void end_run(struct run *r)
{
	flood_count_free(&r->c);
	free(r);
}

static void take(struct run *r, uint32_t n)
{
	struct can_frame cf = flood_frame(&r->f, n);

	flood_count_frame(&r->c, &r->f, &cf);
}

static void take_all(struct run *r)
{
	uint32_t n;

	for (n = 0; n < r->f.count; n++)
		take(r, n);
}

static void assert_counts(const struct run *r, uint32_t lost, uint32_t dup,
			  uint32_t reord, uint32_t corrupt)
{
	assert_int_equal(flood_lost(&r->c, &r->f), lost);
	assert_int_equal(r->c.duplicated, dup);
	assert_int_equal(r->c.reordered, reord);
	assert_int_equal(r->c.corrupted, corrupt);
	assert_int_equal(flood_lossless(&r->c, &r->f),
			 !lost && !dup && !reord && !corrupt);
}

static void every_frame_once_in_order_is_lossless(void **state)
{
	struct run *r = start_run(&crc_flood);

	(void)state;
	take_all(r);
	assert_counts(r, 0, 0, 0, 0);
	assert_int_equal(r->c.received, COUNT);
	end_run(r);
}

static void frames_are_unique_and_carry_their_number(void **state)
{
	struct can_frame a = flood_frame(&crc_flood, 0);
	struct can_frame b = flood_frame(&crc_flood, 1);

	(void)state;
	assert_int_equal(a.len, 8);
	assert_int_equal(flood_le32(a.data), 7);
	assert_int_equal(flood_le32(b.data), 8);
	assert_int_not_equal(flood_le32(a.data + 4), flood_le32(b.data + 4));
}

static void missing_frames_are_lost_not_reordered(void **state)
{
	struct run *r = start_run(&crc_flood);
	uint32_t n;

	(void)state;
	for (n = 0; n < COUNT; n++)
		if (n % 10 != 3)
			take(r, n);
	assert_counts(r, 10, 0, 0, 0);
	end_run(r);
}

static void a_frame_twice_is_duplicated(void **state)
{
	struct run *r = start_run(&crc_flood);

	(void)state;
	take_all(r);
	take(r, 42);
	take(r, COUNT - 1);
	assert_counts(r, 0, 2, 0, 0);
	assert_int_equal(r->c.received, COUNT + 2);
	end_run(r);
}

static void a_frame_after_a_later_one_is_reordered(void **state)
{
	struct run *r = start_run(&crc_flood);
	uint32_t n;

	(void)state;
	for (n = 0; n < COUNT; n++) {
		if (n == 10)
			continue;
		take(r, n);
		if (n == 12)
			take(r, 10);
	}
	assert_counts(r, 0, 0, 1, 0);
	end_run(r);
}

static void the_first_frame_late_is_reordered(void **state)
{
	struct run *r = start_run(&crc_flood);
	uint32_t n;

	(void)state;
	for (n = 1; n < COUNT; n++)
		take(r, n);
	take(r, 0);
	assert_counts(r, 0, 0, 1, 0);
	end_run(r);
}

static void damaged_frames_are_corrupted(void **state)
{
	struct run *r = start_run(&crc_flood);
	struct can_frame cf;

	(void)state;
	take_all(r);
	cf = flood_frame(&r->f, 5);
	cf.data[6] ^= 0x10;		/* check word */
	flood_count_frame(&r->c, &r->f, &cf);
	cf = flood_frame(&r->f, 5);
	cf.data[1] ^= 0x01;		/* sequence number */
	flood_count_frame(&r->c, &r->f, &cf);
	cf = flood_frame(&r->f, 5);
	cf.can_id = 0x124;
	flood_count_frame(&r->c, &r->f, &cf);
	cf = flood_frame(&r->f, 5);
	cf.len = 7;
	flood_count_frame(&r->c, &r->f, &cf);
	cf = flood_frame(&r->f, 5);
	cf.can_id |= CAN_RTR_FLAG;
	flood_count_frame(&r->c, &r->f, &cf);
	assert_counts(r, 0, 0, 0, 5);
	end_run(r);
}

static void a_number_outside_the_flood_is_corrupted(void **state)
{
	struct flood f = crc_flood;
	struct run *r;
	struct can_frame cf;

	(void)state;
	f.count = COUNT + 1;
	cf = flood_frame(&f, COUNT);	/* valid check word, one too far */
	r = start_run(&crc_flood);
	take_all(r);
	flood_count_frame(&r->c, &r->f, &cf);
	assert_counts(r, 0, 0, 0, 1);
	end_run(r);
}

/* the simulator's phantom: bytes 0-3 count up, bytes 4-7 stay */
static void a_fixed_check_word_takes_a_counting_flood(void **state)
{
	struct flood f = { .id = 0x123, .count = COUNT, .fixed = 1,
			   .word = 0xa55a0ff0 };
	struct run *r = start_run(&f);
	struct can_frame cf;
	uint32_t n;

	(void)state;
	for (n = 0; n < COUNT; n++) {
		assert_int_equal(flood_text_frame("123#00000000F00F5AA5", &cf), 0);
		flood_put_le32(cf.data, flood_le32(cf.data) + n);
		flood_count_frame(&r->c, &r->f, &cf);
	}
	assert_counts(r, 0, 0, 0, 0);
	cf.data[5] = 0;
	flood_count_frame(&r->c, &r->f, &cf);
	assert_counts(r, 0, 0, 0, 1);
	end_run(r);
}

static void text_frames_of_candump_and_the_monitor(void **state)
{
	struct can_frame cf;

	(void)state;
	assert_int_equal(flood_text_frame("(1.0) can0 123#0102030405060708", &cf), 0);
	assert_int_equal(cf.can_id, 0x123);
	assert_int_equal(cf.len, 8);
	assert_int_equal(cf.data[7], 8);
	assert_int_equal(flood_text_frame("5 9 chip0 12345678#11.22 125000 60 ok", &cf), 0);
	assert_int_equal(cf.can_id, 0x12345678 | CAN_EFF_FLAG);
	assert_int_equal(cf.len, 2);
	assert_int_equal(cf.data[1], 0x22);
	assert_int_equal(flood_text_frame("1 2 chip0 123# 125000 44 ok", &cf), 0);
	assert_int_equal(cf.len, 0);
	assert_int_equal(flood_text_frame("1 2 chip0 123#R 125000 44 ok", &cf), 0);
	assert_true(cf.can_id & CAN_RTR_FLAG);
	assert_int_equal(flood_text_frame("5 9 chip0 123#11 125000 60 error-ack", &cf), -1);
	assert_int_equal(flood_text_frame("ready", &cf), -1);
	assert_int_equal(flood_text_frame("x 1234#11", &cf), -1);
	assert_int_equal(flood_text_frame("x 123#1", &cf), -1);
	assert_int_equal(flood_text_frame("x 123#112233445566778899", &cf), -1);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(every_frame_once_in_order_is_lossless),
		cmocka_unit_test(frames_are_unique_and_carry_their_number),
		cmocka_unit_test(missing_frames_are_lost_not_reordered),
		cmocka_unit_test(a_frame_twice_is_duplicated),
		cmocka_unit_test(a_frame_after_a_later_one_is_reordered),
		cmocka_unit_test(the_first_frame_late_is_reordered),
		cmocka_unit_test(damaged_frames_are_corrupted),
		cmocka_unit_test(a_number_outside_the_flood_is_corrupted),
		cmocka_unit_test(a_fixed_check_word_takes_a_counting_flood),
		cmocka_unit_test(text_frames_of_candump_and_the_monitor),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
