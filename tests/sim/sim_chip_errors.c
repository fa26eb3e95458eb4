// SPDX-License-Identifier: GPL-2.0
/*
 * One chip's fault confinement: the transmit and receive error counters,
 * EFLG and ERRIF following them, error-active / error-passive / bus-off,
 * and bus-off recovery after 128 occurrences of 11 recessive bits.
 *
 * References: CAN 2.0B part B section 8 (fault confinement rules 1-12);
 * DS21291 section 6 (error detection, register 6-1 EFLG); DS21801
 * section 6 (6.6 error states, register 6-3 EFLG) and 7.6 (ERRIF).
 */
#include "sim_private.h"

#define SIM_EFLG_STATE		(MCP2510_EFLG_TXBO | MCP2510_EFLG_TXEP | \
				 MCP2510_EFLG_RXEP | MCP2510_EFLG_TXWAR | \
				 MCP2510_EFLG_RXWAR | MCP2510_EFLG_EWARN)

/* ---- Error state ---------------------------------------------------------- */

bool sim_chip_error_active(const struct sim_chip *chip)
{
	return chip->tec < SIM_PASSIVE_LIMIT && chip->rec < SIM_PASSIVE_LIMIT;
}

/*
 * EFLG follows the counters; ERRIF rises when an EFLG bit becomes set,
 * and with faults.errif_on_decrease also when a state bit clears (the
 * data sheets leave that open: DS21801 7.6 lists the conditions as
 * limits reached, not left).
 */
void sim_chip_update_eflg(struct sim_chip *chip)
{
	u8 *eflg = sim_reg(chip, MCP2510_REG_EFLG);
	u8 old = *eflg, state = 0;

	if (chip->tec >= SIM_WARNING_LIMIT)
		state |= MCP2510_EFLG_TXWAR;
	if (chip->rec >= SIM_WARNING_LIMIT)
		state |= MCP2510_EFLG_RXWAR;
	if (state)
		state |= MCP2510_EFLG_EWARN;
	if (chip->tec >= SIM_PASSIVE_LIMIT)
		state |= MCP2510_EFLG_TXEP;
	if (chip->rec >= SIM_PASSIVE_LIMIT)
		state |= MCP2510_EFLG_RXEP;
	if (chip->bus_off)
		state |= MCP2510_EFLG_TXBO;
	*eflg = (old & SIM_EFLG_OVR) | state;
	if ((*eflg & ~old) ||
	    (chip->faults.errif_on_decrease && (old & ~*eflg & SIM_EFLG_STATE)))
		*sim_reg(chip, MCP2510_REG_CANINTF) |= MCP2510_INT_ERR;
}

void sim_chip_clear_counters(struct sim_chip *chip)
{
	chip->tec = 0;
	chip->rec = 0;
	chip->bus_off = false;
	chip->recovery_count = 0;
	sim_chip_update_eflg(chip);
}

void sim_chip_tec_add(struct sim_chip *chip, unsigned int n)
{
	chip->tec += n;
	if (chip->tec >= SIM_BUS_OFF_LIMIT && !chip->bus_off) {
		chip->bus_off = true;
		chip->recovery_count = 0;
		chip->recovery_idle_since = sim_now(chip);
		chip->counters.bus_off++;
	}
}

/* ---- Bus-off recovery (CAN 2.0B: 128 x 11 recessive bits) ------------------ */

u64 sim_chip_recovery_at(const struct sim_chip *chip)
{
	u64 seq_ns = (u64)SIM_RECOVERY_BITS * sim_chip_bit_ns(chip);

	return chip->recovery_idle_since +
	       (u64)(SIM_RECOVERY_SEQUENCES - chip->recovery_count) * seq_ns;
}

void sim_chip_recover(struct sim_chip *chip)
{
	sim_chip_clear_counters(chip);
	sim_chip_update_pins(chip);
}

/* The bus was idle from recovery_idle_since to until. */
void sim_chip_recovery_account(struct sim_chip *chip, u64 until)
{
	u32 seq_ns = SIM_RECOVERY_BITS * sim_chip_bit_ns(chip);

	if (!chip->bus_off || until <= chip->recovery_idle_since)
		return;
	chip->recovery_count += sim_div_u64(until - chip->recovery_idle_since,
					    seq_ns);
	chip->recovery_idle_since = until;
}

/* A frame ended: its tail (ACK delimiter, EOF, intermission) is 11 recessive bits. */
void sim_chip_recovery_frame(struct sim_chip *chip, u64 end)
{
	if (!chip->bus_off)
		return;
	chip->recovery_count++;
	chip->recovery_idle_since = end;
	if (chip->recovery_count >= SIM_RECOVERY_SEQUENCES)
		sim_chip_recover(chip);
}
