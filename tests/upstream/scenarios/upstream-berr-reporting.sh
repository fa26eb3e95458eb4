#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# Shows what upstream/mcp251x/0006 adds: "berr-reporting on", a bus-error
# frame and count for the chip's MERRF, and its price in interrupts.
# Thirteen injected bus errors destroy can0's frame before it goes
# through, once with the mode off and once with it on: off, no bus-error
# frame and no count, as before; on, each interface reports bus errors.
# The interrupts each chip raised and the sender's SPI transfers are
# printed for both runs, not judged: MERRF gathers the errors that come
# while one is served, so how many interrupts the mode costs depends on
# how fast the IRQ thread runs (all 13 errors in one, on a slow guest).
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

CAN_ERR_PROT=0x8 CAN_ERR_BUSERROR=0x80

mcp251x_under_test

# bus_errors IF: the bus-errors count of ip -details -statistics.
bus_errors() {
	ip -details -statistics link show "$1" |
		awk '/re-started bus-errors/ { getline; print $2 }'
}
# burst MODE: both interfaces up with berr-reporting MODE, 13 bus errors
# on can0's frame; sets IRQS0/IRQS1 (interrupts of chip0/chip1) and
# XFERS0 (chip0's SPI transfers), and leaves can0's error frames in
# /tmp/err0.txt.
burst() {
	ip link set can0 down
	ip link set can1 down
	can_up can0 125000 berr-reporting "$1"
	can_up can1 125000 berr-reporting "$1"
	errors_start can0 /tmp/err0.txt
	irq0=$(sim_counter 0 irqs_delivered) irq1=$(sim_counter 1 irqs_delivered)
	xfer0=$(sim_counter 0 spi_transfers)
	echo 13 >"$SIM/bus_errors"
	tx0=$(if_stat can0 tx_packets)
	cansend can0 123#5A
	wait_for 30 sent_beyond can0 "$tx0" || fail "$under_test: 123#5A never went through"
	nap 0.5
	errors_stop
	IRQS0=$(($(sim_counter 0 irqs_delivered) - irq0))
	IRQS1=$(($(sim_counter 1 irqs_delivered) - irq1))
	XFERS0=$(($(sim_counter 0 spi_transfers) - xfer0))
	echo "berr-reporting $1: interrupts chip0 $IRQS0, chip1 $IRQS1;" \
		"SPI transfers chip0 $XFERS0;" \
		"bus-errors can0 $(bus_errors can0), can1 $(bus_errors can1)"
}

if ! ip link set can0 type can bitrate 125000 berr-reporting on 2>/tmp/mode.err; then
	echo "$under_test refuses berr-reporting: $(cat /tmp/mode.err)"
	[ -z "$ko" ] || fail "$under_test refuses berr-reporting"
	echo "upstream-berr-reporting: $under_test has no berr-reporting"
	exit 0
fi
[ -n "$ko" ] || fail "$under_test takes berr-reporting: the kernel has the change"

burst off
! error_seen /tmp/err0.txt $CAN_ERR_BUSERROR || fail "$under_test: a bus-error frame with berr-reporting off"
[ "$(bus_errors can0)" -eq 0 ] || fail "$under_test: bus errors counted with berr-reporting off"
off0=$IRQS0

burst on
error_seen /tmp/err0.txt $CAN_ERR_BUSERROR ||
	{ cat /tmp/err0.txt; fail "$under_test: no bus-error frame with berr-reporting on"; }
error_seen /tmp/err0.txt $CAN_ERR_PROT || fail "$under_test: a bus-error frame without CAN_ERR_PROT"
[ "$(bus_errors can0)" -gt 0 ] && [ "$(bus_errors can1)" -gt 0 ] ||
	fail "$under_test: bus errors not counted on both interfaces"
ip link set can0 down
ip link set can1 down
echo "upstream-berr-reporting: $under_test reports bus errors with berr-reporting on;" \
	"interrupts on the sender: $off0 off, $IRQS0 on"
