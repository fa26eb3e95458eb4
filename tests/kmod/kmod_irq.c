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
 */
#include <linux/gpio/driver.h>
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

static bool line_asserted(const struct mcp2510_sim_line *line)
{
	switch (line->type & IRQ_TYPE_SENSE_MASK) {
	case IRQ_TYPE_LEVEL_LOW:
		return !line->level;
	case IRQ_TYPE_LEVEL_HIGH:
		return line->level;
	default:
		return line->edge_pending;
	}
}

static bool line_wants_delivery(const struct mcp2510_sim_line *line)
{
	return !line->masked && line_asserted(line);
}

/* Called with irq_lock held, before line->level takes the new value. */
static void latch_edge(struct mcp2510_sim_line *line, bool level)
{
	bool rising = level && !line->level;
	bool falling = !level && line->level;

	if (!(rising && (line->type & IRQ_TYPE_EDGE_RISING)) &&
	    !(falling && (line->type & IRQ_TYPE_EDGE_FALLING)))
		return;
	if (falling && line->edge_miss) {
		line->edge_miss--;
		line->edges_missed++;
		return;
	}
	line->edge_pending = true;
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
	latch_edge(line, level);
	line->level = level;
	kick = line_wants_delivery(line);
	raw_spin_unlock_irqrestore(&sim->irq_lock, flags);
	if (kick)
		irq_work_queue(&sim->irq_work);
}

static void deliver_pending(struct irq_work *work)
{
	struct mcp2510_sim *sim = container_of(work, struct mcp2510_sim, irq_work);
	struct mcp2510_sim_line *line;
	unsigned int n;
	bool fire;

	for (n = 0; n < sim->gpio.ngpio; n++) {
		line = &sim->lines[n];
		raw_spin_lock(&sim->irq_lock);
		fire = line_wants_delivery(line);
		if (fire)
			line->delivered++;
		raw_spin_unlock(&sim->irq_lock);
		if (fire)
			generic_handle_domain_irq(sim->gpio.irq.domain, n);
	}
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
	kick = line_wants_delivery(&sim->lines[hwirq]);
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
	irq_work_sync(&sim->irq_work);
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
