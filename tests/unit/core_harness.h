/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The portable driver core running against simulated chips: each node is
 * a struct mcp2510_chip whose SPI transfers go to a struct sim_chip and
 * whose delays advance the simulated bus.  Events are recorded for the
 * tests; transport faults can be injected; the bus can be run while the
 * interrupt line of every node is serviced.
 */
#ifndef CORE_HARNESS_H
#define CORE_HARNESS_H

#include "mcp2510_core.h"
#include "mcp2510_sim.h"

#define CH_MAX_NODES	3
#define CH_LOG_MAX	64
#define CH_OSC_HZ	16000000U
/* power-up garbage of node i: sim_chip_init_seeded(..., CH_SEED_BASE + i) */
#define CH_SEED_BASE	0x5eed0000U

struct ch_node;

struct ch_events {
	/* the last CH_LOG_MAX of each kind, and how many in all */
	struct can_frame rx[CH_LOG_MAX];
	unsigned int rx_count;
	unsigned int tx_done[CH_LOG_MAX];
	unsigned int tx_done_count;
	unsigned int tx_aborted[CH_LOG_MAX];
	unsigned int tx_aborted_count;
	enum can_state state[CH_LOG_MAX];
	unsigned int state_count;
	struct can_frame error[CH_LOG_MAX];
	unsigned int error_count;
	/* rx_pass: frames received before it, and what it said */
	struct {
		unsigned int rx_before;
		bool first_waited;
	} pass[CH_LOG_MAX];
	unsigned int pass_count;
	/* optional per-test hooks, called after recording */
	void (*on_rx)(struct ch_node *node, const struct can_frame *cf);
	void (*on_tx_done)(struct ch_node *node, unsigned int slot);
};

struct ch_node {
	struct ch_rig *rig;
	struct sim_chip sim;
	struct mcp2510_chip core;
	struct ch_events ev;
	/* transport faults: fail transfer number fail_at (1-based, 0: never) */
	u64 xfer_count;
	u64 fail_at;
	bool fail_reaches_chip;	/* the failed transfer still happened */
	u8 failed_instr;	/* first byte of the transfer that failed */
	/* called after every transfer that reached the chip */
	void (*after_xfer)(struct ch_node *node);
	/*
	 * Inside a message of several periods (mcp2510_ops.xfer_msg), the
	 * periods still to come after the current one: after_xfer sees a
	 * non-zero value between two periods of one message.
	 */
	unsigned int msg_left;
	u64 messages;		/* SPI messages: xfer_msg calls, xfer as one */
	u64 status_reads;	/* of them, a READ STATUS alone */
	u64 irq_calls;		/* mcp2510_irq_handle() calls by ch_service() */
	bool in_irq;		/* inside one of them */
	/* of them, those a drain waited for: frames staged, none pending */
	u64 drain_waits;
	/* a broken board: MISO always reads this (-1: a working line) */
	int miso_stuck;
	/* a glitch: corrupt_periods periods once xfer_count is corrupt_after */
	u64 corrupt_after;
	u32 corrupt_periods;
	enum sim_corrupt_kind corrupt_kind;
	u32 spi_hz;		/* SCK asked for with SPI time on; 0: the chip's maximum */
	void *test_ctx;
};

struct ch_rig {
	struct sim_bus bus;
	/*
	 * SPI time (off unless a test sets spi.timing): see sim_spi_time.h.
	 * Nodes are serviced one after another, so with several nodes their
	 * interrupt latencies add up where a real host would overlap them.
	 */
	struct sim_spi_bus spi;
	struct ch_node node[CH_MAX_NODES];
	unsigned int nnodes;
};

/* SPI traffic of a node between two points of a test */
struct ch_spi_mark {
	u64 bytes, transfers;
};

/* SPI time of a fast host: 10 us a message, 20 us to the handler */
extern const struct sim_spi_timing ch_pi_like;

/* Allocates (test_calloc) a bus with @n nodes of @variant, not started. */
struct ch_rig *ch_rig_new(unsigned int n, enum mcp2510_model model);
void ch_rig_free(struct ch_rig *rig);

/* 16 MHz oscillator, timing from the calculator; 0 or -errno */
int ch_start(struct ch_node *node, u32 bitrate, u32 ctrlmode);
struct can_bittiming ch_bittiming(u32 bitrate);

/* INT low (active)? */
bool ch_int_asserted(const struct ch_node *node);
/*
 * Call mcp2510_irq_handle() while INT is asserted (at most @max times) and
 * return the number of calls; the last result in *last_ret.
 */
unsigned int ch_service(struct ch_node *node, unsigned int max, int *last_ret);
/* Advance to the next event and service; false when nothing is pending. */
bool ch_step(struct ch_rig *rig);
/* Run the bus for @ns, servicing every node's interrupt after each event. */
void ch_run(struct ch_rig *rig, u64 ns);
/* Run until the bus is idle with nothing pending and no INT asserted. */
void ch_run_idle(struct ch_rig *rig, u64 max_ns);

/*
 * Corrupt MISO (@kind; SIM_CORRUPT_FIXED reads 0x00) for @periods transfers
 * once @after more transfers have gone, counting from now.
 */
void ch_corrupt_after(struct ch_node *node, u64 after,
		      enum sim_corrupt_kind kind, u32 periods);

void ch_spi_mark(const struct ch_node *node, struct ch_spi_mark *m);
/* Traffic since @m */
struct ch_spi_mark ch_spi_since(const struct ch_node *node,
				const struct ch_spi_mark *m);

struct can_frame ch_frame(canid_t id, u8 len, u32 seq);
bool ch_frame_equal(const struct can_frame *a, const struct can_frame *b);

/*
 * The order of a phantom flood's frames as a node receives them: the
 * phantom numbers frame k in its first four bytes (little-endian), so a
 * number not above the last one's is out of order.
 */
struct ch_order {
	u32 received;
	u32 out_of_order;
	u32 last_seq;
};

void ch_order_frame(struct ch_order *o, const struct can_frame *cf);

#endif /* CORE_HARNESS_H */
