// SPDX-License-Identifier: GPL-2.0
/*
 * With the module parameter osc_clk, each chip's oscillator is a clock of
 * the common clock framework, found by the chip's driver as its device's
 * clock: a board's "clocks" property does the same.  Its rate is osc_hz.
 * Writing N to chipN/osc_errors makes the next N prepares fail with EIO,
 * as an oscillator that does not come back from a suspend would; the
 * framework's own debugfs (clk/mcp2510-sim-oscN/) counts prepares and
 * enables, so a scenario sees whether the driver has the clock on.
 */
#include <linux/clk-provider.h>
#include <linux/clkdev.h>
#include <linux/debugfs.h>
#include <linux/spi/spi.h>

#include "kmod.h"

static struct mcp2510_sim_chip *osc_chip(struct clk_hw *hw)
{
	return container_of(hw, struct mcp2510_sim_chip, osc);
}

static int osc_prepare(struct clk_hw *hw)
{
	struct mcp2510_sim_chip *chip = osc_chip(hw);
	int ret = 0;

	mcp2510_sim_lock(chip->sim);
	if (chip->fails.osc) {
		chip->fails.osc--;
		ret = -EIO;
	}
	mcp2510_sim_unlock(chip->sim);
	return ret;
}

static unsigned long osc_recalc_rate(struct clk_hw *hw,
				     unsigned long parent_rate)
{
	return osc_chip(hw)->sim->osc_hz;
}

static const struct clk_ops osc_ops = {
	.prepare = osc_prepare,
	.recalc_rate = osc_recalc_rate,
};

/* After the chip's SPI device was added: the lookup needs its name. */
int mcp2510_sim_osc_add(struct mcp2510_sim_chip *chip)
{
	struct clk_init_data init = { .ops = &osc_ops };
	int ret;

	snprintf(chip->osc_name, sizeof(chip->osc_name), "%s-osc%u",
		 MCP2510_SIM_NAME, chip->index);
	init.name = chip->osc_name;
	chip->osc.init = &init;
	ret = clk_hw_register(NULL, &chip->osc);
	if (ret)
		return ret;
	chip->osc_lookup = clkdev_hw_create(&chip->osc, NULL, "%s",
					    dev_name(&chip->spi->dev));
	if (!chip->osc_lookup) {
		clk_hw_unregister(&chip->osc);
		return -ENOMEM;
	}
	return 0;
}

/* After the chip's SPI device was removed, so its driver let go. */
void mcp2510_sim_osc_remove(struct mcp2510_sim_chip *chip)
{
	if (!chip->osc_lookup)
		return;
	clkdev_drop(chip->osc_lookup);
	clk_hw_unregister(&chip->osc);
	chip->osc_lookup = NULL;
}

MCP2510_SIM_CHIP_U32_ATTR(osc_errors, osc);

void mcp2510_sim_debugfs_osc_create(struct mcp2510_sim_chip *chip,
				    struct dentry *dir)
{
	if (chip->osc_lookup)
		debugfs_create_file_unsafe("osc_errors", 0600, dir, chip,
					   &osc_errors_fops);
}
