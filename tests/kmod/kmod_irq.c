// SPDX-License-Identifier: GPL-2.0
/*
 * The chips' output pins (INT, RX0BF, RX1BF) as lines of one GPIO chip with
 * an interrupt controller, so a driver gets the INT interrupt through the
 * ordinary irq API and libgpiod sees the same pin as a GPIO line.
 *
 * Line numbering: pin-major, so INTn is line n for chip n; RX0BF of chip n
 * is line nchips + n and RX1BF line 2 * nchips + n.
 *
 * The model reports pin changes from under sim->lock, in process or
 * softirq context, where no interrupt handler may run.  Delivery therefore
 * goes through a hard irq_work, which hands the interrupt to the flow
 * handler in hard-irq context as a real GPIO controller's demultiplexer
 * would.  A level interrupt that is still asserted when it is unmasked
 * fires again, the way a level input keeps the parent interrupt raised.
 *
 * With SPI time on, every delivery waits the interrupt latency first (an
 * hrtimer, then the same irq_work); kmod_logic.c keeps the lines' state.
 */
#include <linux/gpio/driver.h>
#include <linux/hrtimer.h>
#include <linux/irq.h>
#include <linux/irq_work.h>
#include <linux/irqdesc.h>
#include <linux/irqdomain.h>
#include <linux/of.h>

#include "kmod.h"

static const char *const pin_names[SIM_PIN_COUNT] = {
	[SIM_PIN_INT] = "INT",
	[SIM_PIN_RX0BF] = "RX0BF",
	[SIM_PIN_RX1BF] = "RX1BF",
};

static const struct {
	const char *name;
	unsigned int type;
} triggers[] = {
	{ "level-low", IRQ_TYPE_LEVEL_LOW },
	{ "level-high", IRQ_TYPE_LEVEL_HIGH },
	{ "edge-falling", IRQ_TYPE_EDGE_FALLING },
	{ "edge-rising", IRQ_TYPE_EDGE_RISING },
	{ "edge-both", IRQ_TYPE_EDGE_BOTH },
};

const char *mcp2510_sim_trigger_name(unsigned int type)
{
	size_t i;

	for (i = 0; i < ARRAY_SIZE(triggers); i++)
		if (triggers[i].type == type)
			return triggers[i].name;
	return "none";
}

int mcp2510_sim_trigger_parse(const char *name, unsigned int *type)
{
	size_t i;

	for (i = 0; i < ARRAY_SIZE(triggers); i++) {
		if (!strcmp(triggers[i].name, name)) {
			*type = triggers[i].type;
			return 0;
		}
	}
	return -EINVAL;
}

unsigned int mcp2510_sim_line(const struct mcp2510_sim *sim, unsigned int chip,
			      enum sim_pin pin)
{
	return pin * sim->nchips + chip;
}

/* Under irq_lock: the earliest delayed delivery gets the timer. */
static void arm_irq_timer(struct mcp2510_sim *sim, u64 due)
{
	struct hrtimer *t = &sim->irq_timer;

	if (hrtimer_is_queued(t) && ktime_to_ns(hrtimer_get_expires(t)) <= due)
		return;
	hrtimer_start(t, ns_to_ktime(due), HRTIMER_MODE_ABS_HARD);
}

/*
 * Under irq_lock, after something that may make the line want delivery:
 * true when the caller should queue the delivery pass now; a delivery
 * delayed by the interrupt latency gets the timer instead.
 */
static bool schedule_delivery(struct mcp2510_sim *sim,
			      struct mcp2510_sim_line *line)
{
	const struct sim_spi_timing *t = &sim->irq_timing;
	u64 delay;

	if (!t->enabled)
		return mcp2510_sim_line_kick(line, 0, 0);
	/* one draw per delivery: a kick while one is due leaves it be */
	if (line->due_set && !line->masked && mcp2510_sim_line_asserted(line))
		return false;
	delay = sim_spi_irq_latency_ns(t, &sim->irq_rng) * sim->irq_time_scale;
	if (mcp2510_sim_line_kick(line, ktime_get_ns(), delay))
		arm_irq_timer(sim, line->due_ns);
	return false;
}

static void pin_changed(void *ctx, struct sim_chip *model, enum sim_pin pin,
			bool level)
{
	struct mcp2510_sim_chip *chip = ctx;
	struct mcp2510_sim *sim = chip->sim;
	struct mcp2510_sim_line *line;
	unsigned long flags;
	bool kick;

	line = &sim->lines[mcp2510_sim_line(sim, chip->index, pin)];
	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	mcp2510_sim_line_set_level(line, level);
	kick = schedule_delivery(sim, line);
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	if (kick)
		irq_work_queue(&sim->irq_work);
}

