#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --driver mcp251x
# Shows what upstream/mcp251x/0007 changes: the MCP2510 has no READ RX
# BUFFER instruction, and mainline reads a received frame one register at
# a time, a chip-select period each; READ goes on from register to
# register, so one period reads the whole buffer.  can1 sends 200 8-byte
# frames 5 ms apart (an interrupt each); can0's chip counts the SPI
# transfers (chip-select periods) and bytes its driver spent on them, and
# with the patch a frame must cost at most 8 periods (without it, 17).
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

frames=200
mcp251x_under_test

rx0=$(if_stat can0 rx_packets)
mcp2510_traffic can1 $frames
# The figure needs the frames, not all of them: with this patch mcp251x
# once lost one of the 200 in eleven runs, cause not yet known (the patch
# changes only how a buffer is read).
wait_for 10 received_beyond can0 $((rx0 + frames - 1)) || true
got=$(($(if_stat can0 rx_packets) - rx0))
[ $got -ge $((frames * 9 / 10)) ] || {
	ip -details -statistics link show can0
	cat "$SIM/chip0/counters"
	fail "$under_test: can0 received $got of $frames frames"
}
mcp2510_transfers_per_frame 0 received $got
ip link set can0 down
ip link set can1 down
echo "upstream-mcp2510-rx: $under_test read $got frames"
