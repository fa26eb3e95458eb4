// SPDX-License-Identifier: GPL-2.0
/*
 * The simulated buses' settings from the environment, read when a bus is
 * created (sim_transport.c says what each variable does): the SPI time
 * of MCP2510_SIM_SPI_TIME and the bus errors of MCP2510_SIM_BUS_ERRORS.
 */
#include <errno.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mcp2510_sim.h"
#include "sim_env.h"

#define SPI_TIME_ENV		"MCP2510_SIM_SPI_TIME"
#define BUS_ERRORS_ENV		"MCP2510_SIM_BUS_ERRORS"

#define SPI_TIME_KEY(field) { #field, offsetof(struct sim_spi_timing, field) }

/* The value of key in "key=value,..." s, its length in *len; NULL: absent. */
static const char *spi_time_value(const char *s, const char *key, size_t *len)
{
	size_t n = strlen(key);

	for (; *s; s += strcspn(s, ","), s += *s == ',') {
		if (!strncmp(s, key, n) && s[n] == '=') {
			*len = strcspn(s + n + 1, ",");
			return s + n + 1;
		}
	}
	return NULL;
}

/* profile= and scale_pct= first, so that single costs may override them. */
static int spi_time_profile(const char *p, struct sim_spi_timing *t)
{
	const char *name, *scale;
	unsigned long pct = 100;
	size_t len;
	int profile;
	char *end;

	name = spi_time_value(p, "profile", &len);
	if (!name)
		return 0;
	profile = sim_spi_profile_find(name, len);
	scale = spi_time_value(p, "scale_pct", &len);
	if (scale) {
		errno = 0;
		pct = strtoul(scale, &end, 10);
		if (errno || end != scale + len || !len)
			return -EINVAL;
	}
	if (profile < 0 || pct > UINT32_MAX)
		return -EINVAL;
	return sim_spi_profile_timing((unsigned int)profile, (uint32_t)pct, t);
}

int sim_env_spi_time(struct sim_spi_bus *spi)
{
	static const struct {
		const char *key;
		size_t offset;
	} keys[] = {
		SPI_TIME_KEY(msg_ns), SPI_TIME_KEY(cs_setup_ns),
		SPI_TIME_KEY(cs_hold_ns), SPI_TIME_KEY(ctlr_max_hz),
		SPI_TIME_KEY(irq_latency_ns), SPI_TIME_KEY(irq_latency_p99_ns),
		SPI_TIME_KEY(wake_ns), SPI_TIME_KEY(wake_p99_ns),
		SPI_TIME_KEY(xfer_ns), SPI_TIME_KEY(idle_clocks),
		SPI_TIME_KEY(poll_hz_per_byte), SPI_TIME_KEY(dma_min_len),
		SPI_TIME_KEY(dma_ns),
	};
	struct sim_spi_timing *t = &spi->timing;
	const char *p = getenv(SPI_TIME_ENV);

	memset(t, 0, sizeof(*t));
	if (!p || !*p)
		return 0;
	if (spi_time_profile(p, t))
		return -EINVAL;
	t->enabled = true;
	while (*p) {
		size_t i, n = strcspn(p, "=");
		unsigned long v;
		char *end;

		if ((n == 7 && !strncmp(p, "profile", n)) ||
		    (n == 9 && !strncmp(p, "scale_pct", n))) {
			p += strcspn(p, ",");
			p += *p == ',';
			continue;
		}
		for (i = 0; i < sizeof(keys) / sizeof(keys[0]); i++)
			if (strlen(keys[i].key) == n && !strncmp(p, keys[i].key, n))
				break;
		if ((i == sizeof(keys) / sizeof(keys[0]) &&
		     (n != 4 || strncmp(p, "seed", n))) || p[n] != '=')
			return -EINVAL;
		errno = 0;
		v = strtoul(p + n + 1, &end, 10);
		if (errno || end == p + n + 1 || v > UINT32_MAX ||
		    (*end && *end != ','))
			return -EINVAL;
		if (i == sizeof(keys) / sizeof(keys[0]))
			sim_spi_seed(spi, (uint32_t)v);
		else
			*(uint32_t *)((char *)t + keys[i].offset) = (uint32_t)v;
		p = *end ? end + 1 : end;
	}
	return 0;
}

int sim_env_bus_errors(struct sim_bus *bus)
{
	const char *p = getenv(BUS_ERRORS_ENV);
	unsigned long v;
	char *end;

	if (!p || !*p)
		return 0;
	errno = 0;
	v = strtoul(p, &end, 10);
	if (errno || *end || v > UINT32_MAX)
		return -EINVAL;
	sim_bus_faults(bus)->bus_errors = (uint32_t)v;
	return 0;
}
