/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Kernel glue of the MCP2510/MCP2515/MCP25625 SocketCAN driver: the state
 * shared by the glue's files.  Everything about the chip itself lives in
 * the portable core (driver/core); this side only adapts it to SPI, the
 * network stack, sysfs, gpiolib and power management.
 */
#ifndef MCP2510_PRIV_H
#define MCP2510_PRIV_H

#include <linux/can/dev.h>
#include <linux/can/rx-offload.h>
#include <linux/atomic.h>
#include <linux/ktime.h>
#include <linux/skbuff.h>
#include <linux/gpio/driver.h>
#include <linux/mutex.h>
#include <linux/spi/spi.h>
#include <linux/spinlock.h>
#include <linux/workqueue.h>

#include "compat.h"
#include "mcp2510_core.h"

#define MCP2510_DRV_NAME	"mcp2510"

/* The longest transfer the core makes: instruction, address, register file. */
#define MCP2510_SPI_BUF_LEN	(2 + MCP2510_REG_COUNT)

/* gpiochip lines: the two RXnBF outputs, then the three TXnRTS inputs. */
#define MCP2510_GPIO_BF_COUNT	2
#define MCP2510_GPIO_RTS_COUNT	3
#define MCP2510_GPIO_COUNT	(MCP2510_GPIO_BF_COUNT + MCP2510_GPIO_RTS_COUNT)

struct regulator;
struct clk;

/* state.c: the device's states; the transitions are listed there */
enum mcp2510_dev_state {
	MCP2510_DEV_OFF,	/* no supply or oscillator */
	MCP2510_DEV_POWERED,	/* INT free; the chip asleep once reset */
	MCP2510_DEV_WAKE_ARMED,	/* suspended asleep, INT a wakeup irq */
	MCP2510_DEV_RUNNING,	/* INT requested, the chip on the bus */
	MCP2510_DEV_BUS_OFF,	/* bus-off reported, the halt not through yet */
	MCP2510_DEV_HALTED,	/* stopped at bus-off until a restart */
};

/* IRQ thread calls handling nothing, or failing, within a second: a storm. */
#define MCP2510_STORM_UNHANDLED_IRQS	32

/* watch.c: what the watch does about the INT line */
enum mcp2510_watch_state {
	MCP2510_WATCH_STOPPED,		/* interface down: the work ends */
	MCP2510_WATCH_IRQ,		/* INT in use */
	MCP2510_WATCH_POLLING,		/* a storm: INT disabled, the work polls */
	MCP2510_WATCH_IRQ_BACK,		/* INT back after a storm, not yet quiet */
};

/* watch.c: health checks, and polling through storms and missed edges */
struct mcp2510_watch {
	struct delayed_work work;
	/* under the chip lock */
	enum mcp2510_watch_state state;
	/* failed a health check, not back yet: whatever INT does meanwhile */
	bool recovering;
	unsigned int backoff_ms;	/* polling time before INT is retried */
	unsigned long poll_until;	/* jiffies */
	unsigned long irq_back_at;	/* jiffies: INT enabled again */
	unsigned long unhandled_since;	/* jiffies: start of the counting */
	unsigned int unhandled_irqs;	/* calls that handled nothing or failed */
	atomic_t irqs_fired;		/* hard IRQs, ever */
	int irqs_seen;			/* irqs_fired when the thread last ran */
	/* ethtool -S, under the names exported */
	u64 irq_storms;			/* storms, however long each polled */
	u64 missed_interrupts;		/* work found by polling an edge line */
};

struct mcp2510_priv {
	struct can_priv can;		/* first: the CAN core expects it */
	struct can_rx_offload offload;	/* frames for the stack, in order */
	/* received frames queued for the stack less those dropped at close */
	unsigned long rx_packets;
	unsigned long rx_bytes;
	/* receive timestamps (rx.c) */
	atomic64_t rx_irq_ns;		/* INT fired, CLOCK_REALTIME; 0: none */
	ktime_t rx_first_ts;		/* for the next frame of the pass */
	ktime_t rx_pass_ts;		/* for the pass's later ones */
	bool rx_in_pass;		/* between rx_pass and the unlock */
	struct net_device *ndev;
	struct spi_device *spi;
	struct regulator *vdd;
	struct regulator *xceiver;
	struct clk *clk;

	/*
	 * Serialises every call into the core and every SPI transfer: the
	 * IRQ thread, the TX work, netdev/ethtool/gpio callbacks and PM all
	 * talk to the one chip.
	 */
	struct mutex lock;
	struct mcp2510_chip chip;
	u8 *spi_tx;			/* DMA-safe bounce buffers, under lock */
	u8 *spi_rx;
	/* a message's transfers: up to two per period (spi.c), under lock */
	struct spi_transfer spi_xfers[2 * MCP2510_XFER_MSG_MAX];
	unsigned long irq_flags;	/* trigger type for request_irq */

	/*
	 * TX: start_xmit queues skbs here (it may not sleep) and the work
	 * loads them into the chip.  Queued, loading and in-flight frames
	 * never exceeds the three hardware buffers, so the netdev queue is
	 * stopped exactly when all of them are taken.
	 */
	spinlock_t tx_lock;
	struct sk_buff *tx_fifo[MCP2510_TXB_COUNT];
	unsigned int tx_fifo_head;
	unsigned int tx_fifo_len;
	bool tx_loading;		/* the work holds a popped skb */
	u8 tx_inflight;			/* bit n: TX buffer n holds a frame */
	/* BQL: frames ended in this hold of the chip lock, under lock */
	unsigned int tx_done_frames;
	unsigned int tx_done_bytes;
	struct work_struct tx_work;

