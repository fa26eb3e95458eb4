#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x --sim-param time_scale=20
# Shows what upstream/mcp251x/0010 adds: received frames, error frames and
# echoes go through can-dev's rx-offload, handed to NAPI in the order the
# IRQ thread read them.  A user sees the NAPI context in the interface's
# "threaded" switch, which moves delivery into a kernel thread of its own
# (napi/canN-ID) that can be given a priority like any thread; an
# interface without NAPI refuses the switch.  With delivery threaded on
# both ends, can0 sends 500 sequence-numbered frames: can1 must receive
# them all in order, and a second socket on can0 all their echoes, which
# can0 must not count as received.  Bus
# time runs 20 times slower than real time: mcp251x, one interrupt per
# frame, loses frames of a burst to overflow under TCG at full speed.
# It still overflows when the host leaves the guest unscheduled for a
# while (bus time follows the guest's clock): a frame may be missing only
# when can1's chip dropped it with its buffers full and the driver
# reported the overflow; none may come twice or out of order.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

frames=500
mcp251x_under_test

can_up can0 500000
can_up can1 500000
threaded=0
for i in 0 1; do
	if echo 1 2>/dev/null >/sys/class/net/can$i/threaded; then
		threaded=$((threaded + 1))
	fi
done
if [ -z "$ko" ]; then
	[ $threaded -eq 0 ] || fail "$under_test takes threaded NAPI: the kernel has the change"
	echo "upstream-rx-offload: $under_test has no NAPI context to thread"
	exit 0
fi
[ $threaded -eq 2 ] || fail "$under_test: no NAPI context: echo 1 >/sys/class/net/canN/threaded refused"
ps | grep -q '\[napi/can1-' || fail "$under_test: no napi/can1 thread with threaded on"

echo 0 >"$SIM/chip1/counters"
can-flood recv can1 $frames -o >/tmp/rx.txt &
rx=$!
can-flood recv can0 $frames -o >/tmp/echo.txt &
echo=$!
wait_for 10 grep -q ready /tmp/rx.txt || fail "can-flood recv on can1 did not start"
wait_for 10 grep -q ready /tmp/echo.txt || fail "can-flood recv on can0 did not start"
can-flood send can0 $frames || fail "can-flood send failed"
wait $rx || true
wait $echo || true
cat /tmp/rx.txt /tmp/echo.txt
dropped=$(sim_counter 1 overflows)
echo "can1: rx_over_errors $(if_stat can1 rx_over_errors), its chip dropped $dropped"
lost="lost=$dropped duplicated=0 reordered=0 corrupted=0"
grep -q "received=$((frames - dropped)) $lost" /tmp/rx.txt ||
	fail "$under_test: can1 did not receive the $frames frames in order, less those its chip dropped"
[ "$dropped" -eq 0 ] || [ "$(if_stat can1 rx_over_errors)" -gt 0 ] ||
	fail "$under_test: can1's chip overflowed and can1 reported no overflow"
whole="received=$frames lost=0 duplicated=0 reordered=0 corrupted=0"
grep -q "$whole" /tmp/echo.txt || fail "$under_test: can0's echoes were not whole and in order"
expect_eq "can0 tx_packets" "$(if_stat can0 tx_packets)" $frames
# rx-offload's poll counts what it delivers, echoes included
expect_eq "can0 rx_packets (the echoes are no received frames)" "$(if_stat can0 rx_packets)" 0
ip link set can0 down
ip link set can1 down
echo "upstream-rx-offload: $under_test delivered through threaded NAPI, $((frames - dropped)) of $frames frames and their echoes in order"
