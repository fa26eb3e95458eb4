#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --sim-param int_trigger=edge-falling --sim-param time_scale=4
# vm-kernels: 6.12 debug
# Timestamps on a sending interface: can0 and can1 send to each other at
# once, and candump on can0 sees can0's own frames (their echoes) among
# the frames from can1.  The stamps never decrease in the order candump
# gets them: an echo is stamped when its transmission was seen complete,
# as a received frame is when it was seen, not later when the stack takes
# it.  On an edge-triggered INT one hold of the chip lock may read a TX
# completion and, in a later pass, a received frame.  Each sender's queue
# holds its whole burst (cangen -i would drop what finds it full), and bus
# time runs 4 times slower than real time, so that the debug kernel under
# TCG takes every frame.
set -eu
. /lib/rig.sh

FRAMES=300
ip link set can0 txqueuelen $((FRAMES + 16))
ip link set can1 txqueuelen $((FRAMES + 16))
can_up can0 500000
can_up can1 500000
dump_start can0 100000 /tmp/dump.txt -t a
cangen can0 -g 1 -i -n $FRAMES -I 100 -L 8 -D i &
gen0=$!
cangen can1 -g 1 -i -n $FRAMES -I 200 -L 8 -D i &
gen1=$!
wait "$gen0" || fail "cangen can0"
wait "$gen1" || fail "cangen can1"
nap 1
kill "$DUMP_PID"
dump_wait
echoes=$(grep -c ' 100 ' /tmp/dump.txt || true)
received=$(grep -c ' 200 ' /tmp/dump.txt || true)
echo "candump on can0: $echoes echoes, $received from can1"
[ "$echoes" -ge 100 ] && [ "$received" -ge 100 ] || fail "too little traffic to judge"
# (SECONDS.MICROSECONDS), both zero-padded: the digits compare as strings
tr -d '()' </tmp/dump.txt | awk '{ split($1, t, "[.]"); k = t[1] "" t[2]
	if (NR > 1 && k < last) { print "back in time: " p; print "          to: " $0; bad = 1 }
	last = k; p = $0 } END { exit bad }' ||
	fail "candump -t a timestamps go back"
echo "driver-echo-timestamp: ok"
