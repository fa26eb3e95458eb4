#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# Reproducer of upstream/mcp251x/0003 (SJW = PS2): DS21291 5.8 and
# DS21801 5.3 ask for "Phase Seg 2 > Sync Jump Width".  can-dev accepts
# "bitrate 125000 sjw 2", which at 16 MHz gives PS2 = SJW = 2, and
# mainline mcp251x writes it into CNF1-3 and comes up; the strict chip
# model then cannot communicate (tests/vm/scenarios/sim-bittiming.sh).  The
# fixed driver refuses to come up with it, and still comes up, and moves a
# frame, with SJW 1 at the same rate.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

mcp251x_under_test

ip link set can0 type can bitrate 125000 sjw 2 || fail "can-dev refused sjw 2"
ip -details link show can0 | grep -q 'phase-seg2 2 sjw 2' ||
	fail "not PS2 = SJW = 2: $(ip -details link show can0)"
if ip link set can0 up 2>/tmp/up.err; then
	up=1
	echo "$under_test came up with PS2 = SJW = 2 (CNF3-CNF1 $(sed -n 's/^20: \(.\{24\}\)\(.\{8\}\).*/\2/p' "$SIM/chip0/regs"))"
	ip link set can0 down
else
	up=0
	echo "$under_test refused PS2 = SJW = 2: $(cat /tmp/up.err)"
fi

can_up can0 125000 sjw 1
can_up can1 125000
frame_passes can0 can1 123 5A || fail "$under_test: no frame from can0 to can1 with SJW 1"
ip link set can0 down
ip link set can1 down

if [ -n "$ko" ]; then
	[ $up -eq 0 ] || fail "$under_test came up with SJW = PS2, which the data sheets forbid"
	echo "upstream-sjw: $under_test refuses SJW = PS2 and works with SJW 1"
else
	[ $up -eq 1 ] || fail "$under_test refused SJW = PS2: the kernel has the fix"
	echo "upstream-sjw: $under_test came up with SJW = PS2"
fi
