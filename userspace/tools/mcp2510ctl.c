// SPDX-License-Identifier: GPL-2.0
/* mcp2510ctl: command-line access to an MCP2510-family CAN controller. */
#include "ctl.h"

int main(int argc, char **argv)
{
	return ctl_main(argc, argv, stdout, stderr);
}
