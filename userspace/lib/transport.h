/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * What the library needs from the thing that reaches the chip: one
 * chip-select-low transfer (or a few in one message), a delay, and a way
 * to wait for the INT pin.
 * spidev.c, sim_transport.c and simbus_client.c provide it.
 */
#ifndef MCP2510_TRANSPORT_H
#define MCP2510_TRANSPORT_H

#include <stdbool.h>
#include <stdint.h>

struct mcp2510_transport;

struct mcp2510_transport_counts {
	uint64_t spi_transfers;
	uint64_t spi_bytes;
	uint64_t interrupts;
};

/* One CS-low period of a message; @rx may be NULL. */
struct mcp2510_transport_xfer {
	const uint8_t *tx;
	uint8_t *rx;
	unsigned int len;
};

struct mcp2510_transport_ops {
	/* One CS-low period; @rx may be NULL.  0 or -errno. */
	int (*xfer)(struct mcp2510_transport *t, const uint8_t *tx,
		    uint8_t *rx, unsigned int len);
	/*
	 * Optional: @n CS-low periods in one message, CS rising only
	 * briefly between them (the core's receive-order check needs them
	 * microseconds apart).  Without it the library calls xfer for each,
	 * which is as good where no time passes between calls (the
	 * simulated bus).  0 or -errno.
	 */
	int (*xfer_msg)(struct mcp2510_transport *t,
			const struct mcp2510_transport_xfer *x, unsigned int n);
	void (*delay_us)(struct mcp2510_transport *t, unsigned int us);
	/*
	 * Wait up to @timeout_ms (0: just look, -1: forever) for INT, or in
	 * polling mode for the next time to look.  1 when the chip should
	 * be serviced, 0 on timeout, -errno.
	 */
	int (*wait_irq)(struct mcp2510_transport *t, int timeout_ms);
	/* Readable while wait_irq(t, 0) would return 1; -1 if none. */
	int (*fd)(const struct mcp2510_transport *t);
	void (*counts)(const struct mcp2510_transport *t,
		       struct mcp2510_transport_counts *c);
	void (*close)(struct mcp2510_transport *t);
	/*
	 * Optional: have @fn(@ctx) called when this chip's INT falls while
	 * another handle waits, for transports where one thread drives
	 * several chips (the simulated bus).
	 */
	void (*set_irq_hook)(struct mcp2510_transport *t,
			     void (*fn)(void *ctx), void *ctx);
};

struct mcp2510_transport {
	const struct mcp2510_transport_ops *ops;
};

struct mcp2510_transport_params {
	uint32_t spi_hz;		/* already defaulted from the variant */
	uint8_t spi_mode;
	const char *int_line;
	unsigned int poll_ms;
	uint32_t osc_hz;
	bool mcp2515;			/* for the simulated chip's variant */
};

/* "/dev/spidevB.C" (the part after "spidev:"). */
int mcp2510_spidev_open(const char *path,
			const struct mcp2510_transport_params *p,
			struct mcp2510_transport **out);
/* "" for a private bus with a phantom node, or a shared bus's name. */
int mcp2510_sim_open(const char *bus_name,
		     const struct mcp2510_transport_params *p,
		     struct mcp2510_transport **out);
/* "NAME@BUS": the chip NAME on the bus BUS shared by processes. */
int mcp2510_simbus_open(const char *spec,
			const struct mcp2510_transport_params *p,
			struct mcp2510_transport **out);

#endif /* MCP2510_TRANSPORT_H */
