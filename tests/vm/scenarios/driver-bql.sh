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
. /lib/bql.sh

restarts() {
	ip -details -statistics link show can0 |
		awk '/re-started bus-errors/ { getline; print $1 }'
}
restarted_thrice() { [ "$(restarts)" -ge 3 ]; }
wait_restarted_thrice() {
	wait_for 60 restarted_thrice || fail "can0 did not restart three times"
}

bql_burst
[ "$LIMIT" -ne "$LIMIT0" ] || fail "the limit stayed at $LIMIT0"
bql_echo_and_loopback_mode

bql_bus_off_restart_ms wait_restarted_thrice
bql_bus_off_manual_restart

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

bql_down_with_frames_pending one-shot off

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

bql_up_again
echo "driver-bql: ok"
