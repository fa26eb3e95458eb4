#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param time_scale=20
# vm-run: --nodes 2 --variant mcp2515 --sim-param time_scale=20
# vm-kernels: 6.12 debug
# FIFO order when frames lose arbitration: can0 sends a burst of
# sequence-numbered frames (can-flood) through its three TX buffers while
# the phantom node keeps putting short runs of frames of higher priority
# (ID 001) on the bus (burst_under_rival, rig.sh).  can1 acknowledges;
# the bus monitor must show the whole burst, each frame once, in the
# order written.  Bus time runs 20 times slower than real
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
# in, whatever can1 under TCG keeps up with.
burst_under_rival $frames $bitrate
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
