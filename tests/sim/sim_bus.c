// SPDX-License-Identifier: GPL-2.0
/*
 * The CAN bus joining the simulated chips and the phantom node
 * (sim_phantom.c): event loop, arbitration, acknowledgement, error frames and their effect on
 * the error counters (CAN 2.0B part B, chapter 8 "fault confinement").
 *
 * A frame is decided when it starts: who sends (arbitration), whether it
 * will be acknowledged and whether some node will destroy it with an error
 * frame.  That fixes how long the bus is busy; the effects on every node
 * are applied when that time has passed.
 */
#include "sim_private.h"

/* where a node at another bit rate flags the frame: early, in arbitration */
#define SIM_MISMATCH_ERROR_BIT	8
/* a runaway guard: no instant needs more steps than this */
#define SIM_MAX_STEPS_PER_INSTANT	1000
#define SIM_NO_SENDER		(-2)

static u32 sim_ns_to_rate(u32 ns)
{
	return ns ? (SIM_NS_PER_SEC + ns / 2) / ns : 0;
}

void sim_bus_init(struct sim_bus *bus)
{
	memset(bus, 0, sizeof(*bus));
	bus->cur_sender = SIM_NO_SENDER;
}

int sim_bus_attach(struct sim_bus *bus, struct sim_chip *chip)
{
	if (chip->bus)
		return -EBUSY;
	if (bus->nchips >= SIM_MAX_NODES)
		return -ENOSPC;
	chip->bus = bus;
	chip->node = bus->nchips;
	bus->chips[bus->nchips++] = chip;
	/* power-on start-up runs from the moment the chip joins the clock */
	if (chip->powered)
		chip->ready_at = bus->now + sim_chip_startup_ns(chip);
	return 0;
}

u64 sim_bus_now(const struct sim_bus *bus)
{
	return bus->now;
}

/* a frame on the bus, or a start of frame whose arbitration is still open */
bool sim_bus_busy(const struct sim_bus *bus)
{
	return bus->busy || bus->sof;
}

bool sim_bus_idle(const struct sim_bus *bus)
{
	return !sim_bus_busy(bus);
}

void sim_bus_set_monitor(struct sim_bus *bus,
			 void (*fn)(void *ctx, const struct sim_bus_record *rec),
			 void *ctx)
{
	bus->monitor = fn;
	bus->monitor_ctx = ctx;
}

struct sim_bus_faults *sim_bus_faults(struct sim_bus *bus)
{
	return &bus->faults;
}

/* ---- Arbitration -------------------------------------------------------------- */

struct sim_contest {
	int sender;		/* node index, SIM_NODE_PHANTOM, SIM_NO_SENDER */
	int buf;
	u32 key;
	struct sim_timing tm;	/* the sender's */
	struct can_frame cf;
};

static bool sim_bus_has_contender(const struct sim_bus *bus)
{
	unsigned int i;

	if (sim_phantom_pending(bus))
		return true;
	for (i = 0; i < bus->nchips; i++)
		if (sim_chip_tx_candidate(bus->chips[i]) >= 0)
			return true;
	return false;
}

/*
 * Lowest arbitration field wins.  Two senders with identical fields
 * cannot be told apart on a real bus; the model lets the lower node
 * index win and the phantom lose such ties.  No side effects.
 */
static void sim_bus_best(struct sim_bus *bus, struct sim_contest *win)
{
	struct can_frame cf;
	unsigned int i;
	u32 ns;

	win->sender = SIM_NO_SENDER;
	for (i = 0; i < bus->nchips; i++) {
		struct sim_chip *chip = bus->chips[i];
		int buf = sim_chip_tx_candidate(chip);
		u32 key;

		if (buf < 0)
			continue;
		sim_chip_tx_frame(chip, buf, &cf);
		key = sim_frame_arbitration_key(&cf);
		if (win->sender != SIM_NO_SENDER && key >= win->key)
			continue;
		win->sender = i;
		win->buf = buf;
		win->key = key;
		win->cf = cf;
		sim_chip_timing(chip, &win->tm);
	}
	if (sim_phantom_peek(bus, &cf, &ns) &&
	    (win->sender == SIM_NO_SENDER ||
	     sim_frame_arbitration_key(&cf) < win->key)) {
		win->sender = SIM_NODE_PHANTOM;
		win->key = sim_frame_arbitration_key(&cf);
		win->cf = cf;
		sim_phantom_timing(ns, &win->tm);
	}
}

/* The arbitration at the end of the start-of-frame bit. */
static void sim_bus_arbitrate(struct sim_bus *bus, struct sim_contest *win)
{
	unsigned int i;

	sim_bus_best(bus, win);
	/* AN739: losers re-arbitrate later, picking their best buffer again */
	for (i = 0; i < bus->nchips; i++)
		if ((int)i != win->sender &&
		    sim_chip_tx_candidate(bus->chips[i]) >= 0)
			sim_chip_tx_lost(bus->chips[i]);
}

