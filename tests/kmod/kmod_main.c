// SPDX-License-Identifier: GPL-2.0
/*
 * mcp2510-sim: simulated MCP2510/MCP2515 chips on one CAN bus, reachable
 * through a virtual SPI controller, for testing SPI CAN drivers in a VM.
 * Module parameters are described in docs/simulator.md.
 */
#define pr_fmt(fmt) KBUILD_MODNAME ": " fmt

#include <linux/device.h>
#include <linux/err.h>
#include <linux/mm.h>
#include <linux/module.h>
#include <linux/moduleparam.h>
#include <linux/slab.h>
#include <linux/string.h>

#include "kmod.h"

static unsigned int nodes = 2;
module_param(nodes, uint, 0444);
MODULE_PARM_DESC(nodes, "simulated chips on the bus, 1..8 (default 2)");

static char *variant = "mcp2510";
module_param(variant, charp, 0444);
MODULE_PARM_DESC(variant, "chip: mcp2510, mcp2515 or mcp25625 (default mcp2510)");

static unsigned int osc_hz = 16000000;
module_param(osc_hz, uint, 0444);
MODULE_PARM_DESC(osc_hz, "oscillator frequency in Hz; the CAN clock is half (default 16000000)");

static char *driver = "mcp2510";
module_param(driver, charp, 0444);
MODULE_PARM_DESC(driver, "driver to bind: mcp2510 (this project) or mcp251x (mainline)");

static unsigned int time_scale = 1;
module_param(time_scale, uint, 0444);
MODULE_PARM_DESC(time_scale, "bus time runs this many times slower than real time (default 1)");

static int spidev_node = -1;
module_param(spidev_node, int, 0444);
MODULE_PARM_DESC(spidev_node, "chip to hand to spidev instead of the driver (default -1: none)");

static char *int_trigger = "level-low";
module_param(int_trigger, charp, 0444);
MODULE_PARM_DESC(int_trigger, "INT trigger type: level-low (default), level-high, edge-falling, edge-rising, edge-both");

static bool gpio_controller;
module_param(gpio_controller, bool, 0444);
MODULE_PARM_DESC(gpio_controller, "give the SPI devices gpio-controller (default no)");

static bool wakeup_source;
module_param(wakeup_source, bool, 0444);
MODULE_PARM_DESC(wakeup_source, "give the SPI devices wakeup-source (default no)");

static bool osc_clk;
module_param(osc_clk, bool, 0444);
MODULE_PARM_DESC(osc_clk, "give each chip its oscillator as a clock, which can fail (default no)");

static bool wakeup_filter;
module_param(wakeup_filter, bool, 0444);
MODULE_PARM_DESC(wakeup_filter, "give the SPI devices microchip,wakeup-filter (default no)");

static unsigned int seed = SIM_DEFAULT_SEED;
module_param(seed, uint, 0444);
MODULE_PARM_DESC(seed, "power-up garbage in the chips' buffers, filters and masks: chip n uses seed + n (default fixed)");

static unsigned int rx_corrupt_every;
module_param(rx_corrupt_every, uint, 0444);
MODULE_PARM_DESC(rx_corrupt_every, "a broken receive path for tests: flip a bit of every Nth received frame (default 0: never)");

struct chip_variant {
	const char *name;
	enum sim_variant model;
	u32 sck_max_hz;		/* DS21291 / DS21801: maximum SPI clock */
};

static const struct chip_variant chip_variants[] = {
	{ "mcp2510", SIM_MCP2510, 5000000 },
	{ "mcp2515", SIM_MCP2515, 10000000 },
	/* an MCP2515 with an integrated transceiver */
	{ "mcp25625", SIM_MCP2515, 10000000 },
};

/* spi_driver names, which driver_override matches */
static const char *const drivers[] = { "mcp2510", "mcp251x" };

static struct mcp2510_sim *the_sim;

static const struct chip_variant *find_variant(const char *name)
{
	size_t i;

	for (i = 0; i < ARRAY_SIZE(chip_variants); i++)
		if (!strcmp(chip_variants[i].name, name))
			return &chip_variants[i];
	return NULL;
}

static int check_params(void)
{
	unsigned int trigger;

	if (nodes < 1 || nodes > SIM_MAX_NODES) {
		pr_err("nodes=%u: need 1..%d\n", nodes, SIM_MAX_NODES);
		return -EINVAL;
	}
	if (!find_variant(variant)) {
		pr_err("variant=%s: unknown\n", variant);
		return -EINVAL;
	}
	if (match_string(drivers, ARRAY_SIZE(drivers), driver) < 0) {
		pr_err("driver=%s: need mcp2510 or mcp251x\n", driver);
		return -EINVAL;
	}
	if (time_scale < 1 || time_scale > MCP2510_SIM_MAX_TIME_SCALE) {
		pr_err("time_scale=%u: need 1..%d\n", time_scale,
		       MCP2510_SIM_MAX_TIME_SCALE);
		return -EINVAL;
	}
	if (mcp2510_sim_trigger_parse(int_trigger, &trigger)) {
		pr_err("int_trigger=%s: unknown\n", int_trigger);
		return -EINVAL;
	}
	if (spidev_node < -1 || spidev_node >= (int)nodes) {
		pr_err("spidev_node=%d: no such chip\n", spidev_node);
		return -EINVAL;
	}
	return 0;
}

