/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Register-accurate model of the Microchip MCP2510 / MCP2515 CAN controller
 * and of the CAN bus that joins several of them.
 *
 * The model is plain C11 with no allocation and no libc beyond memcpy and
 * memset, so the same source runs under cmocka, behind the userspace
 * transport and inside the simulated-SPI kernel module.  Every object is
 * allocated by the caller; the struct members are private by convention
 * (read them only through the functions the headers below declare).
 *
 * tests/sim/README.md lists every choice the data sheets leave open and
 * what is not modelled.
 *
 * The API by concern: sim_chip.h (one chip), sim_bus.h (the bus joining
 * them), sim_phantom.h (a chipless node on the bus), sim_spi_time.h (what
 * SPI costs in time on a board).  Harnesses include this header.
 */
#ifndef MCP2510_SIM_H
#define MCP2510_SIM_H

#include "sim_chip.h"
#include "sim_bus.h"
#include "sim_phantom.h"
#include "sim_spi_time.h"

#endif /* MCP2510_SIM_H */
