#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --driver mcp2510
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510
# vm-run: --nodes 2 --variant mcp2510 --driver mcp251x
# vm-kernels: 6.1
# Two simulated chips on one bus: the interfaces appear down, come up with
# "ip link ... bitrate" (link state UP, no NO-CARRIER), and frames (standard, extended, RTR, all lengths)
# cross the bus both ways, seen by candump and counted in the statistics.
# The mcp251x run checks the model against mainline's independent driver.
set -eu
. /lib/rig.sh

[ "$VM_SIM" = 1 ] || fail "the simulated chips are not loaded"
for i in 0 1; do
	[ -e /sys/class/net/can$i ] || fail "can$i missing"
	ip -o link show can$i | grep -q 'state DOWN' || fail "can$i is not down at start"
done

can_up can0 500000
can_up can1 500000
# Once up, as ip shows it: with carrier, link state UP (can1 first: the
# link state of the interface brought up last is the one that lags).
for i in 1 0; do
	link=$(ip -o link show can$i)
	case $link in
	*NO-CARRIER* | *"state DOWN"*) fail "can$i after up: $link" ;;
	*"state UP "*) ;;
	*) fail "can$i: link state not UP after up: $link" ;;
	esac
done
ip -details link show can1

# 20 ms apart: two RX buffers must keep up even on the debug kernel under
# TCG, where an interrupt takes milliseconds to service.
n=50
dump_start can1 "$n" /tmp/c1.txt
cangen -g 20 -n "$n" -I 123 -L 8 -D i can0
dump_wait
expect_lines /tmp/c1.txt "$n"
[ "$(grep -c '  123  ' /tmp/c1.txt)" -eq "$n" ] || fail "can1 got frames with a wrong id"

dump_start can0 4 /tmp/c0.txt
cansend can1 7FF#DEADBEEF
cansend can1 12345678#0102030405060708
cansend can1 000#
cansend can1 321#R
dump_wait
cat /tmp/c0.txt
expect_lines /tmp/c0.txt 4
grep -q '7FF *\[4\] *DE AD BE EF' /tmp/c0.txt || fail "standard frame lost"
grep -q '12345678 *\[8\] *01 02 03 04 05 06 07 08' /tmp/c0.txt || fail "extended frame lost"
grep -q '000 *\[0\]' /tmp/c0.txt || fail "empty frame lost"
grep -q '321 *\[0\] *remote request' /tmp/c0.txt || fail "RTR frame lost"

ip -details -statistics link show can0
ip -details -statistics link show can1
for i in 0 1; do
	ip -details link show can$i | grep -q 'state ERROR-ACTIVE' ||
		fail "can$i not error-active after clean traffic"
done
tx0=$(cat /sys/class/net/can0/statistics/tx_packets)
rx1=$(cat /sys/class/net/can1/statistics/rx_packets)
[ "$tx0" -eq "$n" ] || fail "can0 tx_packets $tx0, expected $n"
[ "$rx1" -eq "$n" ] || fail "can1 rx_packets $rx1, expected $n"

ip link set can0 down
ip link set can1 down
echo "two-nodes: ok"