/* The chips and the bus, powered and starting up at bus time zero. */
static int build_bus(struct mcp2510_sim *sim, const struct chip_variant *v)
{
	struct mcp2510_sim_chip *chip;
	unsigned int n;
	int ret;

	sim_bus_init(&sim->bus);
	sim->nchips = nodes;
	for (n = 0; n < nodes; n++) {
		chip = &sim->chips[n];
		chip->sim = sim;
		chip->index = n;
		chip->powered = true;
		chip->rts = BIT(MCP2510_TXB_COUNT) - 1;
		ret = sim_chip_init_seeded(&chip->model, v->model, osc_hz,
					   seed + n);
		if (ret) {
			pr_err("osc_hz=%u: rejected by the model\n", osc_hz);
			return ret;
		}
		sim_chip_faults(&chip->model)->rx_corrupt_every = rx_corrupt_every;
		ret = sim_bus_attach(&sim->bus, &chip->model);
		if (ret)
			return ret;
		mcp2510_sim_irq_attach(chip);
	}
	mcp2510_sim_monitor_attach(sim);
	return 0;
}

static struct mcp2510_sim *sim_create(void)
{
	const struct chip_variant *v = find_variant(variant);
	struct mcp2510_sim *sim;
	int ret;

	sim = kvzalloc(sizeof(*sim), GFP_KERNEL);
	if (!sim)
		return ERR_PTR(-ENOMEM);
	spin_lock_init(&sim->lock);
	mcp2510_sim_irq_init(sim);
	sim->chip_name = v->name;
	sim->sck_max_hz = v->sck_max_hz;
	sim->osc_hz = osc_hz;
	mcp2510_sim_trigger_parse(int_trigger, &sim->int_trigger);
	sim->gpio_controller = gpio_controller;
	sim->wakeup_source = wakeup_source;
	sim->wakeup_filter = wakeup_filter;
	sim->osc_clk = osc_clk;
	ret = mcp2510_sim_of_find(sim);
	if (ret)
		goto out_free;
	ret = build_bus(sim, v);
	if (ret)
		goto out_put_of;
	mcp2510_sim_clock_init(sim, time_scale);
	return sim;

out_put_of:
	mcp2510_sim_of_put(sim);
out_free:
	kvfree(sim);
	return ERR_PTR(ret);
}

static int __init mcp2510_sim_init(void)
{
	struct mcp2510_sim *sim;
	int ret;

	ret = check_params();
	if (ret)
		return ret;
	sim = sim_create();
	if (IS_ERR(sim))
		return PTR_ERR(sim);

	/* the controller and the GPIO chip need a parent; there is no platform */
	sim->root = root_device_register(MCP2510_SIM_NAME);
	if (IS_ERR(sim->root)) {
		ret = PTR_ERR(sim->root);
		goto out_free;
	}
	ret = mcp2510_sim_irq_register(sim);
	if (ret)
		goto out_unregister_root;

	/* start the clock: the chips' start-up ends on the bus timer */
	mcp2510_sim_lock(sim);
	mcp2510_sim_unlock(sim);

	ret = mcp2510_sim_spi_register(sim, driver, spidev_node);
	if (ret)
		goto out_stop;

	mcp2510_sim_debugfs_create(sim);
	mcp2510_sim_suspend_attach(sim);
	the_sim = sim;
	return 0;

out_stop:
	mcp2510_sim_clock_stop(sim);
	mcp2510_sim_irq_unregister(sim);
out_unregister_root:
	root_device_unregister(sim->root);
out_free:
	mcp2510_sim_of_put(sim);
	kvfree(sim);
	return ret;
}

static void __exit mcp2510_sim_exit(void)
{
	struct mcp2510_sim *sim = the_sim;

	mcp2510_sim_suspend_detach(sim);
	mcp2510_sim_debugfs_remove(sim);
	/* the drivers may still talk to their chips while they unbind */
	mcp2510_sim_spi_unregister(sim);
	mcp2510_sim_clock_stop(sim);
	mcp2510_sim_irq_unregister(sim);
	root_device_unregister(sim->root);
	mcp2510_sim_of_put(sim);
	kvfree(sim);
}

module_init(mcp2510_sim_init);
module_exit(mcp2510_sim_exit);

MODULE_DESCRIPTION("Simulated MCP2510/MCP2515 CAN controllers on a virtual SPI bus");
MODULE_LICENSE("GPL");
