/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* The chip's INT pin on a GPIO line, through libgpiod. */
#ifndef MCP2510_GPIO_INT_H
#define MCP2510_GPIO_INT_H

struct mcp2510_int_line;

/*
 * @spec is "CHIP:LINE": CHIP as gpiod_chip_open_lookup() takes it
 * (gpiochip0, /dev/gpiochip0, a label or a number), LINE an offset or a
 * line name.  0 or -errno (EINVAL for a malformed spec).
 */
int mcp2510_int_line_open(const char *spec, struct mcp2510_int_line **out);
/* 1 when INT is asserted (low) or fell, 0 on timeout, -errno. */
int mcp2510_int_line_wait(struct mcp2510_int_line *l, int timeout_ms);
int mcp2510_int_line_fd(const struct mcp2510_int_line *l);
void mcp2510_int_line_close(struct mcp2510_int_line *l);

#endif /* MCP2510_GPIO_INT_H */
