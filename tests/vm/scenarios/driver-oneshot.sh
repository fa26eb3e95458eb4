#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515
# One-shot mode on the MCP2515 (OSM in CANCTRL): a frame nobody
# acknowledges is tried once, counted as aborted and dropped, and the
# queue behind it moves on; an acknowledged frame goes through as usual.
# The same frame without one-shot is retried again and again, which shows
# that the mode really reached the chip.  The bus monitor of the simulator
# counts the attempts.
set -eu
. /lib/rig.sh

sim=/sys/kernel/debug/mcp2510-sim
[ -d "$sim" ] || mount -t debugfs none /sys/kernel/debug
[ -d "$sim" ] || fail "no $sim"

stat() { cat "/sys/class/net/$1/statistics/$2"; }
# attempts ID: frames with identifier ID that chip0 put on the bus.
attempts() { awk -v id="$1" '$3 == "chip0" && index($4, id "#") == 1' "$sim/monitor" | wc -l; }

# settle COUNTER VALUE: poll can0's COUNTER until it reaches VALUE (5 s).
settle() {
	_tries=0
	while [ "$(stat can0 "$1")" -lt "$2" ]; do
		_tries=$((_tries + 1))
		[ $_tries -le 50 ] || fail "can0 $1 is $(stat can0 "$1"), expected $2"
		sleep 0.1
	done
}

echo "== without one-shot an unacknowledged frame is retried"
can_up can1 125000
echo 1 >"$sim/no_ack"
echo clear >"$sim/monitor"
can_up can0 125000
cansend can0 100#01 || fail "cansend can0"
sleep 1
retries=$(attempts 100)
echo "100#01 went out $retries times"
[ "$retries" -gt 3 ] || fail "an unacknowledged frame went out only $retries times"
ip link set can0 down

echo "== one-shot: tried once, aborted, and the queue moves on"
can_up can0 125000 one-shot on
ip -details link show can0 | grep -q 'ONE-SHOT' || fail "ONE-SHOT not shown"
echo clear >"$sim/monitor"
aborted0=$(stat can0 tx_aborted_errors)
for n in 1 2 3 4 5; do
	cansend can0 "20$n#0$n" || fail "cansend can0 20$n"
done
settle tx_aborted_errors $((aborted0 + 5))
sleep 0.5
for n in 1 2 3 4 5; do
	got=$(attempts "20$n")
	[ "$got" -eq 1 ] || { cat "$sim/monitor"; fail "20$n#0$n went out $got times in one-shot mode"; }
done
[ "$(stat can0 tx_packets)" -eq 0 ] || fail "an unacknowledged frame counted as sent"
[ "$(stat can0 tx_aborted_errors)" -eq $((aborted0 + 5)) ] || fail "aborts miscounted"

echo "== one-shot: an acknowledged frame is delivered"
echo 0 >"$sim/no_ack"
dump_start can1 1 /tmp/oneshot.txt
cansend can0 300#AA || fail "cansend can0 300#AA"
dump_wait
grep -q '300 *\[1\] *AA' /tmp/oneshot.txt || { cat /tmp/oneshot.txt; fail "can1 did not receive 300#AA"; }
settle tx_packets 1
[ "$(attempts 300)" -eq 1 ] || fail "300#AA went out $(attempts 300) times"
ip -statistics link show can0
echo "driver-oneshot: ok"
