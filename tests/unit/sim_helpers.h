/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Test helpers over the simulated chip: register access through real SPI
 * instruction sequences (one sim_chip_spi() call per chip-select period),
 * frame load/unload in the MCP2510 buffer layout, and node set-up.
 * Reusable by any suite that links tests/sim.
 */
#ifndef SIM_HELPERS_H
#define SIM_HELPERS_H

#include "mcp2510_sim.h"

/* AN739 example 2: 125 kbit/s from a 16 MHz oscillator, 8 TQ */
#define SIMH_OSC_16MHZ		16000000U
#define SIMH_CNF1_125K		0x07
#define SIMH_CNF2_125K		0x90
#define SIMH_CNF3_125K		0x02
/* same oscillator, BRP 3 (divide by 4): 250 kbit/s */
#define SIMH_CNF1_250K		0x03
/* BRP 0: 1 Mbit/s */
#define SIMH_CNF1_1M		0x00

u8 simh_read(struct sim_chip *chip, u8 addr);
void simh_read_seq(struct sim_chip *chip, u8 addr, u8 *out, size_t n);
void simh_write(struct sim_chip *chip, u8 addr, u8 val);
void simh_write_seq(struct sim_chip *chip, u8 addr, const u8 *data, size_t n);
void simh_bit_modify(struct sim_chip *chip, u8 addr, u8 mask, u8 val);
void simh_reset(struct sim_chip *chip);		/* RESET + wait 128 Tosc */
u8 simh_read_status(struct sim_chip *chip);
void simh_rts(struct sim_chip *chip, u8 buffers);

/* request a mode and wait (bus time) until CANSTAT.OPMOD shows it: 0 or -ETIMEDOUT */
int simh_set_mode(struct sim_chip *chip, unsigned int mode);
u8 simh_opmode(struct sim_chip *chip);		/* CANSTAT.OPMOD over SPI */

/* TXBn <- frame (WRITE), then RTS */
void simh_load_tx(struct sim_chip *chip, unsigned int n, const struct can_frame *cf);
void simh_send(struct sim_chip *chip, unsigned int n, const struct can_frame *cf);
/* RXBn -> frame (READ); clears RXnIF with BIT MODIFY when clear is set */
void simh_read_rx(struct sim_chip *chip, unsigned int n, struct can_frame *cf,
		  bool clear);

/* init + attach + start-up + reset + bit timing; stays in configuration mode */
void simh_node_setup(struct sim_bus *bus, struct sim_chip *chip,
		     enum sim_variant variant, u8 cnf1, u8 cnf2, u8 cnf3);
/* simh_node_setup() at AN739's 125 kbit/s (SIMH_CNF*_125K) */
void simh_node_setup_125k(struct sim_bus *bus, struct sim_chip *chip,
			  enum sim_variant variant);
/* ... and then normal mode: the usual two-line start of a test */
void simh_node_up(struct sim_bus *bus, struct sim_chip *chip,
		  enum sim_variant variant);

/* cmocka teardown of a fixture the setup made with test_calloc() */
int simh_teardown(void **state);

/* advance in steps until the bus is idle with nothing pending, at most max_ns */
void simh_run_idle(struct sim_bus *bus, u64 max_ns);

/* frames */
struct can_frame simh_frame(canid_t id, u8 len, const u8 *data);
bool simh_frame_equal(const struct can_frame *a, const struct can_frame *b);

/* bus monitor that keeps the last SIMH_LOG_MAX records */
#define SIMH_LOG_MAX	64
struct simh_log {
	unsigned int count;		/* all records seen */
	struct sim_bus_record rec[SIMH_LOG_MAX];
};
void simh_log_attach(struct sim_bus *bus, struct simh_log *log);
const struct sim_bus_record *simh_log_get(const struct simh_log *log,
					  unsigned int i);

#endif /* SIM_HELPERS_H */
