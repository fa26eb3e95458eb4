#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --driver mcp251x
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# vm-kernels: 6.12
# The simulator unloaded and loaded again with spidev_node=1: chip 0 stays a
# CAN interface, chip 1 becomes /dev/spidevB.1.  Through spidev writes alone
# the chip is reset, set to loopback and made to receive its own frame, and
# its INT line, watched with libgpiod's gpiomon, must fall (and RX0BF, set to
# signal a full RXB0, with it).  On the way the
# spi_errors fault must fail exactly the messages asked for, the
# int_edge_miss fault must hide exactly one falling edge from gpiomon, and a
# power loss must let INT float high and power-on restart the chip.
set -eu
. /lib/rig.sh

sim=$SIM
int1=1   # line INT1: the INT lines come first, one per chip,
rx0bf1=3 # then RX0BF0, RX0BF1, ...

expect_counter() {
	[ "$(sim_counter "$1" "$2")" -eq "$3" ] ||
		fail "chip$1 $2 is $(sim_counter "$1" "$2"), expected $3"
}

# spi BYTES: one write(), so one chip-select-low period; BYTES as printf
# octal escapes
spi() {
	printf "$1" | dd of="$dev" bs=64 count=1 iflag=fullblock 2>/dev/null
}

# state_is CHIP NAME VALUE
state_is() {
	[ "$(sim_state "$1" "$2")" = "$3" ]
}

line_watched() {
	grep -q "INT1 *|gpiomon" /sys/kernel/debug/gpio
}

# gpiomon on INT1 for one falling edge, in the background, into FILE
watch_int1() {
	if gpiod_v1; then
		gpiomon -b -n 1 -f "$gpiochip" "$int1" >"$1" &
	else
		gpiomon -n 1 -e falling -c "$gpiochip" "$int1" >"$1" &
	fi
	MON_PID=$!
	wait_for 5 line_watched || fail "gpiomon did not request INT1"
}

echo "== reload with spidev_node=1"
rmmod mcp2510_sim || fail "cannot unload mcp2510-sim"
[ ! -e /sys/class/net/can0 ] || fail "can0 outlived the simulator"
ko=/opt/mcp2510/modules/mcp2510-sim.ko
for bad in nodes=0 nodes=9 variant=mcp2516 driver=spidev time_scale=0 \
	"spidev_node=2 nodes=2" osc_hz=1; do
	# shellcheck disable=SC2086 # several parameters in one word
	if insmod $ko $bad 2>/dev/null; then
		fail "mcp2510-sim accepted $bad"
	fi
done
insmod $ko nodes=2 variant="$VM_VARIANT" \
	driver="$VM_DRIVER" spidev_node=1 || fail "cannot load mcp2510-sim"
wait_for 5 test -e /sys/class/net/can0 || fail "chip 0 did not become can0"
[ ! -e /sys/class/net/can1 ] || fail "chip 1 became a CAN interface"

dev=/dev/spidev$(sim_state 1 spi_bus).$(sim_state 1 spi_cs)
wait_for 5 test -c "$dev" || fail "$dev did not appear"
spidev=$(sim_state 1 spi_device)
[ "$(basename "$(readlink /sys/bus/spi/devices/"$spidev"/driver)")" = spidev ] ||
	fail "$spidev is not bound to spidev"
gpiochip=$(gpio_chip mcp2510-sim)
gpio_info "$gpiochip"
[ "$(gpio_get "$gpiochip" "$int1")" = 1 ] || fail "INT1 is not idle (high)"

echo "== spi_errors"
spi '\300' # RESET
expect_counter 1 spi_transfers 1
expect_counter 1 spi_bytes 1
echo 2 >$sim/chip1/spi_errors
for try in 1 2; do
	if spi '\300'; then fail "write $try went through despite spi_errors"; fi
done
spi '\300' || fail "the write after the injected errors failed"
[ "$(cat $sim/chip1/spi_errors)" -eq 0 ] || fail "spi_errors not used up"
expect_counter 1 spi_failed 2
expect_counter 1 spi_transfers 2
sleep 0.1 # start-up after RESET: 128 oscillator cycles

