// SPDX-License-Identifier: GPL-2.0
/*
 * gpio-set CHIP LINE FIRST THEN [ARM-FILE ARM-VALUE]: request LINE of the
 * gpiochip device CHIP as an output at FIRST, then set it to THEN through
 * GPIO_V2_LINE_SET_VALUES_IOCTL, the path that reaches the chip driver's
 * .set callback (gpioset only requests lines, which reaches
 * .direction_output instead).  With ARM-FILE, ARM-VALUE is written to it
 * between the two, e.g. to make the simulator fail the next SPI message.
 *
 * Prints "set: ok" or "set: failed: <error>".  Exit 0 when the set
 * succeeded, 1 when it failed, 2 on anything else.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <linux/gpio.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

static void die(const char *what)
{
	fprintf(stderr, "gpio-set: %s: %s\n", what, strerror(errno));
	exit(2);
}

static void arm(const char *file, const char *value)
{
	FILE *f = fopen(file, "w");

	if (!f || fputs(value, f) == EOF || fclose(f) == EOF)
		die(file);
}

int main(int argc, char **argv)
{
	struct gpio_v2_line_request req;
	struct gpio_v2_line_values vals;
	int fd;

	if (argc != 5 && argc != 7) {
		fprintf(stderr, "usage: gpio-set CHIP LINE FIRST THEN [ARM-FILE ARM-VALUE]\n");
		return 2;
	}
	fd = open(argv[1], O_RDWR | O_CLOEXEC);
	if (fd < 0)
		die(argv[1]);

	memset(&req, 0, sizeof(req));
	req.offsets[0] = (unsigned int)strtoul(argv[2], NULL, 0);
	req.num_lines = 1;
	strcpy(req.consumer, "gpio-set");
	req.config.flags = GPIO_V2_LINE_FLAG_OUTPUT;
	req.config.num_attrs = 1;
	req.config.attrs[0].attr.id = GPIO_V2_LINE_ATTR_ID_OUTPUT_VALUES;
	req.config.attrs[0].attr.values = atoi(argv[3]) ? 1 : 0;
	req.config.attrs[0].mask = 1;
	if (ioctl(fd, GPIO_V2_GET_LINE_IOCTL, &req) < 0)
		die("requesting the line");

	if (argc == 7)
		arm(argv[5], argv[6]);

	vals.mask = 1;
	vals.bits = atoi(argv[4]) ? 1 : 0;
	if (ioctl(req.fd, GPIO_V2_LINE_SET_VALUES_IOCTL, &vals) < 0) {
		printf("set: failed: %s\n", strerror(errno));
		return 1;
	}
	printf("set: ok\n");
	return 0;
}
