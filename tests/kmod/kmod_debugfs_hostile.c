// SPDX-License-Identifier: GPL-2.0
/*
 * The hostile-chip faults of /sys/kernel/debug/mcp2510-sim/chipN/: an INT
 * line stuck low, garbage on MISO of a chosen kind, a pulse on the RESET
 * pin, and an RTS that reaches the chip although its transfer fails.
 * They exist to prove that a driver survives a broken board or a chip
 * that resets behind its back; docs/simulator.md describes them.
 */
#include <linux/debugfs.h>
#include <linux/fs.h>
#include <linux/kernel.h>
#include <linux/seq_file.h>
#include <linux/string.h>
#include <linux/uaccess.h>

#include "kmod.h"

/* "fixed 255", "flip 165", "random 12345": kind, then its byte or seed */
#define PATTERN_LEN	32

static int int_stuck_get(void *data, u64 *val)
{
	struct mcp2510_sim_chip *chip = data;

	mcp2510_sim_lock(chip->sim);
	*val = sim_chip_faults(&chip->model)->int_stuck;
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

static int int_stuck_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;

	if (val > 1)
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	sim_chip_faults(&chip->model)->int_stuck = val;
	sim_chip_refresh_pins(&chip->model);
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(int_stuck_fops, int_stuck_get, int_stuck_set,
			 "%llu\n");

/* Reads 0: a pulse has no state to show. */
static int reset_get(void *data, u64 *val)
{
	*val = 0;
	return 0;
}

static int reset_set(void *data, u64 val)
{
	struct mcp2510_sim_chip *chip = data;

	if (val != 1)
		return -EINVAL;
	mcp2510_sim_lock(chip->sim);
	sim_chip_reset_pin(&chip->model);
	mcp2510_sim_unlock(chip->sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(reset_fops, reset_get, reset_set, "%llu\n");

static int pattern_show(struct seq_file *m, void *v)
{
	struct mcp2510_sim_chip *chip = m->private;
	struct sim_chip_faults f;

	mcp2510_sim_lock(chip->sim);
	f = *sim_chip_faults(&chip->model);
	mcp2510_sim_unlock(chip->sim);

	switch (f.spi_corrupt_kind) {
	case SIM_CORRUPT_FIXED:
		seq_printf(m, "fixed %u\n", f.spi_corrupt_byte);
		break;
	case SIM_CORRUPT_RANDOM:
		seq_printf(m, "random %u\n", f.spi_corrupt_seed);
		break;
	default:
		seq_printf(m, "flip %u\n", f.spi_corrupt_xor);
		break;
	}
	return 0;
}

static int pattern_open(struct inode *inode, struct file *file)
{
	return single_open(file, pattern_show, inode->i_private);
}

/* One of "flip [BYTE]", "fixed BYTE", "random [SEED]"; 0 for the defaults. */
static int pattern_parse(const char *text, struct sim_chip_faults *f)
{
	unsigned int value = 0;
	char kind[8];
	int n;

	n = sscanf(text, "%7s %u", kind, &value);
	if (n < 1)
		return -EINVAL;
	if (!strcmp(kind, "random")) {
		f->spi_corrupt_kind = SIM_CORRUPT_RANDOM;
		f->spi_corrupt_seed = value;
		return 0;
	}
	if (value > U8_MAX)
		return -EINVAL;
	if (!strcmp(kind, "flip")) {
		f->spi_corrupt_kind = SIM_CORRUPT_FLIP;
		f->spi_corrupt_xor = value;
		return 0;
	}
	if (!strcmp(kind, "fixed") && n == 2) {
		f->spi_corrupt_kind = SIM_CORRUPT_FIXED;
		f->spi_corrupt_byte = value;
		return 0;
	}
	return -EINVAL;
}

static ssize_t pattern_write(struct file *file, const char __user *ubuf,
			     size_t len, loff_t *ppos)
{
	struct mcp2510_sim_chip *chip = file_inode(file)->i_private;
	struct sim_chip_faults f = { 0 };
	char text[PATTERN_LEN];
	int ret;

	if (len >= sizeof(text))
		return -EINVAL;
	if (copy_from_user(text, ubuf, len))
		return -EFAULT;
	text[len] = '\0';
	ret = pattern_parse(text, &f);
	if (ret)
		return ret;

	mcp2510_sim_lock(chip->sim);
	sim_chip_faults(&chip->model)->spi_corrupt_kind = f.spi_corrupt_kind;
	sim_chip_faults(&chip->model)->spi_corrupt_xor = f.spi_corrupt_xor;
	sim_chip_faults(&chip->model)->spi_corrupt_byte = f.spi_corrupt_byte;
	sim_chip_faults(&chip->model)->spi_corrupt_seed = f.spi_corrupt_seed;
	mcp2510_sim_unlock(chip->sim);
	return len;
}

static const struct file_operations pattern_fops = {
	.owner = THIS_MODULE,
	.open = pattern_open,
	.read = seq_read,
	.write = pattern_write,
	.llseek = seq_lseek,
	.release = single_release,
};

MCP2510_SIM_CHIP_U32_ATTR(spi_errors_rts, rts);

void mcp2510_sim_debugfs_hostile_create(struct mcp2510_sim_chip *chip,
					struct dentry *dir)
{
	debugfs_create_file_unsafe("int_stuck", 0600, dir, chip, &int_stuck_fops);
	debugfs_create_file_unsafe("reset", 0600, dir, chip, &reset_fops);
	debugfs_create_file("spi_corrupt_pattern", 0600, dir, chip,
			    &pattern_fops);
	debugfs_create_file_unsafe("spi_errors_rts", 0600, dir, chip,
				   &spi_errors_rts_fops);
}
