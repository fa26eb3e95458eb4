/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * The chip's INT pin on a GPIO line, through libgpiod: gpio_int_v1.c for
 * libgpiod 1, gpio_int_v2.c for libgpiod 2, one of them built.
 */
#ifndef MCP2510_GPIO_INT_H
#define MCP2510_GPIO_INT_H

struct mcp2510_int_line;

/*
 * @spec is "CHIP:LINE": CHIP as libgpiod 1's gpiod_chip_open_lookup()
 * took it (gpiochip0, /dev/gpiochip0, a number or a label), LINE an
 * offset or a line name; or a line name alone, looked up on every chip.
 * 0 or -errno: EINVAL for a malformed spec, ENOENT for no such chip or
 * line, EBUSY for a line already taken.
 */
int mcp2510_int_line_open(const char *spec, struct mcp2510_int_line **out);
/* 1 when INT is asserted (low) or fell, 0 on timeout, -errno. */
int mcp2510_int_line_wait(struct mcp2510_int_line *l, int timeout_ms);
int mcp2510_int_line_fd(const struct mcp2510_int_line *l);
void mcp2510_int_line_close(struct mcp2510_int_line *l);

#endif /* MCP2510_GPIO_INT_H */
