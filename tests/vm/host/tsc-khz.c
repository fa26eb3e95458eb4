// SPDX-License-Identifier: GPL-2.0
/*
 * Print the host's TSC rate in kHz.  Under TCG a guest's TSC is the
 * host's, but the guest calibrates it against an emulated PIT, and on a
 * busy host that calibration can be off tenfold: guest time then races
 * ahead and watchdogs fire.  vm-run passes this figure as tsc_early_khz.
 */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <time.h>
#include <x86intrin.h>

#define WINDOW_NS	100000000ULL	/* the interval measured */
#define TIGHT_NS	20000ULL	/* a clock read pair this close counts */

static uint64_t monotonic_ns(void)
{
	struct timespec ts;

	clock_gettime(CLOCK_MONOTONIC_RAW, &ts);
	return (uint64_t)ts.tv_sec * 1000000000ULL + (uint64_t)ts.tv_nsec;
}

/* A TSC reading and the time it was taken, from a read not preempted. */
static int sample(uint64_t *tsc, uint64_t *ns)
{
	for (int tries = 0; tries < 1000; tries++) {
		uint64_t before = monotonic_ns();
		uint64_t t = __rdtsc();
		uint64_t after = monotonic_ns();

		if (after - before <= TIGHT_NS) {
			*tsc = t;
			*ns = before + (after - before) / 2;
			return 0;
		}
	}
	return -1;
}

int main(void)
{
	const struct timespec wait = { 0, WINDOW_NS };
	uint64_t tsc0, ns0, tsc1, ns1;

	if (sample(&tsc0, &ns0))
		return 1;
	nanosleep(&wait, NULL);
	if (sample(&tsc1, &ns1) || ns1 <= ns0)
		return 1;
	printf("%llu\n", (unsigned long long)((tsc1 - tsc0) * 1000000ULL / (ns1 - ns0)));
	return 0;
}