static void deliver_pending(struct irq_work *work)
{
	struct mcp2510_sim *sim = container_of(work, struct mcp2510_sim, irq_work);
	u64 now = ktime_get_ns(), next_due = U64_MAX;
	unsigned int n;
	bool fire;

	for (n = 0; n < sim->gpio.ngpio; n++) {
		raw_spin_lock(&sim->irq_lock);
		fire = mcp2510_sim_line_take(&sim->lines[n], now, &next_due);
		raw_spin_unlock(&sim->irq_lock);
		if (fire)
			generic_handle_domain_irq(sim->gpio.irq.domain, n);
	}
	if (next_due == U64_MAX)
		return;
	raw_spin_lock(&sim->irq_lock);
	arm_irq_timer(sim, next_due);
	raw_spin_unlock(&sim->irq_lock);
}

static enum hrtimer_restart irq_timer_fired(struct hrtimer *timer)
{
	struct mcp2510_sim *sim = container_of(timer, struct mcp2510_sim,
					       irq_timer);

	irq_work_queue(&sim->irq_work);
	return HRTIMER_NORESTART;
}

/*
 * Under sim->lock, when SPI time, its seed or time_scale change: the
 * interrupt latency's distribution, drawn in real time (time_scale) for
 * each delivery.
 */
void mcp2510_sim_irq_set_delay(struct mcp2510_sim *sim)
{
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->irq_timing = sim->spi.timing;
	sim->irq_rng = sim->spi_seed;
	sim->irq_time_scale = sim->clock.time_scale;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static struct mcp2510_sim *irq_data_to_sim(struct irq_data *d)
{
	return gpiochip_get_data(irq_data_get_irq_chip_data(d));
}

static void line_mask(struct irq_data *d)
{
	struct mcp2510_sim *sim = irq_data_to_sim(d);
	irq_hw_number_t hwirq = irqd_to_hwirq(d);
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->lines[hwirq].masked = true;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	gpiochip_disable_irq(&sim->gpio, hwirq);
}

static void line_unmask(struct irq_data *d)
{
	struct mcp2510_sim *sim = irq_data_to_sim(d);
	irq_hw_number_t hwirq = irqd_to_hwirq(d);
	unsigned long flags;
	bool kick;

	gpiochip_enable_irq(&sim->gpio, hwirq);
	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->lines[hwirq].masked = false;
	kick = schedule_delivery(sim, &sim->lines[hwirq]);
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	if (kick)
		irq_work_queue(&sim->irq_work);
}

static void line_ack(struct irq_data *d)
{
	struct mcp2510_sim *sim = irq_data_to_sim(d);
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->lines[irqd_to_hwirq(d)].edge_pending = false;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

static int line_set_type(struct irq_data *d, unsigned int type)
{
	struct mcp2510_sim *sim = irq_data_to_sim(d);
	struct mcp2510_sim_line *line = &sim->lines[irqd_to_hwirq(d)];
	irq_flow_handler_t flow;
	unsigned long flags;

	switch (type & IRQ_TYPE_SENSE_MASK) {
	case IRQ_TYPE_LEVEL_LOW:
	case IRQ_TYPE_LEVEL_HIGH:
		flow = handle_level_irq;
		break;
	case IRQ_TYPE_EDGE_FALLING:
	case IRQ_TYPE_EDGE_RISING:
	case IRQ_TYPE_EDGE_BOTH:
		flow = handle_edge_irq;
		break;
	default:
		return -EINVAL;
	}
	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	line->type = type & IRQ_TYPE_SENSE_MASK;
	/* an edge seen under the old trigger type is not one of the new type */
	line->edge_pending = false;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	irq_set_handler_locked(d, flow);
	return 0;
}

static const struct irq_chip line_irq_chip = {
	.name = MCP2510_SIM_NAME,
	.irq_mask = line_mask,
	.irq_unmask = line_unmask,
	.irq_ack = line_ack,
	.irq_set_type = line_set_type,
	/* no wake-up hardware to program: let drivers mark INT as a wake source */
	.flags = IRQCHIP_IMMUTABLE | IRQCHIP_SKIP_SET_WAKE,
	GPIOCHIP_IRQ_RESOURCE_HELPERS,
};

static int line_get(struct gpio_chip *gc, unsigned int offset)
{
	struct mcp2510_sim *sim = gpiochip_get_data(gc);
	unsigned long flags;
	bool level;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	level = sim->lines[offset].level;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	return level;
}

/* The chip's pins are outputs, so the lines are inputs of this controller. */
static int line_get_direction(struct gpio_chip *gc, unsigned int offset)
{
	return GPIO_LINE_DIRECTION_IN;
}

static int line_direction_input(struct gpio_chip *gc, unsigned int offset)
{
	return 0;
}

void mcp2510_sim_irq_init(struct mcp2510_sim *sim)
{
	raw_spin_lock_init(&sim->irq_lock);
	sim->irq_work = IRQ_WORK_INIT_HARD(deliver_pending);
	hrtimer_setup(&sim->irq_timer, irq_timer_fired, CLOCK_MONOTONIC,
		      HRTIMER_MODE_ABS_HARD);
}

/* Before the GPIO chip exists: route the model's pin changes to the lines. */
void mcp2510_sim_irq_attach(struct mcp2510_sim_chip *chip)
{
	struct mcp2510_sim *sim = chip->sim;
	struct mcp2510_sim_line *line;
	enum sim_pin pin;
	unsigned int n;

	for (pin = 0; pin < SIM_PIN_COUNT; pin++) {
		n = mcp2510_sim_line(sim, chip->index, pin);
		line = &sim->lines[n];
		line->level = sim_chip_pin(&chip->model, pin);
		line->masked = true;
		line->type = IRQ_TYPE_LEVEL_LOW;
		snprintf(sim->line_names[n], sizeof(sim->line_names[n]), "%s%u",
			 pin_names[pin], chip->index);
		sim->line_name_ptrs[n] = sim->line_names[n];
	}
	sim_chip_set_pin_cb(&chip->model, pin_changed, chip);
}

int mcp2510_sim_irq_register(struct mcp2510_sim *sim)
{
	struct gpio_chip *gc = &sim->gpio;
	struct gpio_irq_chip *girq = &gc->irq;

	gc->label = MCP2510_SIM_NAME;
	gc->parent = sim->root;
	gc->fwnode = of_fwnode_handle(sim->of_gpio);
	gc->owner = THIS_MODULE;
	gc->base = -1;
	gc->ngpio = sim->nchips * SIM_PIN_COUNT;
	gc->names = sim->line_name_ptrs;
	gc->get = line_get;
	gc->get_direction = line_get_direction;
	gc->direction_input = line_direction_input;

	gpio_irq_chip_set_chip(girq, &line_irq_chip);
	girq->handler = handle_level_irq;
	/*
	 * As on boards: INT is an open-drain, active-low level output.  A
	 * device tree gives the trigger in each interrupt specifier instead,
	 * and gpiolib warns about a default next to one.
	 */
	girq->default_type = sim->of_gpio ? IRQ_TYPE_NONE : IRQ_TYPE_LEVEL_LOW;

	return gpiochip_add_data(gc, sim);
}

/* After the bus timer has stopped, so no pin changes anymore. */
void mcp2510_sim_irq_unregister(struct mcp2510_sim *sim)
{
	/* a delivery pass may re-arm the timer once more */
	hrtimer_cancel(&sim->irq_timer);
	irq_work_sync(&sim->irq_work);
	hrtimer_cancel(&sim->irq_timer);
	gpiochip_remove(&sim->gpio);
}

/* The Linux irq of a line, mapped on first use as gpiod_to_irq() would. */
int mcp2510_sim_irq_of(struct mcp2510_sim *sim, unsigned int line)
{
	unsigned int irq = irq_create_mapping(sim->gpio.irq.domain, line);

	return irq ? irq : -ENXIO;
}

void mcp2510_sim_irq_miss_edges(struct mcp2510_sim *sim, unsigned int line,
				u32 count)
{
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->lines[line].edge_miss = count;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

void mcp2510_sim_irq_reset_counts(struct mcp2510_sim *sim, unsigned int line)
{
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	sim->lines[line].delivered = 0;
	sim->lines[line].edges_missed = 0;
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}

void mcp2510_sim_irq_describe(struct mcp2510_sim *sim, unsigned int line,
			      struct mcp2510_sim_line *out)
{
	unsigned long flags;

	raw_spin_lock_irqsave(&sim->irq_lock, flags);
	*out = sim->lines[line];
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
}
