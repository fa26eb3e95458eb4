// SPDX-License-Identifier: GPL-2.0
/*
 * A virtual SPI controller whose chip selects lead to the simulated chips
 * (kmod_spi_devices.c adds one SPI device per chip).
 *
 * The chip acts on whole chip-select-low periods (an instruction is only
 * complete when CS rises), so the transfers of a message are gathered into
 * one buffer and handed to the model at once, split only where a transfer
 * asks for cs_change.  CS always rises at the end of a message
 * (kmod_logic.c decides, this file applies it to struct spi_message).
 *
 * With SPI time on (debugfs spi_profile, spi_time and friends,
 * docs/simulator.md) a message costs what the model's SPI time arithmetic
 * says: it waits for the bus, pays its host overhead, and each period
 * ends, and the chip acts, when CS rises at the modelled time; the
 * controller sleeps in real time, scaled by time_scale, until then.  Bus
 * time runs on between the periods of one message by the modelled gap
 * (CS high, CS set-up, the next transfers), so frames arrive between
 * chip-select periods when they would on a board.  Off, all periods of a
 * message happen at one bus instant (see run_message()).
 */
#include <linux/spi/spi.h>

#include "kmod.h"

static struct mcp2510_sim *ctlr_to_sim(struct spi_controller *ctlr)
{
	struct mcp2510_sim **slot = spi_controller_get_devdata(ctlr);

	return *slot;
}

static size_t period_limit(struct spi_device *spi)
{
	return MCP2510_SIM_SPI_BUF_LEN;
}

/*
 * Book-keeping before the chip sees a message; true when the spi_errors
 * fault claims it.  The chip samples on the rising edge with the clock
 * idling low or high (modes 0 and 3); other modes or a faster clock would
 * garble real traffic, which the model cannot imitate, so they are counted.
 */
static bool account_message(struct mcp2510_sim_chip *chip,
			    const struct spi_message *msg)
{
	u32 mode = msg->spi->mode & SPI_MODE_X_MASK;
	const struct spi_transfer *xfer;
	u64 overspeed = 0;
	bool fail;

	list_for_each_entry(xfer, &msg->transfers, transfer_list)
		if (xfer->speed_hz > chip->sim->sck_max_hz)
			overspeed++;

	mcp2510_sim_lock(chip->sim);
	if (mode == SPI_MODE_1 || mode == SPI_MODE_2)
		chip->harness.spi_mode_errors++;
	chip->harness.spi_overspeed += overspeed;
	fail = chip->fails.spi > 0;
	if (fail) {
		chip->fails.spi--;
		chip->harness.spi_failed++;
	}
	mcp2510_sim_unlock(chip->sim);
	return fail;
}

/* One message on its way through the controller. */
struct msg_run {
	struct mcp2510_sim_chip *chip;
	struct spi_message *msg;
	struct mcp2510_sim_period period;
	struct sim_spi_msg time;	/* its place on the SPI bus */
	bool begun;
	u64 frames_rx;		/* the chip's count when the last period ended */
};

/*
 * With SPI time on, the controller is busy until CS rises: sleep until
 * then and let the chip act at that bus time, even if bus time stalled
 * meanwhile.  A guest that oversleeps, or comes late, makes CS rise later
 * than modelled: spi_late_ns says by how much.  Called and returns with
 * the lock held.
 */
static void wait_cs_rise(struct mcp2510_sim_chip *chip, u64 cs_rise)
{
	struct mcp2510_sim *sim = chip->sim;
	u64 now = sim_bus_now(&sim->bus);

	if (cs_rise > now) {
		mcp2510_sim_unlock(sim);
		mcp2510_sim_clock_sleep_until(sim, cs_rise);
		mcp2510_sim_lock(sim);
		sim_bus_advance_to(&sim->bus, cs_rise);
		now = sim_bus_now(&sim->bus);
	}
	if (sim->spi.timing.enabled)
		chip->harness.spi_late_ns += now - cs_rise;
}

/*
 * Run the gathered bytes of transfers @first..@last as one CS-low period
 * and hand each transfer its share of what came back on MISO.  The first
 * period takes the message's place on the SPI bus, the last gives it up.
 * Called and returns with the lock held.
 */
static void end_period(struct msg_run *run, struct spi_transfer *first,
		       struct spi_transfer *last, bool final)
{
	struct mcp2510_sim_chip *chip = run->chip;
	struct mcp2510_sim *sim = chip->sim;
	struct mcp2510_sim_period *p = &run->period;
	struct spi_transfer *xfer = first;
	bool later = run->begun;

	if (!run->begun) {
		sim_spi_msg_begin(&sim->spi, &run->time, sim_bus_now(&sim->bus));
		run->begun = true;
	}
	wait_cs_rise(chip, sim_spi_msg_period(&sim->spi, &run->time, p->clock_ns));
	/* frames the chip stored since the message's previous period */
	if (later)
		chip->harness.spi_gap_frames +=
			sim_chip_counters(&chip->model)->frames_rx - run->frames_rx;
	sim_chip_spi(&chip->model, p->tx, p->rx, p->len);
	run->frames_rx = sim_chip_counters(&chip->model)->frames_rx;
	if (final)
		sim_spi_msg_end(&sim->spi, &run->time, &chip->model);

	list_for_each_entry_from(xfer, &run->msg->transfers, transfer_list) {
		mcp2510_sim_period_give(p, xfer->rx_buf, xfer->len);
		if (xfer == last)
			break;
	}
	mcp2510_sim_period_next(p);
}

