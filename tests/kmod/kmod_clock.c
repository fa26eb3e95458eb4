// SPDX-License-Identifier: GPL-2.0
/*
 * Bus time follows the kernel's monotonic clock, slowed down by time_scale.
 * A scenario may change time_scale at run time (debugfs "time_scale"), to
 * give every bit rate the same frame time; bus time then goes on from
 * where it stood.
 *
 * The model only moves when it is told to, so every access first brings it
 * up to the present and afterwards arms a timer for its next event: frames
 * then take as long on the simulated bus as on a real one, and a driver's
 * own waits (start-up, mode changes) see the chip react in time.
 */
#include <linux/hrtimer.h>
#include <linux/ktime.h>
#include <linux/sched.h>

#include "kmod.h"

/*
 * The model may lag behind the clock by MCP2510_SIM_MAX_LAG_NS of real
 * time at most.  A guest too slow to model the bus as fast as it runs (the
 * debug kernel under TCG during a retry storm at full speed) would
 * otherwise fall further behind at every access, each one spending longer
 * with bottom halves off, until nothing else in the guest ran.  Beyond
 * this lag bus time stalls instead, as if the bus had paused; so it does
 * for a guest the host did not run for a while.  Each stall is counted
 * (chipN/counters "clock_stalls"): a measurement across one is void.
 */
static u64 model_now(struct mcp2510_sim *sim)
{
	return mcp2510_sim_clock_model(&sim->clock, ktime_get_ns(),
				       sim_bus_next_event(&sim->bus));
}

void mcp2510_sim_lock(struct mcp2510_sim *sim) __acquires(&sim->lock)
{
	spin_lock_bh(&sim->lock);
	sim_bus_advance_to(&sim->bus, model_now(sim));
}

/*
 * Arming from here, under the lock, is what keeps the timer right: a
 * transfer that schedules an earlier event re-arms it, and the timer's own
 * callback re-arms through the same path rather than by returning
 * HRTIMER_RESTART with an expiry that may already be stale.
 */
static void arm_for_next_event(struct mcp2510_sim *sim)
{
	u64 next = sim_bus_next_event(&sim->bus);
	u64 real;

	if (sim->stopping || next == U64_MAX ||
	    !mcp2510_sim_clock_real(&sim->clock, next, &real))
		return;
	hrtimer_start(&sim->timer, ns_to_ktime(real), HRTIMER_MODE_ABS_SOFT);
}

void mcp2510_sim_unlock(struct mcp2510_sim *sim) __releases(&sim->lock)
{
	arm_for_next_event(sim);
	spin_unlock_bh(&sim->lock);
}

static enum hrtimer_restart bus_timer_fired(struct hrtimer *timer)
{
	struct mcp2510_sim *sim = container_of(timer, struct mcp2510_sim, timer);

	mcp2510_sim_lock(sim);
	mcp2510_sim_unlock(sim);
	return HRTIMER_NORESTART;
}

void mcp2510_sim_clock_init(struct mcp2510_sim *sim, u32 time_scale)
{
	mcp2510_sim_clock_start(&sim->clock, ktime_get_ns(), time_scale);
	hrtimer_setup(&sim->timer, bus_timer_fired, CLOCK_MONOTONIC,
		      HRTIMER_MODE_ABS_SOFT);
}

/* Called under the lock; the unlock re-arms the timer at the new pace. */
void mcp2510_sim_clock_rescale(struct mcp2510_sim *sim, u32 time_scale)
{
	mcp2510_sim_clock_set_scale(&sim->clock, ktime_get_ns(), time_scale);
	mcp2510_sim_irq_set_delay(sim);
}

/* Stalls of the bus clock so far; under the lock. */
u64 mcp2510_sim_clock_stalls(struct mcp2510_sim *sim)
{
	return sim->clock.stalls;
}

/*
 * Sleep, outside the lock, until bus time reaches model_ns: an SPI
 * controller busy until CS rises.  Bus time may stall meanwhile, so the
 * caller still brings the model to model_ns itself.
 */
void mcp2510_sim_clock_sleep_until(struct mcp2510_sim *sim, u64 model_ns)
{
	ktime_t expires;
	u64 real;
	bool ok;

	spin_lock_bh(&sim->lock);
	ok = mcp2510_sim_clock_real(&sim->clock, model_ns, &real);
	spin_unlock_bh(&sim->lock);
	if (!ok)
		return;
	expires = ns_to_ktime(real);
	while (ktime_get_ns() < real) {
		set_current_state(TASK_UNINTERRUPTIBLE);
		schedule_hrtimeout(&expires, HRTIMER_MODE_ABS);
	}
}

void mcp2510_sim_clock_stop(struct mcp2510_sim *sim)
{
	spin_lock_bh(&sim->lock);
	sim->stopping = true;
	spin_unlock_bh(&sim->lock);
	hrtimer_cancel(&sim->timer);
}
