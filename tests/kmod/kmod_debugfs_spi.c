// SPDX-License-Identifier: GPL-2.0
/*
 * SPI time in /sys/kernel/debug/mcp2510-sim/: a board profile by name
 * (spi_profile), the scale of its costs (spi_cost_scale_pct), the seed of
 * the latency draws (spi_seed), the on/off switch (spi_time) and one file
 * per cost of struct sim_spi_timing to set or override single values.
 * docs/simulator.md describes every file, docs/performance.md the
 * profiles.  A change applies to the messages that start after it.
 */
#include <linux/debugfs.h>
#include <linux/fs.h>
#include <linux/kernel.h>
#include <linux/string.h>
#include <linux/uaccess.h>

#include "kmod.h"

#define PROFILE_NAME_LEN	16

/* Under the lock: the profile at the scale, and the interrupt path told. */
static int apply_profile(struct mcp2510_sim *sim, unsigned int profile,
			 u32 scale_pct)
{
	struct sim_spi_timing t;
	int ret;

	ret = sim_spi_profile_timing(profile, scale_pct, &t);
	if (ret)
		return ret;
	sim->spi.timing = t;
	sim->spi_profile = profile;
	sim->spi_scale_pct = scale_pct;
	mcp2510_sim_irq_set_delay(sim);
	return 0;
}

static ssize_t profile_read(struct file *file, char __user *ubuf, size_t len,
			    loff_t *ppos)
{
	struct mcp2510_sim *sim = file->private_data;
	char buf[PROFILE_NAME_LEN + 1];
	int n;

	mcp2510_sim_lock(sim);
	n = scnprintf(buf, sizeof(buf), "%s\n",
		      sim_spi_profile_name(sim->spi_profile));
	mcp2510_sim_unlock(sim);
	return simple_read_from_buffer(ubuf, len, ppos, buf, n);
}

static ssize_t profile_write(struct file *file, const char __user *ubuf,
			     size_t len, loff_t *ppos)
{
	struct mcp2510_sim *sim = file->private_data;
	char buf[PROFILE_NAME_LEN];
	int profile, ret;

	if (len >= sizeof(buf))
		return -EINVAL;
	if (copy_from_user(buf, ubuf, len))
		return -EFAULT;
	buf[len] = '\0';
	profile = sim_spi_profile_find(buf, strcspn(buf, "\n"));
	if (profile < 0)
		return profile;
	mcp2510_sim_lock(sim);
	ret = apply_profile(sim, profile, sim->spi_scale_pct);
	mcp2510_sim_unlock(sim);
	return ret ? ret : len;
}

static const struct file_operations profile_fops = {
	.owner = THIS_MODULE,
	.open = simple_open,
	.read = profile_read,
	.write = profile_write,
	.llseek = default_llseek,
};

static int scale_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = sim->spi_scale_pct;
	mcp2510_sim_unlock(sim);
	return 0;
}

/* A new scale takes the profile afresh: single overrides are dropped. */
static int scale_set(void *data, u64 val)
{
	struct mcp2510_sim *sim = data;
	int ret;

	if (val < SIM_SPI_SCALE_MIN_PCT || val > SIM_SPI_SCALE_MAX_PCT)
		return -EINVAL;
	mcp2510_sim_lock(sim);
	ret = apply_profile(sim, sim->spi_profile, val);
	mcp2510_sim_unlock(sim);
	return ret;
}

DEFINE_DEBUGFS_ATTRIBUTE(scale_fops, scale_get, scale_set, "%llu\n");

static int seed_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = sim->spi_seed;
	mcp2510_sim_unlock(sim);
	return 0;
}

