#!/bin/sh
# vm-run: --nodes 2
# vm-kernels: rt debug
# A hostile chip, as a broken board or a flaky supply makes one:
#  - INT stuck low for a few seconds: the driver stops taking the line and
#    polls the chip instead; the guest stays responsive, the interrupt
#    count and the log stay bounded, frames still arrive meanwhile, and
#    interrupts come back once INT is released;
#  - garbage on MISO at probe: the device is refused, with one log line;
#  - garbage at run time and a reset of the chip in the middle of traffic:
#    the driver notices, re-initialises the chip with the same settings,
#    reports it with an error frame, and traffic goes on.
set -eu
. /lib/rig.sh

log_mark() { dmesg | wc -l; }
log_since() { # MARK [PATTERN]: kernel log lines since MARK (matching)
	dmesg | tail -n +$(($1 + 1)) | grep -e "${2:-.}" || true
}
# exchange FROM TO FRAME: TO receives FRAME sent on FROM
exchange() {
	dump_start "$2" 1 /tmp/ex.txt
	cansend "$1" "$3"
	dump_wait
	[ "$(wc -l </tmp/ex.txt)" -eq 1 ] || fail "$2 did not receive $3 from $1"
}
# recoveries_reach N: can0 has re-initialised its chip N times or more
recoveries_reach() {
	[ "$(ethtool_stat can0 chip_recoveries)" -ge "$1" ]
}
# within WHAT SECONDS COMMAND...: COMMAND succeeds within SECONDS
within() {
	_what=$1
	shift
	wait_for "$@" || fail "$_what: not within the time allowed"
}

# Each kind of garbage takes the same path through the driver: the debug
# kernel, where every process costs a third of a second under TCG, tries
# one of each list.
probe_patterns="fixed 255:fixed 0:random"
runtime_patterns="fixed 255:random 7"
if [ "$VM_KERNEL" = debug ]; then
	probe_patterns=random
	runtime_patterns="random 7"
fi

can_up can0 125000 restart-ms 100
can_up can1 125000 restart-ms 100
exchange can0 can1 100#01
exchange can1 can0 101#02

echo "== INT stuck low for 4 s"
mark=$(log_mark)
echo 0 >$SIM/chip0/counters
echo 1 >$SIM/chip0/int_stuck
# A busy loop of the shell: it must keep running while INT is stuck.
loops=0
end=$(($(date +%s) + 4))
while [ "$(date +%s)" -lt $end ]; do
	loops=$((loops + 1))
done
# While polled, the chip still delivers frames.
exchange can1 can0 102#03
irqs=$(sim_counter 0 irqs_delivered)
echo "stuck INT: $irqs interrupts taken, shell loop ran $loops times"
log_since "$mark"
# (How often it ran depends on the host's load; that it ran at all is the
# point: a CPU lost to the IRQ thread shows in the interrupt count below.)
[ "$loops" -ge 1 ] || fail "the shell loop never ran"
# Without backing off the thread takes an interrupt every few tens of
# microseconds; polling takes 32 per attempt and attempts after 0.1, 0.2,
# 0.4 ... 2 s.
[ "$irqs" -lt 1000 ] || fail "$irqs interrupts in 4 s of stuck INT"
expect_eq "storm reports" "$(log_since "$mark" 'interrupt storm' | wc -l)" 1
[ "$(log_since "$mark" | wc -l)" -le 5 ] || fail "the storm flooded the log"
expect_eq "irq_storms" "$(ethtool_stat can0 irq_storms)" 1
echo 0 >$SIM/chip0/int_stuck
within "INT back" 6 sh -c "dmesg | tail -n +$((mark + 1)) | grep -q 'INT quiet again'"
irqs=$(sim_counter 0 irqs_delivered)
exchange can1 can0 103#04
[ "$(sim_counter 0 irqs_delivered)" -gt "$irqs" ] || fail "the frame came without an interrupt"
exchange can0 can1 104#05
expect_eq "irq_storms" "$(ethtool_stat can0 irq_storms)" 1
log_since "$mark" 'nobody cared' | grep . && fail "the kernel gave up on the irq"

echo "== garbage on MISO at probe"
ip link set can1 down
dev=$(sim_state 1 spi_device)
drv=/sys/bus/spi/drivers/mcp2510
IFS=:
for pattern in $probe_patterns; do
	unset IFS
	echo "$dev" >$drv/unbind
	[ ! -e /sys/class/net/can1 ] || fail "can1 still there after unbind"
	echo "$pattern" >$SIM/chip1/spi_corrupt_pattern
	echo 4294967295 >$SIM/chip1/spi_corrupt
	mark=$(log_mark)
	echo "$dev" >$drv/bind 2>/dev/null || true
	log_since "$mark"
	[ ! -e /sys/class/net/can1 ] || fail "can1 registered on garbage '$pattern'"
	# (The debug kernel's regulator core adds its own lines to every probe.)
	expect_eq "log lines for a refused probe ($pattern)" \
		"$(log_since "$mark" | grep -vc 'dummy supplies not allowed' || true)" 1
	log_since "$mark" | grep -q "$dev: no mcp2510 answers on SPI: -\(ENODEV\|19\)" ||
		fail "the refusal does not say why"
	echo 0 >$SIM/chip1/spi_corrupt
	echo "$dev" >$drv/unbind 2>/dev/null || true
	echo "$dev" >$drv/bind || fail "probe failed once the garbage stopped"
	within "can1 back" 5 test -e /sys/class/net/can1
