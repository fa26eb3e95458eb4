/* SPDX-License-Identifier: GPL-2.0 */
/*
 * What the two halves of the core_hostile target share: the chip the
 * core talks to (fuzz_hostile_chip.c) and the calls made on the core
 * (fuzz_core_hostile.c).
 */
#ifndef FUZZ_HOSTILE_H
#define FUZZ_HOSTILE_H

#include "fuzz_input.h"
#include "mcp2510_core.h"
#include "mcp2510_sim.h"

#define SLOTS			MCP2510_TXB_COUNT

enum miso {
	MISO_INPUT,		/* the front of the input, then the fill byte */
	MISO_STUCK,		/* the fill byte */
	MISO_MODEL,		/* the simulated chip's answer, maybe garbled */
	MISO_COUNT
};

struct hostile {
	struct fuzz_input in;
	struct mcp2510_chip chip;
	enum miso miso;
	u8 fill;			/* MISO once the input ran out */
	struct sim_bus bus;		/* MISO_MODEL: the chip and a peer */
	struct sim_chip sim;
	unsigned int garble;		/* MISO_MODEL: transfers to XOR */
	unsigned int fail_every;	/* every N-th transfer fails; 0: never */
	unsigned long xfers;		/* all transfers */
	unsigned long call_xfers;	/* during the current call */
	unsigned long long call_delay_us;
	/* submitted frames not yet reported, oldest first */
	unsigned int queue[SLOTS];
	unsigned int queued;
};

/* The core and the chip of one input, decided from its back. */
void hostile_init(struct hostile *h, const uint8_t *data, size_t size);
/* Where @slot is in the queue of unreported frames; SLOTS: not there. */
unsigned int queue_pos(const struct hostile *h, unsigned int slot);

#endif /* FUZZ_HOSTILE_H */
