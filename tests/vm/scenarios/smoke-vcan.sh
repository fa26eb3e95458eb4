#!/bin/sh
# vm-run: --nodes 0
# vm-kernels: 6.1
# Proves the rig without the simulated chip: the promised tools are there,
# and frames go cangen/cansend -> vcan0 -> candump through the real
# can-utils, with counts, payloads and interface statistics checked.
set -eu
. /lib/rig.sh

for tool in ip ethtool cansend candump cangen cansequence canfdtest canbusload \
	cangw can-calc-bit-timing gpiodetect gpioinfo gpioget gpioset gpiomon \
	modprobe insmod; do
	command -v "$tool" >/dev/null || fail "missing tool $tool"
done
# iproute2's ip, not busybox's applet: only the former knows "type vcan".
ip -V | grep -q iproute2 || fail "ip is not iproute2's"

ip link add dev vcan0 type vcan
ip link set vcan0 up
ip -details link show vcan0

n=200
dump_start vcan0 "$n" /tmp/dump.txt
cangen -g 0 -n "$n" -I 123 -L 8 -D i vcan0
dump_wait
echo "smoke: candump saw $(wc -l </tmp/dump.txt) of $n frames"
expect_lines /tmp/dump.txt "$n"
[ "$(grep -c ' 123 ' /tmp/dump.txt)" -eq "$n" ] || fail "frames with a wrong id"
head -n 3 /tmp/dump.txt

dump_start vcan0 1 /tmp/one.txt
cansend vcan0 5A1#1122334455667788
dump_wait
grep -q '5A1 *\[8\] *11 22 33 44 55 66 77 88' /tmp/one.txt || fail "cansend frame: $(cat /tmp/one.txt)"

tx=$(cat /sys/class/net/vcan0/statistics/tx_packets)
echo "smoke: vcan0 tx_packets $tx"
[ "$tx" -eq $((n + 1)) ] || fail "tx_packets $tx, expected $((n + 1))"

ip link del vcan0
echo "smoke: ok"
