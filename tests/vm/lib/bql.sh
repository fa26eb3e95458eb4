# Byte queue limit checks for scenario scripts, in the guest at
# /lib/bql.sh, after /lib/rig.sh: driver-bql's, which make
# upstream-check's upstream-bql runs on mcp251x.  Every frame the driver
# takes must be reported done exactly once however it ends, or
# byte_queue_limits/inflight of can0 never returns to 0; too many
# completions would trip a BUG in the kernel's dql.  Failures name
# $under_test when set.

BQL=/sys/class/net/can0/queues/tx-0/byte_queue_limits
[ -r "$BQL/inflight" ] || fail "no $BQL (CONFIG_BQL)"

bql() { read -r _v <"$BQL/$1"; echo "$_v"; }
drained() { [ "$(bql inflight)" -eq 0 ]; }
# expect_drained WHAT: inflight returns to 0 within 20 s.
expect_drained() {
	wait_for 20 drained ||
		fail "${under_test:+$under_test: }after $1: $(bql inflight) bytes still in flight"
	echo "after $1: inflight 0, limit $(bql limit)"
}
no_kernel_warning() {
	if dmesg | grep -E 'BUG:|WARNING:'; then
		fail "${under_test:+$under_test: }the kernel warned"
	fi
}
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

# bql_burst: can0 and can1 up at 125 kbit/s, a burst of 100 frames; sets
# LIMIT0 and LIMIT (the limit before and after: BQL at work moves it).
bql_burst() {
	echo "== a burst"
	# Room in the qdisc for the whole burst: no frame refused with ENOBUFS.
	ip link set can0 txqueuelen 200
	can_up can0 125000
	can_up can1 125000
	LIMIT0=$(bql limit)
	send_all 100 123
	expect_drained "a burst of 100 frames"
	LIMIT=$(bql limit)
}

# bql_echo_and_loopback_mode: frames with and without loopback (the echo
# of a frame whose sender wants none is dropped, not delivered), then
# the controller's loopback mode (the chip receives its own frames and
# sends nothing on the bus) on and off again.
bql_echo_and_loopback_mode() {
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
	send_all 20 122
	expect_drained "loopback mode off again"
	no_kernel_warning
}

# bql_bus_off_restart_ms COMMAND...: can0 with restart-ms 20 keeps
# sending while every frame meets a bus error, until COMMAND returns:
# bus-off and recovery again and again with frames queued.
bql_bus_off_restart_ms() {
	echo "== bus-off and automatic restarts with frames queued"
	ip link set can0 down
	can_up can0 125000 restart-ms 20
	echo 100000 >"$SIM/bus_errors"
	cangen can0 -g 1 -i -I 124 -L 8 &
	_gen=$!
	"$@"
	kill "$_gen"
	wait "$_gen" 2>/dev/null || true
	echo 0 >"$SIM/bus_errors"
	expect_drained "bus-off and automatic restarts"
	no_kernel_warning
}

# bql_bus_off_manual_restart: bus-off with frames pending, restart-ms 0,
# then a manual restart.
bql_bus_off_manual_restart() {
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
}

# bql_down_with_frames_pending [ARG...]: can0 up (with "ip link set can0
# type can" ARGs) and unacknowledged: three frames fill the TX buffers,
# the rest wait in the qdisc; then down.
bql_down_with_frames_pending() {
	echo "== down with frames in the chip and in the driver"
	ip link set can0 down
	can_up can0 125000 "$@"
	echo 1 >"$SIM/no_ack"
	cangen can0 -g 0 -n 8 -i -I 128 -L 8 || fail "cangen can0"
	wait_for 10 busy || fail "no frame in flight"
	echo "in flight before down: $(bql inflight)"
	ip link set can0 down
	expect_drained "down with frames pending"
	echo 0 >"$SIM/no_ack"
}

bql_up_again() {
	echo "== up again"
	can_up can0 125000
	send_all 20 12A
	expect_drained "up again"
	no_kernel_warning
}
