#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x --sim-param int_trigger=edge-falling
# Shows what upstream/mcp251x/0012 (RFC) adds: receive timestamps from the
# time INT fired.  Lone frames, with SPI messages that cost 50 ms each:
# the stack stamps a frame once the driver has read it, two messages
# (100 ms) after its end at least; with the patch the stamp is the time INT
# fired, less than that after the end of the frame.  Then driver-rx-
# timestamp's honesty checks (/lib/rx-timestamps.sh) on lone frames at
# uneven gaps over the slow SPI bus and on floods of 60 frames (500
# kbit/s, both buffers overrun, and 125 kbit/s): every stamp after the
# end of its frame on the bus and before recvmsg() returned it, never
# decreasing in arrival order, in SO_TIMESTAMPNS and in candump -t a.
# Both INT triggers: on a falling edge the hard handler may run while
# the IRQ thread is still busy.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh
. /lib/rx-timestamps.sh

mcp251x_under_test

stamps_offered can1
if [ -z "$ko" ]; then
	! stamp_isolated || fail "$under_test stamps frames when INT fired: the kernel has the change"
	echo "upstream-rx-timestamp: $under_test stamps frames after reading them"
	exit 0
fi
stamp_isolated || fail "$under_test: stamps taken after the chip was read"
stamp_paced
stamp_bursts

echo "upstream-rx-timestamp: $under_test stamps frames when INT fired, honestly"
