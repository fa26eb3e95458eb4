// SPDX-License-Identifier: GPL-2.0
/*
 * The per-chip half of the control surface, /sys/kernel/debug/mcp2510-sim/
 * chipN/: counters, state and registers to read, and the chip's faults.
 * docs/simulator.md describes every file.
 */
#include <linux/debugfs.h>
#include <linux/irq.h>
#include <linux/math64.h>
#include <linux/seq_file.h>
#include <linux/spi/spi.h>
#include <linux/stddef.h>

#include "kmod.h"

#define MODEL_COUNTER(field) { #field, offsetof(struct sim_counters, field) }

static const struct {
	const char *name;
	size_t offset;
} model_counters[] = {
	MODEL_COUNTER(spi_transfers),
	MODEL_COUNTER(spi_bytes),
	MODEL_COUNTER(spi_ignored),
	MODEL_COUNTER(frames_tx),
	MODEL_COUNTER(frames_rx),
	MODEL_COUNTER(interrupts),
	MODEL_COUNTER(overflows),
	MODEL_COUNTER(tx_errors),
	MODEL_COUNTER(rx_errors),
	MODEL_COUNTER(arbitration_lost),
	MODEL_COUNTER(bus_off),
	MODEL_COUNTER(spi_busy_ns),
};

static u64 counter_at(const struct sim_counters *c, size_t offset)
{
	return *(const u64 *)((const u8 *)c + offset);
}

static unsigned int int_line(const struct mcp2510_sim_chip *chip)
{
	return mcp2510_sim_line(chip->sim, chip->index, SIM_PIN_INT);
}

/* One consistent snapshot, relative to the last reset. */
static int counters_show(struct seq_file *m, void *v)
{
	struct mcp2510_sim_chip *chip = m->private;
	struct mcp2510_sim_harness_counters harness;
	struct sim_counters now, base;
	struct mcp2510_sim_line line;
	u64 stalls;
	size_t i;

	mcp2510_sim_lock(chip->sim);
	now = *sim_chip_counters(&chip->model);
	base = chip->baseline;
	harness = chip->harness;
	stalls = mcp2510_sim_clock_stalls(chip->sim) - chip->stalls_baseline;
	mcp2510_sim_unlock(chip->sim);
	mcp2510_sim_irq_describe(chip->sim, int_line(chip), &line);

	for (i = 0; i < ARRAY_SIZE(model_counters); i++)
		seq_printf(m, "%s %llu\n", model_counters[i].name,
			   counter_at(&now, model_counters[i].offset) -
			   counter_at(&base, model_counters[i].offset));
	seq_printf(m, "spi_failed %llu\n", harness.spi_failed);
	seq_printf(m, "spi_mode_errors %llu\n", harness.spi_mode_errors);
	seq_printf(m, "spi_overspeed %llu\n", harness.spi_overspeed);
	seq_printf(m, "spi_late_ns %llu\n", harness.spi_late_ns);
	seq_printf(m, "spi_gap_frames %llu\n", harness.spi_gap_frames);
	seq_printf(m, "irqs_delivered %llu\n", line.delivered);
	seq_printf(m, "int_edges_missed %llu\n", line.edges_missed);
	seq_printf(m, "clock_stalls %llu\n", stalls);
	return 0;
}

static int counters_open(struct inode *inode, struct file *file)
{
	return single_open(file, counters_show, inode->i_private);
}

/* Any write starts the counters from zero again. */
static ssize_t counters_reset(struct file *file, const char __user *ubuf,
			      size_t len, loff_t *ppos)
{
	struct mcp2510_sim_chip *chip = file_inode(file)->i_private;

	mcp2510_sim_lock(chip->sim);
	chip->baseline = *sim_chip_counters(&chip->model);
	memset(&chip->harness, 0, sizeof(chip->harness));
	chip->stalls_baseline = mcp2510_sim_clock_stalls(chip->sim);
	mcp2510_sim_unlock(chip->sim);
	mcp2510_sim_irq_reset_counts(chip->sim, int_line(chip));
	return len;
}

static const struct file_operations counters_fops = {
	.owner = THIS_MODULE,
	.open = counters_open,
	.read = seq_read,
	.write = counters_reset,
	.llseek = seq_lseek,
	.release = single_release,
};

static const char *const opmode_names[] = {
	[MCP2510_MODE_NORMAL] = "normal",
	[MCP2510_MODE_SLEEP] = "sleep",
	[MCP2510_MODE_LOOPBACK] = "loopback",
	[MCP2510_MODE_LISTEN_ONLY] = "listen-only",
	[MCP2510_MODE_CONFIG] = "config",
};

