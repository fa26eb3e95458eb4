#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param time_scale=50
# vm-kernels: 6.12
# mcp2510.ko's operating modes and what ethtool and ip show of them:
# - bit rates from 10 kbit/s to 1 Mbit/s: ip -details shows the bit timing
#   and sample point the project's own calculator (mcp2510ctl bittiming)
#   gives, ethtool -d shows the CNF1-3 it encodes, and a frame crosses the
#   bus at each rate;
# - listen-only: can1 receives, but never acknowledges and never sends;
#   a frame destroyed by an error and sent again reaches it once, also
#   with rxm0/rxm1 "any" (the chip's RXM 11 would take the destroyed copy);
# - loopback: can0's frames come back through the chip, nothing reaches
#   the bus;
# - restart with frames pending: frames queued while nobody acknowledges
#   and the chip goes bus-off survive neither a restart nor ifdown/ifup as
#   stale echo skbs, and the queue moves afterwards;
# - ethtool -i names the driver and the SPI device.
#
# Bus time runs 50 times slower than real time, as in driver-busoff: at
# full speed a lone sender's TEC goes from 96 to 128 within a few
# milliseconds, and an interrupt pass that reads EFLG before the change
# and clears ERRIF after it leaves the interface at error-warning.
set -eu
. /lib/rig.sh

osc=16000000
CANSTAT=14 TEC=28 REC=29 CNF3=40 CNF2=41 CNF1=42
OPMOD_NORMAL=0 OPMOD_LOOPBACK=2 OPMOD_LISTEN_ONLY=3

show() { ip -details -statistics link show "$1"; }

# reg IF ADDR: one byte of IF's register dump, in decimal.
reg() {
	ethtool -d "$1" raw on | od -An -tu1 -v -j "$2" -N 1 | tr -d ' '
}
opmod() { echo $(($(reg "$1" $CANSTAT) >> 5)); }

# timing IF: ip's bit timing of IF in mcp2510ctl's words, on one line.
timing() {
	ip -details link show "$1" | awk '
		/ bitrate [0-9]+ sample-point / { line = $0; getline; print line " " $0; exit }' |
		tr -s ' \t' '  ' | sed 's/^ //; s/ $//'
}

# monitor_from SENDER: lines of the bus monitor sent by SENDER.
monitor_from() { grep -c " $1 " "$SIM/monitor" || true; }

echo "== ethtool -i"
ethtool -i can1 | tee /tmp/drvinfo
grep -qx 'driver: mcp2510' /tmp/drvinfo || fail "ethtool driver name"
grep -qx "bus-info: $(sim_state 1 spi_device)" /tmp/drvinfo ||
	fail "ethtool bus-info is not chip1's SPI device $(sim_state 1 spi_device)"

echo "== bit rates"
bitrates="10000 20000 50000 83333 100000 125000 250000 500000 800000 1000000"
# The debug kernel spends some ten seconds on each rate (a process costs it
# a third of a second): the lowest, a middle and the highest rate take
# the driver's paths there.
[ "$VM_KERNEL" != debug ] || bitrates="10000 125000 1000000"
for bitrate in $bitrates; do
	calc=$(mcp2510ctl bittiming "$bitrate" --clock $osc) ||
		fail "mcp2510ctl cannot make $bitrate bit/s"
	want=$(echo "$calc" | head -n 1)
	ip link set can0 type can bitrate "$bitrate" || fail "can0 refused $bitrate"
	got=$(timing can0)
	[ "$got" = "$want" ] || fail "$bitrate bit/s: ip shows '$got', expected '$want'"
	can_up can0 "$bitrate"
	can_up can1 "$bitrate"
	# CNF1-3 as the chip holds them, against the calculator's encoding.
	cnf=$(printf 'cnf1 0x%02x cnf2 0x%02x cnf3 0x%02x' \
		"$(reg can0 $CNF1)" "$(reg can0 $CNF2)" "$(reg can0 $CNF3)")
	[ "$cnf" = "$(echo "$calc" | tail -n 1)" ] ||
		fail "$bitrate bit/s: chip has '$cnf', expected '$(echo "$calc" | tail -n 1)'"
	[ "$(sim_state 0 bitrate)" -eq "$bitrate" ] ||
		[ "$bitrate" -eq 83333 ] || fail "chip0 runs at $(sim_state 0 bitrate) bit/s"
	dump_start can1 1 /tmp/one.txt
	cansend can0 "1AB#$(printf '%08X' "$bitrate")"
	dump_wait
	grep -q "1AB *\[4\] *$(printf '%08X' "$bitrate" | sed 's/../& /g; s/ $//')" /tmp/one.txt ||
		fail "no frame across the bus at $bitrate bit/s"
	echo "$bitrate bit/s: $got, $cnf"
	ip link set can0 down
	ip link set can1 down
done

