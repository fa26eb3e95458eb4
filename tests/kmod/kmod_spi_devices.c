// SPDX-License-Identifier: GPL-2.0
/*
 * One SPI device per simulated chip on the virtual controller, for a CAN
 * driver (or spidev) to bind to, with what a device tree would give a
 * real chip: its interrupt, oscillator frequency and properties.  Only
 * when the module is not given a device tree (kmod_of.c), which names
 * the devices itself.
 */
#include <linux/device.h>
#include <linux/irq.h>
#include <linux/property.h>
#include <linux/spi/spi.h>
#include <linux/string.h>

#include "kmod.h"

/*
 * Bind the device to exactly one driver: the chip names are in the id
 * tables of both this project's driver and mainline mcp251x, and spidev
 * matches no chip name at all.  Kernels from 6.12.y on keep the override
 * in struct device (Kbuild detects which).
 */
static int force_driver(struct spi_device *spi, const char *driver)
{
#ifdef MCP2510_SIM_OVERRIDE_IN_DEVICE
	return device_set_driver_override(&spi->dev, driver);
#else
	return driver_set_override(&spi->dev, &spi->driver_override, driver,
				   strlen(driver));
#endif
}

/*
 * Since 6.12 a device may use several chip selects (SPI_CS_CNT_MAX); the
 * unused entries must hold the core's "no chip select" value 0xff, which
 * spi_new_device() sets but spi_alloc_device() does not, or the core takes
 * them for a second use of chip select 0.
 */
static void set_chip_select(struct spi_device *spi, u8 cs)
{
#ifdef SPI_CS_CNT_MAX
	u8 idx;

	for (idx = 1; idx < SPI_CS_CNT_MAX; idx++)
		spi_set_chipselect(spi, idx, 0xff);
	spi->cs_index_mask = BIT(0);
#endif
	spi_set_chipselect(spi, 0, cs);
}

static int add_chip_device(struct mcp2510_sim_chip *chip, const char *driver)
{
	struct mcp2510_sim *sim = chip->sim;
	struct spi_device *spi;
	int irq, ret;

	irq = mcp2510_sim_irq_of(sim,
				 mcp2510_sim_line(sim, chip->index, SIM_PIN_INT));
	if (irq < 0)
		return irq;
	/* as a firmware's interrupt specifier would, before any driver looks */
	ret = irq_set_irq_type(irq, sim->int_trigger);
	if (ret)
		return ret;

	spi = spi_alloc_device(sim->ctlr);
	if (!spi)
		return -ENOMEM;
	set_chip_select(spi, chip->index);
	spi->max_speed_hz = sim->sck_max_hz;
	spi->mode = SPI_MODE_0;
	spi->irq = irq;
	strscpy(spi->modalias, sim->chip_name, sizeof(spi->modalias));

	ret = force_driver(spi, driver);
	if (ret)
		goto out_put;

	/*
	 * What a device tree gives a real chip: the oscillator frequency and,
	 * if asked for, gpio-controller.  The node's name is the device's name
	 * from 6.12 on ("spi-<node>").
	 */
	snprintf(chip->swnode_name, sizeof(chip->swnode_name), "%s-chip%u",
		 MCP2510_SIM_NAME, chip->index);
	chip->swnode.name = chip->swnode_name;
	chip->swnode.properties = sim->props;
	ret = device_add_software_node(&spi->dev, &chip->swnode);
	if (ret)
		goto out_put;

	ret = spi_add_device(spi);
	if (ret)
		goto out_remove_swnode;
	chip->spi = spi;
	return 0;

out_remove_swnode:
	device_remove_software_node(&spi->dev);
out_put:
	spi_dev_put(spi);
	return ret;
}

int mcp2510_sim_spi_add_devices(struct mcp2510_sim *sim, const char *driver,
				int spidev_node)
{
	unsigned int n, p = 0;
	int ret;

	sim->props[p++] = PROPERTY_ENTRY_U32("clock-frequency", sim->osc_hz);
	if (sim->gpio_controller)
		sim->props[p++] = PROPERTY_ENTRY_BOOL("gpio-controller");
	if (sim->wakeup_source)
		sim->props[p++] = PROPERTY_ENTRY_BOOL("wakeup-source");
	if (sim->wakeup_filter)
		sim->props[p++] = PROPERTY_ENTRY_BOOL("microchip,wakeup-filter");
	for (n = 0; n < sim->nchips; n++) {
		ret = add_chip_device(&sim->chips[n],
				      (int)n == spidev_node ? "spidev" : driver);
		if (ret) {
			dev_err(sim->root, "chip %u: no SPI device: %d\n", n, ret);
			return ret;
		}
		ret = sim->osc_clk ? mcp2510_sim_osc_add(&sim->chips[n]) : 0;
		if (ret) {
			dev_err(sim->root, "chip %u: no oscillator: %d\n", n, ret);
			return ret;
		}
	}
	return 0;
}
