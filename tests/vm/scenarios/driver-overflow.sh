#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-run: --nodes 2 --variant mcp2515
# vm-kernels: debug
# A flood from the simulator's phantom node, at full speed, overruns the
# two receive buffers of can1 (under TCG the guest is far slower than the
# bus): the overflow is counted (rx_over_errors, rx_errors) and reported as
# an error frame, and every frame the chip did store reaches the stack.
set -eu
. /lib/rig.sh

CAN_ERR_CRTL=0x4 CAN_ERR_CRTL_RX_OVERFLOW=0x01

flood_done() { [ "$(cat "$SIM/flood")" -eq 0 ]; }

can_up can1 500000
echo 0 >"$SIM/chip1/counters"
errors_start can1 /tmp/err1.txt
rx_before=$(if_stat can1 rx_packets)
echo "200 100#00000000 500000" >"$SIM/flood"
wait_for 60 flood_done || fail "the flood never ended"
sleep 1
errors_stop
stored=$(sim_counter 1 frames_rx)
lost=$(sim_counter 1 overflows)
got=$(($(if_stat can1 rx_packets) - rx_before))
echo "chip stored $stored, lost $lost; can1 received $got"
[ $((stored + lost)) -eq 200 ] || fail "the chip saw $((stored + lost)) of 200 frames"
[ "$lost" -gt 0 ] || fail "no overflow: the test proves nothing (guest too fast?)"
[ "$got" -eq "$stored" ] || fail "the chip stored $stored frames, the stack got $got"
[ "$(if_stat can1 rx_over_errors)" -gt 0 ] || fail "rx_over_errors not counted"
[ "$(if_stat can1 rx_errors)" -ge "$(if_stat can1 rx_over_errors)" ] || fail "rx_errors below rx_over_errors"
error_seen /tmp/err1.txt $CAN_ERR_CRTL $CAN_ERR_CRTL_RX_OVERFLOW ||
	{ cat /tmp/err1.txt; fail "no overflow error frame"; }
ip link set can1 down

echo "driver-overflow: ok"
