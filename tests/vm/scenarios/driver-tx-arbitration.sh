#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param time_scale=20
# vm-run: --nodes 2 --variant mcp2515 --sim-param time_scale=20
# vm-kernels: 6.12 debug
# FIFO order when frames lose arbitration: can0 sends a burst of
# sequence-numbered frames (can-flood) through its three TX buffers while
# the phantom node keeps putting short runs of frames of higher priority
# (ID 001) on the bus.  The phantom's frame waits for the frame on the bus
# to end and then meets can0's next one at the start of the next: can0
# loses arbitration to each frame of the run, and sends its frame after
# them.  Runs rather than single frames, so that a guest whose loop runs
# only a few times during the burst (the debug kernel) still makes can0
# lose often.  can1
# acknowledges; the bus monitor must show the whole burst, each frame
# once, in the order written.  Bus time runs 20 times slower than real
# time (a frame at 1 Mbit/s takes about 2 ms), so that the monitor's
# reader under TCG keeps up.
set -eu
. /lib/rig.sh

bitrate=1000000
frames=1000
[ "$VM_KERNEL" != debug ] || frames=300

can_up can0 $bitrate
can_up can1 $bitrate

arb_lost=$(sim_counter 0 arbitration_lost)
# What went on the bus, as the monitor records it: the order can0 sent
# in, whatever can1 under TCG keeps up with.  The phantom's frames are
# another sender's (-o).
can-flood check $frames -i 123 -o -t 5000 -f "$SIM/monitor" >/tmp/bus.txt &
check_pid=$!
wait_for 10 grep -q ready /tmp/bus.txt || fail "can-flood check did not start"

# The competitor: a run of four frames every 10 ms.
(
	while [ ! -e /tmp/stop ]; do
		echo "4 001#00 $bitrate" >"$SIM/flood" 2>/dev/null || true
		nap 0.01
	done
) &
rival_pid=$!

can-flood send can0 $frames -i 123 || fail "can-flood send failed"
touch /tmp/stop
wait "$rival_pid" || true
wait "$check_pid" || true

cat /tmp/bus.txt
lost=$(($(sim_counter 0 arbitration_lost) - arb_lost))
echo "can0 lost arbitration $lost times"
[ "$lost" -ge $((frames / 20)) ] ||
	fail "can0 lost arbitration $lost times: the phantom did not compete"
grep -q "received=$frames lost=0 duplicated=0 reordered=0 corrupted=0" /tmp/bus.txt ||
	fail "the bus did not carry the burst whole and in order"
expect_eq "can0 tx_aborted_errors" "$(if_stat can0 tx_aborted_errors)" 0
expect_eq "can0 tx_packets" "$(if_stat can0 tx_packets)" $frames

ip link set can0 down
ip link set can1 down
echo "driver-tx-arbitration: ok"
