#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510
# vm-kernels: 6.1
# mcp2510d as a service: chip 0 is handed to spidev and bridged by mcp2510d
# to vcan0, chip 1 is can1, driven by mcp2510.ko, on the same simulated
# bus.  Frames go both ways through cangen and candump; a burst sent while
# the daemon is stopped overflows its socket's receive queue, and the
# SO_RXQ_OVFL count must say by how much; then the bus destroys 32 of the
# daemon's frames and chip 0 goes bus-off: it must stay off the bus (it
# would recover by itself after 128 x 11 recessive bits) until
# --restart-ms has passed, vcan0 must carry the bus-off and restarted
# error frames, and traffic must flow again.  At the end every frame sent
# is accounted for, by can1's counters and the daemon's statistics lines
# (SIGUSR1 and at exit).
# Bus time runs 50 times slower than real time, as in driver-busoff-restart:
# chip 0 recovers by itself in 0.56 s instead of 11 ms, so that the daemon
# in a slow guest takes it off the bus first.  A frame takes about 50 ms.
set -eu
. /lib/rig.sh

RESTART_MS=2000

# stat NAME [FILE]: the value after NAME in the daemon's last statistics
# lines in FILE (default: its log).
stat() {
	sed -n "s/.*mcp2510d: stats [a-z]*:.* $1 \([0-9A-Z-]*\).*/\1/p" \
		"${2:-/tmp/d.log}" | tail -1
}
stats_lines() { grep -c ': stats ' /tmp/d.log || true; }
more_stats() { [ "$(stats_lines)" -ge "$1" ]; }
# stats_now: SIGUSR1, then wait for the three lines it prints.
stats_now() {
	_lines=$(stats_lines)
	kill -USR1 "$D_PID"
	wait_for 10 more_stats $((_lines + 3)) || dfail "no statistics on SIGUSR1"
	tail -3 /tmp/d.log
}
# dfail MESSAGE: fail with the daemon's log and its statistics now.
dfail() {
	kill -USR1 "$D_PID" 2>/dev/null && nap 1
	cat /tmp/d.log >&2
	fail "$@"
}
chip0_on_bus() { [ "$(sim_state 0 opmode)" = normal ]; }
daemon_ready() {
	grep -q "INT0 *|mcp2510 " /sys/kernel/debug/gpio && chip0_on_bus
}
logged() { grep -q "$1" /tmp/d.log; }
# to_can1 N ID: N frames cangen sends on vcan0 reach can1.
to_can1() {
	dump_start can1 "$1" /tmp/can1.txt
	cangen vcan0 -n "$1" -g 100 -I "$2" -L 2 -D i
	dump_wait
	expect_lines /tmp/can1.txt "$1"
	[ "$(grep -c " $2 " /tmp/can1.txt)" -eq "$1" ] || fail "can1: frames with a wrong id"
}

echo "== chip 0 to spidev, chip 1 to mcp2510.ko as can1"
rmmod mcp2510_sim || fail "cannot unload mcp2510-sim"
insmod /opt/mcp2510/modules/mcp2510-sim.ko nodes=2 variant="$VM_VARIANT" \
	driver="$VM_DRIVER" spidev_node=0 time_scale=50 ||
	fail "cannot load mcp2510-sim"
wait_for 10 test -e /sys/class/net/can0 || fail "chip 1 did not become a CAN interface"
ip link set can0 name can1
dev=/dev/spidev$(sim_state 0 spi_bus).$(sim_state 0 spi_cs)
wait_for 10 test -c "$dev" || fail "$dev did not appear"
gpiochip=$(gpiodetect | awk '$2 == "[mcp2510-sim]" { print $1 }')
[ -n "$gpiochip" ] || fail "no gpiochip labelled mcp2510-sim"
can_up can1 125000
ip link add dev vcan0 type vcan
ip link set vcan0 up

# A small receive queue for the daemon's socket, so that a short burst
# overflows it; back to the default for everything else.
rmem=$(cat /proc/sys/net/core/rmem_default)
echo 4096 >/proc/sys/net/core/rmem_default
mcp2510d --device "spidev:$dev" --int "$gpiochip:0" --clock 16000000 \
	--variant "$VM_VARIANT" --bitrate 125000 --iface vcan0 \
	--restart-ms $RESTART_MS 2>/tmp/d.log &
D_PID=$!
wait_for 10 daemon_ready || { cat /tmp/d.log; fail "mcp2510d did not bring chip 0 up"; }
echo "$rmem" >/proc/sys/net/core/rmem_default