struct chip_state {
	unsigned int opmode, tec, rec;
	bool ready, bus_off;
	u32 bitrate;
	bool pins[SIM_PIN_COUNT];
};

static void read_state(struct mcp2510_sim_chip *chip, struct chip_state *st)
{
	enum sim_pin pin;

	mcp2510_sim_lock(chip->sim);
	st->opmode = sim_chip_opmode(&chip->model);
	st->ready = sim_chip_ready(&chip->model);
	st->tec = sim_chip_tec(&chip->model);
	st->rec = sim_chip_rec(&chip->model);
	st->bus_off = sim_chip_bus_off(&chip->model);
	st->bitrate = sim_chip_bitrate(&chip->model);
	for (pin = 0; pin < SIM_PIN_COUNT; pin++)
		st->pins[pin] = sim_chip_pin(&chip->model, pin);
	mcp2510_sim_unlock(chip->sim);
}

static int state_show(struct seq_file *m, void *v)
{
	struct mcp2510_sim_chip *chip = m->private;
	struct mcp2510_sim_line line;
	struct chip_state st;

	read_state(chip, &st);
	mcp2510_sim_irq_describe(chip->sim, int_line(chip), &line);

	seq_printf(m, "opmode %s\n", st.opmode < ARRAY_SIZE(opmode_names) &&
		   opmode_names[st.opmode] ? opmode_names[st.opmode] : "unknown");
	seq_printf(m, "ready %d\npowered %d\n", st.ready, chip->powered);
	seq_printf(m, "tec %u\nrec %u\nbus_off %d\n", st.tec, st.rec, st.bus_off);
	seq_printf(m, "bitrate %u\n", st.bitrate);
	seq_printf(m, "int %d\nrx0bf %d\nrx1bf %d\n", st.pins[SIM_PIN_INT],
		   st.pins[SIM_PIN_RX0BF], st.pins[SIM_PIN_RX1BF]);
	seq_printf(m, "irq %d\nirq_type %s\nirq_masked %d\n",
		   chip->spi ? chip->spi->irq : 0,
		   mcp2510_sim_trigger_name(line.type), line.masked);
	if (chip->spi)
		seq_printf(m, "spi_device %s\nspi_bus %d\nspi_cs %u\n",
			   dev_name(&chip->spi->dev), chip->spi->controller->bus_num,
			   spi_get_chipselect(chip->spi, 0));
	return 0;
}

static int state_open(struct inode *inode, struct file *file)
{
	return single_open(file, state_show, inode->i_private);
}

static const struct file_operations state_fops = {
	.owner = THIS_MODULE,
	.open = state_open,
	.read = seq_read,
	.llseek = seq_lseek,
	.release = single_release,
};

/* The register file as "addr: 16 bytes" rows, read without side effects. */
static int regs_show(struct seq_file *m, void *v)
{
	struct mcp2510_sim_chip *chip = m->private;
	u8 regs[MCP2510_REG_COUNT];
	unsigned int addr;

	mcp2510_sim_lock(chip->sim);
	for (addr = 0; addr < MCP2510_REG_COUNT; addr++)
		regs[addr] = sim_chip_peek(&chip->model, addr);
	mcp2510_sim_unlock(chip->sim);

	for (addr = 0; addr < MCP2510_REG_COUNT; addr += 16)
		seq_printf(m, "%02x: %16ph\n", addr, &regs[addr]);
	return 0;
}

static int regs_open(struct inode *inode, struct file *file)
{
	return single_open(file, regs_show, inode->i_private);
}

static const struct file_operations regs_fops = {
	.owner = THIS_MODULE,
	.open = regs_open,
	.read = seq_read,
	.llseek = seq_lseek,
	.release = single_release,
};

