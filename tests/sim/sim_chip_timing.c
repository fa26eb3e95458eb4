// SPDX-License-Identifier: GPL-2.0
/*
 * One chip's sense of time: the oscillator start-up, bit timing from
 * CNF1..CNF3 and the rules it must obey, and the timed events the bus
 * runs (mode changes, wake-up, loopback frames, bus-off recovery).
 *
 * References: DS21291 section 5 (bit timing, 5.8 rules) and 8
 * (oscillator start-up timer); DS21801 section 5 (5.3 programming time
 * segments) and 8 (oscillator, 128 cycles start-up); AN739 "Rules for
 * setting the bit time".
 */
#include "sim_private.h"

u64 sim_now(const struct sim_chip *chip)
{
	return chip->bus ? chip->bus->now : 0;
}

/* 128 oscillator cycles, rounded up to whole nanoseconds */
u64 sim_chip_startup_ns(const struct sim_chip *chip)
{
	return sim_div_u64((u64)SIM_STARTUP_CYCLES * SIM_NS_PER_SEC +
			   chip->osc_hz - 1, chip->osc_hz);
}
/* ---- Bit timing ------------------------------------------------------------- */

/* IPT: the information processing time after the sample point, in quanta */
#define SIM_IPT_TQ	2

/*
 * DS21291 section 5: TQ = 2 (BRP + 1) / Fosc; a bit is SyncSeg (1 TQ) +
 * PropSeg + PS1 + PS2; with BTLMODE clear PS2 is the greater of PS1 and
 * the information processing time (2 TQ).
 *
 * The rules (DS21291 5.8, DS21801 5.3 "Programming Time Segments":
 * "Prop Seg + Phase Seg 1 >= Phase Seg 2", "Phase Seg 2 > Sync Jump
 * Width"; AN739 "Rules for setting the bit time": "PS2 >= IPT ... The
 * IPT = 2 TQ so PS2(min) = 2 TQ", and CNF3's PHSEG2 "from 2 - 8 TQ").
 * The data sheets' third rule, PropSeg + PS1 >= TDELAY, always holds on
 * the model's bus, which has no propagation delay.  SAM (three samples,
 * "should only be used at slower bus rates", AN739 CNF2) and the BRP are
 * not restricted by any rule the data sheets state.
 */
void sim_chip_timing(const struct sim_chip *chip, struct sim_timing *t)
{
	u8 cnf1 = chip->regs[MCP2510_REG_CNF1];
	u8 cnf2 = chip->regs[MCP2510_REG_CNF2];
	u8 cnf3 = chip->regs[MCP2510_REG_CNF3];
	u32 brp = FIELD_GET(MCP2510_CNF1_BRP_MASK, cnf1) + 1;
	u32 prseg = FIELD_GET(MCP2510_CNF2_PRSEG_MASK, cnf2) + 1;
	u32 ps1 = FIELD_GET(MCP2510_CNF2_PHSEG1_MASK, cnf2) + 1;
	u32 sjw = FIELD_GET(MCP2510_CNF1_SJW_MASK, cnf1) + 1;
	u32 ps2, cycles;

	if (cnf2 & MCP2510_CNF2_BTLMODE)
		ps2 = FIELD_GET(MCP2510_CNF3_PHSEG2_MASK, cnf3) + 1;
	else
		ps2 = ps1 > SIM_IPT_TQ ? ps1 : SIM_IPT_TQ;
	t->nbt = 1 + prseg + ps1 + ps2;
	t->ps1 = ps1;
	t->ps2 = ps2;
	t->sjw = sjw;
	t->valid = ps2 >= SIM_IPT_TQ && prseg + ps1 >= ps2 && ps2 > sjw;
	cycles = 2 * brp * t->nbt;
	t->ns = sim_div_u64((u64)cycles * SIM_NS_PER_SEC + chip->osc_hz / 2,
			    chip->osc_hz);
}

u32 sim_chip_bit_ns(const struct sim_chip *chip)
{
	struct sim_timing t;

	sim_chip_timing(chip, &t);
	return t.ns;
}

bool sim_chip_timing_valid(const struct sim_chip *chip)
{
	struct sim_timing t;

	sim_chip_timing(chip, &t);
	return t.valid;
}

u32 sim_chip_bitrate(const struct sim_chip *chip)
{
	struct sim_timing t;

	sim_chip_timing(chip, &t);
	if (!t.valid || !t.ns)
		return 0;
	return (SIM_NS_PER_SEC + t.ns / 2) / t.ns;
}

/* ---- Events ------------------------------------------------------------------- */

u64 sim_chip_next_event(const struct sim_chip *chip)
{
	u64 now = sim_now(chip), t = U64_MAX;

	if (!chip->powered)
		return t;
	if (now < chip->ready_at)
		return chip->ready_at;
	if (chip->mode_pending && !sim_chip_mode_held(chip))
		t = sim_min_u64(t, chip->mode_at);
	if (chip->wake_pending)
		t = sim_min_u64(t, chip->wake_at);
	if (chip->tx.active && chip->tx.loopback)
		t = sim_min_u64(t, chip->tx.end_at);
	else if (!chip->tx.active && chip->opmode == MCP2510_MODE_LOOPBACK &&
		 sim_chip_pick_buffer(chip) >= 0)
		t = now;
	if (chip->bus_off && chip->bus && !sim_bus_busy(chip->bus))
		t = sim_min_u64(t, sim_chip_recovery_at(chip));
	return t < now ? now : t;
}

void sim_chip_run_events(struct sim_chip *chip)
{
	u64 now = sim_now(chip);
	int buf;

	if (!sim_chip_ready(chip))
		return;
	if (chip->wake_pending && now >= chip->wake_at) {
		chip->wake_pending = false;
		chip->regs[MCP2510_REG_CANCTRL] &= ~MCP2510_CANCTRL_REQOP_MASK;
		chip->regs[MCP2510_REG_CANCTRL] |=
			FIELD_PREP(MCP2510_CANCTRL_REQOP_MASK, MCP2510_MODE_LISTEN_ONLY);
		sim_chip_enter_mode(chip, MCP2510_MODE_LISTEN_ONLY);
	}
	if (chip->tx.active && chip->tx.loopback && now >= chip->tx.end_at)
		sim_chip_loopback_end(chip);
	sim_chip_mode_try(chip);
	if (!chip->tx.active && chip->opmode == MCP2510_MODE_LOOPBACK) {
		buf = sim_chip_pick_buffer(chip);
		if (buf >= 0)
			sim_chip_loopback_start(chip, buf);
	}
	if (chip->bus_off && chip->bus && !sim_bus_busy(chip->bus) &&
	    now >= sim_chip_recovery_at(chip))
		sim_chip_recover(chip);
	sim_chip_update_pins(chip);
}
