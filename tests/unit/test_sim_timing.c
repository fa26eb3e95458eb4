// SPDX-License-Identifier: GPL-2.0
/*
 * The model's SPI time arithmetic (sim_spi_time.h): the clock
 * a transfer runs at, what a period and a message cost, the one bus queue,
 * the interrupt latency, and that with timing off nothing takes time.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include "sim_helpers.h"

static const struct sim_spi_timing board = {
	.enabled = true,
	.msg_ns = 10000,
	.cs_setup_ns = 50,
	.cs_hold_ns = 100,
	.ctlr_max_hz = 0,
	.irq_latency_ns = 20000,
};

/* An MCP2510 and an idle SPI bus with the board's timing. */
static void board_setup(struct sim_chip *chip, struct sim_spi_bus *sb)
{
	assert_int_equal(sim_chip_init(chip, SIM_MCP2510, SIMH_OSC_16MHZ), 0);
	sim_spi_bus_init(sb);
	sb->timing = board;
}

static void test_sck_limits(void **state)
{
	struct sim_chip c2510, c2515;
	struct sim_spi_timing t = board;

	(void)state;
	assert_int_equal(sim_chip_init(&c2510, SIM_MCP2510, SIMH_OSC_16MHZ), 0);
	assert_int_equal(sim_chip_init(&c2515, SIM_MCP2515, SIMH_OSC_16MHZ), 0);
	assert_int_equal(sim_chip_sck_max_hz(&c2510), 5000000);
	assert_int_equal(sim_chip_sck_max_hz(&c2515), 10000000);

	/* the chip's limit wins over a faster request; 0 asks for the limit */
	assert_int_equal(sim_spi_speed_hz(&t, 20000000, 5000000), 5000000);
	assert_int_equal(sim_spi_speed_hz(&t, 0, 10000000), 10000000);
	assert_int_equal(sim_spi_speed_hz(&t, 1000000, 10000000), 1000000);
	/* so does the controller's */
	t.ctlr_max_hz = 4000000;
	assert_int_equal(sim_spi_speed_hz(&t, 0, 10000000), 4000000);
	assert_int_equal(sim_spi_speed_hz(&t, 8000000, 5000000), 4000000);
	assert_int_equal(sim_spi_speed_hz(&t, 2000000, 5000000), 2000000);
}

static void test_clock_time(void **state)
{
	struct sim_spi_timing t = board;

	(void)state;
	/* 3 bytes at 5 MHz: 24 bits of 200 ns */
	assert_int_equal(sim_spi_clock_ns(&t, 3, 0, 5000000), 4800);
	/* clamped: asking for 10 MHz of an MCP2510 still takes 5 MHz time */
	assert_int_equal(sim_spi_clock_ns(&t, 3, 10000000, 5000000), 4800);
	/* rounded up: 8 bits at 3 MHz are 2666.7 ns */
	assert_int_equal(sim_spi_clock_ns(&t, 1, 3000000, 5000000), 2667);
	/* the largest period the kernel module takes, without overflow */
	assert_int_equal(sim_spi_clock_ns(&t, 4096, 1000, 5000000),
			 4096ULL * 8 * 1000000);
	assert_int_equal(sim_spi_clock_ns(&t, 0, 0, 5000000), 0);
	t.enabled = false;
	assert_int_equal(sim_spi_clock_ns(&t, 3, 0, 5000000), 0);
}

static void test_message_time(void **state)
{
	struct sim_chip chip;
	struct sim_spi_bus sb;
	struct sim_spi_msg m;

	(void)state;
	board_setup(&chip, &sb);

	/* overhead once, then setup + clock + hold per period */
	sim_spi_msg_begin(&sb, &m, 1000);
	assert_int_equal(sim_spi_msg_period(&sb, &m, 3200), 1000 + 10000 + 50 + 3200 + 100);
	assert_int_equal(sim_spi_msg_period(&sb, &m, 1600), 14350 + 50 + 1600 + 100);
	sim_spi_msg_end(&sb, &m, &chip);
	assert_int_equal(sb.free_at, 16100);
	assert_int_equal(sim_chip_counters(&chip)->spi_busy_ns, 15100);

	/* a message asked for while the bus is busy waits its turn */
	sim_spi_msg_begin(&sb, &m, 2000);
	assert_int_equal(m.start, 16100);
	assert_int_equal(sim_spi_msg_period(&sb, &m, 0), 16100 + 10000 + 150);
	sim_spi_msg_end(&sb, &m, &chip);
	assert_int_equal(sim_chip_counters(&chip)->spi_busy_ns, 15100 + 10150);

	/* one asked for after the bus went free starts at once */
	sim_spi_msg_begin(&sb, &m, 100000);
	assert_int_equal(m.start, 100000);
	sim_spi_msg_end(&sb, &m, &chip);

	assert_int_equal(sim_spi_irq_due(&sb, 5000), 25000);
}

/* Off: everything at the time asked for, no busy time, no queue. */
static void test_off_takes_no_time(void **state)
{
	struct sim_chip chip;
	struct sim_spi_bus sb;
	struct sim_spi_msg m;

	(void)state;
	sim_spi_bus_init(&sb);
	assert_false(sb.timing.enabled);
	board_setup(&chip, &sb);
	sb.timing.enabled = false;
	sim_spi_msg_begin(&sb, &m, 7000);
	assert_int_equal(sim_spi_msg_period(&sb, &m, 12345), 7000);
	sim_spi_msg_end(&sb, &m, &chip);
	sim_spi_msg_begin(&sb, &m, 10);
	assert_int_equal(m.start, 10);
	assert_int_equal(sim_spi_msg_period(&sb, &m, 0), 10);
	assert_int_equal(sim_chip_counters(&chip)->spi_busy_ns, 0);
	assert_int_equal(sim_spi_irq_due(&sb, 5000), 5000);
}

int main(void)
{
	const struct CMUnitTest tests[] = {
		cmocka_unit_test(test_sck_limits),
		cmocka_unit_test(test_clock_time),
		cmocka_unit_test(test_message_time),
		cmocka_unit_test(test_off_takes_no_time),
	};

	return cmocka_run_group_tests(tests, NULL, NULL);
}
