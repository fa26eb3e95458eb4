#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# vm-kernels: 6.1
# The simulator's bus faults and its phantom node, judged through mainline
# mcp251x (a driver this project did not write) and the CAN rules every
# controller follows: injected bus errors cost the transmitter 8 and each
# receiver 1 per error and the frame is repeated; a frame nobody
# acknowledges drives the sender error-passive (TEC 128, no further), after
# which receivers that cannot acknowledge take every repetition; a flood of back-to-back frames is either stored or
# counted as overflow, never lost silently; a mode change slower than
# mcp251x's one-second wait makes it give up.
set -eu
. /lib/rig.sh

sim=$SIM

expect() { # WHAT GOT WANTED
	[ "$2" -eq "$3" ] || fail "$1 is $2, expected $3"
}
reset_counts() {
	for i in 0 1; do echo 0 >$sim/chip$i/counters; done
	: >$sim/monitor
}
monitor_count() { # OUTCOME: monitor lines with that outcome
	grep -c " $1\$" $sim/monitor || true
}

can_up can0 125000
can_up can1 125000
echo off >$sim/phantom

echo "== bus_errors: three error frames, then the frame goes through"
reset_counts
echo 3 >$sim/bus_errors
dump_start can1 1 /tmp/be.txt
cansend can0 123#AA
dump_wait
cat $sim/monitor
grep -q '123 *\[1\] *AA$' /tmp/be.txt || fail "can1 did not receive 123#AA"
expect "bus_errors left" "$(cat $sim/bus_errors)" 0
expect "error-injected lines" "$(monitor_count error-injected)" 3
expect "ok lines" "$(monitor_count ok)" 1
expect "chip0 tx_errors" "$(sim_counter 0 tx_errors)" 3
expect "chip1 rx_errors" "$(sim_counter 1 rx_errors)" 3
expect "chip0 TEC" "$(sim_state 0 tec)" $((3 * 8 - 1))
expect "chip1 REC" "$(sim_state 1 rec)" $((3 - 1))
expect "can1 rx_packets" "$(cat /sys/class/net/can1/statistics/rx_packets)" 1

echo "== no_ack: the sender turns error-passive, the receivers take every copy"
# An error-passive sender's error flag is recessive, so after its ACK errors
# the receivers see a valid frame while the sender keeps repeating it.
ip link set can0 down # configuration mode clears the error counters
can_up can0 125000
reset_counts
rx_before=$(cat /sys/class/net/can1/statistics/rx_packets)
echo 1 >$sim/no_ack
cansend can0 124#BB
sleep 1
expect "chip0 TEC" "$(sim_state 0 tec)" 128
ip -details link show can0 | grep -q 'state ERROR-PASSIVE' ||
	fail "mcp251x does not report can0 error-passive"
echo 0 >$sim/no_ack
sleep 0.5
expect "chip0 TEC" "$(sim_state 0 tec)" 127
acks=$(sim_counter 0 tx_errors)
copies=$(($(cat /sys/class/net/can1/statistics/rx_packets) - rx_before))
stored=$(sim_counter 1 frames_rx) lost=$(sim_counter 1 overflows)
echo "$acks ACK errors; chip1 stored $stored copies, lost $lost; can1 got $copies"
[ "$acks" -gt 16 ] || fail "only $acks ACK errors"
# 16 ACK errors take TEC to 128; every later one is a copy, plus the good frame
expect "chip1 copies stored + lost" $((stored + lost)) $((acks - 16 + 1))
expect "can1 copies" "$copies" "$stored"
[ "$(monitor_count error-ack)" -gt 0 ] || fail "the monitor shows no ACK error"
[ "$(tail -n 1 $sim/monitor | cut -d' ' -f7)" = ok ] || fail "the last frame was not good"

echo "== a lone node gets no ACK"
ip link set can0 down
ip link set can1 down
can_up can0 125000
reset_counts
cansend can0 125#CC
sleep 1
[ "$(monitor_count error-ack)" -gt 0 ] || fail "a lone node's frame was acknowledged"
expect "ok lines" "$(monitor_count ok)" 0
expect "chip0 TEC" "$(sim_state 0 tec)" 128
rx_before=$(cat /sys/class/net/can1/statistics/rx_packets)
ip link set can1 up
sleep 0.5
[ "$(cat /sys/class/net/can1/statistics/rx_packets)" -gt "$rx_before" ] ||
	fail "can1 did not receive 125#CC once it joined"
tail -n 1 $sim/monitor | grep -q ' chip0 125#CC 125000 [0-9]* ok$' ||
	fail "125#CC did not go through once can1 joined"

echo "== flood: every frame stored or counted as overflow"
reset_counts
n=200
dump_start can1 "$n" /tmp/fl.txt -T 3000
echo "$n 100#0000000000000000 125000" >$sim/flood
tries=0
while [ "$(cat $sim/flood)" -ne 0 ]; do
	tries=$((tries + 1))
	[ $tries -le 100 ] || fail "the flood did not finish"
	sleep 0.1
done
dump_wait
for i in 0 1; do
	stored=$(sim_counter $i frames_rx) lost=$(sim_counter $i overflows)
	echo "chip$i: $stored stored, $lost overflowed"
	expect "chip$i frames_rx + overflows" $((stored + lost)) "$n"
done
grep -v ' phantom 100#' $sim/monitor || true
expect "phantom frames on the bus" "$(grep -c ' phantom 100#[0-9A-F]* 125000 [0-9]* ok$' $sim/monitor)" "$n"
expect "can1 frames received" "$(wc -l </tmp/fl.txt)" "$(sim_counter 1 frames_rx)"

echo "== mode_delay_us: slower than mcp251x waits"
ip link set can1 down
echo 2000000 >$sim/chip1/mode_delay_us
if ip link set can1 up 2>/dev/null; then fail "can1 came up despite a 2 s mode change"; fi
echo 100000 >$sim/chip1/mode_delay_us
ip link set can1 down 2>/dev/null || true
ip link set can1 up || fail "can1 did not come up with a 0.1 s mode change"
echo 0 >$sim/chip1/mode_delay_us

ip -details -statistics link show can0
ip link set can0 down
ip link set can1 down
echo "sim-faults: ok"
