// SPDX-License-Identifier: GPL-2.0
/* Structured reads from a fuzzer's input (see fuzz_input.h). */
#include <string.h>

#include "fuzz_input.h"

void fuzz_input_init(struct fuzz_input *in, const uint8_t *data, size_t size)
{
	in->data = data;
	in->front = 0;
	in->back = size;
}

size_t fuzz_input_left(const struct fuzz_input *in)
{
	return in->back - in->front;
}

size_t fuzz_front_bytes(struct fuzz_input *in, uint8_t *buf, size_t len)
{
	size_t n = fuzz_input_left(in);

	if (n > len)
		n = len;
	if (n)
		memcpy(buf, in->data + in->front, n);
	in->front += n;
	return n;
}

uint8_t fuzz_back_u8(struct fuzz_input *in)
{
	if (!fuzz_input_left(in))
		return 0;
	return in->data[--in->back];
}

uint16_t fuzz_back_u16(struct fuzz_input *in)
{
	uint16_t v = fuzz_back_u8(in);

	return (uint16_t)(v << 8 | fuzz_back_u8(in));
}

uint32_t fuzz_back_u32(struct fuzz_input *in)
{
	uint32_t v = fuzz_back_u16(in);

	return v << 16 | fuzz_back_u16(in);
}

bool fuzz_back_bool(struct fuzz_input *in)
{
	return fuzz_back_u8(in) & 1;
}

unsigned int fuzz_back_below(struct fuzz_input *in, unsigned int n)
{
	return fuzz_back_u8(in) % n;
}
