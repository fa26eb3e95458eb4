/* SPDX-License-Identifier: GPL-2.0 */
/*
 * A broken promise is a finding like a crash: say which one and abort, so
 * libFuzzer saves the input.  Unlike assert() it cannot be compiled out.
 */
#ifndef FUZZ_CHECK_H
#define FUZZ_CHECK_H

#include <stdio.h>
#include <stdlib.h>
#include <linux/can.h>

#define FUZZ_CHECK(cond)						\
	do {								\
		if (!(cond)) {						\
			fprintf(stderr, "%s:%d: check failed: %s\n",	\
				__FILE__, __LINE__, #cond);		\
			abort();					\
		}							\
	} while (0)

/*
 * A data frame or a remote frame as SocketCAN delivers it: an identifier
 * in its format's range, at most 8 bytes, and zeros past its length (all
 * zeros in a remote frame, which carries a length but no data).
 */
static inline void fuzz_check_frame(const struct can_frame *cf)
{
	canid_t id = cf->can_id & ~(CAN_EFF_FLAG | CAN_RTR_FLAG);
	unsigned int i;

	FUZZ_CHECK(id <= (cf->can_id & CAN_EFF_FLAG ? CAN_EFF_MASK :
			  CAN_SFF_MASK));
	FUZZ_CHECK(cf->len <= CAN_MAX_DLEN);
	for (i = 0; i < CAN_MAX_DLEN; i++)
		FUZZ_CHECK(cf->data[i] == 0 ||
			   (!(cf->can_id & CAN_RTR_FLAG) && i < cf->len));
}

#endif /* FUZZ_CHECK_H */
