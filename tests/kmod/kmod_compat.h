/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The simulator is written against the newest kernel's API; what an older
 * kernel (down to 6.1) lacks of it is supplied here, and only here, as in
 * driver/compat.h: the root Kbuild defines MCP2510_HAVE_<feature> for each
 * piece the headers have.
 */
#ifndef MCP2510_SIM_KMOD_COMPAT_H
#define MCP2510_SIM_KMOD_COMPAT_H

#include <linux/hrtimer.h>

/* hex_to_bin() has had a header of its own since 6.x; 7.x needs it. */
#ifdef MCP2510_HAVE_LINUX_HEX_H
#include <linux/hex.h>
#else
#include <linux/kernel.h>
#endif

/* hrtimer_setup() came in 6.13; hrtimer_init() went in 6.15. */
#ifndef MCP2510_HAVE_HRTIMER_SETUP
static inline void
hrtimer_setup(struct hrtimer *timer,
	      enum hrtimer_restart (*function)(struct hrtimer *),
	      clockid_t clock_id, enum hrtimer_mode mode)
{
	hrtimer_init(timer, clock_id, mode);
	timer->function = function;
}
#endif

#endif /* MCP2510_SIM_KMOD_COMPAT_H */
