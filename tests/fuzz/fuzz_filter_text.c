// SPDX-License-Identifier: GPL-2.0
/*
 * The text forms of acceptance filters: identifiers ("7ff", "1fffffffx")
 * and receive modes ("filtered", "std", "ext", "any"), as sysfs and
 * mcp2510ctl hand them to the core, newline and all.
 *
 * The parsers take a length and no NUL, so the input sits in a buffer of
 * exactly its size: ASan sees any read past it.  What a parser accepts
 * must be valid for the registers and come back unchanged through the
 * formatter; a refusal must leave the output untouched.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_check.h"
#include "mcp2510_core.h"

/* mcp2510_filter_id_format() needs at least this much room */
#define FILTER_TEXT_MAX		12

static size_t without_newline(const char *s, size_t len)
{
	return len && s[len - 1] == '\n' ? len - 1 : len;
}

static void check_filter_id(const char *s, size_t len)
{
	struct mcp2510_filter_id id = { .id = 0x5a5a5a5a, .ext = true };
	struct mcp2510_filter_id again;
	struct mcp2510_filters f;
	char text[FILTER_TEXT_MAX];
	int n;

	if (mcp2510_filter_id_parse(s, len, &id)) {
		FUZZ_CHECK(id.id == 0x5a5a5a5a && id.ext);
		return;
	}
	FUZZ_CHECK(id.id <= (id.ext ? CAN_EFF_MASK : CAN_SFF_MASK));
	n = mcp2510_filter_id_format(&id, text);
	FUZZ_CHECK(n > 0 && n < FILTER_TEXT_MAX && text[n] == '\0');
	FUZZ_CHECK(mcp2510_filter_id_parse(text, (size_t)n, &again) == 0);
	FUZZ_CHECK(again.id == id.id && again.ext == id.ext);

	/* valid as every mask and filter at once */
	mcp2510_filters_default(&f);
	for (n = 0; n < MCP2510_MASK_COUNT; n++)
		f.mask[n] = id;
	for (n = 0; n < MCP2510_FILTER_COUNT; n++)
		f.filter[n] = id;
	FUZZ_CHECK(mcp2510_filters_check(&f) == 0);
}

static void check_rxm(const char *s, size_t len)
{
	const char *name;
	u8 rxm = 0xa5;

	if (mcp2510_rxm_parse(s, len, &rxm)) {
		FUZZ_CHECK(rxm == 0xa5);
		return;
	}
	name = mcp2510_rxm_name(rxm);
	FUZZ_CHECK(name);
	len = without_newline(s, len);
	FUZZ_CHECK(strlen(name) == len && !memcmp(name, s, len));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char *s = malloc(size ? size : 1);

	FUZZ_CHECK(s);
	if (size)
		memcpy(s, data, size);
	check_filter_id(s, size);
	check_rxm(s, size);
	free(s);
	return 0;
}
