#!/bin/sh
# vm-run: --nodes 2 --sim-param int_trigger=edge-falling
# vm-kernels: rt debug
# An edge-triggered INT, as a firmware may describe it: the driver takes
# the trigger type the firmware gives, and a lost edge (INT already low,
# so no further edge will come) stalls nothing.  One lost edge on a quiet
# chip: the frame still arrives and the next one raises an edge again.
# Then lost edges on both chips during traffic both ways: every frame
# arrives or is counted lost by the chip that overflowed, in order (but
# for adjacent swaps after an overflow).
set -eu
. /lib/rig.sh

can_up can0 500000
can_up can1 500000
# request_irq() programs the trigger the driver asks for: had it asked for
# its default, level-low, the line would show that now.
for i in 0 1; do
	[ "$(sim_state $i irq_type)" = edge-falling ] ||
		fail "chip$i's INT is $(sim_state $i irq_type), not edge-falling"
done

echo "== one lost edge on a quiet chip"
missed=$(ethtool_stat can1 missed_interrupts)
echo 1 >$SIM/chip1/int_edge_miss
dump_start can1 2 /tmp/one.txt
cansend can0 321#01
# INT of chip1 is now low with no edge delivered; only the driver's own
# polling can empty the chip and let the next frame make an edge.
sleep 0.5
cansend can0 321#02
dump_wait
cat /tmp/one.txt
expect_lines /tmp/one.txt 2
expect_eq "chip1 edges missed" "$(sim_counter 1 int_edges_missed)" 1
[ "$(ethtool_stat can1 missed_interrupts)" -gt "$missed" ] ||
	fail "can1 did not report finding work without an interrupt"
[ "$(sim_state 1 int)" -eq 1 ] || fail "chip1's INT is still asserted"

echo "== lost edges on both chips during traffic both ways"
# A lost edge stalls a chip until the driver polls it: room in the queues
# for the frames cangen sends meanwhile.
ip link set can0 txqueuelen 1000
ip link set can1 txqueuelen 1000
n=200
for i in 0 1; do echo 0 >$SIM/chip$i/counters; done
# each side sees the other's frames and the echo of its own
dump_start can0 $((2 * n)) /tmp/at0.txt
dump_start can1 $((2 * n)) /tmp/at1.txt
echo 5 >$SIM/chip0/int_edge_miss
echo 5 >$SIM/chip1/int_edge_miss
cangen can0 -n $n -g 5 -I 100 -L 8 -D i &
gen0=$!
cangen can1 -n $n -g 5 -I 200 -L 8 -D i &
gen1=$!
wait $gen0 || fail "cangen on can0 failed"
wait $gen1 || fail "cangen on can1 failed"
dump_wait
for i in 0 1; do
	echo "chip$i: $(sim_counter $i int_edges_missed) edges missed, $(sim_counter $i irqs_delivered) interrupts; can$i: $(ethtool_stat can$i missed_interrupts) found by polling"
done
# Each side echoes all of its own frames.  A chip left unserviced until
# the driver polls it may overflow: what it did not store, it counted.
for i in 0 1; do
	own=$((100 * (i + 1))) other=$((200 - 100 * i))
	got=$(grep -c " $own  *\[8\]" /tmp/at$i.txt || true)
	expect_eq "can$i echoes of its frames" "$got" $n
	got=$(grep -c " $other  *\[8\]" /tmp/at$i.txt || true)
	lost=$(sim_counter $i overflows)
	echo "can$i: received $got of the other side's frames, chip$i lost $lost"
	expect_eq "can$i frames received + lost" $((got + lost)) $n
	# one report per overflow, however many frames it cost
	over=$(cat /sys/class/net/can$i/statistics/rx_over_errors)
	[ "$lost" -eq 0 ] || [ "$over" -gt 0 ] || fail "can$i did not report its overflows"
done
# counters FILE ID: the counter cangen -D i put in the first two bytes of
# each frame ID in candump FILE, as fixed-width hex, in arrival order.
counters() {
	grep " $2  *\[8\]" "$1" | awk '{ print $5 $4 }'
}
# nearly_in_order: of the counters on stdin, none comes twice and each is
# above the one two before it: at most two adjacent frames swapped.
nearly_in_order() {
	awk '{ v = "x" $1 }
	     NR > 2 && v <= p2 { bad = 1 }
	     seen[v]++ { bad = 1 }
	     { p2 = p1; p1 = v }
	     END { exit bad }'
}
# Each side's echoes of its own frames arrive in send order.  Received
# frames too, unless the chip overflowed: then two adjacent frames may
# swap (RXB1 can hold the newer frame, see driver/core/irq_rx.c).
for i in 0 1; do
	own=$((100 * (i + 1))) other=$((200 - 100 * i))
	counters /tmp/at$i.txt $own >/tmp/seq.txt
	sort -c /tmp/seq.txt 2>/dev/null ||
		{ head /tmp/seq.txt; fail "can$i: echoes of id $own out of order"; }
	counters /tmp/at$i.txt $other >/tmp/seq.txt
	if [ "$(sim_counter $i overflows)" -eq 0 ]; then
		sort -c /tmp/seq.txt 2>/dev/null ||
			{ head /tmp/seq.txt; fail "can$i: id $other out of order"; }
	else
		nearly_in_order </tmp/seq.txt ||
			{ head /tmp/seq.txt; fail "can$i: id $other out of order beyond a swap"; }
	fi
done
for i in 0 1; do
	expect_eq "chip$i edges missed" "$(sim_counter $i int_edges_missed)" 5
done
ip -details -statistics link show can1
ip link set can0 down
ip link set can1 down
echo "driver-edge-int: ok"
