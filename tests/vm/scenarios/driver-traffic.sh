#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-run: --nodes 2 --variant mcp2515
# vm-kernels: 6.12 rt debug
# mcp2510.ko on two simulated chips sharing one bus, at 125 kbit/s,
# 500 kbit/s and 1 Mbit/s: single frames (standard, extended, remote,
# empty) both ways with their content checked, a burst at full speed both
# ways (the sender keeps all three TX buffers busy, frames leave
# back-to-back) that must arrive complete and in send order, and the
# interface statistics agreeing with what was sent and received.
#
# Bus time runs as much slower than real time as gives every bit rate the
# frame time of 1,250 bit/s (800 times slower at 1 Mbit/s).  The receiver
# must empty a buffer within two frame times, and under TCG the model
# alone costs the guest about a millisecond of CPU per frame; a guest
# stalled by a loaded host then finds every frame that fell due at once
# and the chip overflows, whatever the driver.
set -eu
. /lib/rig.sh

burst=30

show() {
	ip -details -statistics link show can0
	ip -details -statistics link show can1
}

# expect FROM TO FRAME PATTERN: TO receives FRAME sent by FROM.
expect() {
	dump_start "$2" 1 /tmp/one.txt
	cansend "$1" "$3" || fail "cansend $1 $3"
	dump_wait
	grep -q "$4" /tmp/one.txt || {
		cat /tmp/one.txt
		fail "$2 did not receive $3 from $1"
	}
}

# in_order FILE: the identifiers in candump FILE count up by one from 0.
in_order() {
	n=0
	while read -r _ id _; do
		[ "$((0x$id))" -eq "$((n % 0x800))" ] || {
			echo "frame $n has id $id"
			return 1
		}
		n=$((n + 1))
	done <"$1"
}

# flood FROM TO: a full-speed burst arrives complete and in order.
flood() {
	dump_start "$2" "$burst" /tmp/burst.txt
	cangen -g 0 -p 1000 -n "$burst" -I i -L 8 -D i "$1" || fail "cangen on $1"
	dump_wait
	got=$(wc -l </tmp/burst.txt)
	[ "$got" -eq "$burst" ] || { show; fail "$1 -> $2 burst: $got of $burst frames"; }
	in_order /tmp/burst.txt || fail "$1 -> $2 burst out of order"
}

# grew IF COUNTER BEFORE EXPECTED: COUNTER of IF grew by EXPECTED.
grew() {
	_now=$(if_stat "$1" "$2")
	[ $((_now - $3)) -eq "$4" ] || { show; fail "$1 $2 grew by $((_now - $3)), expected $4"; }
}

for bitrate in 125000 500000 1000000; do
	echo "== $bitrate bit/s"
	tx0=$(if_stat can0 tx_packets) rx1=$(if_stat can1 rx_packets)
	tx1=$(if_stat can1 tx_packets) rx0=$(if_stat can0 rx_packets)
	txb0=$(if_stat can0 tx_bytes) rxb1=$(if_stat can1 rx_bytes)

	echo $((bitrate / 1250)) >"$SIM/time_scale"
	can_up can0 "$bitrate"
	can_up can1 "$bitrate"
	ip -details link show can0 | grep -q "bitrate $bitrate " ||
		fail "can0 does not report bitrate $bitrate"
	ip -details link show can0 | grep -q "state ERROR-ACTIVE" ||
		fail "can0 is not error-active after coming up"

	expect can0 can1 123#DEADBEEF '123 *\[4\] *DE AD BE EF'
	expect can1 can0 7FF#0011223344556677 '7FF *\[8\] *00 11 22 33 44 55 66 77'
	expect can0 can1 1ABCDEF0#42 '1ABCDEF0 *\[1\] *42'
	expect can1 can0 000# '000 *\[0\]'
	expect can0 can1 321#R '321 *\[0\] *remote request'
	flood can0 can1
	flood can1 can0

	# can0 sent three single frames (4 + 1 + 0 data bytes) and a burst,
	# can1 two and a burst; the receivers count exactly the same.
	grew can0 tx_packets "$tx0" $((3 + burst))
	grew can1 rx_packets "$rx1" $((3 + burst))
	grew can1 tx_packets "$tx1" $((2 + burst))
	grew can0 rx_packets "$rx0" $((2 + burst))
	grew can0 tx_bytes "$txb0" $((5 + 8 * burst))
	grew can1 rx_bytes "$rxb1" $((5 + 8 * burst))
	for dev in can0 can1; do
		for counter in rx_errors tx_errors rx_dropped tx_dropped rx_over_errors; do
			[ "$(if_stat $dev $counter)" -eq 0 ] || { show; fail "$dev $counter is $(if_stat $dev $counter)"; }
		done
	done

	show
	ip link set can0 down
	ip link set can1 down
done
echo "driver-traffic: ok"
