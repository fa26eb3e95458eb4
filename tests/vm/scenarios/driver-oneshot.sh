#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515
# vm-kernels: debug
# One-shot mode on the MCP2515 (OSM in CANCTRL): a frame nobody
# acknowledges is tried once, counted as aborted and dropped, and the
# queue behind it moves on; an acknowledged frame goes through as usual.
# The same frame without one-shot is retried again and again, which shows
# that the mode really reached the chip.  The bus monitor of the simulator
# counts the attempts.
#
# An unacknowledged frame is tried again every 0.5 ms of bus time at
# 125 kbit/s.  The debug kernel takes longer than that to model one
# attempt, so the model would never catch up with bus time: there bus
# time runs 20 times slower.
set -eu
. /lib/rig.sh

[ "$VM_KERNEL" != debug ] || echo 20 >"$SIM/time_scale"

# attempts ID: frames with identifier ID that chip0 put on the bus.
attempts() { awk -v id="$1" '$3 == "chip0" && index($4, id "#") == 1' "$SIM/monitor" | wc -l; }

# reached COUNTER VALUE: can0's COUNTER is VALUE or more.
reached() { [ "$(if_stat can0 "$1")" -ge "$2" ]; }

# settle COUNTER VALUE: wait until can0's COUNTER reaches VALUE.
settle() {
	wait_for 10 reached "$1" "$2" ||
		fail "can0 $1 is $(if_stat can0 "$1"), expected $2"
}

echo "== without one-shot an unacknowledged frame is retried"
can_up can1 125000
echo 1 >"$SIM/no_ack"
echo clear >"$SIM/monitor"
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
echo clear >"$SIM/monitor"
aborted0=$(if_stat can0 tx_aborted_errors)
for n in 1 2 3 4 5; do
	cansend can0 "20$n#0$n" || fail "cansend can0 20$n"
done
settle tx_aborted_errors $((aborted0 + 5))
sleep 0.5
for n in 1 2 3 4 5; do
	got=$(attempts "20$n")
	[ "$got" -eq 1 ] || { cat "$SIM/monitor"; fail "20$n#0$n went out $got times in one-shot mode"; }
done
[ "$(if_stat can0 tx_packets)" -eq 0 ] || fail "an unacknowledged frame counted as sent"
[ "$(if_stat can0 tx_aborted_errors)" -eq $((aborted0 + 5)) ] || fail "aborts miscounted"

echo "== one-shot: an acknowledged frame is delivered"
echo 0 >"$SIM/no_ack"
dump_start can1 1 /tmp/oneshot.txt
cansend can0 300#AA || fail "cansend can0 300#AA"
dump_wait
grep -q '300 *\[1\] *AA' /tmp/oneshot.txt || { cat /tmp/oneshot.txt; fail "can1 did not receive 300#AA"; }
settle tx_packets 1
[ "$(attempts 300)" -eq 1 ] || fail "300#AA went out $(attempts 300) times"
ip -statistics link show can0
echo "driver-oneshot: ok"