done
unset IFS
echo "flip 0" >$SIM/chip1/spi_corrupt_pattern
can_up can1 125000 restart-ms 100
exchange can0 can1 105#06

echo "== garbage on MISO at run time"
errors_start can0 /tmp/err.txt
before=$(ethtool_stat can0 chip_recoveries)
n=0
IFS=:
for pattern in $runtime_patterns; do
	unset IFS
	n=$((n + 1))
	mark=$(log_mark)
	echo "$pattern" >$SIM/chip0/spi_corrupt_pattern
	# The two transfers of the next health check read garbage.
	echo 2 >$SIM/chip0/spi_corrupt
	within "recovery from '$pattern'" 5 recoveries_reach $((before + n))
	log_since "$mark"
	expect_eq "'lost its configuration' lines" "$(log_since "$mark" 'lost its configuration' | wc -l)" 1
	expect_eq "'re-initialised' lines" "$(log_since "$mark" 're-initialised' | wc -l)" 1
	exchange can1 can0 106#07
done
echo "== garbage until cleared: one report, recovery when it stops"
mark=$(log_mark)
echo "fixed 255" >$SIM/chip0/spi_corrupt_pattern
echo 4294967295 >$SIM/chip0/spi_corrupt
sleep 3
echo 0 >$SIM/chip0/spi_corrupt
within "recovery after garbage" 5 recoveries_reach $((before + n + 1))
log_since "$mark"
expect_eq "'lost its configuration' lines" "$(log_since "$mark" 'lost its configuration' | wc -l)" 1
exchange can0 can1 107#08
exchange can1 can0 108#09
sleep 0.2
errors_stop
cat /tmp/err.txt
# CAN_ERR_RESTARTED (0x100) in the error frame's class bits
error_seen /tmp/err.txt 0x100 || fail "no 'controller restarted' error frame"

echo "== chip reset in the middle of traffic"
n=400
rx0=$(if_stat can1 rx_packets) tx0=$(if_stat can0 tx_packets)
drop0=$(if_stat can0 tx_dropped)
for i in 0 1; do echo 0 >$SIM/chip$i/counters; done
before=$(ethtool_stat can0 chip_recoveries)
# -T: candump ends 5 s after its last frame, or after its start when no
# frame came; the debug kernel may take seconds to get cangen going.
candump -T 5000 can1 >/tmp/stream.txt &
cdpid=$!
sleep 0.5
cangen can0 -n $n -g 4 -I 300 -L 8 -D i -i &
gen=$!
sleep 0.6
echo 1 >$SIM/chip0/reset
wait $gen || fail "cangen failed"
within "recovery from the reset" 5 recoveries_reach $((before + 1))
wait $cdpid || true
sent=$(($(if_stat can0 tx_packets) - tx0))
got=$(($(if_stat can1 rx_packets) - rx0))
dropped=$(($(if_stat can0 tx_dropped) - drop0))
on_bus=$(sim_counter 0 frames_tx) stored=$(sim_counter 1 frames_rx) lost=$(sim_counter 1 overflows)
echo "can0 sent $sent, gave up $dropped; chip0 put $on_bus on the bus"
echo "chip1 stored $stored, lost $lost to overflow; can1 received $got"
dmesg | grep -i 'echo_skb' && fail "an echo skb complaint"
# can0 reports what went out (a frame given up at the reset may have gone
# out just before it, unreported); can1 delivers all its chip stored; the
# burst after the recovery may overflow chip1, which the chip counts.
[ "$on_bus" -ge "$sent" ] && [ "$on_bus" -le $((sent + dropped)) ] ||
	fail "chip0 sent $on_bus frames, can0 reported $sent and gave up $dropped"
expect_eq "frames can1 received" "$got" "$stored"
expect_eq "chip1 frames stored + lost" $((stored + lost)) "$on_bus"
# All 20 arrive, but for those chip1 dropped with both receive buffers
# full: a host stall longer than two frame times overflows it whatever
# the driver does (docs/vm-rig.md).
ovf_before=$(sim_counter 1 overflows) drop_before=$(if_stat can0 tx_dropped)
# Room in the queue for the 20 and what is left of the burst before the
# reset: cangen gives up on a full queue, and the debug kernel may still
# be sending that burst.
ip link set can0 txqueuelen 100
dump_start can1 20 /tmp/after.txt
cangen can0 -n 20 -g 4 -I 301 -L 8 || fail "cangen after recovery failed"
dump_wait
after=$(grep -c ' 301  *\[8\]' /tmp/after.txt || true)
dropped_rx=$(($(sim_counter 1 overflows) - ovf_before))
echo "after the recovery: can1 received $after of 20, chip1 dropped $dropped_rx"
expect_eq "can0 frames given up after the recovery" $(($(if_stat can0 tx_dropped) - drop_before)) 0
expect_eq "frames after the recovery, received or dropped by chip1" $((after + dropped_rx)) 20
[ "$(grep -c ' 300  *\[8\]' /tmp/stream.txt || true)" -gt 0 ] || fail "no frame before the reset"

ip -details -statistics link show can0
ethtool -S can0
ip link set can0 down
ip link set can1 down
echo "driver-hostile: ok"
