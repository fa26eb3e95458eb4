#!/bin/sh
# vm-run: --nodes 0
# Proves the rig without the simulated chip: a vcan interface, cangen ->
# candump through the real can-utils, frame counts checked, and the tools the
# guest promises are all there.
set -eu

for tool in ip ethtool cansend candump cangen cansequence canfdtest canbusload \
	cangw gpiodetect gpioinfo gpioget gpioset gpiomon modprobe insmod; do
	command -v "$tool" >/dev/null || { echo "smoke: missing tool $tool"; exit 1; }
done

ip link add dev vcan0 type vcan
ip link set vcan0 up
ip -details link show vcan0

n=200
candump -n "$n" -T 20000 vcan0 >/tmp/dump.txt &
dump=$!
sleep 0.5 # let candump bind before frames go out
cangen -g 0 -n "$n" -I 123 -L 8 -D i vcan0
wait "$dump"

got=$(wc -l </tmp/dump.txt)
echo "smoke: candump saw $got of $n frames"
[ "$got" -eq "$n" ]
# Every frame carries id 123 and an incrementing payload.
[ "$(grep -c ' 123 ' /tmp/dump.txt)" -eq "$n" ]
head -n 3 /tmp/dump.txt

# A single cansend is seen, in order, by a raw socket.
candump -n 1 -T 5000 vcan0 >/tmp/one.txt &
dump=$!
sleep 0.3
cansend vcan0 5A1#1122334455667788
wait "$dump"
grep -q '5A1 *\[8\] *11 22 33 44 55 66 77 88' /tmp/one.txt || { cat /tmp/one.txt; exit 1; }

# Statistics agree: the interface counted both runs.
tx=$(cat /sys/class/net/vcan0/statistics/tx_packets)
echo "smoke: vcan0 tx_packets $tx"
[ "$tx" -eq $((n + 1)) ]

ip link del vcan0
echo "smoke: ok"
