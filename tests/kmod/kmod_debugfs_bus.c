// SPDX-License-Identifier: GPL-2.0
/*
 * The bus half of the control surface in /sys/kernel/debug/mcp2510-sim/:
 * the phantom node (inject, flood, phantom), bus faults (bus_errors,
 * no_ack), bus time and the monitor.  docs/simulator.md describes every
 * file; kmod_debugfs_chip.c adds the chipN/ directories.
 */
#include <linux/debugfs.h>
#include <linux/fs.h>
#include <linux/hrtimer.h>
#include <linux/kernel.h>
#include <linux/pm_domain.h>
#include <linux/string.h>
#include <linux/uaccess.h>

#include "kmod.h"

#define COMMAND_LEN	96
/* eight data bytes, so that a flood without a frame is one of full frames */
#define FLOOD_DEFAULT_FRAME	"123#0000000000000000"

/* Copy a short text command from userspace, NUL-terminated. */
static int read_command(const char __user *ubuf, size_t len, char *buf,
			size_t size)
{
	if (len >= size)
		return -EINVAL;
	if (copy_from_user(buf, ubuf, len))
		return -EFAULT;
	buf[len] = '\0';
	return 0;
}

/* The next blank-separated word of a command, NULL at its end. */
static char *next_word(char **cursor)
{
	char *word;

	do {
		word = strsep(cursor, " \t\n");
	} while (word && !*word);
	return word;
}

static int parse_bitrate(char *word, u32 *bitrate)
{
	*bitrate = 0;
	return word ? kstrtou32(word, 0, bitrate) : 0;
}

static ssize_t inject_write(struct file *file, const char __user *ubuf,
			    size_t len, loff_t *ppos)
{
	struct mcp2510_sim *sim = file_inode(file)->i_private;
	char command[COMMAND_LEN], *cursor = command, *frame;
	struct can_frame cf;
	u32 bitrate;
	int ret;

	ret = read_command(ubuf, len, command, sizeof(command));
	if (ret)
		return ret;
	frame = next_word(&cursor);
	if (!frame || mcp2510_sim_frame_parse(frame, &cf) ||
	    parse_bitrate(next_word(&cursor), &bitrate) || next_word(&cursor))
		return -EINVAL;

	mcp2510_sim_lock(sim);
	ret = sim_phantom_send(&sim->bus, &cf, bitrate);
	mcp2510_sim_unlock(sim);
	return ret ? ret : len;
}

static const struct file_operations inject_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.write = inject_write,
};

/*
 * "[devices|noirq] MS FRAME [BITRATE]": the phantom sends FRAME MS
 * milliseconds from now, on a kernel timer.  With "devices" the time
 * counts from the next system suspend's devices phase (the simulator's
 * root device suspends after the chips, so their drivers have prepared
 * them; MS 0 sends the frame from within that callback), with "noirq"
 * from its noirq phase (device interrupts suspended, wakeup interrupts
 * armed).  The timer runs while the guest's tasks are frozen, so a
 * scenario can put a frame on the bus in the middle of a suspend.  A new
 * write replaces a frame not yet sent.
 */
static void inject_send(struct mcp2510_sim *sim)
{
	mcp2510_sim_lock(sim);
	sim->inject_result = sim_phantom_send(&sim->bus, &sim->inject_frame,
					      sim->inject_bitrate);
	mcp2510_sim_unlock(sim);
}

static enum hrtimer_restart inject_timer_fired(struct hrtimer *timer)
{
	inject_send(container_of(timer, struct mcp2510_sim, inject_timer));
	return HRTIMER_NORESTART;
}

static ssize_t inject_later_write(struct file *file, const char __user *ubuf,
				  size_t len, loff_t *ppos)
{
	struct mcp2510_sim *sim = file_inode(file)->i_private;
	char command[COMMAND_LEN], *cursor = command, *word, *frame;
	u8 phase = MCP2510_SIM_INJECT_NOW;
	struct can_frame cf;
	u32 ms, bitrate;
	int ret;

	ret = read_command(ubuf, len, command, sizeof(command));
	if (ret)
		return ret;
	word = next_word(&cursor);
	if (word && !strcmp(word, "devices"))
		phase = MCP2510_SIM_INJECT_DEVICES;
	else if (word && !strcmp(word, "noirq"))
		phase = MCP2510_SIM_INJECT_NOIRQ;
	if (phase != MCP2510_SIM_INJECT_NOW)
		word = next_word(&cursor);
	if (!word || kstrtou32(word, 0, &ms))
		return -EINVAL;
	frame = next_word(&cursor);
	if (!frame || mcp2510_sim_frame_parse(frame, &cf) ||
	    parse_bitrate(next_word(&cursor), &bitrate) || next_word(&cursor))
		return -EINVAL;

	hrtimer_cancel(&sim->inject_timer);
	mcp2510_sim_lock(sim);
	sim->inject_frame = cf;
	sim->inject_bitrate = bitrate;
	sim->inject_result = 0;
	sim->inject_ms = ms;
	sim->inject_phase = phase;
	mcp2510_sim_unlock(sim);
	if (phase == MCP2510_SIM_INJECT_NOW)
		hrtimer_start(&sim->inject_timer, ms_to_ktime(ms),
			      HRTIMER_MODE_REL_SOFT);
	return len;
}

