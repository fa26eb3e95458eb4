#!/bin/sh
# vm-run: --nodes 2 --sim-param time_scale=50
# vm-kernels: debug
# Restarts that fail, under can-dev as kernels before the end of 2023 have
# it (6.1.21, which Raspberry Pi OS shipped): can_restart() turns the
# carrier on after do_set_mode() whatever it returned, and calls BUG()
# when a restart finds the carrier on.  The rig's kernels all have the
# newer can-dev, so on those made from 6.1's sources (6.1, debug) the
# scenario puts can-dev with that old can_restart() in place of the
# kernel's (tests/vm/old-can-dev); elsewhere it runs on the kernel's own.
#  - An automatic restart (restart-ms) of a chip without power: the
#    interface must end bus-off with its carrier off, the driver's retries
#    must not crash, and once the chip has power it is back on the bus.
#  - A manual restart of a chip without power (old can-dev reports it
#    done): bus-off with the carrier off again, and the next manual
#    restart, with the chip powered, brings it back.
# Bus time runs 50 times slower than real time, as in driver-busoff-restart:
# at real pace the 32 destroyed attempts, the bus-off and the chip's own
# recovery take 33 ms, less than the debug kernel under TCG on a loaded
# host may take to serve one interrupt, and the driver finds the chip
# already back on the bus with TEC at 0.
set -eu
. /lib/rig.sh

mods=/opt/mcp2510/modules
old=$mods/old-can-dev/can-dev.ko
case $VM_KERNEL in
6.1 | debug) [ -f "$old" ] || fail "no $old for kernel $VM_KERNEL (make old-can-dev-modules)" ;;
*) old= ;;
esac

# use_can_dev FILE: can-dev from FILE (empty: the kernel's own) under new
# chips and driver, and the virtual CAN drivers that use it.
users=
for _m in vcan vxcan; do [ ! -d "/sys/module/$_m" ] || users="$users $_m"; done
use_can_dev() {
	for _m in mcp2510 mcp2510_sim $users can_dev; do
		[ ! -d "/sys/module/$_m" ] || rmmod "$_m" || fail "cannot unload $_m"
	done
	if [ -n "$1" ]; then
		insmod "$1" || fail "cannot load $1"
	else
		modprobe can-dev || fail "cannot load the kernel's can-dev"
	fi
	for _m in $users; do modprobe "$_m" || fail "cannot load $_m"; done
	chips_load mcp2510
}
# Later scenarios of this boot get the kernel's can-dev back.
[ -z "$old" ] || trap 'use_can_dev "" >/dev/null 2>&1 || true' EXIT
if [ -n "$old" ]; then
	use_can_dev "$old"
	echo "can-dev with the old can_restart(): $old"
else
	echo "can-dev: the kernel's own"
fi

describe() {
	echo "$1: $(ip -details link show "$1" | grep -o 'state [A-Z-]*' | tail -1)," \
		"carrier $(carrier "$1"), operstate $(operstate "$1")," \
		"chip0 $(sim_state 0 opmode)"
}
# crosses ID: a frame with ID sent on can0 reaches can1.
crosses() {
	dump_start "can1,$1:7FF" 1 /tmp/x.txt
	cansend can0 "$1#5A"
	dump_wait
	grep -q "$1 *\[1\] *5A" /tmp/x.txt
}
# bus_off_unpowered: can0 goes bus-off, then its chip loses power.
bus_off_unpowered() {
	echo 32 >"$SIM/bus_errors"
	cansend can0 123#01
	wait_for 30 no_carrier can0 || { describe can0; fail "can0 never went bus-off"; }
	echo 0 >"$SIM/chip0/power"
}
# Either can-dev's words for a failed restart.
failed_restarts() { dmesg | grep -cE "can0: (Restart failed|Error .* during restart)" || true; }
failed_more() { [ "$(failed_restarts)" -gt "$1" ]; }

can_up can1 125000

echo "== automatic restart of a chip without power"
can_up can0 125000 restart-ms 1000
failed=$(failed_restarts)
bus_off_unpowered
wait_for 10 failed_more "$failed" || { describe can0; fail "no failed restart"; }
# The driver tries again at most once a second: give it two tries.
failed=$(failed_restarts)
wait_for 10 failed_more $((failed + 1)) || { describe can0; fail "the driver did not try again"; }
wait_for 5 off_bus can0 || { describe can0; fail "a failed automatic restart left can0 with its carrier on"; }
describe can0
echo 1 >"$SIM/chip0/power"
wait_for 15 on_bus can0 || { describe can0; fail "not back on the bus after the power came back"; }
crosses 456 || fail "no traffic after the automatic restart"

echo "== manual restart of a chip without power"
ip link set can0 down
can_up can0 125000 restart-ms 0
bus_off_unpowered
if ip link set can0 type can restart; then
	echo "the restart was reported done"
fi
wait_for 5 off_bus can0 || { describe can0; fail "a failed manual restart left can0 with its carrier on"; }
describe can0
echo 1 >"$SIM/chip0/power"
ip link set can0 type can restart || { describe can0; fail "restart refused once the chip is back"; }
wait_for 10 on_bus can0 || { describe can0; fail "not back on the bus after the manual restart"; }
crosses 457 || fail "no traffic after the manual restart"

ip link set can0 down
ip link set can1 down
echo "driver-restart-old-candev: ok"
