#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# Shows what upstream/mcp251x/0011 adds: byte queue limits.  Every frame
# mcp251x takes must be reported to BQL and reported done exactly once
# however it ends, or the stack's count of bytes in flight
# (byte_queue_limits/inflight) never returns to 0: sent, echo not wanted
# by the sender (can-echo), in the controller's loopback mode, bus-off
# with automatic restarts, bus-off with frames pending and a manual
# restart, given up when the interface goes down.  The limit must move
# off its initial value (without BQL it never does), and too many
# completions would trip a BUG in the kernel's dql: the kernel log must
# stay free of BUG and WARNING lines.  driver-bql's checks
# (/lib/bql.sh), but for one-shot mode and a failing SPI bus, which
# mcp251x does not handle.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh
. /lib/bql.sh

mcp251x_under_test
bql_burst
if [ -z "$ko" ]; then
	[ "$LIMIT" -eq "$LIMIT0" ] || fail "the limit of $under_test moved: the kernel has the change"
	echo "upstream-bql: $under_test leaves the limit at $LIMIT0: no BQL"
	exit 0
fi
[ "$LIMIT" -ne "$LIMIT0" ] || fail "$under_test: the limit stayed at $LIMIT0: no BQL"
bql_echo_and_loopback_mode

# mcp251x leaves recovery from bus-off with restart-ms to the chip: three
# seconds of errors are dozens of bus-offs and recoveries.
bql_bus_off_restart_ms nap 3
bql_bus_off_manual_restart
bql_down_with_frames_pending
bql_up_again
echo "upstream-bql: $under_test reports every frame to BQL and every one done, limit $LIMIT0 -> $(bql limit)"