static void inject_phase_reached(struct device *dev, u8 phase)
{
	struct mcp2510_sim *sim = dev_get_drvdata(dev);
	bool start;
	u32 ms;

	mcp2510_sim_lock(sim);
	start = sim->inject_phase == phase;
	if (start)
		sim->inject_phase = MCP2510_SIM_INJECT_NOW;
	ms = sim->inject_ms;
	mcp2510_sim_unlock(sim);
	if (!start)
		return;
	if (ms) {
		hrtimer_start(&sim->inject_timer, ms_to_ktime(ms),
			      HRTIMER_MODE_REL_SOFT);
		return;
	}
	inject_send(sim);
	/* the start of frame goes out at the next advance: now */
	mcp2510_sim_lock(sim);
	mcp2510_sim_unlock(sim);
}

static int sim_suspend(struct device *dev)
{
	inject_phase_reached(dev, MCP2510_SIM_INJECT_DEVICES);
	return 0;
}

static int sim_suspend_noirq(struct device *dev)
{
	inject_phase_reached(dev, MCP2510_SIM_INJECT_NOIRQ);
	return 0;
}

void mcp2510_sim_suspend_attach(struct mcp2510_sim *sim)
{
	sim->pm_domain.ops.suspend = sim_suspend;
	sim->pm_domain.ops.suspend_noirq = sim_suspend_noirq;
	dev_set_drvdata(sim->root, sim);
	dev_pm_domain_set(sim->root, &sim->pm_domain);
}

void mcp2510_sim_suspend_detach(struct mcp2510_sim *sim)
{
	dev_pm_domain_set(sim->root, NULL);
}

/* "pending", or "sent" with how sim_phantom_send() took the frame. */
static ssize_t inject_later_read(struct file *file, char __user *ubuf,
				 size_t len, loff_t *ppos)
{
	struct mcp2510_sim *sim = file_inode(file)->i_private;
	char text[24];
	int result, n;
	bool armed;

	mcp2510_sim_lock(sim);
	armed = sim->inject_phase != MCP2510_SIM_INJECT_NOW;
	result = sim->inject_result;
	mcp2510_sim_unlock(sim);
	if (armed || hrtimer_active(&sim->inject_timer))
		n = scnprintf(text, sizeof(text), "pending\n");
	else
		n = scnprintf(text, sizeof(text), "sent %d\n", result);
	return simple_read_from_buffer(ubuf, len, ppos, text, n);
}

static const struct file_operations inject_later_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = inject_later_read,
	.write = inject_later_write,
	.llseek = default_llseek,
};

static ssize_t flood_write(struct file *file, const char __user *ubuf,
			   size_t len, loff_t *ppos)
{
	struct mcp2510_sim *sim = file_inode(file)->i_private;
	char command[COMMAND_LEN], *cursor = command, *word, *frame;
	struct can_frame cf;
	u32 count, bitrate;
	bool checked;
	int ret;

	ret = read_command(ubuf, len, command, sizeof(command));
	if (ret)
		return ret;
	word = next_word(&cursor);
	if (!word || kstrtou32(word, 0, &count))
		return -EINVAL;
	frame = next_word(&cursor);
	if (mcp2510_sim_frame_parse(frame ? frame : FLOOD_DEFAULT_FRAME, &cf) ||
	    parse_bitrate(next_word(&cursor), &bitrate))
		return -EINVAL;
	word = next_word(&cursor);
	checked = word && !strcmp(word, "checked");
	if ((word && !checked) || next_word(&cursor))
		return -EINVAL;

	mcp2510_sim_lock(sim);
	if (checked)
		ret = sim_phantom_flood_checked(&sim->bus, &cf, count, bitrate);
	else
		ret = sim_phantom_flood(&sim->bus, &cf, count, bitrate);
	mcp2510_sim_unlock(sim);
	return ret ? ret : len;
}

/* How many frames the phantom still has to send: poll this to await a flood. */
static ssize_t flood_read(struct file *file, char __user *ubuf, size_t len,
			  loff_t *ppos)
{
	struct mcp2510_sim *sim = file_inode(file)->i_private;
	char text[16];
	u32 pending;
	int n;

	mcp2510_sim_lock(sim);
	pending = sim_phantom_pending(&sim->bus);
	mcp2510_sim_unlock(sim);
	n = scnprintf(text, sizeof(text), "%u\n", pending);
	return simple_read_from_buffer(ubuf, len, ppos, text, n);
}

static const struct file_operations flood_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = flood_read,
	.write = flood_write,
	.llseek = default_llseek,
};

