/* SPDX-License-Identifier: GPL-2.0 */
/*
 * mcp2510-sim: the chip and bus model of tests/sim behind a virtual SPI
 * controller, with each chip's output pins as interrupt-capable GPIO lines,
 * so that a real SPI CAN driver probes, takes interrupts and moves frames
 * exactly as it would on a board.  Test equipment only: nothing here is part
 * of the driver.
 *
 * Locking: sim->lock (taken with bottom halves off, because the bus timer
 * runs in softirq context) guards the model, the monitor ring and the fault
 * counters.  sim->irq_lock is a raw spinlock because the irq_chip callbacks
 * run under the irq descriptor's raw lock; it nests inside sim->lock when
 * the model reports a pin change.
 */
#ifndef MCP2510_SIM_KMOD_H
#define MCP2510_SIM_KMOD_H

#include <linux/clk-provider.h>
#include <linux/gpio/driver.h>
#include <linux/hrtimer.h>
#include <linux/irq_work.h>
#include <linux/pm.h>
#include <linux/property.h>
#include <linux/spinlock.h>

#include "../sim/mcp2510_sim.h"
#include "kmod_compat.h"
#include "kmod_logic.h"

#define MCP2510_SIM_NAME		"mcp2510-sim"
#define MCP2510_SIM_LINES		(SIM_MAX_NODES * SIM_PIN_COUNT)
/* Largest chip-select-low period; spidev's default buffer is as large. */
#define MCP2510_SIM_SPI_BUF_LEN		4096
#define MCP2510_SIM_MONITOR_LEN		256
#define MCP2510_SIM_LINE_NAME_LEN	12

/* What this module counts per chip on top of the model's counters. */
struct mcp2510_sim_harness_counters {
	u64 spi_failed;		/* messages failed by the spi_errors fault */
	u64 spi_mode_errors;	/* messages in SPI mode 1 or 2 (the chip does 0 and 3) */
	u64 spi_overspeed;	/* transfers faster than the chip's SCK limit */
	u64 spi_late_ns;	/* SPI time on: bus time CS rose later than modelled */
	u64 spi_gap_frames;	/* frames stored between two periods of one message */
};

struct mcp2510_sim_chip {
	struct mcp2510_sim *sim;
	unsigned int index;
	struct sim_chip model;
	struct sim_counters baseline;	/* model counters at the last reset */
	struct mcp2510_sim_harness_counters harness;
	u64 stalls_baseline;		/* the bus clock's stalls at the last reset */
	/* faults to come, set through debugfs */
	struct {
		u32 spi;		/* "spi_errors": messages to fail */
		u32 rts;		/* "spi_errors_rts" */
		u32 osc;		/* "osc_errors": prepares to fail */
	} fails;
	struct clk_hw osc;		/* with osc_clk: the oscillator (kmod_osc.c) */
	struct clk_lookup *osc_lookup;
	char osc_name[24];
	bool powered;			/* as last set through debugfs "power" */
	u8 rts;				/* TXnRTS levels as set through debugfs "rts" */
	struct software_node swnode;
	char swnode_name[24];
	struct spi_device *spi;
};

struct mcp2510_sim_monitor {
	struct sim_bus_record ring[MCP2510_SIM_MONITOR_LEN];
	/* per record, CLOCK_REALTIME ns: end_ns on the bus; when modelled */
	u64 end_real_ns[MCP2510_SIM_MONITOR_LEN];
	u64 seen_real_ns[MCP2510_SIM_MONITOR_LEN];
	u64 written;		/* records ever written */
	u64 cleared;		/* records before this are not shown */
};

struct mcp2510_sim {
	spinlock_t lock;		/* see the top of this file */
	struct sim_bus bus;
	struct mcp2510_sim_chip chips[SIM_MAX_NODES];
	unsigned int nchips;
	struct mcp2510_sim_monitor monitor;

