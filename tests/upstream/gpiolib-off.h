/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Forced into the 6.12 build of mcp251x.c by upstream-check: the file comes
 * from a newer kernel whose gpio_chip set callbacks return int, which the
 * 6.12 headers do not have, so its gpiochip is left out of that build (the
 * rest of the file builds unchanged).
 */
#undef CONFIG_GPIOLIB
