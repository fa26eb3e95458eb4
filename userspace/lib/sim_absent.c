// SPDX-License-Identifier: LGPL-2.1-or-later
/* Linked instead of sim_transport.c and the shared bus when the library is
 * built without the chip model (MCP2510_SIM=0): "sim" transports are then
 * refused. */
#include <errno.h>

#include "transport.h"

int mcp2510_sim_open(const char *bus_name,
		     const struct mcp2510_transport_params *p,
		     struct mcp2510_transport **out)
{
	(void)bus_name;
	(void)p;
	(void)out;
	return -EPROTONOSUPPORT;
}

int mcp2510_simbus_open(const char *spec,
			const struct mcp2510_transport_params *p,
			struct mcp2510_transport **out)
{
	return mcp2510_sim_open(spec, p, out);
}
