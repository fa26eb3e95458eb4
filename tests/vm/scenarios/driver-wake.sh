#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --sim-param wakeup_source=1 --sim-param wakeup_filter=1
# vm-kernels: 6.1
# Wake-on-CAN in a real suspend-to-idle.  The chips' software node says
# wakeup-source (and microchip,wakeup-filter: CNF3.WAKFIL).  The
# simulator's phantom sends a frame a second after the suspend reached
# its noirq phase ("inject_later noirq"), from a kernel timer that keeps
# running while tasks are frozen.  The guest has no cpuidle driver, so
# suspend-to-idle idles the CPUs without freezing the tick: kernel
# timers, the simulated bus's among them, still fire, and the frame
# arrives while the system sleeps in the suspend-to-idle loop.
#  1. can0 may wake the system, can1 not: the frame wakes chip0, its INT
#     is the wakeup interrupt (/sys/power/pm_wakeup_irq, "Triggering
#     wakeup from IRQ" after "suspend-to-idle") and an event of can0's
#     wakeup source, and resume puts the chip back in normal mode: frames
#     flow both ways.  The frame that woke chip0 is lost to it (it woke
#     in listen-only mode); nobody awake acknowledged it, so the phantom
#     sends it again and can0 receives that copy once it is back.
#  2. can0 may not, can1 may: the same frame wakes the system through
#     chip1's INT alone, chip0's is no wakeup interrupt.
#  3. A frame while the devices are still suspending ("inject_later
#     devices 0": chip0 is armed, its INT not yet a suspended wakeup
#     interrupt): the driver reports the wake-up, so the system does not
#     sleep with a chip that already woke and can wake nothing any more.
#     Depending on when the driver's thread reports it, the PM core
#     aborts the suspend (EBUSY) or leaves suspend-to-idle at once.
# Nothing else in this rig wakes a suspend-to-idle (an RTC alarm does
# not), so the case where no device may wake it would sleep for good.
set -eu
. /lib/rig.sh

[ -d "$SIM" ] || fail "no $SIM"
[ -w /sys/power/pm_debug_messages ] || fail "no /sys/power/pm_debug_messages (CONFIG_PM_SLEEP_DEBUG)"
[ -r /sys/power/pm_wakeup_irq ] || fail "no /sys/power/pm_wakeup_irq (CONFIG_PM_SLEEP_DEBUG)"
grep -qw freeze /sys/power/state || fail "no suspend-to-idle in /sys/power/state"
# With a cpuidle driver, suspend-to-idle could freeze the tick, and the
# simulator's timers, with it: the frame would never come.
read -r idle </sys/devices/system/cpu/cpuidle/current_driver || idle=none
[ "$idle" = none ] || fail "cpuidle driver $idle: suspend-to-idle may stop the simulated bus"

dev0=/sys/class/net/can0/device
dev1=/sys/class/net/can1/device
irq0=$(sim_state 0 irq)
read -r wake0 <"$dev0/power/wakeup" || fail "can0's device has no power/wakeup"
[ "$wake0" = enabled ] || fail "can0's wakeup is '$wake0', wakeup-source should enable it"
echo disabled >"$dev1/power/wakeup"
echo none >/sys/power/pm_test 2>/dev/null || true
echo 1 >/sys/power/pm_debug_messages

# exchange TAG: a frame each way between can0 and can1.
exchange() {
	frame_passes can0 can1 123 "$1" || fail "can1 did not receive 123#$1"
	frame_passes can1 can0 456 "$1" || fail "can0 did not receive 456#$1"
}

# back_to_normal: after a resume, chip0 runs again and frames flow.
back_to_normal() {
	[ "$(sim_state 0 opmode)" = normal ] || fail "chip0 in $(sim_state 0 opmode) after resume"
	wait_operstate can0 up || fail "can0 not up after resume"
	can_state_is can0 ERROR-ACTIVE || fail "can0 not error-active after resume"
	exchange "$1"
}

# wake_irq: WAKE_IRQ = the interrupt recorded as the last suspend's
# wakeup, empty when none was (the file then fails with ENODATA).
wake_irq() {
	WAKE_IRQ=
	read -r WAKE_IRQ </sys/power/pm_wakeup_irq 2>/dev/null || true
}

# wake_count: WAKE_COUNT = how often can0's device reported a wakeup
# event (its wakeup source's activations; power/wakeup_count counts only
# events while userspace checks /sys/power/wakeup_count).
wake_count() {
	read -r WAKE_COUNT <"$dev0/power/wakeup_active_count"
}

echo "== up, and WAKFIL in chip0's CNF3"
can_up can0 125000
can_up can1 125000
exchange 01
# regs row 20: CNF3 is its ninth byte
cnf3=$(awk '$1 == "20:" { print $10 }' "$SIM/chip0/regs")
[ $((0x$cnf3 & 0x40)) -ne 0 ] || fail "CNF3 is 0x$cnf3: no WAKFIL"

