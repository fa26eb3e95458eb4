#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515
# vm-kernels: debug
# Byte queue limits on the transmit path.  Every frame the driver takes
# is reported to BQL and must be reported done exactly once however it
# ends, or the stack's count of bytes in flight (byte_queue_limits/
# inflight) never returns to 0: sent, echo not wanted by the sender,
# aborted at bus-off, aborted by a restart, dropped by one-shot mode,
# given up when the interface goes down (with and without a working SPI
# bus).  The limit must also move off its initial value: BQL at work.
# Too many completions would trip a BUG in the kernel's dql instead: the
# kernel log must stay free of BUG and WARNING lines.  MCP2515: the only
# variant with one-shot mode.
set -eu
. /lib/rig.sh

[ -d "$SIM" ] || mount -t debugfs none /sys/kernel/debug
BQL=/sys/class/net/can0/queues/tx-0/byte_queue_limits
[ -r "$BQL/inflight" ] || fail "no $BQL (CONFIG_BQL)"

bql() { read -r _v <"$BQL/$1"; echo "$_v"; }
drained() { [ "$(bql inflight)" -eq 0 ]; }
# expect_drained WHAT: inflight returns to 0 within 20 s.
expect_drained() {
	wait_for 20 drained || fail "after $1: $(bql inflight) bytes still in flight"
	echo "after $1: inflight 0, limit $(bql limit)"
}
no_kernel_warning() {
	if dmesg | grep -E 'BUG:|WARNING:'; then
		fail "the kernel warned"
	fi
}
restarts() {
	ip -details -statistics link show can0 |
		awk '/re-started bus-errors/ { getline; print $1 }'
}
restarted_thrice() { [ "$(restarts)" -ge 3 ]; }
is_bus_off() { can_state_is can0 BUS-OFF; }
# busy: frames in flight now (the chip holds unacknowledged ones).
busy() { [ "$(bql inflight)" -gt 0 ]; }
sent_reached() { [ "$(if_stat can0 tx_packets)" -ge "$1" ]; }
# send_all N ID: can0 sends N frames with identifier ID, and all N go out
# (the receiving chip may overflow under the emulator: can0's count is
# the one that matters).
send_all() {
	_sent0=$(if_stat can0 tx_packets)
	cangen can0 -g 0 -n "$1" -I "$2" -L 8 || fail "cangen can0"
	wait_for 30 sent_reached $((_sent0 + $1)) ||
		fail "can0 sent $(($(if_stat can0 tx_packets) - _sent0)) of $1 frames"
}

echo "== a burst"
# Room in the qdisc for the whole burst: no frame refused with ENOBUFS.
ip link set can0 txqueuelen 200
can_up can0 125000
can_up can1 125000
limit0=$(bql limit)
send_all 100 123
expect_drained "a burst of 100 frames"
[ "$(bql limit)" -ne "$limit0" ] || fail "the limit stayed at $limit0"
# The echo of a frame whose sender wants none is dropped, not delivered.
can-echo can0 >/dev/null || fail "can-echo did not finish"
expect_drained "frames with and without loopback"
no_kernel_warning

echo "== the controller's loopback mode"
# The chip receives its own frames and sends nothing on the bus.
ip link set can0 down
can_up can0 125000 loopback on
send_all 20 122
can-echo can0 >/dev/null || fail "can-echo did not finish in loopback mode"
expect_drained "frames sent in loopback mode"
ip link set can0 down
can_up can0 125000 loopback off
send_all 20 122
expect_drained "loopback mode off again"
no_kernel_warning

echo "== bus-off and restart with frames queued"
ip link set can0 down
can_up can0 125000 restart-ms 20
echo 100000 >"$SIM/bus_errors"
cangen can0 -g 1 -i -I 124 -L 8 &
gen=$!
wait_for 60 restarted_thrice || fail "can0 did not restart three times"
kill "$gen"
wait "$gen" 2>/dev/null || true
echo 0 >"$SIM/bus_errors"
expect_drained "bus-off and automatic restarts"
no_kernel_warning

echo "== bus-off, frames pending, manual restart"
# ip link keeps what it is not told: each section sets what it changed.
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

echo "== one-shot: unacknowledged frames are dropped"
ip link set can0 down
can_up can0 125000 one-shot on
echo 1 >"$SIM/no_ack"
aborted0=$(if_stat can0 tx_aborted_errors)
cangen can0 -g 0 -n 5 -I 127 -L 8 || fail "cangen can0"
expect_drained "one-shot failures"
[ "$(if_stat can0 tx_aborted_errors)" -eq $((aborted0 + 5)) ] ||
	fail "$(($(if_stat can0 tx_aborted_errors) - aborted0)) of 5 frames aborted"
echo 0 >"$SIM/no_ack"
no_kernel_warning

echo "== down with frames in the chip and in the driver"
ip link set can0 down
can_up can0 125000 one-shot off
echo 1 >"$SIM/no_ack"
# Three fill the TX buffers, the rest wait in the qdisc.
cangen can0 -g 0 -n 8 -i -I 128 -L 8 || fail "cangen can0"
wait_for 10 busy || fail "no frame in flight"
echo "in flight before down: $(bql inflight)"
ip link set can0 down
expect_drained "down with frames pending"
echo 0 >"$SIM/no_ack"

echo "== down while the SPI fails: the frames cannot be aborted"
can_up can0 125000
echo 1 >"$SIM/no_ack"
cangen can0 -g 0 -n 3 -I 129 -L 8 || fail "cangen can0"
wait_for 10 busy || fail "no frame in flight"
echo 4294967295 >"$SIM/chip0/spi_errors"
ip link set can0 down
echo 0 >"$SIM/chip0/spi_errors"
expect_drained "down with a failing SPI"
echo 0 >"$SIM/no_ack"

echo "== up again"
can_up can0 125000
send_all 20 12A
expect_drained "up again"
no_kernel_warning
echo "driver-bql: ok"
