/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Reading a fuzzer's input as structured values.
 *
 * Two independent streams share the one buffer: the front holds data
 * (bytes a simulated peer sends, register contents a hostile chip
 * returns), the back holds decisions (which operation comes next, its
 * arguments).  Keeping them apart means a mutation of the data does not
 * shift every later decision, which lets the fuzzer change one without
 * scrambling the other.  When a stream runs dry it yields zeros: every
 * input is valid and inputs stay short.
 */
#ifndef FUZZ_INPUT_H
#define FUZZ_INPUT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct fuzz_input {
	const uint8_t *data;
	size_t front;		/* next unread byte from the front */
	size_t back;		/* one past the next unread byte from the back */
};

void fuzz_input_init(struct fuzz_input *in, const uint8_t *data, size_t size);
/* Bytes left for either stream. */
size_t fuzz_input_left(const struct fuzz_input *in);

/* Up to @len bytes off the front into @buf; returns how many. */
size_t fuzz_front_bytes(struct fuzz_input *in, uint8_t *buf, size_t len);

/* Decisions, from the back; 0 when nothing is left. */
uint8_t fuzz_back_u8(struct fuzz_input *in);
uint16_t fuzz_back_u16(struct fuzz_input *in);
uint32_t fuzz_back_u32(struct fuzz_input *in);
bool fuzz_back_bool(struct fuzz_input *in);
/* 0 .. @n - 1 (n > 0) */
unsigned int fuzz_back_below(struct fuzz_input *in, unsigned int n);

#endif /* FUZZ_INPUT_H */