/*
 * The first request on an idle bus, or one still pending when the bus
 * goes idle, sends its start-of-frame bit at once.  A node whose request
 * comes while that bit is on the bus hard-synchronises on its edge and
 * joins the arbitration from the next bit (CAN 2.0B part B, "Start of
 * Frame": every station synchronises on the leading edge of the start of
 * frame of the station that began first; "Hard Synchronization": on the
 * recessive-to-dominant edge after bus idle).  So the arbitration is decided at the end of that bit, among
 * every request made until then, and the frame's time counts from its
 * start of frame.
 */
static void sim_bus_begin_sof(struct sim_bus *bus)
{
	struct sim_contest first;
	unsigned int i;

	sim_bus_best(bus, &first);
	if (first.sender == SIM_NO_SENDER)
		return;
	bus->sof = true;
	bus->sof_at = bus->now;
	bus->sof_ns = first.tm.ns;
	/*
	 * The edge wakes sleeping chips; only the nodes listening now can
	 * take part in the frame (one woken by it cannot).
	 */
	bus->cur_listeners = 0;
	for (i = 0; i < bus->nchips; i++) {
		struct sim_chip *chip = bus->chips[i];

		sim_chip_bus_activity(chip);
		if (sim_chip_listening(chip))
			bus->cur_listeners |= 1U << i;
	}
}

static u64 sim_bus_sof_end(const struct sim_bus *bus)
{
	return bus->sof_at + bus->sof_ns;
}

/* ---- Frames -------------------------------------------------------------------- */

struct sim_verdict {
	bool acked;
	bool flagged;		/* an error-active node at another rate objects */
};

/* How the other nodes react to a frame sent with timing tm. */
static void sim_bus_judge(struct sim_bus *bus, int sender,
			  const struct sim_timing *tm, struct sim_verdict *v)
{
	struct sim_timing rx;
	unsigned int i;

	v->acked = false;
	v->flagged = false;
	/* the sender is no receiver of its own frame */
	if (sender >= 0)
		bus->cur_listeners &= ~(1U << sender);
	for (i = 0; i < bus->nchips; i++) {
		struct sim_chip *chip = bus->chips[i];

		if (!(bus->cur_listeners & (1U << i)) || !sim_chip_listening(chip))
			continue;
		sim_chip_timing(chip, &rx);
		if (sim_timings_match(&rx, tm)) {
			/* listen-only nodes never drive the ACK slot */
			if (chip->opmode == MCP2510_MODE_NORMAL)
				v->acked = true;
		} else if (chip->opmode == MCP2510_MODE_NORMAL &&
			   sim_chip_error_active(chip)) {
			v->flagged = true;
		}
	}
	if (bus->phantom.attached && sender != SIM_NODE_PHANTOM) {
		u32 pns = sim_phantom_rx_ns(bus);

		sim_phantom_timing(pns, &rx);
		if (!pns || sim_timings_match(&rx, tm))
			v->acked = true;
		else
			v->flagged = true;
	}
	if (bus->faults.no_ack)
		v->acked = false;
}

static void sim_bus_start_frame(struct sim_bus *bus)
{
	struct sim_bus_record *rec = &bus->cur;
	struct sim_frame_info info;
	struct sim_verdict v;
	struct sim_contest win;
	u64 start = bus->sof_at;
	u32 error_bit = 0;
	unsigned int i;

	bus->sof = false;
	sim_bus_arbitrate(bus, &win);
	/* every request was withdrawn during the start of frame: nothing follows */
	if (win.sender == SIM_NO_SENDER)
		return;
	sim_frame_measure(&win.cf, &info);
	sim_bus_judge(bus, win.sender, &win.tm, &v);

	memset(rec, 0, sizeof(*rec));
	rec->kind = SIM_REC_ERROR;
	if (bus->faults.bus_errors) {
		/* a corrupted frame fails its CRC check after the ACK delimiter */
		bus->faults.bus_errors--;
		rec->cause = SIM_ERR_INJECTED;
		error_bit = info.stuffed_len + 3;
	} else if (v.flagged) {
		rec->cause = SIM_ERR_BITRATE;
		error_bit = SIM_MISMATCH_ERROR_BIT;
	} else if (!v.acked) {
		/* the sender flags the ACK error in the ACK delimiter */
		rec->cause = SIM_ERR_ACK;
		error_bit = info.stuffed_len + 2;
	} else {
		rec->kind = SIM_REC_FRAME;
		rec->cause = SIM_ERR_NONE;
	}
	rec->sender = win.sender;
	rec->frame = win.cf;
	rec->bitrate = sim_ns_to_rate(win.tm.ns);
	rec->bits = rec->cause ? error_bit + SIM_ERROR_FRAME_BITS : info.bits;
	rec->acked = v.acked;
	rec->start_ns = start;
	rec->end_ns = start + (u64)rec->bits * win.tm.ns;

	for (i = 0; i < bus->nchips; i++)
		sim_chip_recovery_account(bus->chips[i], start);
	bus->busy = true;
	/* a winner much faster than the start of frame cannot end in the past */
	bus->busy_until = rec->end_ns > bus->now ? rec->end_ns : bus->now;
	bus->cur_sender = win.sender;
	bus->cur_tm = win.tm;
	if (win.sender >= 0)
		sim_chip_tx_start(bus->chips[win.sender], win.buf);
}

