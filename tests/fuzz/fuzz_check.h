/* SPDX-License-Identifier: GPL-2.0 */
/*
 * A broken promise is a finding like a crash: say which one and abort, so
 * libFuzzer saves the input.  Unlike assert() it cannot be compiled out.
 */
#ifndef FUZZ_CHECK_H
#define FUZZ_CHECK_H

#include <stdio.h>
#include <stdlib.h>

#define FUZZ_CHECK(cond)						\
	do {								\
		if (!(cond)) {						\
			fprintf(stderr, "%s:%d: check failed: %s\n",	\
				__FILE__, __LINE__, #cond);		\
			abort();					\
		}							\
	} while (0)

#endif /* FUZZ_CHECK_H */
