/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Internals shared by the model's source files; not for harnesses.
 */
#ifndef MCP2510_SIM_PRIVATE_H
#define MCP2510_SIM_PRIVATE_H

#include "mcp2510_sim.h"

#define SIM_NS_PER_SEC		1000000000U
/* bit times of an error flag, its delimiter and the intermission */
#define SIM_ERROR_FRAME_BITS	(6 + 8 + 3)
/* bus-off recovery: 128 occurrences of 11 consecutive recessive bits */
#define SIM_RECOVERY_SEQUENCES	128
#define SIM_RECOVERY_BITS	11
/* error counter limits, CAN 2.0B fault confinement */
#define SIM_WARNING_LIMIT	96
#define SIM_PASSIVE_LIMIT	128
#define SIM_BUS_OFF_LIMIT	256
#define SIM_REC_AFTER_PASSIVE	119

/*
 * 64-by-32-bit division without the compiler's 64-bit division helpers,
 * which a 32-bit kernel does not link: plain shift and subtract, 64
 * rounds at most.
 */
static inline u64 sim_div_u64(u64 n, u32 d)
{
	u64 q = 0, r = 0;
	int i;

	if (!d)
		return U64_MAX;
	for (i = 63; i >= 0; i--) {
		r = (r << 1) | ((n >> i) & 1);
		if (r >= d) {
			r -= d;
			q |= 1ULL << i;
		}
	}
	return q;
}

static inline u64 sim_min_u64(u64 a, u64 b)
{
	return a < b ? a : b;
}

/* frame helpers (sim_frame.c) */
struct sim_frame_info {
	u32 bits;		/* error-free length incl. intermission */
	u32 stuffed_len;	/* SOF through CRC sequence, with stuff bits */
};
void sim_frame_measure(const struct can_frame *cf, struct sim_frame_info *info);
u32 sim_frame_arbitration_key(const struct can_frame *cf);
bool sim_timings_match(const struct sim_timing *a, const struct sim_timing *b);

/* between the chip's own files (sim_chip_*.c) */
#define SIM_ADDR_MASK		0x7f	/* the address pointer has 7 bits */
#define SIM_EFLG_OVR		(MCP2510_EFLG_RX1OVR | MCP2510_EFLG_RX0OVR)
/* registers (sim_chip_regs.c) */
void sim_chip_reset(struct sim_chip *chip, bool power_on);
u8 *sim_reg(struct sim_chip *chip, unsigned int addr);
bool sim_reg_bit_modifiable(unsigned int addr);
u8 sim_reg_read(const struct sim_chip *chip, unsigned int addr);
void sim_reg_write(struct sim_chip *chip, unsigned int addr, u8 val, u8 mask);
/* modes and pins (sim_chip_mode.c) */
void sim_chip_enter_mode(struct sim_chip *chip, unsigned int mode);
bool sim_chip_mode_held(const struct sim_chip *chip);
void sim_chip_mode_request(struct sim_chip *chip);
void sim_chip_mode_try(struct sim_chip *chip);
void sim_chip_update_pins(struct sim_chip *chip);
void sim_chip_wake(struct sim_chip *chip);
/* transmit (sim_chip_tx.c) */
void sim_chip_abort_all(struct sim_chip *chip);
void sim_chip_loopback_end(struct sim_chip *chip);
void sim_chip_loopback_start(struct sim_chip *chip, unsigned int buf);
int sim_chip_pick_buffer(const struct sim_chip *chip);
void sim_chip_request(struct sim_chip *chip, unsigned int n);
u8 *sim_txbctrl(struct sim_chip *chip, unsigned int n);
/* receive (sim_chip_rx.c) */
void sim_chip_accept(struct sim_chip *chip, const struct can_frame *cf);

/* The phantom node (sim_phantom.c), as the bus asks it. */
void sim_phantom_timing(u32 ns, struct sim_timing *t);
u32 sim_phantom_rx_ns(const struct sim_bus *bus);
bool sim_phantom_peek(const struct sim_bus *bus, struct can_frame *cf, u32 *ns);
void sim_phantom_sent(struct sim_bus *bus);
bool sim_rxb_full(const struct sim_chip *chip, unsigned int n);
/* fault confinement (sim_chip_errors.c) */
void sim_chip_clear_counters(struct sim_chip *chip);
void sim_chip_recover(struct sim_chip *chip);
u64 sim_chip_recovery_at(const struct sim_chip *chip);
void sim_chip_tec_add(struct sim_chip *chip, unsigned int n);
void sim_chip_update_eflg(struct sim_chip *chip);

/* chip side, called by the bus (sim_chip_*.c) */
u32 sim_chip_bit_ns(const struct sim_chip *chip);
void sim_chip_timing(const struct sim_chip *chip, struct sim_timing *t);
bool sim_chip_listening(const struct sim_chip *chip);
bool sim_chip_error_active(const struct sim_chip *chip);
int sim_chip_tx_candidate(const struct sim_chip *chip);
void sim_chip_tx_frame(const struct sim_chip *chip, unsigned int buf,
		       struct can_frame *cf);
void sim_chip_tx_start(struct sim_chip *chip, unsigned int buf);
bool sim_chip_sending(const struct sim_chip *chip);
void sim_chip_tx_lost(struct sim_chip *chip);
void sim_chip_tx_end(struct sim_chip *chip, bool ok, bool count_error);
void sim_chip_rx_ok(struct sim_chip *chip, const struct can_frame *cf);
void sim_chip_rx_error(struct sim_chip *chip, const struct can_frame *heard);
void sim_chip_bus_activity(struct sim_chip *chip);
u64 sim_chip_next_event(const struct sim_chip *chip);
void sim_chip_run_events(struct sim_chip *chip);
void sim_chip_recovery_account(struct sim_chip *chip, u64 until);
void sim_chip_recovery_frame(struct sim_chip *chip, u64 end);

/* bus side, called by the chip (sim_bus.c) */
u64 sim_now(const struct sim_chip *chip);
bool sim_bus_busy(const struct sim_bus *bus);

#endif /* MCP2510_SIM_PRIVATE_H */