int mcp2510_sim_chip_u32_get(struct mcp2510_sim_chip *chip, const u32 *field,
			     u64 *val)
{
	mcp2510_sim_lock(chip->sim);
	*val = *field;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

int mcp2510_sim_chip_u32_set(struct mcp2510_sim_chip *chip, u32 *field,
			     u64 val)
{
	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	*field = val;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

MCP2510_SIM_CHIP_U32_ATTR(spi_errors, spi);

static int spi_corrupt_get(void *data, u64 *val)
{
	struct mcp2510_sim_chip *chip = data;

	mcp2510_sim_lock(chip->sim);
	*val = sim_chip_faults(&chip->model)->spi_corrupt;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

static int spi_corrupt_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;

	/* U32_MAX (SIM_CORRUPT_FOREVER) keeps the garbage until 0 is written */
	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	sim_chip_faults(&chip->model)->spi_corrupt = val;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(spi_corrupt_fops, spi_corrupt_get, spi_corrupt_set,
			 "%llu\n");

static int power_get(void *data, u64 *val)
{
	struct mcp2510_sim_chip *chip = data;

	*val = READ_ONCE(chip->powered);
	return 0;
}

static int power_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;

	if (val > 1)
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	sim_chip_power(&chip->model, val);
	WRITE_ONCE(chip->powered, val);
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(power_fops, power_get, power_set, "%llu\n");

static int wake_delay_us_get(void *data, u64 *val)
{
	struct mcp2510_sim_chip *chip = data;

	mcp2510_sim_lock(chip->sim);
	*val = div_u64(sim_chip_faults(&chip->model)->wake_delay_ns, NSEC_PER_USEC);
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

static int wake_delay_us_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;

	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	sim_chip_faults(&chip->model)->wake_delay_ns = val * NSEC_PER_USEC;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(wake_delay_us_fops, wake_delay_us_get,
			 wake_delay_us_set, "%llu\n");

static int mode_delay_us_get(void *data, u64 *val)
{
	struct mcp2510_sim_chip *chip = data;

	mcp2510_sim_lock(chip->sim);
	*val = div_u64(sim_chip_faults(&chip->model)->mode_delay_ns, NSEC_PER_USEC);
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

static int mode_delay_us_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;

	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	sim_chip_faults(&chip->model)->mode_delay_ns = val * NSEC_PER_USEC;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(mode_delay_us_fops, mode_delay_us_get,
			 mode_delay_us_set, "%llu\n");

static int int_edge_miss_get(void *data, u64 *val)
{
	struct mcp2510_sim_chip *chip = data;
	struct mcp2510_sim_line line;

	mcp2510_sim_irq_describe(chip->sim, int_line(chip), &line);
	*val = line.edge_miss;
	return 0;
}

static int int_edge_miss_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;

	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_irq_miss_edges(chip->sim, int_line(chip), val);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(int_edge_miss_fops, int_edge_miss_get,
			 int_edge_miss_set, "%llu\n");

/* TXnRTS input levels as bits 0-2 (1: high, the pull-ups' idle level). */
static int rts_get(void *data, u64 *val)
{
	struct mcp2510_sim_chip *chip = data;

	mcp2510_sim_lock(chip->sim);
	*val = chip->rts;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

static int rts_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;
	unsigned int n;

	if (val >= BIT(MCP2510_TXB_COUNT))
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	chip->rts = val;
	for (n = 0; n < MCP2510_TXB_COUNT; n++)
		sim_chip_set_rts(&chip->model, n, val & BIT(n));
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(rts_fops, rts_get, rts_set, "%llu\n");

void mcp2510_sim_debugfs_chip_create(struct mcp2510_sim_chip *chip,
				     struct dentry *parent)
{
	struct dentry *dir;
	char name[8];

	snprintf(name, sizeof(name), "chip%u", chip->index);
	dir = debugfs_create_dir(name, parent);
	debugfs_create_file("counters", 0600, dir, chip, &counters_fops);
	debugfs_create_file("state", 0400, dir, chip, &state_fops);
	debugfs_create_file("regs", 0400, dir, chip, &regs_fops);
	debugfs_create_file_unsafe("spi_errors", 0600, dir, chip, &spi_errors_fops);
	debugfs_create_file_unsafe("spi_corrupt", 0600, dir, chip, &spi_corrupt_fops);
	debugfs_create_file_unsafe("power", 0600, dir, chip, &power_fops);
	debugfs_create_file_unsafe("wake_delay_us", 0600, dir, chip,
				   &wake_delay_us_fops);
	debugfs_create_file_unsafe("mode_delay_us", 0600, dir, chip,
				   &mode_delay_us_fops);
	debugfs_create_file_unsafe("int_edge_miss", 0600, dir, chip,
				   &int_edge_miss_fops);
	debugfs_create_file_unsafe("rts", 0600, dir, chip, &rts_fops);
	mcp2510_sim_debugfs_hostile_create(chip, dir);
	mcp2510_sim_debugfs_osc_create(chip, dir);
}
