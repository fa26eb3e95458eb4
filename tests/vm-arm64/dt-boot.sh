#!/bin/sh
# The arm64 guest's scenario: the MCP2510s are described only by the device
# tree (the first by this project's generic overlay, the second by the
# board's tree, see sim-controller.dtsi), so everything the driver knows of
# them -- that they exist, their oscillator, their interrupt -- must come
# from there.  Prints "PASS: what" or "FAIL: what" per check; the host
# counts them.  A failed step that later checks need ends the scenario.
# shellcheck source=../vm/rig.sh
. /lib/rig.sh

mods=/lib/mcp2510
dt=/proc/device-tree
node0=mcp2510-sim/spi/can@0
node1=mcp2510-sim/spi/can@1
failed=0

pass() { echo "PASS: $*"; }
flunk() { echo "FAIL: $*"; failed=1; }
# check WHAT COMMAND...: run COMMAND, PASS or FAIL WHAT by its status.
check() {
	_what=$1
	shift
	"$@" && { pass "$_what"; return 0; }
	flunk "$_what"
	return 1
}
# Give up: the remaining checks depend on this one.
need() { check "$@" || { echo "== stopping: the checks after this need it"; exit 1; }; }

dt_string() { tr '\0' '\n' <"$dt/$1" | head -n 1; }
# A one-cell property (big-endian) as a decimal number.
dt_u32() { printf '%d' "0x$(od -An -tx1 "$dt/$1" | tr -d ' \n')"; }

# The interface whose device is the tree node NODE (can@0, can@1).
iface_of() {
	for _net in /sys/class/net/can*; do
		[ "$(basename "$(readlink -f "$_net/device/of_node")")" = "$1" ] &&
			{ basename "$_net"; return 0; }
	done
	return 1
}

wait_for() {
	_tries=0
	until "$@"; do
		_tries=$((_tries + 1))
		[ "$_tries" -le 100 ] || return 1
		sleep 0.1
	done
}

# Count of the irq with this hardware number on the simulated GPIO chip,
# summed over the CPUs.
irq_count() {
	awk -v hw="$1" '$0 ~ / mcp2510-sim +/ {
		n = 0
		for (i = 2; i <= NF; i++) {
			if ($i == "mcp2510-sim") break
			n += $i
		}
		if ($(i + 1) == hw) { print n; exit }
	}' /proc/interrupts
}

# sysfs shows an unset string attribute as "" or "(null)", by kernel version.
is_unset() { [ -z "$1" ] || [ "$1" = "(null)" ] || { echo "  got '$1'"; return 1; }; }
is_equal() { [ "$1" = "$2" ] || { echo "  got '$1', expected '$2'"; return 1; }; }

# --- the tree as the kernel got it
need "the overlay's node is in the tree" \
	is_equal "$(dt_string $node0/compatible)" microchip,mcp2510
check "the overlay's oscillator is a fixed-clock at 16 MHz" \
	is_equal "$(dt_string mcp2510-osc/compatible) $(dt_u32 mcp2510-osc/clock-frequency)" \
	"fixed-clock 16000000"
check "can@0 takes its clock from the overlay's oscillator" \
	is_equal "$(dt_u32 $node0/clocks)" "$(dt_u32 mcp2510-osc/phandle)"
check "can@0 has no clock-frequency property to fall back on" \
	test ! -e $dt/$node0/clock-frequency
check "can@0's interrupt is on the simulated GPIO chip" \
	is_equal "$(dt_u32 $node0/interrupt-parent)" "$(dt_u32 mcp2510-sim/gpio/phandle)"
check "the board's own can@1 is beside it" \
	is_equal "$(dt_string $node1/compatible)" microchip,mcp2510

# --- the simulated controller in device-tree mode
need "mcp2510-sim.ko loads" insmod $mods/mcp2510-sim.ko
spi_devs=$(ls -d /sys/bus/spi/devices/spi*.* 2>/dev/null)
check "the SPI core made two devices" is_equal "$(echo "$spi_devs" | wc -w)" 2
for dev in $spi_devs; do
	node=none
	[ -e "$dev/of_node" ] && node=$(basename "$(readlink -f "$dev/of_node")")
	check "$(basename "$dev") was made from a tree node ($node)" \
		test "$node" != none
	check "$(basename "$dev") is not forced onto a driver" \
		is_unset "$(cat "$dev/driver_override")"
