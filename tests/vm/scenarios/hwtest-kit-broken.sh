#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510 --module broken/reorder.ko --sim-param time_scale=10 --timeout 240
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510 --module broken/drop-echo.ko --timeout 240
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510 --sim-param time_scale=10 --sim-param rx_corrupt_every=25 --timeout 240
# vm-kernels: 6.1
# The hardware test kit notices a broken driver and says where, seeing
# only can0 and can1 (debugfs unmounted).  The driver is built broken on
# purpose (tests/hw/broken/NAME.patch, loaded with --module): one that
# hands every 32nd frame received since the link came up on behind the
# next, and one that drops the echo of every other frame sent.  The third
# run keeps the driver and breaks the chips' receive path instead (the
# simulator's rx_corrupt_every flips a bit of every 25th frame), which to
# the kit looks like a driver that damages frames.  Each run asks the kit
# for the checks that must fail, which bring one that must still pass:
# echo-needs-ack with echo; with the floods, at one bit rate, a transit
# of 20 lone frames (fewer than 32 and 25: none of them is touched) and
# floods of 100 (four frames touched each way, so a lost one cannot hide
# them all).
set -eu
. /lib/rig.sh

umount /sys/kernel/debug
trap 'mount -t debugfs debugfs /sys/kernel/debug' EXIT

# kit CHECKS: the kit on can0 and can1 with CHECKS alone; it must fail.
kit() {
	status=0
	KIT_CHECKS=$1 KIT_FRAMES=100 KIT_TRANSITS=20 KIT_BITRATES=125000 \
		mcp2510-hwtest -o /tmp/kit can0 can1 || status=$?
	[ $status -eq 1 ] || fail "the kit exited with $status on a broken driver, expected 1"
	grep -q '"verdict": "fail"' /tmp/kit/summary.json || fail "the summary's verdict is not fail"
	grep '^flood ' /tmp/kit/results.txt || true
}

# verdicts VERDICT NAME...: exactly these checks have VERDICT.
verdicts() {
	want=$1
	shift
	got=$(sed -n "s/^check \([^ ]*\) $want .*/\1/p" /tmp/kit/results.txt | tr '\n' ' ')
	[ "$got" = "$* " ] || fail "checks with verdict $want: '$got', expected '$* '"
}

# floods_fail PATTERN WHAT: the kit fails both floods, each flood's line
# matching PATTERN after "fail", and passes the lone frames.
floods_fail() {
	kit floods
	verdicts fail flood-can0-125000 flood-can1-125000
	verdicts pass transit-125000
	for dir in can0 can1; do
		grep -q "^check flood-$dir-125000 fail $1" /tmp/kit/results.txt ||
			fail "the flood from $dir does not report $2"
	done
}

case $VM_DRIVER_KO in
broken/reorder.ko)
	floods_fail '.* reordered [1-9][0-9]*, corrupted 0,' "reordered frames alone"
	;;
broken/drop-echo.ko)
	kit echo
	verdicts fail echo
	verdicts pass echo-needs-ack
	grep -q '^check echo fail echoes 0, across 1,' /tmp/kit/results.txt ||
		fail "the echo check does not report the missing echo"
	;;
*)
	case " $VM_SIM_PARAMS " in
	*" rx_corrupt_every="*) ;;
	*) fail "neither a broken driver nor a broken receive path" ;;
	esac
	floods_fail '.*corrupted [1-9]' "corrupted frames"
	grep -q '"corrupted": [1-9]' /tmp/kit/summary.json || fail "the summary holds no corrupted frames"
	;;
esac
echo "hwtest-kit-broken: ok"