echo "== listen-only"
can_up can0 125000
can_up can1 125000 listen-only on
[ "$(opmod can1)" -eq $OPMOD_LISTEN_ONLY ] || fail "chip1 not in listen-only mode"
: >"$SIM/monitor"
# The phantom's frame, acknowledged by can0, reaches the listener too.
dump_start can1 1 /tmp/lo.txt
echo 321#ABCD >"$SIM/inject"
dump_wait
echo off >"$SIM/phantom"
grep -q '321 *\[2\] *AB CD' /tmp/lo.txt || fail "listen-only can1 received nothing"
# can1 never sends.
dump_start can0 1 /tmp/none.txt -T 1000
cansend can1 322#01 || true
dump_wait
[ ! -s /tmp/none.txt ] || { cat /tmp/none.txt; fail "can0 received a frame from listen-only can1"; }
[ "$(monitor_from chip1)" -eq 0 ] || { cat "$SIM/monitor"; fail "listen-only chip1 sent on the bus"; }
[ "$(if_stat can1 tx_packets)" -eq 0 ] || fail "listen-only can1 counted a sent frame"
# can1 never acknowledges: can0 alone gets ACK errors.
cansend can0 323#02
wait_for 10 grep -q 'chip0 323#02 .* error-ack$' "$SIM/monitor" ||
	{ cat "$SIM/monitor"; fail "listen-only can1 acknowledged a frame"; }
ip link set can0 down
ip link set can1 down
# A frame destroyed by an error, then sent again, reaches the listener
# once: with the default filters and with "any" on both buffers.
for rxm in filtered any; do
	echo $rxm >/sys/class/net/can1/mcp2510/rxm0
	echo $rxm >/sys/class/net/can1/mcp2510/rxm1
	can_up can0 125000
	can_up can1 125000 listen-only on
	echo clear >"$SIM/monitor"
	echo 1 >"$SIM/bus_errors"
	dump_start can1 2 /tmp/lo2.txt -T 3000
	echo 324#BEEF >"$SIM/inject"
	dump_wait
	echo off >"$SIM/phantom"
	cat "$SIM/monitor"
	grep -q 'phantom 324#BEEF .* error-' "$SIM/monitor" ||
		fail "rxm $rxm: the phantom's first 324#BEEF was not destroyed"
	expect_lines /tmp/lo2.txt 1
	ip link set can0 down
	ip link set can1 down
done
echo filtered >/sys/class/net/can1/mcp2510/rxm0
echo filtered >/sys/class/net/can1/mcp2510/rxm1

echo "== loopback"
can_up can0 125000 loopback on
can_up can1 125000
[ "$(opmod can0)" -eq $OPMOD_LOOPBACK ] || fail "chip0 not in loopback mode"
: >"$SIM/monitor"
rx0=$(if_stat can0 rx_packets) rx1=$(if_stat can1 rx_packets)
# The stack's echo and the chip's copy: two identical lines.
dump_start can0 2 /tmp/lb.txt
dump0=$DUMP_PID
dump_start can1 1 /tmp/lb1.txt -T 2000
cansend can0 456#C0FFEE
dump_wait
wait "$dump0" || true
cat /tmp/lb.txt
[ "$(grep -c '456 *\[3\] *C0 FF EE' /tmp/lb.txt)" -eq 2 ] || fail "loopback frame did not come back"
[ $(($(if_stat can0 rx_packets) - rx0)) -eq 1 ] || fail "can0 did not receive its own frame"
[ ! -s /tmp/lb1.txt ] || fail "can1 received a loopback frame"
[ "$(if_stat can1 rx_packets)" -eq "$rx1" ] || fail "can1 counted a loopback frame"
[ ! -s "$SIM/monitor" ] || { cat "$SIM/monitor"; fail "a loopback frame reached the bus"; }
ip link set can0 down
ip link set can1 down

# pending_busoff: can0 up alone with frames queued, then driven bus-off.
pending_busoff() {
	can_up can0 125000 loopback off
	for i in 1 2 3 4 5 6; do cansend can0 "10$i#0$i"; done
	wait_for 30 can_state_is can0 ERROR-PASSIVE || { show can0; fail "can0 never went error-passive"; }
	echo 1000 >"$SIM/bus_errors"
	wait_for 30 can_state_is can0 BUS-OFF || { show can0; fail "can0 never went bus-off"; }
	echo 0 >"$SIM/bus_errors"
}

# moves: with can1 back, a new frame from can0 reaches it.
moves() {
	can_up can1 125000 listen-only off
	dump_start can1,7FF:7FF 1 /tmp/after.txt
	cansend can0 "7FF#$1"
	dump_wait
	grep -q "7FF *\[1\] *$1" /tmp/after.txt || { show can0; fail "can0's queue is stuck after $2"; }
	ip link set can1 down
}

echo "== restart with frames pending"
echo 1 >"$SIM/no_ack"
pending_busoff
ip link set can0 type can restart || fail "restart refused"
echo 0 >"$SIM/no_ack"
moves 01 restart
ip link set can0 down

echo "== ifdown/ifup with frames pending"
echo 1 >"$SIM/no_ack"
pending_busoff
ip link set can0 down
echo 0 >"$SIM/no_ack"
ip link set can0 up
moves 02 ifdown/ifup
ip link set can0 down
show can0
if dmesg | grep -i 'echo'; then
	fail "the kernel log complains about echo skbs"
fi
echo "driver-modes: ok"
