#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-kernels: rt debug
# mcp2510.ko brought up and down again and again, and unloaded under load:
# 100 x ifup/ifdown of can0 (20 on the RT kernel, 10 on the debug kernel),
# each time with a frame that reaches can1;
# then rmmod while cangen floods can0 and candump listens on can1, insmod
# again, and traffic works on the new interfaces.  No splat, no leak: vm-run
# fails on any kernel report, and on the debug kernel /init ends with a
# kmemleak scan that must find nothing.
set -eu
. /lib/rig.sh

cycles=100
case $VM_KERNEL in
6.1 | 6.12) ;;
rt)
	# Fewer cycles give PREEMPT_RT the same paths to judge in a fifth of
	# the time.
	cycles=20
	;;
debug)
	# Every process costs the debug kernel a third of a second under TCG:
	# 10 cycles give lockdep and kmemleak every path of open and close.
	cycles=10
	;;
esac
mods=/opt/mcp2510/modules

show() { ip -details -statistics link show "$1"; }

# more_irqs CHIP N: more than N interrupts of CHIP reached Linux.
more_irqs() { [ "$(sim_counter "$1" irqs_delivered)" -gt "$2" ]; }

# until_sent N: poll, more finely than wait_for, until can0 sent frame N+1.
until_sent() {
	_tries=0
	while ! sent_beyond can0 "$1"; do
		_tries=$((_tries + 1))
		[ $_tries -le 400 ] || return 1
		nap 0.05
	done
}

echo "== $cycles x ifup/ifdown with a frame each"
ip link set can0 type can bitrate 500000
can_up can1 500000
start=$(uptime_s)
dump_start can1 "$cycles" /tmp/cycles.txt
i=0
while [ $i -lt $cycles ]; do
	ip link set can0 up || fail "cycle $i: can0 did not come up"
	cansend can0 "$(printf '%03X#%02X' "$i" $((i % 256)))" || fail "cycle $i: cansend"
	until_sent "$i" || { show can0; fail "cycle $i: the frame was never sent"; }
	ip link set can0 down || fail "cycle $i: can0 did not go down"
	i=$((i + 1))
done
dump_wait
echo "$cycles cycles in $(($(uptime_s) - start)) s"
expect_lines /tmp/cycles.txt "$cycles"
awk '{ want = sprintf("%03X", NR - 1); if ($2 != want) { print "line " NR ": " $0; exit 1 } }' \
	/tmp/cycles.txt || fail "can1 got the cycles' frames out of order"
[ "$(if_stat can0 tx_packets)" -eq $cycles ] || fail "can0 tx_packets $(if_stat can0 tx_packets)"
[ "$(if_stat can0 tx_dropped)" -eq 0 ] || fail "can0 dropped frames"
[ "$(sim_state 0 opmode)" = sleep ] || fail "chip0 is $(sim_state 0 opmode), not asleep, while can0 is down"
ip link set can1 down

echo "== rmmod during a flood"
can_up can0 500000
can_up can1 500000
candump can1 >/tmp/flood.txt &
dump=$!
# -i: a slow kernel fills the TX queue, and cangen would stop at the
# first ENOBUFS; the flood must go on until rmmod.
cangen -g 1 -i -I 100 -L 8 -D i can0 2>/dev/null &
gen=$!
wait_for 20 grep -q . /tmp/flood.txt || fail "the flood does not reach can1"
irqs=$(sim_counter 1 irqs_delivered)
wait_for 20 more_irqs 1 $((irqs + 20)) || fail "the flood stopped before rmmod"
rmmod mcp2510 || fail "rmmod mcp2510 failed"
[ ! -e /sys/class/net/can0 ] && [ ! -e /sys/class/net/can1 ] ||
	fail "the interfaces outlived the module"
# Both tools lose their interface; neither may hang.
wait_for 10 sh -c "! kill -0 $gen 2>/dev/null" || kill "$gen"
wait "$gen" || true
wait_for 10 sh -c "! kill -0 $dump 2>/dev/null" || kill "$dump"
wait "$dump" || true
echo "can1 received $(wc -l </tmp/flood.txt) frames before rmmod"

echo "== insmod again"
insmod $mods/mcp2510.ko || fail "insmod mcp2510.ko failed"
wait_for 20 test -e /sys/class/net/can1 || fail "can0/can1 did not come back"
can_up can0 500000
can_up can1 500000
dump_start can0 1 /tmp/back0.txt
cansend can1 7FF#5AA5
dump_wait
grep -q '7FF *\[2\] *5A A5' /tmp/back0.txt || fail "no traffic can1 -> can0 after insmod"
dump_start can1 1 /tmp/back1.txt
cansend can0 12345678#01
dump_wait
grep -q '12345678 *\[1\] *01' /tmp/back1.txt || fail "no traffic can0 -> can1 after insmod"
show can0
ip link set can0 down
ip link set can1 down
echo "driver-lifecycle: ok"
