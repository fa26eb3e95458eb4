// SPDX-License-Identifier: GPL-2.0
/*
 * The phantom node: a node on the simulated bus with no chip behind it,
 * which acknowledges every frame, sends what a test queues or floods at
 * bus speed, and never leaves error-active.  sim_bus.c asks it for its
 * next frame at arbitration and tells it when that frame went out.
 */
#include "sim_private.h"

static u32 sim_rate_to_ns(u32 bitrate)
{
	return bitrate ? (SIM_NS_PER_SEC + bitrate / 2) / bitrate : 0;
}

/*
 * The phantom's timing at bit time ns: an ideal node, which tolerates
 * whatever the node it talks to tolerates.
 */
void sim_phantom_timing(u32 ns, struct sim_timing *t)
{
	memset(t, 0, sizeof(*t));
	t->ns = ns;
	t->valid = true;
}

/* bit time the phantom listens at; 0 means it follows whatever is sent */
u32 sim_phantom_rx_ns(const struct sim_bus *bus)
{
	if (bus->phantom.bitrate)
		return sim_rate_to_ns(bus->phantom.bitrate);
	return bus->nchips ? sim_chip_bit_ns(bus->chips[0]) : 0;
}

u32 sim_phantom_pending(const struct sim_bus *bus)
{
	const struct sim_phantom *ph = &bus->phantom;

	return ph->attached ? ph->count + ph->flood_left : 0;
}

static void sim_put_le32(u8 *b, u32 v)
{
	unsigned int i;

	for (i = 0; i < 4; i++)
		b[i] = v >> (8 * i);
}

/* CRC-32, reflected, polynomial 0xEDB88320: the check of a checked flood */
static u32 sim_crc32(const u8 *p, unsigned int len)
{
	u32 crc = 0xffffffff;
	unsigned int bit;

	while (len--) {
		crc ^= *p++;
		for (bit = 0; bit < 8; bit++)
			crc = (crc >> 1) ^ (0xedb88320 & -(crc & 1));
	}
	return ~crc;
}

/*
 * frame k of a flood: the first min(len, 4) data bytes, little endian, + k;
 * in a checked flood bytes 4-7 then carry the CRC-32 of the id and bytes 0-3
 */
static void sim_flood_frame(const struct sim_phantom *ph, struct can_frame *cf)
{
	unsigned int n = ph->flood.len < 4 ? ph->flood.len : 4, i;
	u8 checked[8];
	u32 v = 0;

	*cf = ph->flood;
	for (i = 0; i < n; i++)
		v |= (u32)cf->data[i] << (8 * i);
	v += ph->flood_sent;
	for (i = 0; i < n; i++)
		cf->data[i] = v >> (8 * i);
	if (!ph->flood_checked)
		return;
	sim_put_le32(checked, cf->can_id);
	memcpy(checked + 4, cf->data, 4);
	sim_put_le32(cf->data + 4, sim_crc32(checked, sizeof(checked)));
}

/* The phantom's next frame and its bit time; false if it has none. */
bool sim_phantom_peek(const struct sim_bus *bus, struct can_frame *cf, u32 *ns)
{
	const struct sim_phantom *ph = &bus->phantom;

	if (!ph->attached)
		return false;
	if (ph->count) {
		*cf = ph->queue[ph->head];
		*ns = ph->queue_rate[ph->head];
		return true;
	}
	if (ph->flood_left) {
		sim_flood_frame(ph, cf);
		*ns = ph->flood_rate;
		return true;
	}
	return false;
}

void sim_phantom_sent(struct sim_bus *bus)
{
	struct sim_phantom *ph = &bus->phantom;

	if (ph->count) {
		ph->head = (ph->head + 1) % SIM_PHANTOM_QUEUE;
		ph->count--;
	} else if (ph->flood_left) {
		ph->flood_left--;
		ph->flood_sent++;
	}
}

void sim_phantom_attach(struct sim_bus *bus, u32 bitrate)
{
	bus->phantom.attached = true;
	bus->phantom.bitrate = bitrate;
}

void sim_phantom_detach(struct sim_bus *bus)
{
	memset(&bus->phantom, 0, sizeof(bus->phantom));
}

/* bit time for a phantom frame: its own rate, or the first chip's */
static int sim_phantom_frame_ns(struct sim_bus *bus, const struct can_frame *cf,
				u32 bitrate, u32 *ns)
{
	if (!cf || cf->len > CAN_MAX_DLEN || bitrate > SIM_NS_PER_SEC)
		return -EINVAL;
	*ns = bitrate ? sim_rate_to_ns(bitrate) :
	      bus->nchips ? sim_chip_bit_ns(bus->chips[0]) : 0;
	if (!*ns)
		return -EINVAL;
	if (!bus->phantom.attached)
		sim_phantom_attach(bus, bitrate);
	return 0;
}

int sim_phantom_send(struct sim_bus *bus, const struct can_frame *cf, u32 bitrate)
{
	struct sim_phantom *ph = &bus->phantom;
	unsigned int slot;
	u32 ns;
	int ret;

	if (ph->count >= SIM_PHANTOM_QUEUE)
		return -ENOSPC;
	ret = sim_phantom_frame_ns(bus, cf, bitrate, &ns);
	if (ret)
		return ret;
	slot = (ph->head + ph->count) % SIM_PHANTOM_QUEUE;
	ph->queue[slot] = *cf;
	ph->queue_rate[slot] = ns;
	ph->count++;
	return 0;
}

int sim_phantom_flood(struct sim_bus *bus, const struct can_frame *cf,
		      u32 count, u32 bitrate)
{
	struct sim_phantom *ph = &bus->phantom;
	u32 ns;
	int ret;

	if (ph->flood_left)
		return -EBUSY;
	ret = sim_phantom_frame_ns(bus, cf, bitrate, &ns);
	if (ret)
		return ret;
	ph->flood = *cf;
	ph->flood_rate = ns;
	ph->flood_left = count;
	ph->flood_sent = 0;
	ph->flood_checked = false;
	return 0;
}

int sim_phantom_flood_checked(struct sim_bus *bus, const struct can_frame *cf,
			      u32 count, u32 bitrate)
{
	int ret;

	if (cf->len != 8 || cf->can_id & CAN_RTR_FLAG)
		return -EINVAL;
	ret = sim_phantom_flood(bus, cf, count, bitrate);
	if (!ret)
		bus->phantom.flood_checked = true;
	return ret;
}
