#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# Reproducer of upstream/mcp251x/0001 (receive order): the phantom node
# floods can1 with 3000 numbered frames back to back at 1 Mbit/s, more
# than mainline mcp251x can take, and can-flood counts the frames that
# reach the socket after a newer one.  mcp251x frees RXB0, hands its frame
# to the stack and only then reads CANINTF again to see whether RXB1 is
# full; meanwhile one frame can fill the freed RXB0 and the next one RXB1,
# and mcp251x then reads RXB1, the newer frame, first.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

mcp251x_under_test

frames=3000
rounds=6
can_up can1 1000000
round=1 reordered=0
while [ $round -le $rounds ]; do
	can-flood recv can1 $frames -o -t 3000 -l 1000 >/tmp/flood.txt &
	pid=$!
	wait_for 10 grep -q ready /tmp/flood.txt || fail "can-flood did not start"
	echo "$frames 123#0000000000000000 1000000 checked" >"$SIM/flood"
	wait $pid || true
	line=$(grep '^flood:' /tmp/flood.txt) || fail "round $round: no count from can-flood"
	echo "round $round: $line"
	n=${line#*reordered=}
	n=${n%% *}
	d=${line#*duplicated=}
	d=${d%% *}
	c=${line#*corrupted=}
	c=${c%% *}
	[ "$d" -eq 0 ] && [ "$c" -eq 0 ] || fail "round $round: duplicated or corrupted frames"
	reordered=$((reordered + n))
	# The kernel's mcp251x has shown the defect: no need for more rounds.
	[ -n "$ko" ] || [ $reordered -eq 0 ] || break
	round=$((round + 1))
done
ip link set can1 down

if [ -n "$ko" ]; then
	[ $reordered -eq 0 ] ||
		fail "$under_test: $reordered frames reached the socket after a newer one"
	echo "upstream-rx-order: $under_test delivered $rounds floods in order"
else
	[ $reordered -gt 0 ] ||
		fail "$under_test delivered $rounds floods in order: the kernel has the fix"
	echo "upstream-rx-order: $under_test delivered $reordered frames after a newer one"
fi
