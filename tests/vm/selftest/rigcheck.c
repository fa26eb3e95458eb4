// SPDX-License-Identifier: GPL-2.0
/*
 * rigcheck: proves that the rig's kernel-log checks catch what they claim to.
 * Each parameter provokes one kind of report on purpose; vm-run must then
 * fail.  Built and loaded only by tests/vm/selftest/run.
 */
#include <linux/module.h>
#include <linux/mutex.h>
#include <linux/slab.h>
#include <linux/bug.h>

static bool warn;
module_param(warn, bool, 0444);
MODULE_PARM_DESC(warn, "WARN once");

static bool lockdep;
module_param(lockdep, bool, 0444);
MODULE_PARM_DESC(lockdep, "take two mutexes in both orders (one thread: no deadlock)");

static bool kasan;
module_param(kasan, bool, 0444);
MODULE_PARM_DESC(kasan, "read one byte past a 16-byte allocation");

static bool leak;
module_param(leak, bool, 0444);
MODULE_PARM_DESC(leak, "allocate eight objects and drop every pointer to them");

static DEFINE_MUTEX(rigcheck_a);
static DEFINE_MUTEX(rigcheck_b);

/* Written through so the compiler keeps the allocation and the read. */
static void *volatile rigcheck_sink;

static int __init rigcheck_init(void)
{
	if (warn)
		WARN(1, "rigcheck: deliberate warning\n");

	if (lockdep) {
		mutex_lock(&rigcheck_a);
		mutex_lock(&rigcheck_b);
		mutex_unlock(&rigcheck_b);
		mutex_unlock(&rigcheck_a);
		mutex_lock(&rigcheck_b);
		mutex_lock(&rigcheck_a);
		mutex_unlock(&rigcheck_a);
		mutex_unlock(&rigcheck_b);
	}

	if (kasan) {
		char *p = kmalloc(16, GFP_KERNEL);

		if (p) {
			rigcheck_sink = p;
			pr_info("rigcheck: byte past the end: %d\n",
				((volatile char *)p)[16]);
			kfree(p);
		}
	}

	/*
	 * Several objects: a stale copy of a pointer (a reused stack, a
	 * register spill) hides a leak from kmemleak, but not all of them.
	 */
	if (leak) {
		int i;

		for (i = 0; i < 8; i++)
			rigcheck_sink = kzalloc(64 + 32 * i, GFP_KERNEL);
		rigcheck_sink = NULL;
	}

	return 0;
}

static void __exit rigcheck_exit(void)
{
}

module_init(rigcheck_init);
module_exit(rigcheck_exit);
MODULE_DESCRIPTION("Self-test of the QEMU rig's kernel report checks");
MODULE_LICENSE("GPL");
