// SPDX-License-Identifier: GPL-2.0
/*
 * Bus monitor: the last MCP2510_SIM_MONITOR_LEN frames and error frames
 * the bus carried, as one text line each (debugfs "monitor"):
 *
 *   <start_ns> <end_ns> <sender> <frame> <bitrate> <bits> <outcome>
 *
 * sender is chipN or phantom, frame is in cansend syntax, outcome is ok,
 * error-ack, error-bitrate or error-injected.  Writing anything clears it.
 *
 * Records are numbered from the module's start; a reader's file position
 * is a record number, so a record overwritten while a reader pauses is
 * skipped instead of shifting every line that follows.
 *
 * "monitor_times" shows the same records as
 *
 *   <end_ns> <end_real_ns> <seen_real_ns> <sender> <frame> <outcome>
 *
 * for comparing with timestamps taken in the guest: end_real_ns is when
 * the frame ended on the bus, seen_real_ns when the model got there (and
 * the receivers' RXnIF and INT changed), both CLOCK_REALTIME, what
 * SO_TIMESTAMP reports.  seen_real_ns is later by the bus timer's lag.
 */
#include <linux/debugfs.h>
#include <linux/fs.h>
#include <linux/seq_file.h>
#include <linux/timekeeping.h>

#include "kmod.h"

#define FRAME_TEXT_LEN	40

static_assert((MCP2510_SIM_MONITOR_LEN & (MCP2510_SIM_MONITOR_LEN - 1)) == 0);

/* One record with its times, as a reader gets it. */
struct monitor_entry {
	struct sim_bus_record rec;
	u64 end_real_ns;
	u64 seen_real_ns;
};

/*
 * CLOCK_REALTIME of bus time @model_ns, under the lock.  Bus time maps to
 * the monotonic clock (kmod_clock.c); a time before the mapping's last
 * rebase (a stall, a new time_scale) maps to the rebase itself, later
 * than it was, never earlier.
 */
static u64 model_to_real(struct mcp2510_sim *sim, u64 model_ns)
{
	u64 mono;

	if (!mcp2510_sim_clock_real(&sim->clock, model_ns, &mono))
		return 0;
	return ktime_to_ns(ktime_mono_to_real(ns_to_ktime(mono)));
}

static void record(void *ctx, const struct sim_bus_record *rec)
{
	struct mcp2510_sim *sim = ctx;
	struct mcp2510_sim_monitor *mon = &sim->monitor;
	unsigned int i = mon->written & (MCP2510_SIM_MONITOR_LEN - 1);

	mon->ring[i] = *rec;
	mon->end_real_ns[i] = model_to_real(sim, rec->end_ns);
	mon->seen_real_ns[i] = ktime_get_real_ns();
	mon->written++;
}

void mcp2510_sim_monitor_attach(struct mcp2510_sim *sim)
{
	sim_bus_set_monitor(&sim->bus, record, sim);
}

/* Copies record *@pos, moving @pos past records already overwritten. */
static bool fetch(struct mcp2510_sim *sim, loff_t *pos,
		  struct monitor_entry *e)
{
	struct mcp2510_sim_monitor *mon = &sim->monitor;
	u64 seq = *pos, oldest;
	bool found;

	mcp2510_sim_lock(sim);
	oldest = mon->written > MCP2510_SIM_MONITOR_LEN ?
		 mon->written - MCP2510_SIM_MONITOR_LEN : 0;
	seq = max3(seq, oldest, mon->cleared);
	found = seq < mon->written;
	if (found) {
		unsigned int i = seq & (MCP2510_SIM_MONITOR_LEN - 1);

		e->rec = mon->ring[i];
		e->end_real_ns = mon->end_real_ns[i];
		e->seen_real_ns = mon->seen_real_ns[i];
	}
	mcp2510_sim_unlock(sim);
	*pos = seq;
	return found;
}

static void *monitor_start(struct seq_file *m, loff_t *pos)
{
	struct monitor_entry *e = m->private;

	return fetch(file_inode(m->file)->i_private, pos, e) ? e : NULL;
}

static void *monitor_next(struct seq_file *m, void *v, loff_t *pos)
{
	++*pos;
	return fetch(file_inode(m->file)->i_private, pos, v) ? v : NULL;
}

static void monitor_stop(struct seq_file *m, void *v)
{
}

static const char *outcome(const struct sim_bus_record *rec)
{
	if (rec->kind == SIM_REC_FRAME)
		return "ok";
	switch (rec->cause) {
	case SIM_ERR_ACK:
		return "error-ack";
	case SIM_ERR_BITRATE:
		return "error-bitrate";
	case SIM_ERR_INJECTED:
		return "error-injected";
	case SIM_ERR_SENDER_LOST:
		return "error-sender-lost";
	default:
		return "error";
	}
}

static void show_sender(struct seq_file *m, const struct sim_bus_record *rec)
{
	if (rec->sender == SIM_NODE_PHANTOM)
		seq_puts(m, "phantom");
	else
		seq_printf(m, "chip%d", rec->sender);
}

static int monitor_show(struct seq_file *m, void *v)
{
	const struct sim_bus_record *rec = &((struct monitor_entry *)v)->rec;
	char frame[FRAME_TEXT_LEN];

	mcp2510_sim_frame_format(frame, sizeof(frame), &rec->frame);
	seq_printf(m, "%llu %llu ", rec->start_ns, rec->end_ns);
	show_sender(m, rec);
	seq_printf(m, " %s %u %u %s\n", frame, rec->bitrate, rec->bits,
		   outcome(rec));
	return 0;
}

static int monitor_times_show(struct seq_file *m, void *v)
{
	const struct monitor_entry *e = v;
	char frame[FRAME_TEXT_LEN];

	mcp2510_sim_frame_format(frame, sizeof(frame), &e->rec.frame);
	seq_printf(m, "%llu %llu %llu ", e->rec.end_ns, e->end_real_ns,
		   e->seen_real_ns);
	show_sender(m, &e->rec);
	seq_printf(m, " %s %s\n", frame, outcome(&e->rec));
	return 0;
}

static const struct seq_operations monitor_seq_ops = {
	.start = monitor_start,
	.next = monitor_next,
	.stop = monitor_stop,
	.show = monitor_show,
};

static const struct seq_operations monitor_times_seq_ops = {
	.start = monitor_start,
	.next = monitor_next,
	.stop = monitor_stop,
	.show = monitor_times_show,
};

/* seq_file's private area holds the record being printed */
static int monitor_open(struct inode *inode, struct file *file)
{
	return seq_open_private(file, &monitor_seq_ops,
				sizeof(struct monitor_entry));
}

static int monitor_times_open(struct inode *inode, struct file *file)
{
	return seq_open_private(file, &monitor_times_seq_ops,
				sizeof(struct monitor_entry));
}

static ssize_t monitor_clear(struct file *file, const char __user *buf,
			     size_t len, loff_t *ppos)
{
	struct mcp2510_sim *sim = file_inode(file)->i_private;

	mcp2510_sim_lock(sim);
	sim->monitor.cleared = sim->monitor.written;
	mcp2510_sim_unlock(sim);
	return len;
}

const struct file_operations mcp2510_sim_monitor_fops = {
	.owner = THIS_MODULE,
	.open = monitor_open,
	.read = seq_read,
	.write = monitor_clear,
	.llseek = seq_lseek,
	.release = seq_release_private,
};

const struct file_operations mcp2510_sim_monitor_times_fops = {
	.owner = THIS_MODULE,
	.open = monitor_times_open,
	.read = seq_read,
	.llseek = seq_lseek,
	.release = seq_release_private,
};