static int seed_set(void *data, u64 val)
{
	struct mcp2510_sim *sim = data;

	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_lock(sim);
	sim->spi_seed = val;
	sim_spi_seed(&sim->spi, val);
	mcp2510_sim_irq_set_delay(sim);
	mcp2510_sim_unlock(sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(seed_fops, seed_get, seed_set, "%llu\n");

static int spi_time_get(struct mcp2510_sim *sim, u32 *field, u64 *val)
{
	mcp2510_sim_lock(sim);
	*val = *field;
	mcp2510_sim_unlock(sim);
	return 0;
}

static int spi_time_set(struct mcp2510_sim *sim, u32 *field, u64 val)
{
	if (val > U32_MAX)
		return -EINVAL;
	mcp2510_sim_lock(sim);
	*field = val;
	mcp2510_sim_irq_set_delay(sim);
	mcp2510_sim_unlock(sim);
	return 0;
}

#define SPI_TIME_ATTR(name, field)					\
static u32 *name##_field(struct mcp2510_sim *sim)			\
{									\
	return &sim->spi.timing.field;					\
}									\
									\
static int name##_get(void *data, u64 *val)				\
{									\
	return spi_time_get(data, name##_field(data), val);		\
}									\
									\
static int name##_set(void *data, u64 val)				\
{									\
	return spi_time_set(data, name##_field(data), val);		\
}									\
									\
DEFINE_DEBUGFS_ATTRIBUTE(name##_fops, name##_get, name##_set, "%llu\n")

static int spi_time_on_get(void *data, u64 *val)
{
	struct mcp2510_sim *sim = data;

	mcp2510_sim_lock(sim);
	*val = sim->spi.timing.enabled;
	mcp2510_sim_unlock(sim);
	return 0;
}

static int spi_time_on_set(void *data, u64 val)
{
	struct mcp2510_sim *sim = data;

	if (val > 1)
		return -EINVAL;
	mcp2510_sim_lock(sim);
	sim->spi.timing.enabled = val;
	mcp2510_sim_irq_set_delay(sim);
	mcp2510_sim_unlock(sim);
	return 0;
}

DEFINE_DEBUGFS_ATTRIBUTE(spi_time_fops, spi_time_on_get, spi_time_on_set,
			 "%llu\n");
SPI_TIME_ATTR(spi_msg_ns, msg_ns);
SPI_TIME_ATTR(spi_cs_setup_ns, cs_setup_ns);
SPI_TIME_ATTR(spi_cs_hold_ns, cs_hold_ns);
SPI_TIME_ATTR(spi_ctlr_max_hz, ctlr_max_hz);
SPI_TIME_ATTR(irq_latency_ns, irq_latency_ns);
SPI_TIME_ATTR(irq_latency_p99_ns, irq_latency_p99_ns);
SPI_TIME_ATTR(spi_wake_ns, wake_ns);
SPI_TIME_ATTR(spi_wake_p99_ns, wake_p99_ns);
SPI_TIME_ATTR(spi_xfer_ns, xfer_ns);
SPI_TIME_ATTR(spi_idle_clocks, idle_clocks);
SPI_TIME_ATTR(spi_poll_hz_per_byte, poll_hz_per_byte);
SPI_TIME_ATTR(spi_dma_min_len, dma_min_len);
SPI_TIME_ATTR(spi_dma_ns, dma_ns);

static const struct {
	const char *name;
	const struct file_operations *fops;
} spi_time_files[] = {
	{ "spi_time", &spi_time_fops },
	{ "spi_cost_scale_pct", &scale_fops },
	{ "spi_seed", &seed_fops },
	{ "spi_msg_ns", &spi_msg_ns_fops },
	{ "spi_cs_setup_ns", &spi_cs_setup_ns_fops },
	{ "spi_cs_hold_ns", &spi_cs_hold_ns_fops },
	{ "spi_ctlr_max_hz", &spi_ctlr_max_hz_fops },
	{ "irq_latency_ns", &irq_latency_ns_fops },
	{ "irq_latency_p99_ns", &irq_latency_p99_ns_fops },
	{ "spi_wake_ns", &spi_wake_ns_fops },
	{ "spi_wake_p99_ns", &spi_wake_p99_ns_fops },
	{ "spi_xfer_ns", &spi_xfer_ns_fops },
	{ "spi_idle_clocks", &spi_idle_clocks_fops },
	{ "spi_poll_hz_per_byte", &spi_poll_hz_per_byte_fops },
	{ "spi_dma_min_len", &spi_dma_min_len_fops },
	{ "spi_dma_ns", &spi_dma_ns_fops },
};

void mcp2510_sim_debugfs_spi_create(struct mcp2510_sim *sim,
				    struct dentry *dir)
{
	unsigned int n;

	sim->spi_scale_pct = 100;
	debugfs_create_file("spi_profile", 0600, dir, sim, &profile_fops);
	for (n = 0; n < ARRAY_SIZE(spi_time_files); n++)
		debugfs_create_file_unsafe(spi_time_files[n].name, 0600, dir,
					   sim, spi_time_files[n].fops);
}
