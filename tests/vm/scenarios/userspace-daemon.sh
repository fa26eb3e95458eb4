#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510
# vm-kernels: 6.1
# mcp2510d as a service: chip 0 is handed to spidev and bridged by mcp2510d
# to vcan0, chip 1 is can1, driven by mcp2510.ko, on the same simulated
# bus.  Frames go both ways through cangen and candump; the bus destroys 32
# of the daemon's frames and chip 0 goes bus-off: it must stay off the bus
# (it would recover by itself after 128 x 11 recessive bits) until
# --restart-ms has passed, vcan0 must carry the bus-off and restarted error
# frames, and traffic must flow again.  Then a second daemon, started with
# a small socket receive queue, is stopped while a burst arrives: what the
# queue dropped must be counted (SO_RXQ_OVFL), exactly; with restart-ms 0
# it stays bus-off until SIGHUP.  Each daemon's
# statistics lines (SIGUSR1 and at exit) and can1's counters account for
# every frame.
# Bus time runs 50 times slower than real time, as in driver-busoff-restart:
# chip 0 recovers by itself in 0.56 s instead of 11 ms, so that the daemon
# in a slow guest takes it off the bus first.  A frame takes about 50 ms.
set -eu
. /lib/rig.sh

RESTART_MS=1500
DLOG=/tmp/d.log

