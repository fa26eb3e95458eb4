#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510
# vm-kernels: 6.1
# Bit timing on the strict chip model (tests/sim/README.md, "Invalid bit
# timing"), this project's driver and then mainline mcp251x on new chips:
# at the usual rates from 16 MHz both program timing the data sheets allow
# and frames cross.  Asked for SJW = PS2 (125 kbit/s with "sjw 2": PS2 is
# 2 quanta there), which can-dev accepts but DS21291 5.8 and DS21801 5.3
# forbid ("Phase Seg 2 > Sync Jump Width"), this driver refuses to start;
# mainline programs it, and its chip cannot communicate: chip1, error
# active, flags its frames until chip0 is bus-off.  The chip recovers on
# its own and retries, chip1 turns error passive after 128 such frames and
# the ACK errors that follow fill the monitor's ring within a fraction of a
# second: the lasting evidence is chip0's bus-off count (ACK errors alone
# leave an error-passive sender at TEC 128, never bus-off).
set -eu
. /lib/rig.sh

[ "$VM_SIM" = 1 ] || fail "the simulated chips are not loaded"

usual_rates() {
	for br in 125000 250000 500000 1000000; do
		can_up can0 $br
		can_up can1 $br
		expect_eq "$1 at $br bit/s: chip0's bit rate" "$(sim_state 0 bitrate)" $br
		dump_start can1 1 /tmp/bt.txt
		cansend can0 123#11
		dump_wait
		grep -q '123 *\[1\] *11$' /tmp/bt.txt || fail "$1 at $br bit/s: no frame across"
		ip link set can0 down
		ip link set can1 down
		echo "$1: $br bit/s ok"
	done
}

chip0_bus_off() {
	[ "$(sim_counter 0 bus_off)" -gt 0 ]
}

for drv in mcp2510 mcp251x; do
	[ "$drv" = "$VM_DRIVER" ] || chips_load $drv
	usual_rates $drv
	ip link set can0 type can bitrate 125000 sjw 2 || fail "$drv: sjw 2 refused"
	ip -details link show can0 | grep -q 'phase-seg2 2 sjw 2' ||
		fail "$drv: not PS2 = SJW = 2: $(ip -details link show can0)"
	if [ "$drv" = mcp2510 ]; then
		! ip link set can0 up 2>/tmp/up.err || fail "mcp2510 started with PS2 = SJW"
		echo "mcp2510: refuses PS2 = SJW: $(cat /tmp/up.err)"
		continue
	fi
	can_up can0 125000 sjw 2
	can_up can1 125000
	expect_eq "mcp251x with PS2 = SJW: chip0's bit rate" "$(sim_state 0 bitrate)" 0
	echo "mcp251x: CNF3-CNF1 $(sed -n 's/^20: \(.\{24\}\)\(.\{8\}\).*/\2/p' "$SIM/chip0/regs")"
	echo x >"$SIM/chip0/counters"
	echo x >"$SIM/chip1/counters"
	rx_before=$(if_stat can1 rx_packets)
	cansend can0 123#22
	wait_for 10 chip0_bus_off || fail "mcp251x with PS2 = SJW: chip0 never bus-off"
	expect_eq "can1 frames" "$(if_stat can1 rx_packets)" "$rx_before"
	expect_eq "chip1 frames" "$(sim_counter 1 frames_rx)" 0
	echo "mcp251x: programs PS2 = SJW, and its frames end in error frames:" \
		"chip0 $(sim_counter 0 tx_errors) tx errors, bus-off," \
		"chip1 $(sim_counter 1 rx_errors) rx errors"
	ip link set can0 down
	ip link set can1 down
done
