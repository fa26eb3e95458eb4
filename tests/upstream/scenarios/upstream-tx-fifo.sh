#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x --sim-param time_scale=20
# Shows what upstream/mcp251x/0009 adds: frames sent from all three
# transmit buffers, in the order they were queued.  can0 sends a burst of
# 200 sequence-numbered frames at 1 Mbit/s while the phantom node keeps
# winning arbitration with runs of frames of higher priority
# (burst_under_rival, rig.sh).  The bus monitor must show the burst whole
# and in order, and can0's frames back to back, the next one starting as
# soon as the last ended (3 bit times of intermission): with one buffer
# the next frame is not loaded until the last one's interrupt is served,
# tens of bit times later.  Bus time runs 20 times slower than real time,
# as in driver-tx-arbitration, for the monitor's reader.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

frames=200
bitrate=1000000
mcp251x_under_test

can_up can0 $bitrate
can_up can1 $bitrate
burst_under_rival $frames $bitrate
grep -q "received=$frames lost=0 duplicated=0 reordered=0 corrupted=0" /tmp/bus.txt ||
	fail "$under_test: the bus did not carry the burst whole and in order"
expect_eq "can0 tx_packets" "$(if_stat can0 tx_packets)" $frames
# Pairs of can0's frames the monitor still holds one after the other, and
# of them those back to back: the gap from one's end to the next one's
# start at most 3 bit times.
set -- $(awk -v bit_ns=$((1000000000 / bitrate)) '
	$3 == "chip0" && prev != "" {
		pairs++
		if ($1 - prev <= 3 * bit_ns)
			tight++
	}
	{ prev = $3 == "chip0" ? $2 : "" }
	END { print pairs + 0, tight + 0 }' "$SIM/monitor")
echo "$under_test: of $1 pairs of can0's frames in a row on the bus, $2 back to back"
ip link set can0 down
ip link set can1 down

if [ -n "$ko" ]; then
	[ "$2" -gt 0 ] || fail "$under_test: no two of can0's frames back to back"
	echo "upstream-tx-fifo: $under_test sent $frames frames in order, $2 of $1 pairs back to back"
else
	[ "$2" -eq 0 ] || fail "$under_test sends frames back to back: the kernel has the change"
	echo "upstream-tx-fifo: $under_test sent $frames frames in order, none back to back"
fi
