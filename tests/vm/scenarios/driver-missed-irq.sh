#!/bin/sh
# vm-run: --nodes 2 --sim-param int_trigger=edge-falling
# vm-kernels: debug
# missed_interrupts counts chip events that the driver's polling of an
# edge-triggered INT found without an interrupt for them: edges that were
# lost.  With every edge delivered it must stay 0, although the polling
# often runs while an interrupt's thread waits for the chip: that work
# is the thread's, not a missed interrupt.
set -eu
. /lib/rig.sh

can_up can0 500000
can_up can1 500000
ip link set can1 txqueuelen 1000
for i in 0 1; do echo 0 >"$SIM/chip$i/counters"; done
missed=$(ethtool_stat can0 missed_interrupts)
n=1500
dump_start can0 "$n" /tmp/at0.txt
cangen can1 -n "$n" -g 1 -I 100 -L 8 || fail "cangen on can1 failed"
dump_wait
lost=$(sim_counter 0 overflows)
echo "can0: $(wc -l </tmp/at0.txt) frames, chip0 lost $lost, $(sim_counter 0 irqs_delivered) interrupts"
expect_eq "chip0 edges missed" "$(sim_counter 0 int_edges_missed)" 0
expect_eq "can0 missed_interrupts" \
	"$(($(ethtool_stat can0 missed_interrupts) - missed))" 0
echo "driver-missed-irq: ok"