done

# --- the driver, bound by compatible
need "mcp2510.ko loads" insmod $mods/mcp2510.ko
need "two CAN interfaces appear" wait_for test -e /sys/class/net/can1
if0=$(iface_of can@0) && if1=$(iface_of can@1)
need "each tree node has its interface ($if0, $if1)" test -n "$if0" -a -n "$if1"
for ifc in $if0 $if1; do
	check "$ifc is bound to the mcp2510 driver" is_equal \
		"$(basename "$(readlink -f "/sys/class/net/$ifc/device/driver")")" mcp2510
	check "$ifc's device matched microchip,mcp2510" is_equal \
		"$(cat "/sys/class/net/$ifc/device/modalias")" "spi:mcp2510"
done
check "the driver holds the overlay's clock enabled" \
	is_equal "$(cat /sys/kernel/debug/clk/mcp2510-osc/clk_enable_count)" 1
check "and the board's clock for can@1" \
	is_equal "$(cat /sys/kernel/debug/clk/oscillator-can1/clk_enable_count)" 1
check "the probe saw a 16 MHz oscillator twice" \
	is_equal "$(dmesg | grep -c 'mcp2510, oscillator 16000000 Hz')" 2

# --- up at 125 kbit/s: the CAN clock is half the tree's oscillator
can_up "$if0" 125000
can_up "$if1" 125000
ip -details link show "$if0"
check "$if0 runs on an 8 MHz CAN clock" \
	sh -c "ip -details link show $if0 | grep -q 'clock 8000000'"
check "$if0 is at 125000 bit/s" \
	sh -c "ip -details link show $if0 | grep -q 'bitrate 125000 '"
check "$if0's irq is INT0 of the tree's GPIO chip, level-low" \
	sh -c "grep -q ' mcp2510-sim  *0 *Level' /proc/interrupts"
irqs0=$(irq_count 0)

# --- frames both ways, and from the phantom node to both
dump_start "$if1" 2 /tmp/rx1.txt
cansend "$if0" 123#DEADBEEF
cansend "$if0" 12345678#0102030405060708
dump_wait
cat /tmp/rx1.txt
check "$if1 received both frames from $if0" sh -c \
	"grep -q '123 *\[4\] *DE AD BE EF' /tmp/rx1.txt &&
	 grep -q '12345678 *\[8\] *01 02 03 04 05 06 07 08' /tmp/rx1.txt"

dump_start "$if0" 1 /tmp/rx0.txt
cansend "$if1" 7FF#CAFE
dump_wait
cat /tmp/rx0.txt
check "$if0 received the frame from $if1" grep -q '7FF *\[2\] *CA FE' /tmp/rx0.txt

dump_start "$if0" 1 /tmp/ph0.txt
dump_start "$if1" 1 /tmp/ph1.txt
echo 42A#0011223344 >/sys/kernel/debug/mcp2510-sim/inject
wait
check "both received the phantom node's frame" sh -c \
	"grep -q '42A *\[5\] *00 11 22 33 44' /tmp/ph0.txt &&
	 grep -q '42A *\[5\] *00 11 22 33 44' /tmp/ph1.txt"
check "INT0 was taken as an interrupt" test "$(irq_count 0)" -gt "${irqs0:-0}"

ip -details -statistics link show "$if0"
ip -details -statistics link show "$if1"
for ifc in $if0 $if1; do
	check "$ifc is error-active" \
		sh -c "ip -details link show $ifc | grep -q 'state ERROR-ACTIVE'"
done

# --- unbinding and binding again: the tree's devices go and come back
ip link set "$if0" down
ip link set "$if1" down
check "mcp2510.ko unloads" rmmod mcp2510
check "mcp2510-sim.ko unloads" rmmod mcp2510-sim
check "the SPI devices are gone" sh -c '! ls -d /sys/bus/spi/devices/spi*.* 2>/dev/null'
check "the clocks are released" \
	is_equal "$(cat /sys/kernel/debug/clk/mcp2510-osc/clk_enable_count)" 0
insmod $mods/mcp2510-sim.ko && insmod $mods/mcp2510.ko
check "the tree's two chips probe again after reloading" \
	wait_for test -e /sys/class/net/can1

exit $failed
