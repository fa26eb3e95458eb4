// SPDX-License-Identifier: GPL-2.0
/*
 * Device-tree mode.  A tree with a node compatible with "mcp2510,sim" says
 * where the chips sit, the way a board's tree does for real ones:
 *
 *	mcp2510-sim {
 *		compatible = "mcp2510,sim";
 *		gpio_can: gpio {		(the chips' output pins)
 *			gpio-controller;
 *			#gpio-cells = <2>;
 *			interrupt-controller;
 *			#interrupt-cells = <2>;
 *		};
 *		spi_can: spi {			(chip select n leads to chip n)
 *			#address-cells = <1>;
 *			#size-cells = <0>;
 *			can@0 { compatible = "microchip,mcp2510"; reg = <0>; ... };
 *		};
 *	};
 *
 * The GPIO chip and the SPI controller then carry those nodes, and the SPI
 * core creates the chips' devices from the children of "spi", so drivers
 * bind by compatible and take their clock and interrupt from the tree.
 * The two are child nodes, not devices of their own, so that nothing but
 * this module provides them.
 */
#define pr_fmt(fmt) KBUILD_MODNAME ": " fmt

#include <linux/of.h>

#include "kmod.h"

int mcp2510_sim_of_find(struct mcp2510_sim *sim)
{
	struct device_node *np;
	int ret = 0;

	np = of_find_compatible_node(NULL, NULL, "mcp2510,sim");
	if (!np)
		return 0;
	sim->of_spi = of_get_child_by_name(np, "spi");
	sim->of_gpio = of_get_child_by_name(np, "gpio");
	if (!sim->of_spi || !sim->of_gpio) {
		pr_err("%pOF: needs a spi and a gpio child\n", np);
		mcp2510_sim_of_put(sim);
		ret = -EINVAL;
	}
	of_node_put(np);
	return ret;
}

void mcp2510_sim_of_put(struct mcp2510_sim *sim)
{
	of_node_put(sim->of_spi);
	of_node_put(sim->of_gpio);
	sim->of_spi = NULL;
	sim->of_gpio = NULL;
}