# sleep_until_frame TAG: suspend to idle; the phantom sends 7ff#TAG
# a second after the suspend reached its noirq phase (the rest of that
# phase took up to 170 ms under TCG: a frame before its end aborts the
# suspend instead, as it should, but shows less).  Shows the PM
# messages of that suspend and checks that the system did enter
# suspend-to-idle, that an interrupt ended it and that it resumed.
sleep_until_frame() {
	read -r _ok_before </sys/power/suspend_stats/success
	dmesg -c >/dev/null
	echo "noirq 1000 7ff#$1" >"$SIM/inject_later"
	read -r _t0 _ </proc/uptime
	echo freeze >/sys/power/state || fail "suspend failed: $(dmesg | tail -n 5)"
	read -r _t1 _ </proc/uptime
	echo "echo freeze returned after $(awk -v a="$_t0" -v b="$_t1" 'BEGIN { printf "%.2f", b - a }') s"
	dmesg | grep -E 'PM: (suspend|resume|Triggering|noirq)|suspend-to-idle' || true
	read -r _sent <"$SIM/inject_later"
	[ "$_sent" = "sent 0" ] || fail "inject_later: $_sent"
	read -r _ok_after </sys/power/suspend_stats/success
	expect_eq "suspend_stats/success" "$_ok_after" $((_ok_before + 1))
	dmesg | grep -q 'PM: resume from suspend-to-idle' || fail "no resume from suspend-to-idle"
	wake_irq
	# the wakeup came from inside the idle loop, after it was entered
	dmesg | awk -v irq="$WAKE_IRQ" '
		/PM: suspend-to-idle/ { idle = 1 }
		idle && index($0, "Triggering wakeup from IRQ " irq) { found = 1 }
		END { exit !found }' || fail "IRQ '$WAKE_IRQ' did not end a suspend-to-idle"
}

echo "== suspend to idle, can0 may wake the system: the frame wakes it"
wake_count
before=$WAKE_COUNT
dump_start can0,7ff:7ff 1 /tmp/b1.txt
sleep_until_frame b1
[ "$WAKE_IRQ" = "$irq0" ] || fail "wakeup irq '$WAKE_IRQ', chip0's INT is $irq0"
wake_count
[ "$WAKE_COUNT" -gt "$before" ] || fail "can0's wakeup events stayed at $WAKE_COUNT"
echo "wakeup irq $WAKE_IRQ (chip0's INT), can0 wakeup events $before -> $WAKE_COUNT"
# Lost to chip0, which woke in listen-only mode; unacknowledged, the
# phantom sent it again, and can0 took that copy once it was back.
dump_wait
grep -q '7FF *\[1\] *B1' /tmp/b1.txt || { cat /tmp/b1.txt; fail "can0 did not receive the phantom's 7ff#b1 after resume"; }
back_to_normal 02

echo "== suspend to idle, only can1 may wake it: the same frame wakes it through chip1"
echo disabled >"$dev0/power/wakeup"
echo enabled >"$dev1/power/wakeup"
irq1=$(sim_state 1 irq)
sleep_until_frame b2
[ "$WAKE_IRQ" = "$irq1" ] || fail "wakeup irq '$WAKE_IRQ', chip1's INT is $irq1"
dmesg | grep -q "Triggering wakeup from IRQ $irq0" && fail "chip0's INT woke the system with its wakeup disabled"
echo "wakeup irq $WAKE_IRQ (chip1's INT), none from chip0"
back_to_normal 03

echo "== a frame while the devices suspend: the system does not sleep"
echo enabled >"$dev0/power/wakeup"
echo disabled >"$dev1/power/wakeup"
wake_count
before=$WAKE_COUNT
dmesg -c >/dev/null
echo "devices 0 7ff#c1" >"$SIM/inject_later"
read -r t0 _ </proc/uptime
if echo freeze >/sys/power/state 2>/tmp/freeze.err; then
	outcome="suspend-to-idle left at once"
else
	outcome="suspend aborted: $(cat /tmp/freeze.err)"
	grep -q 'busy' /tmp/freeze.err || fail "the suspend failed, but not with EBUSY"
fi
read -r t1 _ </proc/uptime
echo "$outcome, after $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }') s"
dmesg | grep -E 'PM: (suspend|resume|Some|Wakeup|last active|Triggering|noirq)|suspend-to-idle|abort' || true
dmesg | grep -q 'Triggering wakeup from IRQ' && fail "a wakeup interrupt: the frame came too late for this case"
wake_count
[ "$WAKE_COUNT" -gt "$before" ] || fail "can0's wakeup events stayed at $WAKE_COUNT"
back_to_normal 04
echo "driver-wake: ok"
