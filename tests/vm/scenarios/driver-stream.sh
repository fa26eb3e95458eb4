#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param time_scale=40 --timeout 300
# vm-kernels: 6.1
# Long streams through mcp2510.ko at 500 kbit/s: 10,000 frames can0 ->
# can1, then floods both ways at once (can0 sends standard, can1 extended
# identifiers).  The driver loses nothing, keeps the order exactly, and
# the interface statistics agree with what was sent and received.
#
# Bus time runs 40 times slower than real time, for the reason given in
# driver-traffic.sh: under TCG the guest spends milliseconds of CPU on each
# frame (about 3 ms for both sides together, measured).  A frame of 8
# bytes then lasts about 10 ms, so the receiver has some 20 ms to empty a
# buffer and the 10,000 frames take about 100 s.  Bus time follows the
# guest's clock, which also runs while the host does not schedule the
# guest: a stall of more than two frame times makes the receiving chip
# drop a frame, whatever the driver does (at time scales 28 to 60, 0.1-2%
# of the frames on a host busy with other QEMU guests, a few per 10,000 on
# a quieter one).  So a frame may be missing only when the receiving chip
# counted it as an overflow and the driver reported the overflow.  Such
# stalls also leave the older frame in RXB1 now and then; the driver
# tells (driver/core/irq_rx.c), so no disorder at all is accepted.
# The debug kernel spends several times the CPU on a frame: there bus
# time runs 200 times slower and the streams are a tenth as long, which
# still keeps all three TX buffers and both RX buffers busy throughout.
# One 10,000-frame stream per make check is enough: on the other kernels
# than 6.1 the stream is 3,000 frames (the suite's time budget; `make
# soak` runs for hours).
#
set -eu
. /lib/rig.sh

stream=10000
both=500
if [ "$VM_KERNEL" = debug ]; then
	stream=1000 both=100
	echo 200 >"$SIM/time_scale"
elif [ "$VM_KERNEL" != 6.1 ]; then
	stream=3000
fi

show() {
	ip -details -statistics link show can0
	ip -details -statistics link show can1
}

# missing FILE SENT MODULO: how many of the SENT frames, whose identifiers
# count up from 0 modulo MODULO, are not in candump FILE.  Fails, naming
# the frame, when one comes twice or after a newer one.
missing() {
	awk -v sent="$2" -v m="$3" '
		function hex(s,  i, n) {
			n = 0
			for (i = 1; i <= length(s); i++)
				n = n * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
			return n
		}
		BEGIN { prev = -1 }
		{
			gap = (hex($2) - prev + m) % m
			if (gap < 1 || gap > m / 2) {
				printf "frame %d: id %s after %x\n", NR, $2, prev | "cat >&2"
				bad = 1
				exit 1
			}
			skipped += gap - 1
			prev = hex($2)
		}
		END {
			if (!bad)
				print skipped + (sent - 1 - prev + m) % m
		}' "$1"
}

# grew IF COUNTER BEFORE EXPECTED: COUNTER of IF grew by EXPECTED.
grew() {
	_now=$(if_stat "$1" "$2")
	[ $((_now - $3)) -eq "$4" ] || { show; fail "$1 $2 grew by $((_now - $3)), expected $4"; }
}

# snapshot: the counters a stream is judged by, as shell variables.
snapshot() {
	for dev in can0 can1; do
		for c in tx_packets rx_packets rx_bytes rx_over_errors; do
			eval "${dev}_$c=$(if_stat $dev $c)"
		done
	done
	ovf0=$(sim_counter 0 overflows) ovf1=$(sim_counter 1 overflows)
}

# arrived FILE SENT FROM TO CHIP MODULO: of SENT frames FROM -> TO, those
# in candump FILE arrived in order; every frame missing was dropped by
# TO's chip (CHIP) with its receive buffers full, and the driver reported
# the overflow: the driver itself lost none.  A chip overflows when the
# host leaves the guest unscheduled for more than two frame times, which
# bus time, following the guest's clock, does not notice.
arrived() {
	_got=$(wc -l <"$1")
	_lost=$(missing "$1" "$2" "$6") || fail "$3 -> $4: out of order"
	[ "$_lost" -eq $(($2 - _got)) ] || fail "$3 -> $4: $_got frames, $_lost missing of $2"
	eval "_ovf=\$(($(sim_counter "$5" overflows) - ovf$5))"
	[ "$_lost" -eq "$_ovf" ] || { show; fail "$3 -> $4: $_lost frames lost, chip$5 dropped $_ovf"; }
	eval "_over=\$(($(if_stat "$4" rx_over_errors) - ${4}_rx_over_errors))"
	if [ "$_lost" -gt 0 ]; then
		echo "$3 -> $4: chip$5 overflowed, $_lost of $2 frames lost (host stalls)"
		[ "$_over" -ge 1 ] || fail "$4 did not report the overflow"
	fi
	grew "$3" tx_packets "$(eval echo "\$${3}_tx_packets")" "$2"
	grew "$4" rx_packets "$(eval echo "\$${4}_rx_packets")" "$_got"
	grew "$4" rx_bytes "$(eval echo "\$${4}_rx_bytes")" $((8 * _got))
}

no_errors() {
	for dev in can0 can1; do
		for c in tx_errors rx_dropped tx_dropped; do
			[ "$(if_stat $dev $c)" -eq 0 ] || { show; fail "$dev $c is $(if_stat $dev $c)"; }
		done
	done
}

for dev in can0 can1; do
	ip link set $dev txqueuelen 1000
	can_up $dev 500000
done

echo "== $stream frames can0 -> can1"
snapshot
start=$(uptime_s)
dump_start can1 "$stream" /tmp/stream.txt -T 5000
cangen -g 0 -n "$stream" -I i -L 8 -D i can0 || fail "cangen on can0"
dump_wait
echo "$stream frames in $(($(uptime_s) - start)) s"
arrived /tmp/stream.txt "$stream" can0 can1 1 2048
no_errors

echo "== $both frames each way at once"
snapshot
start=$(uptime_s)
# Each side also hears its own frames, looped back: take the other's only.
dump_start can1,0:80000000 "$both" /tmp/to1.txt
dump1=$DUMP_PID
dump_start can0,80000000:80000000 "$both" /tmp/to0.txt
dump0=$DUMP_PID
cangen -g 0 -n "$both" -I i -L 8 -D i can0 &
gen0=$!
cangen -g 0 -n "$both" -e -I i -L 8 -D i can1 || fail "cangen on can1"
wait $gen0 || fail "cangen on can0"
wait $dump1 || true
wait $dump0 || true
echo "2 x $both frames in $(($(uptime_s) - start)) s"
arrived /tmp/to1.txt "$both" can0 can1 1 2048
arrived /tmp/to0.txt "$both" can1 can0 0 536870912
no_errors
show
ip link set can0 down
ip link set can1 down
echo "driver-stream: ok"
