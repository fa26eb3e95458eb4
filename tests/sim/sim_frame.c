// SPDX-License-Identifier: GPL-2.0
/*
 * What a CAN 2.0B frame looks like on the wire: its length in bits,
 * including the stuff bits its real bit pattern needs, and its place in
 * arbitration.
 */
#include "sim_private.h"

/* SOF + 29-bit id + SRR/IDE/RTR + r1/r0 + DLC + 64 data bits + CRC 15 */
#define SIM_MAX_UNSTUFFED	(1 + 29 + 3 + 2 + 4 + 64 + 15)
#define SIM_CRC15_POLY		0x4599
/* CRC delimiter, ACK slot and delimiter, EOF, intermission */
#define SIM_FRAME_TAIL_BITS	(1 + 2 + 7 + 3)

struct sim_bits {
	u8 bit[SIM_MAX_UNSTUFFED];
	unsigned int len;
};

static void sim_bits_put(struct sim_bits *b, u32 value, unsigned int width)
{
	while (width--)
		b->bit[b->len++] = (value >> width) & 1;
}

static unsigned int sim_frame_dlc(const struct can_frame *cf)
{
	if (cf->len == CAN_MAX_DLEN && cf->len8_dlc > CAN_MAX_DLEN &&
	    cf->len8_dlc <= 15)
		return cf->len8_dlc;
	return cf->len > CAN_MAX_DLEN ? CAN_MAX_DLEN : cf->len;
}

/* CAN CRC-15 over the bits so far, appended to them */
static void sim_bits_put_crc(struct sim_bits *b)
{
	u32 crc = 0;
	unsigned int i;

	for (i = 0; i < b->len; i++) {
		u32 next = b->bit[i] ^ ((crc >> 14) & 1);

		crc = (crc << 1) & 0x7fff;
		if (next)
			crc ^= SIM_CRC15_POLY;
	}
	sim_bits_put(b, crc, 15);
}

/* Destuffed bit sequence from SOF to the end of the CRC sequence. */
static void sim_frame_encode(const struct can_frame *cf, struct sim_bits *b)
{
	bool rtr = cf->can_id & CAN_RTR_FLAG;
	unsigned int dlc = sim_frame_dlc(cf);
	unsigned int len = rtr ? 0 : (dlc > CAN_MAX_DLEN ? CAN_MAX_DLEN : dlc);
	unsigned int i;

	b->len = 0;
	sim_bits_put(b, 0, 1);				/* SOF */
	if (cf->can_id & CAN_EFF_FLAG) {
		u32 id = cf->can_id & CAN_EFF_MASK;

		sim_bits_put(b, id >> 18, 11);
		sim_bits_put(b, 1, 1);			/* SRR */
		sim_bits_put(b, 1, 1);			/* IDE */
		sim_bits_put(b, id & 0x3ffff, 18);
		sim_bits_put(b, rtr, 1);
		sim_bits_put(b, 0, 2);			/* r1, r0 */
	} else {
		sim_bits_put(b, cf->can_id & CAN_SFF_MASK, 11);
		sim_bits_put(b, rtr, 1);
		sim_bits_put(b, 0, 2);			/* IDE, r0 */
	}
	sim_bits_put(b, dlc, 4);
	for (i = 0; i < len; i++)
		sim_bits_put(b, cf->data[i], 8);
	sim_bits_put_crc(b);
}

/*
 * After five equal bits the sender inserts one of the opposite level,
 * which starts the next run; this applies from SOF through the last CRC
 * bit (a stuff bit after the final CRC bit included).
 */
static unsigned int sim_stuff_bits(const struct sim_bits *b)
{
	unsigned int i, run = 1, stuffed = 0;
	u8 prev = b->bit[0];

	for (i = 1; i < b->len; i++) {
		if (b->bit[i] == prev) {
			run++;
		} else {
			prev = b->bit[i];
			run = 1;
		}
		if (run == 5) {
			stuffed++;
			prev = !prev;
			run = 1;
		}
	}
	return stuffed;
}

void sim_frame_measure(const struct can_frame *cf, struct sim_frame_info *info)
{
	struct sim_bits b;

	sim_frame_encode(cf, &b);
	info->stuffed_len = b.len + sim_stuff_bits(&b);
	info->bits = info->stuffed_len + SIM_FRAME_TAIL_BITS;
}

u32 sim_frame_bits(const struct can_frame *cf)
{
	struct sim_frame_info info;

	sim_frame_measure(cf, &info);
	return info.bits;
}

/*
 * The arbitration field as a number whose bits go out MSB first: a
 * dominant 0 wins, so the smaller key wins.  Standard: id, RTR, IDE=0.
 * Extended: base id, SRR=1, IDE=1, id extension, RTR.  Hence a data
 * frame beats a remote frame with the same id and a standard frame beats
 * an extended one with the same base id.
 */
u32 sim_frame_arbitration_key(const struct can_frame *cf)
{
	u32 rtr = !!(cf->can_id & CAN_RTR_FLAG);

	if (cf->can_id & CAN_EFF_FLAG) {
		u32 id = cf->can_id & CAN_EFF_MASK;

		return (id >> 18) << 21 | 1U << 20 | 1U << 19 |
		       (id & 0x3ffff) << 1 | rtr;
	}
	return (cf->can_id & CAN_SFF_MASK) << 21 | rtr << 20;
}

/*
 * Whether a node with timing t keeps in step with a node whose bit time
 * is d ns off its own: the CAN oscillator-tolerance conditions (Bosch,
 * "The Configuration of the CAN Bit Timing"), for a relative difference
 * of 2 df between two nodes each within df of the nominal rate:
 *	df <= SJW / (20 NBT)
 *	(stuffing leaves at most 10 bits between two recessive-to-dominant
 *	 edges; the phase error gathered meanwhile must fit in one
 *	 resynchronisation of at most SJW quanta),
 *	df <= min(PS1, PS2) / (2 (13 NBT - PS2))
 *	(around an error flag up to 13 bits pass without a usable edge, and
 *	 the sample point must stay within its phase segments).
 * Cross-multiplied: no division, d and the bit time fit in 32 bits.
 */
static bool sim_node_tolerates(const struct sim_timing *t, u32 d)
{
	u32 ps_min = t->ps1 < t->ps2 ? t->ps1 : t->ps2;

	if (!t->nbt)
		return true;	/* the ideal node */
	return (u64)d * (13U * t->nbt - t->ps2) <= (u64)ps_min * t->ns &&
	       (u64)d * 10U * t->nbt <= (u64)t->sjw * t->ns;
}

/*
 * Two nodes understand each other when both timings obey the data
 * sheets' rules and each tolerates the difference of their bit times.
 */
bool sim_timings_match(const struct sim_timing *a, const struct sim_timing *b)
{
	u32 d;

	if (!a->valid || !b->valid || !a->ns || !b->ns)
		return false;
	d = a->ns > b->ns ? a->ns - b->ns : b->ns - a->ns;
	if (!a->nbt && !b->nbt)
		return !d;
	return sim_node_tolerates(a, d) && sim_node_tolerates(b, d);
}
