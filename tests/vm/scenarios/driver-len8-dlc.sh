#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-run: --nodes 2 --variant mcp2515
# vm-kernels: 6.1
# Classical CAN frames with a raw DLC of 9..15 (ip link ... cc-len8-dlc).
# Both chips send a DLC above 8 as written, with eight data bytes, and
# store a received one as it came.  With the mode on, a sent frame's
# len8_dlc is its DLC on the wire (the bus monitor shows it as "_X") and
# a received DLC above 8 reaches the sockets as len 8 plus len8_dlc.
# Without it, TX ignores len8_dlc (DLC 8 on the wire) and RX reads such
# a DLC as length 8 with no len8_dlc.  Debian 12's can-utils cannot send
# or show a raw DLC: can-dlc (tests/vm/guest) does, in the syntax of
# later can-utils (123#1122334455667788_E).
set -eu
. /lib/rig.sh

[ -d "$SIM" ] || mount -t debugfs none /sys/kernel/debug
# modes LEN8_CAN0 LEN8_CAN1: both interfaces (down) up again with
# cc-len8-dlc on or off.
modes() {
	ip link set can0 down
	ip link set can1 down
	can_up can0 500000 cc-len8-dlc "$1"
	can_up can1 500000 cc-len8-dlc "$2"
}

echo "== cc-len8-dlc on both ends"
can_up can0 500000 cc-len8-dlc on
can_up can1 500000 cc-len8-dlc on
ip -details link show can0 | grep -q 'CC-LEN8-DLC' ||
	{ ip -details link show can0; fail "can0 does not show cc-len8-dlc on"; }
dlc_exchange can0 can1 123#1122334455667788_E 123#1122334455667788_E 123#1122334455667788_E
dlc_exchange can1 can0 7FF#0102030405060708_9 7FF#0102030405060708_9 7FF#0102030405060708_9
dlc_exchange can0 can1 1ABCDEF5#A1A2A3A4A5A6A7A8_F 1ABCDEF5#A1A2A3A4A5A6A7A8_F 1ABCDEF5#A1A2A3A4A5A6A7A8_F
# A plain 8-byte frame is still DLC 8; len8_dlc counts only beside len 8.
dlc_exchange can1 can0 123#1122334455667788 123#1122334455667788 123#1122334455667788
dlc_exchange can0 can1 321#AABBCC_C 321#AABBCC 321#AABBCC

echo "== cc-len8-dlc on the sender only"
modes on off
dlc_exchange can0 can1 123#1122334455667788_E 123#1122334455667788_E 123#1122334455667788
modes off on
dlc_exchange can1 can0 123#1122334455667788_D 123#1122334455667788_D 123#1122334455667788

echo "== cc-len8-dlc off on the sender"
dlc_exchange can0 can1 123#1122334455667788_E 123#1122334455667788 123#1122334455667788
echo "driver-len8-dlc: ok"
