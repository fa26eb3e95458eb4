#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param time_scale=100
# vm-kernels: debug
# A bus-off that the driver is still handling when the system suspends.
# Every SPI message is made slow (spi_msg_ns), and the system suspends as
# soon as the IRQ thread has begun to stop the chip at the bus-off
# (CANINTE cleared): the rest of the stop, and the bus-off report that
# makes can-dev schedule the restart-ms restart, come after the suspend
# took the interface down.  No restart may run while the chip sleeps (it
# would fail: "Restart failed", a restart counted for nothing), nor
# after the resume, which started the chip afresh.
# can1 is the one: the devices suspend in the reverse order of their
# registration, so the other chip's slowed-down suspend cannot delay it.
# Bus time runs 100 times slower than real time, and the bus at 50 kbit/s,
# so that the chip stays bus-off long enough (2.8 s) for the slowed-down
# driver to see it (about 0.8 s on an idle host); a host too busy to run
# the guest in time lets the chip recover first, and the bus-off is tried
# again.
set -eu
. /lib/rig.sh

[ -w /sys/power/pm_test ] || fail "no /sys/power/pm_test (CONFIG_PM_DEBUG)"

restarts() {
	ip -details -statistics link show can1 |
		awk '/re-started bus-errors/ { getline; print $1 }'
}
# caninte_off: chip1's CANINTE (0x2b: row 0x20 of regs, byte 11) is 0.
caninte_off() {
	while read -r _addr _row; do
		[ "$_addr" = "20:" ] || continue
		# shellcheck disable=SC2086 # the row's 16 bytes as words
		set -- $_row
		[ "${12}" = 00 ]
		return
	done <"$SIM/chip1/regs"
	return 1
}

# busoff_stopping: drive chip1 bus-off with every SPI message slowed down;
# true once the IRQ thread has begun to stop the chip, false when it
# never did.
busoff_stopping() {
	# 2 ms of bus time: 0.2 s in real time.
	echo 2000000 >"$SIM/spi_msg_ns"
	echo 1 >"$SIM/spi_time"
	echo 32 >"$SIM/bus_errors"
	cansend can1 123#01
	_polls=0
	until caninte_off; do
		_polls=$((_polls + 1))
		[ $_polls -lt 600 ] || return 1
		nap 0.02
	done
}

can_up can0 50000
can_up can1 50000 restart-ms 1000
caninte_off && fail "CANINTE is 0 on a running chip"
try=1
while :; do
	before=$(restarts)
	busoff_stopping && break
	[ "$try" -lt 3 ] || fail "chip1 was never stopped at a bus-off in $try tries (chip1 bus-offs: $(sim_counter 1 bus_off))"
	echo "try $try: chip1 recovered before its driver saw the bus-off"
	echo 0 >"$SIM/spi_time"
	ip link set can1 down
	can_up can1 50000 restart-ms 1000
	try=$((try + 1))
done
echo devices >/sys/power/pm_test
echo freeze >/sys/power/state || fail "suspend failed: $(dmesg | tail -n 5)"
echo none >/sys/power/pm_test
echo 0 >"$SIM/spi_time"
dmesg | grep 'can1: bus-off' || fail "the bus-off was never reported"
nap 3
if dmesg | grep -E 'can1: .*(Restart failed|during restart|carrier is OK)'; then
	fail "a restart scheduled at the suspend ran"
fi
expect_eq "can1 restarts" "$(restarts)" "$before"
can_state_is can1 ERROR-ACTIVE || fail "can1 not error-active after resume"
frame_passes can1 can0 456 02 || fail "can0 did not receive 456#02"
echo "driver-suspend-busoff: ok"