	/* bus time from ktime_get_ns(): see kmod_logic.h */
	struct mcp2510_sim_clock clock;
	struct hrtimer timer;
	/* what SPI messages and interrupt delivery cost (kmod_spi.c) */
	struct sim_spi_bus spi;
	/* the board profile spi last took, at spi_cost_scale_pct, and spi_seed */
	unsigned int spi_profile;
	u32 spi_scale_pct;
	u32 spi_seed;
	bool stopping;

	raw_spinlock_t irq_lock;
	struct mcp2510_sim_line lines[MCP2510_SIM_LINES];
	struct irq_work irq_work;
	/*
	 * The interrupt latency's distribution (SPI time off: none), its
	 * draws' generator and time_scale, for deliveries under irq_lock.
	 */
	struct sim_spi_timing irq_timing;
	u32 irq_rng;
	u32 irq_time_scale;
	struct hrtimer irq_timer;	/* delayed deliveries; under irq_lock */
	struct gpio_chip gpio;
	char line_names[MCP2510_SIM_LINES][MCP2510_SIM_LINE_NAME_LEN];
	const char *line_name_ptrs[MCP2510_SIM_LINES];

	struct device *root;
	/* the tree's description of the controllers, or NULL: see kmod_of.c */
	struct device_node *of_spi;
	struct device_node *of_gpio;
	struct spi_controller *ctlr;
	const char *chip_name;		/* the SPI modalias: "mcp2510", "mcp2515" */
	u32 sck_max_hz;			/* the chip's SPI clock limit */
	u32 osc_hz;
	unsigned int int_trigger;	/* IRQ_TYPE_* the chips' INT lines get */
	bool gpio_controller;		/* the chips offer their pins as GPIOs */
	bool osc_clk;			/* the oscillators are clocks (kmod_osc.c) */
	bool wakeup_source;		/* the chips' INT may wake the system */
	bool wakeup_filter;		/* and their CNF3.WAKFIL is asked for */
	struct property_entry props[5];	/* the chips' software node, terminated */
	u8 spi_tx[MCP2510_SIM_SPI_BUF_LEN];
	u8 spi_rx[MCP2510_SIM_SPI_BUF_LEN];

	struct dentry *debugfs;
	/* debugfs "inject_later": a phantom frame on a kernel timer */
	struct hrtimer inject_timer;
	struct can_frame inject_frame;	/* under lock */
	u32 inject_bitrate;		/* under lock */
	int inject_result;		/* under lock: sim_phantom_send()'s */
	u8 inject_phase;		/* under lock: MCP2510_SIM_INJECT_* */
	u32 inject_ms;			/* under lock */
	struct dev_pm_domain pm_domain;	/* the root device's suspend */
};

/* When debugfs inject_later starts its timer. */
enum {
	MCP2510_SIM_INJECT_NOW,		/* at the write */
	MCP2510_SIM_INJECT_DEVICES,	/* in the system suspend's devices phase */
	MCP2510_SIM_INJECT_NOIRQ,	/* in its noirq phase */
};

/* kmod_clock.c */
#define MCP2510_SIM_MAX_TIME_SCALE	1000000
void mcp2510_sim_clock_init(struct mcp2510_sim *sim, u32 time_scale);
void mcp2510_sim_clock_rescale(struct mcp2510_sim *sim, u32 time_scale);
void mcp2510_sim_clock_stop(struct mcp2510_sim *sim);
void mcp2510_sim_clock_sleep_until(struct mcp2510_sim *sim, u64 model_ns);
u64 mcp2510_sim_clock_stalls(struct mcp2510_sim *sim);
void mcp2510_sim_lock(struct mcp2510_sim *sim) __acquires(&sim->lock);
void mcp2510_sim_unlock(struct mcp2510_sim *sim) __releases(&sim->lock);

/* kmod_irq.c */
void mcp2510_sim_irq_init(struct mcp2510_sim *sim);
void mcp2510_sim_irq_set_delay(struct mcp2510_sim *sim);
int mcp2510_sim_irq_register(struct mcp2510_sim *sim);
void mcp2510_sim_irq_unregister(struct mcp2510_sim *sim);
void mcp2510_sim_irq_attach(struct mcp2510_sim_chip *chip);
int mcp2510_sim_irq_of(struct mcp2510_sim *sim, unsigned int line);
unsigned int mcp2510_sim_line(const struct mcp2510_sim *sim, unsigned int chip,
			      enum sim_pin pin);