echo "== vcan0 -> can1, can1 -> vcan0"
to_can1 10 123
dump_start vcan0 10 /tmp/vcan0.txt
cangen can1 -n 10 -g 100 -I 321 -L 8 -D i
dump_wait
expect_lines /tmp/vcan0.txt 10
[ "$(grep -c " 321 " /tmp/vcan0.txt)" -eq 10 ] || fail "vcan0: frames with a wrong id"
stats_now
expect_eq "to-iface" "$(stat to-iface)" 10
expect_eq "to-chip" "$(stat to-chip)" 10

echo "== a burst while the daemon is stopped: counted, not silent"
rx1=$(if_stat can1 rx_packets)
kill -STOP "$D_PID"
cangen vcan0 -n 40 -g 0 -I 200 -L 8 -D i
kill -CONT "$D_PID"
# what the queue kept goes out at about 20 frames a second
can1_got_more() { [ "$(if_stat can1 rx_packets)" -gt "$1" ]; }
wait_for 20 can1_got_more "$rx1" || dfail "nothing of the burst reached can1"
settled() {
	_a=$(if_stat can1 rx_packets)
	nap 1
	[ "$(if_stat can1 rx_packets)" -eq "$_a" ]
}
wait_for 20 settled || dfail "the burst never ended"
stats_now
burst=$(($(if_stat can1 rx_packets) - rx1))
lost=$(stat rxq-overflow)
echo "burst: $burst of 40 reached can1, $lost dropped by the socket's queue"
[ "$lost" -gt 0 ] || dfail "the receive queue overflowed silently"
expect_eq "burst forwarded + dropped" $((burst + lost)) 40
expect_eq "to-chip" "$(stat to-chip)" $((10 + burst))

echo "== bus-off, and the restart $RESTART_MS ms later"
errors_start vcan0 /tmp/err.txt
echo 32 >"$SIM/bus_errors"
cansend vcan0 100#01
wait_for 30 logged "bus-off, scheduling restart in $RESTART_MS ms" ||
	dfail "mcp2510d reported no bus-off"
# Off the bus for longer than the chip's own recovery (0.56 s here).
_now
end=$((NOW_S + 2))
checks=0
while [ "$NOW_S" -lt "$end" ] && ! logged restarted; do
	chip0_on_bus && ! logged restarted && fail "chip 0 back on the bus before its restart"
	checks=$((checks + 1))
	nap 0.2
	_now
done
[ "$checks" -gt 0 ] || fail "the restart came before the first look"
wait_for 15 logged restarted || dfail "no restart"
wait_for 10 chip0_on_bus || dfail "chip 0 not back on the bus after its restart"
errors_stop
cat /tmp/err.txt
error_seen /tmp/err.txt 0x40 || fail "vcan0 carried no bus-off error frame"
error_seen /tmp/err.txt 0x100 || fail "vcan0 carried no restarted error frame"
to_can1 10 456

echo "== every frame accounted for"
kill -TERM "$D_PID"
wait "$D_PID" || { cat /tmp/d.log; fail "mcp2510d exited with an error"; }
cat /tmp/d.log
logged "mcp2510d: stopped" || fail "no stop message"
ip -details -statistics link show can1
# the last three lines are the statistics at exit
expect_eq "to-iface" "$(stat to-iface)" 10
expect_eq "can1 tx_packets" "$(if_stat can1 tx_packets)" 10
# 10 + burst + 1 queued on chip 0, of which the one that met the bus errors
# was aborted at bus-off; the other 20 reached can1
expect_eq "to-chip" "$(stat to-chip)" $((10 + burst + 1 + 10))
expect_eq "tx-aborted" "$(stat tx-aborted)" 1
expect_eq "can1 rx_packets" "$(if_stat can1 rx_packets)" $((10 + burst + 10))
expect_eq "rxq-overflow" "$(stat rxq-overflow)" "$lost"
expect_eq "bus-off" "$(stat bus-off)" 1
expect_eq "restarts" "$(stat restarts)" 1
expect_eq "iface-full" "$(stat iface-full)" 0
expect_eq "event-overflow" "$(stat event-overflow)" 0
expect_eq "chip-rx-overflow" "$(stat chip-rx-overflow)" 0
expect_eq "chip0 bus-offs" "$(sim_counter 0 bus_off)" 1
[ "$(stat state)" = ERROR-ACTIVE ] || fail "final state $(stat state)"

ip link set can1 down
ip link del vcan0
echo "userspace-daemon: ok"
