/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Helpers the files of the portable core share with each other but not
 * with their callers.
 */
#ifndef MCP2510_CORE_PRIV_H
#define MCP2510_CORE_PRIV_H

#include "mcp2510_core.h"

/* Longest transfer: instruction, address and the whole register file. */
#define MCP2510_XFER_MAX	(2 + MCP2510_REG_COUNT)

/* spi.c */
int mcp2510_xfer(struct mcp2510_chip *chip, const u8 *tx, u8 *rx,
		 unsigned int len);
/* @n chip-select periods in one message (ops->xfer_msg), or one by one. */
int mcp2510_xfer_msg(struct mcp2510_chip *chip, const struct mcp2510_xfer *x,
		     unsigned int n);

/* bringup.c */
void mcp2510_delay_us(struct mcp2510_chip *chip, unsigned int us);

/* tx.c */
void mcp2510_tx_reset(struct mcp2510_chip *chip);
/* Slots whose frame the chip should still hold with TXREQ set. */
u8 mcp2510_tx_pending(const struct mcp2510_chip *chip);
/* Slots whose TXnIF was seen: raise tx_done in queue order. */
void mcp2510_tx_complete(struct mcp2510_chip *chip, u8 slots);
/* Slots the chip dropped without sending (TXREQ gone, no TXnIF). */
void mcp2510_tx_lost(struct mcp2510_chip *chip, u8 slots);
/* Drop every queued frame, raising tx_aborted in queue order. */
void mcp2510_tx_abort_all(struct mcp2510_chip *chip);

/* tx_request.c */
/* READ STATUS @status: settle the slots whose RTS had an unknown outcome. */
void mcp2510_tx_resolve(struct mcp2510_chip *chip, u8 status);
/* Load @regs (@nregs of them) into @slot with priority @txp. */
int mcp2510_tx_load(struct mcp2510_chip *chip, unsigned int slot, u8 txp,
		    const u8 *regs, unsigned int nregs);
/* The same and its RTS in one message: 0 once requested, or -EIO. */
int mcp2510_tx_send(struct mcp2510_chip *chip, unsigned int slot, u8 txp,
		    const u8 *regs, unsigned int nregs);
/* READ STATUS for the slots whose RTS had an unknown outcome. */
int mcp2510_tx_status_resolve(struct mcp2510_chip *chip);
/*
 * Clear @intf_clear in CANINTF and request the staged frames once no older
 * frame is pending, in one message.
 */
int mcp2510_tx_kick(struct mcp2510_chip *chip, u8 intf_clear);

/* error.c */
enum can_state mcp2510_error_eflg_state(u8 eflg);
/* Whether TEC/REC are within the limits of the state EFLG shows. */
bool mcp2510_error_state_plausible(u8 eflg, const struct can_berr_counter *bec);
/* Follow EFLG/TEC/REC into chip->state, raising state and error events. */
void mcp2510_error_state_update(struct mcp2510_chip *chip, u8 eflg,
				const struct can_berr_counter *bec);
/* Report RXnOVR from @eflg; returns the EFLG bits to clear. */
u8 mcp2510_error_overflow(struct mcp2510_chip *chip, u8 eflg,
			  const struct can_berr_counter *bec);
/* A MERRF: count it and report it if bus-error reporting is on. */
void mcp2510_error_bus(struct mcp2510_chip *chip,
		       const struct can_berr_counter *bec);

/* The interrupt flags one pass handles (irq_flags.c reads them). */
struct irq_flags {
	u8 intf;		/* CANINTF bits to handle */
	u8 eflg;
	u8 txreq;		/* slots with TXREQ set ... */
	bool have_txreq;	/* ... when READ STATUS was read */
	u8 status;		/* what it read */
	bool full;		/* CANINTF and EFLG were read */
	bool rx_continued;	/* nothing read: see flags_from_rx_status() */
	bool polled;		/* read by a drain's poll: see status_get() */
};

/* irq_flags.c */
int flags_read(struct mcp2510_chip *chip, struct irq_flags *f);

/* irq_rx.c */
/* The READ STATUS that ended the last pass shows a frame to take. */
static inline bool rx_status_more(const struct mcp2510_chip *chip)
{
	return chip->irq.rx_status & (MCP2510_STATUS_RX0IF |
				      MCP2510_STATUS_RX1IF);
}

/* Take the flagged RX buffers in @intf, the older frame first. */
int rx_take(struct mcp2510_chip *chip, u8 intf);
/* Poll READ STATUS for the next frame: 1 when it came, 0, or an error. */
int rx_poll(struct mcp2510_chip *chip);
/* Whether the pass's first frame waited in the chip (see rx_pass). */
bool rx_first_waited(const struct mcp2510_chip *chip,
		     const struct irq_flags *f);

/* irq_tx.c */
/* Sent and dropped frames; returns the TXnIF bits to clear. */
u8 handle_tx(struct mcp2510_chip *chip, const struct irq_flags *f);
/* Poll for the end of a drain: 1 when a pass is due, 0, or an error. */
int tx_drain_poll(struct mcp2510_chip *chip);

/* irq_error.c */
int handle_errors(struct mcp2510_chip *chip, const struct irq_flags *f);

/* filter.c */
int mcp2510_filters_write(struct mcp2510_chip *chip);

#endif /* MCP2510_CORE_PRIV_H */
