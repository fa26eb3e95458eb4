#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-kernels: debug
# The hardware acceptance filters set through sysfs decide what can1
# receives: RXB0 takes standard 0x120-0x12f; RXB1, with a standard mask,
# takes standard 0x7e0 and the extended frames whose top 11 bits are those
# of 0x1abcdef.  Everything else is dropped by the chip (and counted
# nowhere, as on real hardware).  RXB1 in "any" mode takes all the rest;
# back at the defaults, every frame passes.
set -eu
. /lib/rig.sh
f=/sys/class/net/can1/mcp2510

send_all() {
	for frame in 120#01 12F#02 130#03 7E0#04 7E1#05 01ABCDEF#06 \
		01ABCDEE#07 00000120#08; do
		cansend can0 "$frame"
	done
}

# receive EXPECTED: can1 gets exactly the frames EXPECTED (candump lines
# reduced to "id:data"), in send order.  candump waits for one frame more
# than expected and stops 3 s after the last one, so extras are seen.
receive() {
	dump_start can1 $(($(echo "$1" | wc -w) + 1)) /tmp/rx.txt -T 3000
	send_all
	dump_wait
	got=$(awk '{ printf "%s:%s ", $2, $4 }' /tmp/rx.txt)
	[ "$got" = "$1" ] || {
		cat /tmp/rx.txt
		fail "can1 received '$got', expected '$1'"
	}
}

# The defaults, to come back to: every frame passes.
names="mask0 mask1 filter0 filter1 filter2 filter3 filter4 filter5 rxm0 rxm1 rollover"
for name in $names; do
	eval "default_$name=\$(cat $f/$name)"
done

echo 7f0 >$f/mask0
echo 120 >$f/filter0
echo 120 >$f/filter1
echo 7ff >$f/mask1
echo 7e0 >$f/filter2
echo 1abcdefx >$f/filter3
echo 7e0 >$f/filter4
echo 1abcdefx >$f/filter5
echo 0 >$f/rollover
can_up can0 500000
can_up can1 500000
# A standard filter takes no extended frame (0x0000120) and the standard
# mask lets 0x1abcdee through with 0x1abcdef.
receive "120:01 12F:02 7E0:04 01ABCDEF:06 01ABCDEE:07 "
ip link set can1 down

# RXB1 "any": its filters are off, it takes whatever RXB0 does not.
echo any >$f/rxm1
can_up can1 500000
receive "120:01 12F:02 130:03 7E0:04 7E1:05 01ABCDEF:06 01ABCDEE:07 00000120:08 "
ip link set can1 down

for name in $names; do
	eval "echo \$default_$name" >"$f/$name"
done
can_up can1 500000
receive "120:01 12F:02 130:03 7E0:04 7E1:05 01ABCDEF:06 01ABCDEE:07 00000120:08 "
ip -statistics link show can1
echo "driver-filters: ok"