/*
 * The lock is held over the whole message, so bus time only moves between
 * its periods when SPI time makes the controller sleep, and then exactly
 * to the modelled moment CS rises: frames that end in the gap between two
 * periods reach the chip before the next period acts, as on a board.  The
 * guest may not run for milliseconds between two periods; letting the bus
 * catch up with the clock further than modelled would deliver frames
 * there that no board could (the driver's receive order relies on two
 * frames never arriving between two periods of one message).  Transfer
 * delays are honoured after the message.
 */
static int run_message(struct mcp2510_sim_chip *chip, struct spi_message *msg)
{
	struct mcp2510_sim *sim = chip->sim;
	u32 chip_max_hz = sim_chip_sck_max_hz(&chip->model);
	struct msg_run run = { .chip = chip, .msg = msg };
	struct spi_transfer *xfer, *first = NULL;
	struct mcp2510_sim_xfer x;
	int ret = 0;

	mcp2510_sim_period_init(&run.period, sim->spi_tx, sim->spi_rx,
				MCP2510_SIM_SPI_BUF_LEN);
	mcp2510_sim_lock(sim);
	list_for_each_entry(xfer, &msg->transfers, transfer_list) {
		x.tx = xfer->tx_buf;
		x.len = xfer->len;
		x.speed_hz = xfer->speed_hz;
		x.cs_change = xfer->cs_change;
		x.last = list_is_last(&xfer->transfer_list, &msg->transfers);
		ret = mcp2510_sim_period_add(&run.period, &x, &sim->spi,
					     chip_max_hz);
		if (ret < 0)
			break;
		if (!first)
			first = xfer;
		if (ret) {
			end_period(&run, first, xfer, x.last);
			first = NULL;
		}
	}
	mcp2510_sim_unlock(sim);
	if (ret < 0)
		return ret;

	list_for_each_entry(xfer, &msg->transfers, transfer_list) {
		msg->actual_length += xfer->len;
		spi_transfer_delay_exec(xfer);
	}
	return 0;
}

/* Whether a transfer of @msg is an RTS (alone, or after a load or a clear). */
static bool message_has_rts(struct spi_message *msg)
{
	const struct spi_transfer *xfer;

	list_for_each_entry(xfer, &msg->transfers, transfer_list) {
		const u8 *tx = xfer->tx_buf;

		if (tx && xfer->len &&
		    (tx[0] & ~MCP2510_RTS_ALL) == MCP2510_INSTR_RTS)
			return true;
	}
	return false;
}

/*
 * The spi_errors_rts fault, after @msg reached the chip: a message with
 * an RTS that fails all the same, and spi_errors for the messages after
 * it.  True when it claims @msg.
 */
static bool rts_fails(struct mcp2510_sim_chip *chip, struct spi_message *msg)
{
	bool has_rts = message_has_rts(msg);
	bool fail = false;

	mcp2510_sim_lock(chip->sim);
	if (chip->fails.rts && has_rts) {
		chip->fails.spi = chip->fails.rts - 1;
		chip->fails.rts = 0;
		chip->harness.spi_failed++;
		fail = true;
	}
	mcp2510_sim_unlock(chip->sim);
	return fail;
}

static int transfer_one_message(struct spi_controller *ctlr,
				struct spi_message *msg)
{
	struct mcp2510_sim *sim = ctlr_to_sim(ctlr);
	struct mcp2510_sim_chip *chip;
	int ret;

	chip = &sim->chips[spi_get_chipselect(msg->spi, 0)];
	ret = account_message(chip, msg) ? -EIO : run_message(chip, msg);
	if (!ret && rts_fails(chip, msg))
		ret = -EIO;
	msg->status = ret;
	spi_finalize_current_message(ctlr);
	return ret;
}

int mcp2510_sim_spi_register(struct mcp2510_sim *sim, const char *driver,
			     int spidev_node)
{
	struct spi_controller *ctlr;
	int ret;

	ctlr = spi_alloc_host(sim->root, sizeof(sim));
	if (!ctlr)
		return -ENOMEM;
	*(struct mcp2510_sim **)spi_controller_get_devdata(ctlr) = sim;
	ctlr->bus_num = -1;
	ctlr->num_chipselect = sim->nchips;
	/* accept every mode so that a wrong one shows up in spi_mode_errors */
	ctlr->mode_bits = SPI_CPOL | SPI_CPHA;
	ctlr->bits_per_word_mask = SPI_BPW_MASK(8);
	ctlr->max_transfer_size = period_limit;
	ctlr->max_message_size = period_limit;
	ctlr->transfer_one_message = transfer_one_message;
	/* from a device tree, the SPI core adds the devices its nodes name */
	ctlr->dev.of_node = sim->of_spi;

	ret = spi_register_controller(ctlr);
	if (ret)
		goto out_put;
	sim->ctlr = ctlr;
	if (sim->of_spi)
		return 0;

	ret = mcp2510_sim_spi_add_devices(sim, driver, spidev_node);
	if (ret)
		goto out_unregister;
	return 0;

out_unregister:
	mcp2510_sim_spi_unregister(sim);
	return ret;
out_put:
	spi_controller_put(ctlr);
	return ret;
}

/* Unbinds the drivers, removes the devices and frees the controller. */
void mcp2510_sim_spi_unregister(struct mcp2510_sim *sim)
{
	unsigned int n;

	spi_unregister_controller(sim->ctlr);
	sim->ctlr = NULL;
	for (n = 0; n < sim->nchips; n++)
		mcp2510_sim_osc_remove(&sim->chips[n]);
}