# stat NAME: the value after NAME in the daemon's last statistics lines.
stat() {
	sed -n "s/.*mcp2510d: stats [a-z]*:.* $1 \([0-9A-Z-]*\).*/\1/p" "$DLOG" | tail -1
}
stats_lines() { grep -c ': stats ' "$DLOG" || true; }
more_stats() { [ "$(stats_lines)" -ge "$1" ]; }
# dfail MESSAGE: fail with the daemon's log and its statistics now.
dfail() {
	kill -USR1 "$D_PID" 2>/dev/null && nap 1
	cat "$DLOG" >&2
	fail "$@"
}
# stats_now: SIGUSR1, then wait for the three lines it prints.
stats_now() {
	_lines=$(stats_lines)
	kill -USR1 "$D_PID"
	wait_for 10 more_stats $((_lines + 3)) || dfail "no statistics on SIGUSR1"
	tail -3 "$DLOG"
}
logged() { grep -q "$1" "$DLOG"; }
chip0_on_bus() { [ "$(sim_state 0 opmode)" = normal ]; }
daemon_ready() {
	grep -q "INT0 *|mcp2510 " /sys/kernel/debug/gpio && chip0_on_bus
}
# daemon_start LOG RMEM RESTART_MS: mcp2510d on chip 0 with a socket
# receive queue of RMEM bytes (the default for sockets made meanwhile).
daemon_start() {
	DLOG=$1
	_rmem=$(cat /proc/sys/net/core/rmem_default)
	echo "$2" >/proc/sys/net/core/rmem_default
	mcp2510d --device "spidev:$dev" --int "$gpiochip:0" --clock 16000000 \
		--variant "$VM_VARIANT" --bitrate 125000 --iface vcan0 \
		--restart-ms "$3" 2>"$DLOG" &
	D_PID=$!
	wait_for 10 daemon_ready || dfail "mcp2510d did not bring chip 0 up"
	echo "$_rmem" >/proc/sys/net/core/rmem_default
}
# daemon_stop: SIGTERM; it must end cleanly with its statistics.
daemon_stop() {
	kill -TERM "$D_PID"
	wait "$D_PID" || { cat "$DLOG"; fail "mcp2510d exited with an error"; }
	cat "$DLOG"
	logged "mcp2510d: stopped" || fail "no stop message"
	[ "$(stat state)" = ERROR-ACTIVE ] || fail "final state $(stat state)"
}
# to_can1 N ID: N frames cangen sends on vcan0 reach can1.
to_can1() {
	dump_start can1 "$1" /tmp/can1.txt
	cangen vcan0 -n "$1" -g 100 -I "$2" -L 2 -D i
	dump_wait
	[ "$(wc -l </tmp/can1.txt)" -eq "$1" ] ||
		{ cat /tmp/can1.txt; dfail "can1 got $(wc -l </tmp/can1.txt) of $1 frames"; }
	[ "$(grep -c " $2 " /tmp/can1.txt)" -eq "$1" ] || fail "can1: frames with a wrong id"
}
can1_got_more() { [ "$(if_stat can1 rx_packets)" -gt "$1" ]; }
can1_settled() {
	_a=$(if_stat can1 rx_packets)
	nap 0.5
	[ "$(if_stat can1 rx_packets)" -eq "$_a" ]
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
gpiochip=$(gpio_chip mcp2510-sim)
[ -n "$gpiochip" ] || fail "no gpiochip labelled mcp2510-sim"
can_up can1 125000
ip link add dev vcan0 type vcan
ip link set vcan0 up
daemon_start /tmp/d.log "$(cat /proc/sys/net/core/rmem_default)" $RESTART_MS

echo "== vcan0 -> can1, can1 -> vcan0"
to_can1 5 123
dump_start vcan0 5 /tmp/vcan0.txt
cangen can1 -n 5 -g 100 -I 321 -L 8 -D i
dump_wait
expect_lines /tmp/vcan0.txt 5
[ "$(grep -c " 321 " /tmp/vcan0.txt)" -eq 5 ] || fail "vcan0: frames with a wrong id"
stats_now
expect_eq "to-iface" "$(stat to-iface)" 5
expect_eq "to-chip" "$(stat to-chip)" 5

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
	chip0_on_bus && ! logged restarted && dfail "chip 0 back on the bus before its restart"
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
to_can1 5 456

echo "== the first daemon's account"
daemon_stop
expect_eq "to-iface" "$(stat to-iface)" 5
expect_eq "can1 tx_packets" "$(if_stat can1 tx_packets)" 5
# 11 frames queued on chip 0; the one that met the bus errors was aborted
# at bus-off, the other 10 reached can1
expect_eq "to-chip" "$(stat to-chip)" 11
expect_eq "tx-aborted" "$(stat tx-aborted)" 1
expect_eq "can1 rx_packets" "$(if_stat can1 rx_packets)" 10
expect_eq "error-frames" "$(stat error-frames)" 4
for c in rxq-overflow iface-full bus-off-drops chip-rx-overflow event-overflow; do
	expect_eq "$c" "$(stat $c)" 0
done
expect_eq "bus-off" "$(stat bus-off)" 1
expect_eq "restarts" "$(stat restarts)" 1
expect_eq "chip0 bus-offs" "$(sim_counter 0 bus_off)" 1

echo "== a burst while a daemon with a small queue is stopped: counted"
daemon_start /tmp/d2.log 4096 0
rx1=$(if_stat can1 rx_packets)
kill -STOP "$D_PID"
cangen vcan0 -n 40 -g 0 -I 200 -L 8 -D i
kill -CONT "$D_PID"
# what the queue kept goes out at about 20 frames a second
wait_for 20 can1_got_more "$rx1" || dfail "nothing of the burst reached can1"
wait_for 20 can1_settled || dfail "the burst never ended"
stats_now
burst=$(($(if_stat can1 rx_packets) - rx1))
lost=$(stat rxq-overflow)
echo "burst: $burst of 40 reached can1, $lost dropped by the socket's queue"
[ "$lost" -gt 0 ] || dfail "the receive queue overflowed silently"
expect_eq "burst forwarded + dropped" $((burst + lost)) 40

echo "== restart-ms 0: bus-off until SIGHUP"
echo 32 >"$SIM/bus_errors"
cansend vcan0 100#02
wait_for 30 logged "bus-off, restart with SIGHUP" || dfail "mcp2510d reported no bus-off"
nap 1.5
chip0_on_bus && dfail "chip 0 left bus-off without SIGHUP"
kill -HUP "$D_PID"
wait_for 10 logged restarted || dfail "no restart on SIGHUP"
wait_for 10 chip0_on_bus || dfail "chip 0 not back on the bus after SIGHUP"
to_can1 1 457
daemon_stop
# the burst's frames, the one aborted at bus-off and the one after it
expect_eq "to-chip" "$(stat to-chip)" $((burst + 2))
expect_eq "tx-aborted" "$(stat tx-aborted)" 1
expect_eq "rxq-overflow" "$(stat rxq-overflow)" "$lost"
expect_eq "bus-off" "$(stat bus-off)" 1
expect_eq "restarts" "$(stat restarts)" 1
expect_eq "can1 rx_packets" "$(if_stat can1 rx_packets)" $((10 + burst + 1))
expect_eq "can1 rx_over_errors" "$(if_stat can1 rx_over_errors)" 0

ip link set can1 down
ip link del vcan0
echo "userspace-daemon: ok"
