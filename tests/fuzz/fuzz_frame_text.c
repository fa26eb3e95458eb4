// SPDX-License-Identifier: GPL-2.0
/*
 * cansend syntax in, candump syntax out (userspace/tools/frame_text.h).
 *
 * The input is the text, in a buffer of exactly its length plus the NUL,
 * so ASan sees any read past the end.  A frame the parser accepts must be
 * a valid classic CAN frame that survives formatting and parsing again
 * unchanged; a refusal must say why.  The same bytes, read as a struct
 * can_frame of any content (length 255, error flag, stray bits), must
 * format within the documented bounds, and the formatted text of any
 * frame that is not an error frame must parse back.
 */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "frame_text.h"
#include "fuzz_check.h"

#define LABEL		"can0"

static bool frame_equal(const struct can_frame *a, const struct can_frame *b)
{
	return a->can_id == b->can_id && a->len == b->len &&
	       !memcmp(a->data, b->data, sizeof(a->data));
}

static void check_parse(const uint8_t *data, size_t size)
{
	char *text = malloc(size + 1);
	char formatted[FRAME_TEXT_MAX];
	struct can_frame cf, again;
	const char *why = NULL;
	int n;

	FUZZ_CHECK(text);
	memcpy(text, data, size);
	text[size] = '\0';
	if (frame_parse(text, &cf, &why)) {
		FUZZ_CHECK(why && *why);
		free(text);
		return;
	}
	fuzz_check_frame(&cf);
	n = frame_format(&cf, formatted, sizeof(formatted));
	FUZZ_CHECK(n > 0 && (size_t)n < sizeof(formatted));
	FUZZ_CHECK(frame_parse(formatted, &again, &why) == 0);
	FUZZ_CHECK(frame_equal(&cf, &again));
	free(text);
}

/* Whatever the frame holds, the text stays within the documented sizes. */
static void check_format(const uint8_t *data, size_t size)
{
	char log[FRAME_LOG_MAX(sizeof(LABEL) - 1)];
	char formatted[FRAME_TEXT_MAX];
	struct timespec ts = { 0 };
	struct can_frame cf, again;
	const char *why;
	uint32_t sec;
	int n;

	if (size < sizeof(cf))
		return;
	memcpy(&cf, data, sizeof(cf));
	memcpy(&sec, data, sizeof(sec));
	ts.tv_sec = sec;
	ts.tv_nsec = (long)(data[4] * 3906250L);	/* 0 .. 999 999 999 */
	n = frame_format(&cf, formatted, sizeof(formatted));
	FUZZ_CHECK(n > 0 && (size_t)n < sizeof(formatted));
	n = frame_format_log(&cf, &ts, LABEL, log, sizeof(log));
	FUZZ_CHECK(n > 0 && (size_t)n < sizeof(log));
	if (cf.can_id & CAN_ERR_FLAG) {
		FUZZ_CHECK(frame_parse(formatted, &again, &why) != 0);
		return;
	}
	FUZZ_CHECK(frame_parse(formatted, &again, &why) == 0);
	fuzz_check_frame(&again);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	check_parse(data, size);
	check_format(data, size);
	return 0;
}
