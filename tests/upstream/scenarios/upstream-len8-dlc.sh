#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# Shows what upstream/mcp251x/0005 adds: "cc-len8-dlc on", Classical CAN
# frames with a raw DLC of 9..15.  Both ends in the mode exchange DLC 14,
# 9 and 15 and a plain 8-byte frame; the bus monitor shows each DLC on the
# wire as sent and the receiving socket gets it as len 8 plus len8_dlc.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

mcp251x_under_test

if ! ip link set can0 type can bitrate 500000 cc-len8-dlc on 2>/tmp/mode.err; then
	echo "$under_test refuses cc-len8-dlc: $(cat /tmp/mode.err)"
	[ -z "$ko" ] || fail "$under_test refuses cc-len8-dlc"
	echo "upstream-len8-dlc: $under_test has no cc-len8-dlc"
	exit 0
fi
[ -n "$ko" ] || fail "$under_test takes cc-len8-dlc: the kernel has the change"
can_up can0 500000 cc-len8-dlc on
can_up can1 500000 cc-len8-dlc on
dlc_exchange can0 can1 123#1122334455667788_E 123#1122334455667788_E 123#1122334455667788_E
dlc_exchange can1 can0 7FF#0102030405060708_9 7FF#0102030405060708_9 7FF#0102030405060708_9
dlc_exchange can0 can1 1ABCDEF5#A1A2A3A4A5A6A7A8_F 1ABCDEF5#A1A2A3A4A5A6A7A8_F 1ABCDEF5#A1A2A3A4A5A6A7A8_F
dlc_exchange can1 can0 123#1122334455667788 123#1122334455667788 123#1122334455667788
ip link set can0 down
ip link set can1 down
echo "upstream-len8-dlc: $under_test sends and receives DLC 9..15 with cc-len8-dlc"
