#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --driver mcp251x
# Shows what upstream/mcp251x/0008 changes: the MCP2510 has no LOAD TX
# BUFFER instruction, and mainline writes a frame one register at a
# time, a chip-select period each; WRITE goes on from register to
# register, so one period loads the whole frame.  can0 sends 200 8-byte
# frames 5 ms apart (an interrupt each); its chip counts the SPI
# transfers (chip-select periods) and bytes the driver spent on them, and
# with the patch a frame must cost at most 8 periods (without it, 17).
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

frames=200
mcp251x_under_test

tx0=$(if_stat can0 tx_packets)
mcp2510_traffic can0 $frames
wait_for 30 sent_beyond can0 $((tx0 + frames - 1)) ||
	fail "$under_test: can0 sent $(($(if_stat can0 tx_packets) - tx0)) of $frames frames"
mcp2510_transfers_per_frame 0 sent $frames
ip link set can0 down
ip link set can1 down
echo "upstream-mcp2510-tx: $under_test sent $frames frames"
