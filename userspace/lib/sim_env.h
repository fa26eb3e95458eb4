/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The simulated buses' settings from the environment (sim_env.c).
 */
#ifndef MCP2510_SIM_ENV_H
#define MCP2510_SIM_ENV_H

#include "mcp2510_sim.h"

/* MCP2510_SIM_SPI_TIME into *spi: 0, or -EINVAL for a malformed value. */
int sim_env_spi_time(struct sim_spi_bus *spi);
/* MCP2510_SIM_BUS_ERRORS into bus's faults: 0, or -EINVAL likewise. */
int sim_env_bus_errors(struct sim_bus *bus);

#endif /* MCP2510_SIM_ENV_H */
