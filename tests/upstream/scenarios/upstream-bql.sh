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
# stay free of BUG and WARNING lines.  driver-bql's checks, but for
# one-shot mode and a failing SPI bus, which mcp251x does not handle.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

mcp251x_under_test
BQL=/sys/class/net/can0/queues/tx-0/byte_queue_limits
[ -r "$BQL/inflight" ] || fail "no $BQL (CONFIG_BQL)"

bql() { read -r _v <"$BQL/$1"; echo "$_v"; }
drained() { [ "$(bql inflight)" -eq 0 ]; }
expect_drained() {
	wait_for 20 drained || fail "$under_test: after $1, $(bql inflight) bytes still in flight"
	echo "after $1: inflight 0, limit $(bql limit)"
}
no_kernel_warning() {
	if dmesg | grep -E 'BUG:|WARNING:'; then
		fail "$under_test: the kernel warned"
	fi
}
restarted() { [ "$(ip -details link show can0 | grep -c 'state ERROR-ACTIVE')" -eq 1 ]; }
is_bus_off() { can_state_is can0 BUS-OFF; }
busy() { [ "$(bql inflight)" -gt 0 ]; }
sent_reached() { [ "$(if_stat can0 tx_packets)" -ge "$1" ]; }
# send_all N ID: can0 sends N frames with identifier ID, and all N go out.
send_all() {
	_sent0=$(if_stat can0 tx_packets)
	cangen can0 -g 0 -n "$1" -I "$2" -L 8 || fail "cangen can0"
	wait_for 30 sent_reached $((_sent0 + $1)) ||
		fail "can0 sent $(($(if_stat can0 tx_packets) - _sent0)) of $1 frames"
}

echo "== a burst"
ip link set can0 txqueuelen 200
can_up can0 125000
can_up can1 125000
limit0=$(bql limit)
send_all 100 123
expect_drained "a burst of 100 frames"
if [ ! -f $ko ]; then
	[ "$(bql limit)" -eq "$limit0" ] || fail "the limit of $under_test moved: the kernel has the change"
	echo "upstream-bql: $under_test leaves the limit at $limit0: no BQL"
	exit 0
fi
[ "$(bql limit)" -ne "$limit0" ] || fail "$under_test: the limit stayed at $limit0: no BQL"
can-echo can0 >/dev/null || fail "can-echo did not finish"
expect_drained "frames with and without loopback"
no_kernel_warning

echo "== the controller's loopback mode"
ip link set can0 down
can_up can0 125000 loopback on
send_all 20 122
can-echo can0 >/dev/null || fail "can-echo did not finish in loopback mode"
expect_drained "frames sent in loopback mode"
ip link set can0 down
can_up can0 125000 loopback off
no_kernel_warning

echo "== bus-off, automatic restarts"
ip link set can0 down
can_up can0 125000 restart-ms 20
echo 100000 >"$SIM/bus_errors"
cangen can0 -g 1 -i -I 124 -L 8 &
gen=$!
wait_for 30 is_bus_off || true
nap 2
kill "$gen"
wait "$gen" 2>/dev/null || true
echo 0 >"$SIM/bus_errors"
expect_drained "bus-off and automatic restarts"
no_kernel_warning

echo "== bus-off, frames pending, manual restart"
ip link set can0 down
can_up can0 125000 restart-ms 0
echo 100000 >"$SIM/bus_errors"
cangen can0 -g 0 -n 3 -I 125 -L 8 || fail "cangen can0"
wait_for 30 is_bus_off || fail "can0 did not go bus-off"
echo 0 >"$SIM/bus_errors"
expect_drained "bus-off"
ip link set can0 type can restart || fail "manual restart"
send_all 3 126
expect_drained "a manual restart"
no_kernel_warning

echo "== down with frames in the chip and in the driver"
ip link set can0 down
can_up can0 125000
echo 1 >"$SIM/no_ack"
cangen can0 -g 0 -n 8 -i -I 128 -L 8 || fail "cangen can0"
wait_for 10 busy || fail "no frame in flight"
echo "in flight before down: $(bql inflight)"
ip link set can0 down
expect_drained "down with frames pending"
echo 0 >"$SIM/no_ack"

echo "== up again"
can_up can0 125000
send_all 20 12A
expect_drained "up again"
no_kernel_warning
echo "upstream-bql: $under_test reports every frame to BQL and every one done, limit $limit0 -> $(bql limit)"