/* "on [bitrate]" joins the phantom to the bus (it acknowledges), "off" leaves. */
static ssize_t phantom_write(struct file *file, const char __user *ubuf,
			     size_t len, loff_t *ppos)
{
	struct mcp2510_sim *sim = file_inode(file)->i_private;
	char command[COMMAND_LEN], *cursor = command, *word;
	bool on;
	u32 bitrate;
	int ret;

	ret = read_command(ubuf, len, command, sizeof(command));
	if (ret)
		return ret;
	word = next_word(&cursor);
	if (!word || (strcmp(word, "on") && strcmp(word, "off")))
		return -EINVAL;
	on = !strcmp(word, "on");
	if (parse_bitrate(next_word(&cursor), &bitrate) || next_word(&cursor))
		return -EINVAL;

	mcp2510_sim_lock(sim);
	if (on)
		sim_phantom_attach(&sim->bus, bitrate);
	else
		sim_phantom_detach(&sim->bus);
	mcp2510_sim_unlock(sim);
	return len;
}

static const struct file_operations phantom_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.write = phantom_write,
};

static int bus_errors_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = sim_bus_faults(&sim->bus)->bus_errors;
	mcp2510_sim_unlock(sim);
	return 0;
}

static int bus_errors_set(void *data, u64 val)
{
	struct mcp2510_sim *sim = data;

	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_lock(sim);
	sim_bus_faults(&sim->bus)->bus_errors = val;
	mcp2510_sim_unlock(sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(bus_errors_fops, bus_errors_get, bus_errors_set,
			 "%llu\n");

static int no_ack_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = sim_bus_faults(&sim->bus)->no_ack;
	mcp2510_sim_unlock(sim);
	return 0;
}

static int no_ack_set(void *data, u64 val)
{
	struct mcp2510_sim *sim = data;

	if (val > 1)
		return -EINVAL;
	mcp2510_sim_lock(sim);
	sim_bus_faults(&sim->bus)->no_ack = val;
	mcp2510_sim_unlock(sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(no_ack_fops, no_ack_get, no_ack_set, "%llu\n");

static int time_ns_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = sim_bus_now(&sim->bus);
	mcp2510_sim_unlock(sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(time_ns_fops, time_ns_get, NULL, "%llu\n");

static int time_scale_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = sim->clock.time_scale;
	mcp2510_sim_unlock(sim);
	return 0;
}

static int time_scale_set(void *data, u64 val)
{
	struct mcp2510_sim *sim = data;

	if (val < 1 || val > MCP2510_SIM_MAX_TIME_SCALE)
		return -EINVAL;
	mcp2510_sim_lock(sim);
	mcp2510_sim_clock_rescale(sim, val);
	mcp2510_sim_unlock(sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(time_scale_fops, time_scale_get, time_scale_set,
			 "%llu\n");

static int clock_stalls_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = mcp2510_sim_clock_stalls(sim);
	mcp2510_sim_unlock(sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(clock_stalls_fops, clock_stalls_get, NULL, "%llu\n");

void mcp2510_sim_debugfs_create(struct mcp2510_sim *sim)
{
	struct dentry *dir = debugfs_create_dir(MCP2510_SIM_NAME, NULL);
	unsigned int n;

	sim->debugfs = dir;
	hrtimer_setup(&sim->inject_timer, inject_timer_fired, CLOCK_MONOTONIC,
		      HRTIMER_MODE_REL_SOFT);
	debugfs_create_file("inject", 0200, dir, sim, &inject_fops);
	debugfs_create_file("inject_later", 0600, dir, sim, &inject_later_fops);
	debugfs_create_file("flood", 0600, dir, sim, &flood_fops);
	debugfs_create_file("phantom", 0200, dir, sim, &phantom_fops);
	debugfs_create_file("monitor", 0600, dir, sim, &mcp2510_sim_monitor_fops);
	debugfs_create_file("monitor_times", 0400, dir, sim,
			    &mcp2510_sim_monitor_times_fops);
	debugfs_create_file_unsafe("bus_errors", 0600, dir, sim, &bus_errors_fops);
	debugfs_create_file_unsafe("no_ack", 0600, dir, sim, &no_ack_fops);
	debugfs_create_file_unsafe("time_ns", 0400, dir, sim, &time_ns_fops);
	debugfs_create_file_unsafe("time_scale", 0600, dir, sim,
				   &time_scale_fops);
	debugfs_create_file_unsafe("clock_stalls", 0400, dir, sim,
				   &clock_stalls_fops);
	mcp2510_sim_debugfs_spi_create(sim, dir);
	for (n = 0; n < sim->nchips; n++)
		mcp2510_sim_debugfs_chip_create(&sim->chips[n], dir);
}

void mcp2510_sim_debugfs_remove(struct mcp2510_sim *sim)
{
	debugfs_remove_recursive(sim->debugfs);
	hrtimer_cancel(&sim->inject_timer);
}