	/* netdev.c: a failed restart's carrier and retry, after can-dev's */
	struct work_struct restart_failed_work;

	/* sysfs acceptance filters, programmed into the chip on open */
	struct mcp2510_filters filters;

	/* gpiochip: RXnBF levels to restore after each chip reset */
	struct gpio_chip gpio;
	u8 bf_set;			/* bit n: RXnBF driven by gpiolib */
	u8 bf_level;			/* bit n: RXnBF high */

	struct mcp2510_watch watch;

	enum mcp2510_dev_state state;	/* state.c: through its functions */
	/*
	 * The interface was up at suspend: what resume brings back.  Not a
	 * state of the device, which a failed resume may leave OFF with the
	 * interface up.
	 */
	bool suspended_running;
};

/* spi.c: the core's transport and the chip lock */
extern const struct mcp2510_ops mcp2510_spi_ops;
void mcp2510_lock(struct mcp2510_priv *priv);
void mcp2510_unlock(struct mcp2510_priv *priv);

/* events.c: the core's reports turned into skbs and statistics */
extern const struct mcp2510_events mcp2510_netdev_events;

/* rx.c */
int mcp2510_rx_init(struct mcp2510_priv *priv);
void mcp2510_rx_queue(struct mcp2510_priv *priv, struct sk_buff *skb);
unsigned int mcp2510_rx_queue_echo(struct mcp2510_priv *priv,
				   unsigned int slot, unsigned int *frame_len);
void mcp2510_rx_deliver(struct mcp2510_priv *priv);
void mcp2510_rx_stamp_irq(struct mcp2510_priv *priv);
void mcp2510_rx_pass(struct mcp2510_priv *priv, bool first_waited);
ktime_t mcp2510_rx_stamp_frame(struct mcp2510_priv *priv);
ktime_t mcp2510_rx_stamp_event(struct mcp2510_priv *priv);
void mcp2510_get_stats64(struct net_device *ndev,
			 struct rtnl_link_stats64 *stats);
void mcp2510_rx_disable(struct mcp2510_priv *priv);
void mcp2510_rx_del(struct mcp2510_priv *priv);

/* netdev.c */
extern const struct net_device_ops mcp2510_netdev_ops;
int mcp2510_do_set_mode(struct net_device *ndev, enum can_mode mode);
int mcp2510_do_get_berr_counter(const struct net_device *ndev,
				struct can_berr_counter *bec);
int mcp2510_hw_up(struct mcp2510_priv *priv);
void mcp2510_hw_down(struct mcp2510_priv *priv);
void mcp2510_restart_init(struct mcp2510_priv *priv);
void mcp2510_restart_cancel(struct mcp2510_priv *priv);
int mcp2510_chip_reset_sleep(struct mcp2510_priv *priv);
void mcp2510_halt_locked(struct mcp2510_priv *priv);

/* tx.c */
netdev_tx_t mcp2510_start_xmit(struct sk_buff *skb, struct net_device *ndev);
void mcp2510_tx_work(struct work_struct *work);
void mcp2510_tx_slot_release(struct mcp2510_priv *priv, unsigned int slot,
			     unsigned int bytes);
void mcp2510_tx_report_done(struct mcp2510_priv *priv);
void mcp2510_tx_retry(struct mcp2510_priv *priv);
void mcp2510_tx_flush(struct mcp2510_priv *priv);
void mcp2510_tx_wake_queue(struct mcp2510_priv *priv);

/* irq.c */
irqreturn_t mcp2510_irq_hard(int irq, void *data);
irqreturn_t mcp2510_irq_thread(int irq, void *data);
unsigned long mcp2510_irq_trigger(struct mcp2510_priv *priv);

/* watch.c */
void mcp2510_watch_init(struct mcp2510_priv *priv);
void mcp2510_watch_start(struct mcp2510_priv *priv);
void mcp2510_watch_stop(struct mcp2510_priv *priv);
void mcp2510_watch_storm(struct mcp2510_priv *priv);

/* ethtool_stats.c */
int mcp2510_get_sset_count(struct net_device *ndev, int sset);
void mcp2510_get_strings(struct net_device *ndev, u32 sset, u8 *data);
void mcp2510_get_ethtool_stats(struct net_device *ndev,
			       struct ethtool_stats *stats, u64 *data);

/* sysfs.c */
extern const struct attribute_group mcp2510_filter_group;

/* gpio.c */
int mcp2510_gpio_register(struct mcp2510_priv *priv);
void mcp2510_gpio_unregister(struct mcp2510_priv *priv);
void mcp2510_gpio_restore(struct mcp2510_priv *priv);

/* ethtool.c */
extern const struct ethtool_ops mcp2510_ethtool_ops;

/* state.c */
enum mcp2510_dev_state mcp2510_dev_state(const struct mcp2510_priv *priv);
bool mcp2510_dev_running(const struct mcp2510_priv *priv);
void mcp2510_dev_enter(struct mcp2510_priv *priv, enum mcp2510_dev_state to);

/* pm.c */
extern const struct dev_pm_ops mcp2510_pm_ops;
int mcp2510_power_on(struct mcp2510_priv *priv);
void mcp2510_power_off(struct mcp2510_priv *priv);

#endif /* MCP2510_PRIV_H */