/*
 * After an ACK error an error-passive sender's flag is recessive: the
 * receivers see a frame without error (and take it), the sender retries.
 */
static bool sim_bus_passive_ack_error(const struct sim_bus *bus)
{
	const struct sim_chip *sender;

	if (bus->cur.cause != SIM_ERR_ACK || bus->cur_sender < 0)
		return false;
	sender = bus->chips[bus->cur_sender];
	return !sim_chip_error_active(sender);
}

/*
 * Only nodes that heard the start of frame can take it: one woken by it,
 * or switched to a listening mode meanwhile, cannot.
 */
static void sim_bus_end_receivers(struct sim_bus *bus, bool valid)
{
	struct sim_timing rx;
	unsigned int i;

	for (i = 0; i < bus->nchips; i++) {
		struct sim_chip *chip = bus->chips[i];
		bool heard;

		if (!(bus->cur_listeners & (1U << i)) || !sim_chip_listening(chip))
			continue;
		sim_chip_timing(chip, &rx);
		heard = sim_timings_match(&rx, &bus->cur_tm);
		if (valid && heard)
			sim_chip_rx_ok(chip, &bus->cur.frame);
		else
			sim_chip_rx_error(chip, heard ? &bus->cur.frame : NULL);
	}
}

/*
 * A sender reset or unpowered mid-frame stopped driving the bus: six
 * recessive bits later every receiver flags a stuff error, so nobody takes
 * the frame.  (The record keeps the frame's full length; the error frame
 * comes earlier on a real bus.)
 */
static void sim_bus_check_sender(struct sim_bus *bus)
{
	if (bus->cur_sender < 0 || sim_chip_sending(bus->chips[bus->cur_sender]))
		return;
	bus->cur.kind = SIM_REC_ERROR;
	bus->cur.cause = SIM_ERR_SENDER_LOST;
}

static void sim_bus_end_frame(struct sim_bus *bus)
{
	const struct sim_bus_record *rec = &bus->cur;
	bool ok, passive_ack;
	unsigned int i;

	sim_bus_check_sender(bus);
	ok = rec->kind == SIM_REC_FRAME;
	passive_ack = sim_bus_passive_ack_error(bus);

	bus->busy = false;
	/* ACK delimiter, EOF and intermission: 11 recessive bits for bus-off nodes */
	for (i = 0; i < bus->nchips; i++)
		sim_chip_recovery_frame(bus->chips[i], bus->now);

	if (bus->cur_sender >= 0) {
		struct sim_chip *sender = bus->chips[bus->cur_sender];

		if (ok)
			sim_chip_tx_end(sender, true, false);
		else
			sim_chip_tx_end(sender, false, !passive_ack);
	} else if (bus->cur_sender == SIM_NODE_PHANTOM && ok) {
		sim_phantom_sent(bus);
	}
	sim_bus_end_receivers(bus, ok || passive_ack);
	bus->cur_sender = SIM_NO_SENDER;
	if (bus->monitor)
		bus->monitor(bus->monitor_ctx, rec);
}

/* ---- Time ------------------------------------------------------------------------ */

u64 sim_bus_next_event(const struct sim_bus *bus)
{
	u64 t = U64_MAX;
	unsigned int i;

	if (bus->busy)
		t = bus->busy_until;
	else if (bus->sof)
		t = sim_bus_sof_end(bus);
	else if (sim_bus_has_contender(bus))
		t = bus->now;
	for (i = 0; i < bus->nchips; i++)
		t = sim_min_u64(t, sim_chip_next_event(bus->chips[i]));
	return t;
}

/* Everything due at bus->now. */
static void sim_bus_step(struct sim_bus *bus)
{
	unsigned int i;

	if (bus->busy && bus->now >= bus->busy_until)
		sim_bus_end_frame(bus);
	for (i = 0; i < bus->nchips; i++)
		sim_chip_run_events(bus->chips[i]);
	if (bus->busy)
		return;
	if (!bus->sof)
		sim_bus_begin_sof(bus);
	else if (bus->now >= sim_bus_sof_end(bus))
		sim_bus_start_frame(bus);
}

void sim_bus_advance_to(struct sim_bus *bus, u64 when)
{
	unsigned int same_instant = 0;

	if (bus->advancing)
		return;		/* called from a callback: the outer loop goes on */
	bus->advancing = true;
	while (same_instant < SIM_MAX_STEPS_PER_INSTANT) {
		u64 next = sim_bus_next_event(bus);

		if (next > when)
			break;
		if (next > bus->now) {
			bus->now = next;
			same_instant = 0;
		} else {
			same_instant++;
		}
		sim_bus_step(bus);
	}
	if (when > bus->now)
		bus->now = when;
	bus->advancing = false;
}

void sim_bus_advance(struct sim_bus *bus, u64 ns)
{
	u64 when = bus->now + ns;

	sim_bus_advance_to(bus, when < bus->now ? U64_MAX : when);
}
