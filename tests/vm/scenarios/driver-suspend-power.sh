#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param osc_clk=1 --sim-param wakeup_source=1
# vm-kernels: debug
# The oscillator does not come back at a resume: its clock fails to
# prepare once (osc_errors 1).  The resume says so and leaves can0 up but
# off the bus, and down and up must power the chip again: the clock is
# on once more (the clock framework's debugfs counts its enables) and
# frames flow.  A suspend with wake-on-CAN enabled while the chip is
# without power (the clock fails at that resume too) has nothing to arm:
# it says so, and warns of no state it did not expect.
set -eu
. /lib/rig.sh

[ -w /sys/power/pm_test ] || fail "no /sys/power/pm_test (CONFIG_PM_DEBUG)"
CLK=/sys/kernel/debug/clk/mcp2510-sim-osc0
[ -r "$CLK/clk_enable_count" ] || fail "no $CLK"
enables() {
	read -r _n <"$CLK/clk_enable_count"
	echo "$_n"
}

# suspend_devices: one suspend and resume of the devices
suspend_devices() {
	echo devices >/sys/power/pm_test
	echo freeze >/sys/power/state || fail "suspend failed: $(dmesg | tail -n 5)"
	echo none >/sys/power/pm_test
}

wakeup=/sys/class/net/can0/device/power/wakeup
can_up can0 250000
can_up can1 250000
expect_eq "chip0's oscillator enables while up" "$(enables)" 1
echo disabled >"$wakeup"
echo 2 >"$SIM/chip0/osc_errors"
suspend_devices
dmesg | grep 'cannot bring the chip back' || fail "no resume error for a failed oscillator"
expect_eq "chip0's oscillator enables after the resume" "$(enables)" 0
echo enabled >"$wakeup"
suspend_devices
echo disabled >"$wakeup"
dmesg | grep 'no wake-up from the bus' || fail "no word of the wake-up a chip without power cannot arm"
expect_eq "chip0's oscillator enables after the second resume" "$(enables)" 0
ip link set can0 down
ip link set can0 up || fail "can0 does not come back up"
wait_operstate can0 up || fail "can0: link state '$OPERSTATE' after up"
expect_eq "chip0's oscillator enables after down and up" "$(enables)" 1
frame_passes can0 can1 123 01 || fail "can1 did not receive 123#01"
frame_passes can1 can0 456 02 || fail "can0 did not receive 456#02"
echo "driver-suspend-power: ok"