echo "== loopback frame raises INT"
spi '\002\050\001\265\003'     # CNF3..CNF1: 125 kbit/s at 16 MHz
spi '\002\053\001'             # CANINTE: RX0IE
spi '\002\140\140'             # RXB0CTRL: receive any frame
spi '\002\061\044\140\000\000\001\021' # TXB0: 123#11
spi '\002\014\005'             # BFPCTRL: RX0BF signals "RXB0 full"
spi '\002\017\100'             # CANCTRL: REQOP loopback
wait_for 5 state_is 1 opmode loopback || fail "chip1 did not enter loopback"
[ "$(sim_state 1 bitrate)" -eq 125000 ] || fail "chip1 bit rate $(sim_state 1 bitrate)"

watch_int1 /tmp/edge1.txt
spi '\201' # RTS TXB0
wait "$MON_PID" || fail "gpiomon failed"
cat /tmp/edge1.txt
grep -qi 'falling' /tmp/edge1.txt || fail "gpiomon saw no falling edge on INT1"
[ "$(sim_state 1 int)" -eq 0 ] || fail "INT1 not asserted"
expect_counter 1 frames_rx 1
expect_counter 1 interrupts 1
[ "$(gpio_get "$gpiochip" "$rx0bf1")" = 0 ] || fail "RX0BF1 does not show RXB0 full"

echo "== int_edge_miss"
spi '\002\054\000' # CANINTF = 0: INT rises, RXB0 is free again
[ "$(sim_state 1 int)" -eq 1 ] || fail "INT1 still asserted"
[ "$(gpio_get "$gpiochip" "$rx0bf1")" = 1 ] || fail "RX0BF1 still low with RXB0 free"
echo 1 >$sim/chip1/int_edge_miss
watch_int1 /tmp/edge2.txt
spi '\201' # the second frame: this falling edge is lost
wait_for 5 state_is 1 int 0 || fail "no second frame"
sleep 1
kill -0 "$MON_PID" 2>/dev/null || fail "gpiomon saw the edge that was to be missed"
[ "$(cat $sim/chip1/int_edge_miss)" -eq 0 ] || fail "int_edge_miss not used up"
expect_counter 1 int_edges_missed 1
spi '\002\054\000'
spi '\201' # the third frame: delivered again
wait "$MON_PID" || fail "gpiomon failed"
grep -qi 'falling' /tmp/edge2.txt || fail "the edge after the missed one was lost too"
expect_counter 1 frames_rx 3
expect_counter 1 interrupts 3

echo "== power loss"
[ "$(gpio_get "$gpiochip" "$int1")" = 0 ] || fail "INT1 not asserted before the power loss"
echo 0 >$sim/chip1/power
[ "$(gpio_get "$gpiochip" "$int1")" = 1 ] || fail "INT1 of an unpowered chip is not pulled high"
[ "$(sim_state 1 ready)" = 0 ] || fail "an unpowered chip claims to be ready"
echo 1 >$sim/chip1/power
wait_for 5 state_is 1 ready 1 || fail "chip1 did not start up after power-on"
[ "$(sim_state 1 opmode)" = config ] || fail "chip1 is not in configuration mode after power-on"
[ "$(gpio_get "$gpiochip" "$int1")" = 1 ] || fail "INT1 asserted after power-on"

echo "== chip 0 still works as can0"
ip link set can0 type can bitrate 125000
ip link set can0 up || {
	cat $sim/chip0/state $sim/chip0/regs
	fail "cannot bring can0 up"
}
echo 1 >$sim/phantom 2>/dev/null && fail "phantom accepted a bad command"
echo on >$sim/phantom
dump_start can0 1 /tmp/c0.txt
echo 7FF#0102 >$sim/inject
dump_wait
grep -q '7FF *\[2\] *01 02$' /tmp/c0.txt || fail "can0 missed the phantom's 7FF#0102"

# a running driver holds INT0, and with it the module that provides it
if rmmod mcp2510_sim 2>/dev/null; then fail "mcp2510-sim unloaded under a running can0"; fi
ip link set can0 down
rmmod mcp2510_sim || fail "cannot unload mcp2510-sim at the end"
[ ! -e /sys/class/net/can0 ] || fail "can0 outlived the simulator"
echo "sim-spidev: ok"