void mcp2510_sim_irq_miss_edges(struct mcp2510_sim *sim, unsigned int line,
				u32 count);
void mcp2510_sim_irq_reset_counts(struct mcp2510_sim *sim, unsigned int line);
void mcp2510_sim_irq_describe(struct mcp2510_sim *sim, unsigned int line,
			      struct mcp2510_sim_line *out);
const char *mcp2510_sim_trigger_name(unsigned int type);
int mcp2510_sim_trigger_parse(const char *name, unsigned int *type);

/* kmod_of.c */
int mcp2510_sim_of_find(struct mcp2510_sim *sim);
void mcp2510_sim_of_put(struct mcp2510_sim *sim);

/* kmod_spi.c */
int mcp2510_sim_spi_register(struct mcp2510_sim *sim, const char *driver,
			     int spidev_node);
void mcp2510_sim_spi_unregister(struct mcp2510_sim *sim);

/* kmod_spi_devices.c */
int mcp2510_sim_spi_add_devices(struct mcp2510_sim *sim, const char *driver,
				int spidev_node);

/* kmod_monitor.c */
void mcp2510_sim_monitor_attach(struct mcp2510_sim *sim);
extern const struct file_operations mcp2510_sim_monitor_fops;
extern const struct file_operations mcp2510_sim_monitor_times_fops;

/* kmod_frame_text.c */
int mcp2510_sim_frame_parse(const char *text, struct can_frame *cf);
int mcp2510_sim_frame_format(char *buf, size_t size, const struct can_frame *cf);

/* kmod_debugfs_bus.c, kmod_debugfs_chip.c, kmod_debugfs_hostile.c */
void mcp2510_sim_debugfs_create(struct mcp2510_sim *sim);
void mcp2510_sim_debugfs_remove(struct mcp2510_sim *sim);
/* kmod_debugfs_spi.c: SPI time, board profiles and their scale */
void mcp2510_sim_debugfs_spi_create(struct mcp2510_sim *sim,
				    struct dentry *dir);
void mcp2510_sim_suspend_attach(struct mcp2510_sim *sim);
void mcp2510_sim_suspend_detach(struct mcp2510_sim *sim);
void mcp2510_sim_debugfs_chip_create(struct mcp2510_sim_chip *chip,
				     struct dentry *parent);
/* debugfs files for a u32 of a chip, read and written under the lock */
int mcp2510_sim_chip_u32_get(struct mcp2510_sim_chip *chip, const u32 *field,
			     u64 *val);
int mcp2510_sim_chip_u32_set(struct mcp2510_sim_chip *chip, u32 *field,
			     u64 val);
#define MCP2510_SIM_CHIP_U32_ATTR(name, member)				\
static u32 *name##_field(struct mcp2510_sim_chip *chip)			\
{									\
	return &chip->fails.member;					\
}									\
									\
static int name##_get(void *data, u64 *val)				\
{									\
	return mcp2510_sim_chip_u32_get(data, name##_field(data), val);	\
}									\
									\
static int name##_set(void *data, u64 val)				\
{									\
	return mcp2510_sim_chip_u32_set(data, name##_field(data), val);	\
}									\
									\
DEFINE_DEBUGFS_ATTRIBUTE(name##_fops, name##_get, name##_set, "%llu\n")

int mcp2510_sim_osc_add(struct mcp2510_sim_chip *chip);
void mcp2510_sim_osc_remove(struct mcp2510_sim_chip *chip);
void mcp2510_sim_debugfs_osc_create(struct mcp2510_sim_chip *chip,
				    struct dentry *dir);
void mcp2510_sim_debugfs_hostile_create(struct mcp2510_sim_chip *chip,
					struct dentry *dir);

#endif /* MCP2510_SIM_KMOD_H */
