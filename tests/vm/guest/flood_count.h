/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The frames of a counted flood and the count of what arrived, without
 * any I/O: can-flood (tests/vm/guest) sends and receives through it, and
 * tests/unit/test_flood_count.c checks it on the host.
 *
 * Frame n of a flood (n = 0 .. count - 1) is a standard or extended frame
 * with the flood's identifier and eight data bytes:
 *
 *   bytes 0-3  the sequence number, start + n, little-endian
 *   bytes 4-7  the check word: a CRC-32 of the identifier (four bytes,
 *              little-endian) and bytes 0-3, little-endian; or, in a flood
 *              with a fixed check word, that word whatever n is
 *
 * The fixed word is for a sender that can only count, such as the
 * simulator's phantom node: its flood adds n to bytes 0-3 of one frame
 * and leaves bytes 4-7 alone.  Then a damaged sequence number is seen as
 * one frame lost and another duplicated or out of range (corrupted).
 *
 * Each frame received is exactly one of
 *   corrupted   not a frame of the flood: another identifier or length,
 *               a remote or error frame, a sequence number outside the
 *               flood, or a wrong check word
 *   duplicated  a frame of the flood already received
 *   reordered   received after a frame with a higher sequence number
 *   in order    none of these
 * and lost are the frames of the flood never received.
 */
#ifndef FLOOD_COUNT_H
#define FLOOD_COUNT_H

#include <errno.h>
#include <linux/can.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

struct flood {
	canid_t id;		/* with CAN_EFF_FLAG for an extended one */
	uint32_t start;		/* sequence number of frame 0 */
	uint32_t count;
	int fixed;		/* 1: the check word is @word */
	uint32_t word;
};

struct flood_count {
	uint32_t received, unique, duplicated, reordered, corrupted;
	uint32_t highest;	/* highest n received; valid with unique */
	unsigned char *seen;	/* a bit per frame of the flood */
};

static inline uint32_t flood_le32(const unsigned char *b)
{
	return b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
	       (uint32_t)b[3] << 24;
}

static inline void flood_put_le32(unsigned char *b, uint32_t v)
{
	int i;

	for (i = 0; i < 4; i++)
		b[i] = (unsigned char)(v >> (8 * i));
}

/* CRC-32 (reflected, polynomial 0xEDB88320) of @len bytes at @p */
static inline uint32_t flood_crc32(const unsigned char *p, size_t len)
{
	uint32_t crc = 0xffffffff;
	int bit;

	while (len--) {
		crc ^= *p++;
		for (bit = 0; bit < 8; bit++)
			crc = (crc >> 1) ^ (0xedb88320 & -(crc & 1));
	}
	return ~crc;
}

static inline uint32_t flood_check_word(const struct flood *f, uint32_t seq)
{
	unsigned char b[8];

	if (f->fixed)
		return f->word;
	flood_put_le32(b, f->id);
	flood_put_le32(b + 4, seq);
	return flood_crc32(b, sizeof(b));
}

/* frame @n of flood @f */
static inline struct can_frame flood_frame(const struct flood *f, uint32_t n)
{
	struct can_frame cf = { .can_id = f->id, .len = 8 };
	uint32_t seq = f->start + n;

	flood_put_le32(cf.data, seq);
	flood_put_le32(cf.data + 4, flood_check_word(f, seq));
	return cf;
}

/* 0, or -1 without memory for the flood's bitmap */
static inline int flood_count_init(struct flood_count *c, const struct flood *f)
{
	memset(c, 0, sizeof(*c));
	c->seen = calloc(f->count / 8 + 1, 1);
	return c->seen ? 0 : -1;
}

static inline void flood_count_free(struct flood_count *c)
{
	free(c->seen);
	c->seen = NULL;
}

/* takes one received frame into @c */
static inline void flood_count_frame(struct flood_count *c, const struct flood *f,
			      const struct can_frame *cf)
{
	uint32_t seq, n;

	c->received++;
	if (cf->can_id != f->id || cf->len != 8) {
		c->corrupted++;
		return;
	}
	seq = flood_le32(cf->data);
	n = seq - f->start;
	if (n >= f->count || flood_le32(cf->data + 4) != flood_check_word(f, seq)) {
		c->corrupted++;
		return;
	}
	if (c->seen[n / 8] & (1u << (n % 8))) {
		c->duplicated++;
		return;
	}
	c->seen[n / 8] |= 1u << (n % 8);
	if (c->unique && n < c->highest)
		c->reordered++;
	else
		c->highest = n;
	c->unique++;
}

static inline uint32_t flood_lost(const struct flood_count *c, const struct flood *f)
{
	return f->count - c->unique;
}

/* every frame of the flood came once, in order, intact, and nothing else */
static inline int flood_lossless(const struct flood_count *c, const struct flood *f)
{
	return !flood_lost(c, f) && !c->duplicated && !c->reordered &&
	       !c->corrupted;
}

/* @s, a whole unsigned number in @base, into *@v: 0, or -1 */
static inline int flood_number(const char *s, int base, unsigned long *v)
{
	char *end;

	errno = 0;
	*v = strtoul(s, &end, base);
	return errno || !*s || *end ? -1 : 0;
}

/* @s, an identifier in hex (eight digits: extended), into *@id: 0, or -1 */
static inline int flood_id(const char *s, canid_t *id)
{
	unsigned long v;

	if (flood_number(s, 16, &v) || v > CAN_EFF_MASK)
		return -1;
	*id = (canid_t)v | (strlen(s) == 8 ? CAN_EFF_FLAG : 0);
	return 0;
}

static inline int flood_hex(int ch)
{
	if (ch >= '0' && ch <= '9')
		return ch - '0';
	if (ch >= 'a' && ch <= 'f')
		return ch - 'a' + 10;
	if (ch >= 'A' && ch <= 'F')
		return ch - 'A' + 10;
	return -1;
}

/*
 * The frame in one line of text, in cansend syntax (123#11223344,
 * 12345678#11, 123#R): the first word with a '#' in it, so that lines of
 * candump -L and of the simulator's bus monitor both do.  0, or -1 when
 * the line holds no frame or says "error" (a frame an error destroyed,
 * in the monitor).  Data bytes may be separated by dots.
 */
static inline int flood_text_frame(const char *line, struct can_frame *cf)
{
	const char *p, *hash = strchr(line, '#');
	int digits = 0, hi, lo;

	if (!hash || strstr(line, "error"))
		return -1;
	for (p = hash; p > line && p[-1] != ' ' && p[-1] != '\t'; p--)
		digits++;
	memset(cf, 0, sizeof(*cf));
	for (; p < hash; p++) {
		if (flood_hex(*p) < 0)
			return -1;
		cf->can_id = cf->can_id << 4 | (canid_t)flood_hex(*p);
	}
	if (digits == 8)
		cf->can_id |= CAN_EFF_FLAG;
	else if (digits != 3)
		return -1;
	for (p = hash + 1; *p == 'R' || flood_hex(*p) >= 0 || *p == '.';) {
		if (*p == 'R') {
			cf->can_id |= CAN_RTR_FLAG;
			return 0;
		}
		if (*p == '.') {
			p++;
			continue;
		}
		hi = flood_hex(p[0]);
		lo = flood_hex(p[1]);
		if (lo < 0 || cf->len == CAN_MAX_DLEN)
			return -1;
		cf->data[cf->len++] = (unsigned char)(hi << 4 | lo);
		p += 2;
	}
	return 0;
}

#endif /* FLOOD_COUNT_H */
