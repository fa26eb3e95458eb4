#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-run: --nodes 2 --variant mcp2515
# vm-run: --nodes 2 --variant mcp2515 --sim-param int_trigger=edge-falling
# vm-kernels: debug
# Receive timestamps come from the time INT fired.  A flood from the
# phantom node fills both receive buffers of can1 (under TCG it overruns
# them); for every frame the stack got, its SO_TIMESTAMPNS stamp is not
# before the frame ended on the bus (the simulator's monitor_times) and
# is before recvmsg() returned it, and the stamps never decrease in the
# order the frames arrive, as candump -t a shows them too.  ethtool -T
# offers software stamps, not hardware ones.  The error figures go to
# make bench (rx_timestamp_error_us); here they are only printed.  On an
# edge-triggered INT the thread loops over passes and the hard handler
# may run during one: the same checks hold, and lone frames at uneven
# gaps over a slow SPI bus make that happen often (stamp_paced).
set -eu
. /lib/rig.sh
. /lib/rx-timestamps.sh

stamps_offered can1
stamp_isolated || fail "stamps taken after the chip was read"
stamp_paced
stamp_bursts

echo "driver-rx-timestamp: ok"
