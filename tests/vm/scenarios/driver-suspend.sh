#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-kernels: rt debug
# System sleep with the interfaces up.  The rig has no firmware to sleep
# in, so the kernel's PM test mode runs the whole device suspend and
# resume path and skips only the platform's sleep itself
# (/sys/power/pm_test = devices, then suspend-to-idle).  After the
# resume both chips are back on the bus with their bit timing and
# hardware filters, and frames flow both ways.  A resume that finds the
# chip dead says so and leaves the interface up but off the bus, and
# down/up brings it back once the chip has power.
set -eu
. /lib/rig.sh

[ -d "$SIM" ] || fail "no $SIM"
[ -w /sys/power/pm_test ] || fail "no /sys/power/pm_test (CONFIG_PM_DEBUG)"
grep -qw freeze /sys/power/state || fail "no suspend-to-idle in /sys/power/state"


# sleep_and_wake: one pass through every device's suspend and resume.
sleep_and_wake() {
	echo devices >/sys/power/pm_test
	echo freeze >/sys/power/state || fail "suspend failed: $(dmesg | tail -n 5)"
	echo none >/sys/power/pm_test
}

# exchange TAG: a frame each way between can0 and can1.
exchange() {
	frame_passes can0 can1 123 "$1" || fail "can1 did not receive 123#$1"
	frame_passes can1 can0 456 "$1" || fail "can0 did not receive 456#$1"
}

echo "== before the sleep"
f=/sys/class/net/can0/mcp2510
echo 7ff >"$f/mask0"
echo 123 >"$f/filter0"
echo 7ff >"$f/mask1"
echo 456 >"$f/filter2"
can_up can0 250000
can_up can1 250000
exchange 01
[ "$(sim_state 0 bitrate)" -eq 250000 ] || fail "chip0 bit rate $(sim_state 0 bitrate)"

echo "== suspend and resume"
sleep_and_wake
dmesg | grep -i 'PM: suspend' | tail -n 4
[ "$(sim_state 0 opmode)" = normal ] || fail "chip0 in $(sim_state 0 opmode) after resume"
[ "$(sim_state 0 bitrate)" -eq 250000 ] || fail "chip0 bit rate $(sim_state 0 bitrate) after resume"
ip -details link show can0 | grep -q 'state ERROR-ACTIVE' || fail "can0 not error-active after resume"
exchange 02
# The filters came back too: a frame they do not pass stays out.
dump_start can0 1 /tmp/filtered.txt
cansend can1 457#03
cansend can1 456#04
dump_wait
grep -q '457' /tmp/filtered.txt && fail "the hardware filters were lost over the sleep"
grep -q '456 *\[1\] *04' /tmp/filtered.txt || fail "can0 did not receive 456#04"

echo "== a dead chip at resume, then down/up once it has power"
echo 0 >"$SIM/chip0/power"
sleep_and_wake || true
dmesg | grep -q 'cannot bring the chip back' || fail "no resume error for a dead chip"
echo 1 >"$SIM/chip0/power"
sleep 0.2
ip link set can0 down
ip link set can0 up || fail "can0 does not come back up"
exchange 05
echo "driver-suspend: ok"
