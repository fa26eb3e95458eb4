#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --driver mcp2510
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510
# vm-kernels: 6.12
# The userspace port against the kernel driver on one bus: chip 0 is can0,
# driven by mcp2510.ko; chip 1 is handed to spidev, and mcp2510ctl drives it
# through /dev/spidevB.C with its INT line taken through libgpiod.  Frames
# sent by mcp2510ctl must reach candump on can0, frames sent by cansend on
# can0 must come out of "mcp2510ctl dump", and chip 1's INT must have been
# delivered to Linux while the tool held the line, so the tool was woken by
# interrupts and not by its polling fallback.  Then the same both ways, one
# frame each, with mcp2510ctl-gpiod2, the build against libgpiod 2 (make
# userspace-gpiod2), naming the INT line as libgpiod 2 cannot itself: the
# chip by its label, and the line by its name alone on every chip.
set -eu
. /lib/rig.sh


# wait_for CONDITION...: up to 5 s for the command to succeed
wait_for() {
	_n=0
	until "$@"; do
		_n=$((_n + 1))
		[ $_n -le 50 ] || return 1
		sleep 0.1
	done
}

# ctl COMMAND [ARGS]: mcp2510ctl on chip 1, at can0's bit rate
ctl() {
	mcp2510ctl --device "spidev:$dev" --int "$gpiochip:$int1" \
		--clock 16000000 --variant "$VM_VARIANT" --bitrate 125000 "$@"
}

# the tool holds INT1 through libgpiod (consumer "mcp2510") and chip 1
# runs in normal mode, so it takes part in the bus
dump_ready() {
	grep -q "INT1 *|mcp2510 " /sys/kernel/debug/gpio &&
		[ "$(sim_state 1 opmode)" = normal ]
}

# expect_grew CHIP NAME BEFORE WHAT
expect_grew() {
	_now=$(sim_counter "$1" "$2")
	[ "$_now" -gt "$3" ] ||
		fail "chip$1 $2 stayed at $_now during $4: INT was not delivered"
}

echo "== reload with spidev_node=1"
[ "$VM_SIM" = 1 ] || fail "the simulated chips are not loaded"
rmmod mcp2510_sim || fail "cannot unload mcp2510-sim"
insmod /opt/mcp2510/modules/mcp2510-sim.ko nodes=2 variant="$VM_VARIANT" \
	driver="$VM_DRIVER" spidev_node=1 || fail "cannot load mcp2510-sim"
wait_for test -e /sys/class/net/can0 || fail "chip 0 did not become can0"
drv=$(basename "$(readlink /sys/class/net/can0/device/driver)")
[ "$drv" = mcp2510 ] || fail "can0 is bound to '$drv', not mcp2510"
[ ! -e /sys/class/net/can1 ] || fail "chip 1 became a CAN interface"

dev=/dev/spidev$(sim_state 1 spi_bus).$(sim_state 1 spi_cs)
wait_for test -c "$dev" || fail "$dev did not appear"
gpiodetect
gpiochip=$(gpio_chip mcp2510-sim)
[ -n "$gpiochip" ] || fail "no gpiochip labelled mcp2510-sim"
int1=$(gpio_info "$gpiochip" |
	sed -n 's/^[[:space:]]*line *\([0-9]*\):[[:space:]]*"INT1".*/\1/p')
[ -n "$int1" ] || fail "$gpiochip has no line named INT1"
echo "chip 1: $dev, INT on $gpiochip line $int1"

can_up can0 125000

echo "== mcp2510ctl -> can0"
irqs=$(sim_counter 1 irqs_delivered)
edges=$(sim_counter 1 interrupts)
dump_start can0 3 /tmp/can0.txt
ctl send 123#DEADBEEF || fail "mcp2510ctl send of a standard frame failed"
ctl send 12345678#0102030405060708 321#R ||
	fail "mcp2510ctl send of an extended and an RTR frame failed"
dump_wait
cat /tmp/can0.txt
expect_lines /tmp/can0.txt 3
grep -q ' 123 *\[4\] *DE AD BE EF$' /tmp/can0.txt ||
	fail "can0 missed mcp2510ctl's 123#DEADBEEF"
grep -q ' 12345678 *\[8\] *01 02 03 04 05 06 07 08$' /tmp/can0.txt ||
	fail "can0 missed mcp2510ctl's extended frame"
grep -q ' 321 *\[0\] *remote request$' /tmp/can0.txt ||
	fail "can0 missed mcp2510ctl's RTR frame"
expect_grew 1 interrupts "$edges" "send"
expect_grew 1 irqs_delivered "$irqs" "send"

echo "== can0 -> mcp2510ctl"
# the readiness check below relies on the tool leaving normal mode on exit
[ "$(sim_state 1 opmode)" != normal ] ||
	fail "chip 1 stayed in normal mode after mcp2510ctl exited"
irqs=$(sim_counter 1 irqs_delivered)
edges=$(sim_counter 1 interrupts)
ctl dump --count 3 --timeout 5000 >/tmp/dump.txt &
ctl_pid=$!
wait_for dump_ready || fail "mcp2510ctl dump did not bring chip 1 up with INT1"
cansend can0 7FF#0102 || fail "cansend 7FF#0102 failed"
cansend can0 1ABCDEF0#11223344 || fail "cansend of an extended frame failed"
cansend can0 456#R2 || fail "cansend of an RTR frame failed"
wait "$ctl_pid" || { cat /tmp/dump.txt; fail "mcp2510ctl dump failed"; }
cat /tmp/dump.txt
expect_lines /tmp/dump.txt 3
label=$VM_VARIANT
grep -q "^([0-9]*\.[0-9]*) $label 7FF#0102$" /tmp/dump.txt ||
	fail "mcp2510ctl dump missed 7FF#0102"
grep -q "^([0-9]*\.[0-9]*) $label 1ABCDEF0#11223344$" /tmp/dump.txt ||
	fail "mcp2510ctl dump missed 1ABCDEF0#11223344"
grep -q "^([0-9]*\.[0-9]*) $label 456#R2$" /tmp/dump.txt ||
	fail "mcp2510ctl dump missed 456#R2"
expect_grew 1 interrupts "$edges" "dump"
expect_grew 1 irqs_delivered "$irqs" "dump"

echo "== the SPI the tool used"
for c in spi_mode_errors spi_overspeed spi_failed overflows; do
	[ "$(sim_counter 1 $c)" -eq 0 ] || fail "chip1 $c is $(sim_counter 1 $c)"
done
cat $SIM/chip1/counters
ip -details -statistics link show can0
tx0=$(cat /sys/class/net/can0/statistics/tx_packets)
rx0=$(cat /sys/class/net/can0/statistics/rx_packets)
[ "$tx0" -eq 3 ] || fail "can0 tx_packets $tx0, expected 3"
[ "$rx0" -eq 3 ] || fail "can0 rx_packets $rx0, expected 3"

echo "== a live chip answers; filters set by mcp2510ctl filter stay"
ctl info || fail "mcp2510ctl info refused a chip that is there"
ctl filter mask0=7ff mask1=7ff filter0=123 filter1=123 filter2=123 \
	filter3=123 filter4=123 filter5=123 >/tmp/filter.txt ||
	fail "mcp2510ctl filter failed"
grep -qx 'filter0 123' /tmp/filter.txt || fail "filter did not show filter0 123"
ctl dump --count 1 --timeout 5000 >/tmp/dump.txt &
ctl_pid=$!
wait_for dump_ready || fail "mcp2510ctl dump did not bring chip 1 up with INT1"
cansend can0 124#01 || fail "cansend 124#01 failed"
cansend can0 123#02 || fail "cansend 123#02 failed"
wait "$ctl_pid" || { cat /tmp/dump.txt; fail "filtered mcp2510ctl dump failed"; }
cat /tmp/dump.txt
grep -q "^([0-9]*\.[0-9]*) $label 123#02$" /tmp/dump.txt ||
	fail "dump did not keep the filters mcp2510ctl filter set"

echo "== a missing gpiochip is named, not the spidev device"
if mcp2510ctl --device "$dev" --int gpiochip99:0 --variant "$VM_VARIANT" \
	info 2>/tmp/err.txt; then
	fail "mcp2510ctl info with a missing gpiochip succeeded"
fi
cat /tmp/err.txt
grep -q "^mcp2510ctl: INT line gpiochip99:0: .*(spidev:$dev itself opens fine)" \
	/tmp/err.txt || fail "a missing gpiochip was not named"
# filter alone accepts every frame again, for what follows
ctl filter >/dev/null || fail "mcp2510ctl filter (accept all) failed"

echo "== the libgpiod 2 build: mcp2510ctl-gpiod2 <-> can0"
command -v mcp2510ctl-gpiod2 >/dev/null ||
	fail "mcp2510ctl-gpiod2 is missing: make userspace-gpiod2"
# ctl2 INT COMMAND [ARGS]: the libgpiod 2 build on chip 1
ctl2() {
	_int=$1
	shift
	mcp2510ctl-gpiod2 --device "spidev:$dev" --int "$_int" \
		--clock 16000000 --variant "$VM_VARIANT" --bitrate 125000 "$@"
}
irqs=$(sim_counter 1 irqs_delivered)
edges=$(sim_counter 1 interrupts)
dump_start can0 1 /tmp/can0-v2.txt
ctl2 mcp2510-sim:INT1 send 2A5#C0FFEE ||
	fail "mcp2510ctl-gpiod2 send with INT on mcp2510-sim:INT1 failed"
dump_wait
cat /tmp/can0-v2.txt
expect_lines /tmp/can0-v2.txt 1
grep -q ' 2A5 *\[3\] *C0 FF EE$' /tmp/can0-v2.txt ||
	fail "can0 missed mcp2510ctl-gpiod2's 2A5#C0FFEE"
expect_grew 1 interrupts "$edges" "send (libgpiod 2)"
expect_grew 1 irqs_delivered "$irqs" "send (libgpiod 2)"
irqs=$(sim_counter 1 irqs_delivered)
# dump returns with its frame: the long timeout only covers a slow guest
ctl2 INT1 dump --count 1 --timeout 20000 >/tmp/dump-v2.txt &
ctl_pid=$!
wait_for dump_ready || fail "mcp2510ctl-gpiod2 dump did not bring chip 1 up with INT1"
cansend can0 3C3#AB || fail "cansend 3C3#AB failed"
wait "$ctl_pid" || { cat /tmp/dump-v2.txt; fail "mcp2510ctl-gpiod2 dump failed"; }
cat /tmp/dump-v2.txt
expect_lines /tmp/dump-v2.txt 1
grep -q "^([0-9]*\.[0-9]*) $label 3C3#AB$" /tmp/dump-v2.txt ||
	fail "mcp2510ctl-gpiod2 dump missed 3C3#AB"
expect_grew 1 irqs_delivered "$irqs" "dump (libgpiod 2)"

ip link set can0 down
echo "userspace-spidev: ok"
