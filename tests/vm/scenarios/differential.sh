#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --driver mcp2510
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# vm-kernels: 6.12
# This project's driver against mainline mcp251x, on what a user sees of
# both.  The same steps run twice on new chips, once bound to each driver
# (the one vm-run loaded first, then the other), and each run writes what
# it observed in a canonical form, one "key value" line per observation:
# the frames local and remote listeners got, with echo on and with a
# socket's CAN_RAW_LOOPBACK off, and in the controller's loopback mode; the
# statistics both drivers keep; the error frames (candump with an error
# filter), CAN state and state counters for a sender nobody acknowledges, for
# injected bus errors and for bus-off, then a manual restart and one with
# restart-ms.  The two records must be equal, except for the keys listed
# in "differ", where this driver reports more or differently on purpose:
# docs/differences-from-mcp251x.md says why for each.
#
# While errors build up, bus time runs 100 times slower than real time (300
# times on the debug kernel) so that, at 125 kbit/s, either driver sees each
# error state before the next errors push the counters past it (4 errors
# from warning to passive: some 0.2 s), however busy the host.  Bring-ups
# and restarts run at full speed: mcp251x's wake-up gives the chip's
# oscillator 5 ms of real time, which slowed bus time on a starved guest
# does not always cover.
set -eu
. /lib/rig.sh

# bus_slow, bus_fast: bus time for building up errors, and for the rest.
bus_slow() {
	if [ "$VM_KERNEL" = debug ]; then
		echo 300 >"$SIM/time_scale"
	else
		echo 100 >"$SIM/time_scale"
	fi
}
bus_fast() { echo 1 >"$SIM/time_scale"; }

rate=125000
_quiet=0

[ "$VM_SIM" = 1 ] || fail "the simulated chips are not loaded"

# Keys whose values differ on purpose, as "PHASE.IF.NAME" patterns (case
# syntax), by reason; docs/differences-from-mcp251x.md says more.
# - mcp251x has no berr-counter callback and no berr-reporting; one-shot is
#   this driver's on an MCP2515 only.
differ='*.berr_counter_shown|ctrlmode.berr-reporting|ctrlmode.one-shot'
# - Returns to a better state: the chip (model) raises no interrupt when an
#   EFLG flag clears, and mcp251x sends no error frame a socket can receive
#   then; this driver does.
differ="$differ|*.recovery"
# - mcp251x takes tx_bytes from the echo skb, which a socket with
#   CAN_RAW_LOOPBACK off does not leave: such frames count 0 bytes.
differ="$differ|loopback-off.can0.tx_bytes"
# - The frame pending at bus-off: can-dev's restart counts it as dropped and
#   aborted, and mcp251x also in tx_errors, yet its chip sends it after the
#   restart; with this driver it never goes out.
differ="$differ|restart.can0.tx_errors"
differ="$differ|restart.can1.rx_packets|restart.can1.rx_bytes"
# - restart-ms: mcp251x leaves bus-off recovery to the chip and tells can-dev
#   nothing (no bus-off count, no restart, no CAN_ERR_RESTARTED, the pending
#   frame goes out); this driver goes through can-dev's bus-off and
#   restart, which counts both and drops the pending frame.
r=bus-off-restart-ms
differ="$differ|$r.can0.errors|$r.can0.restarts|$r.can0.bus_off|$r.can0.tx_packets"
differ="$differ|$r.can0.tx_bytes|$r.can0.tx_dropped|$r.can0.tx_aborted_errors"
differ="$differ|$r.can1.rx_packets|$r.can1.rx_bytes"
# - the series' module (vm-run --module) ends that frame at bus-off
#   (0011, BQL), in tx_errors alone: can-dev's restart counts none.
[ -z "$VM_MCP251X_KO" ] ||
	differ="$differ|restart.can0.tx_dropped|restart.can0.tx_aborted_errors"

# excluded KEY: KEY is one of those.
excluded() {
	eval "case \$1 in $differ) return 0 ;; esac"
	return 1
}

rec() { echo "$phase.$*" >>"$out"; }

# step NAME: the keys that follow are NAME's; the log says when it began.
step() {
	phase=$1
	_now
	echo "== $drv: $phase at $NOW_S s"
}

# snapshot [-s] IF...: each IF's CAN state, carrier and the statistics
# both drivers keep, the counters as what changed since the last snapshot
# (so that a difference shows in the step that made it); -s: state, carrier
# and state counters only, the traffic counters go to the next snapshot;
# -q: the traffic counters are not recorded, the next snapshot starts
# from them.
snapshot() {
	_traffic=1 _quiet=0
	case $1 in
	-s) _traffic=0; shift ;;
	-q) _quiet=1; shift ;;
	esac
	for _if in "$@"; do
		[ $_traffic = 0 ] || _snapshot_traffic "$_if"
		_snapshot_can "$_if"
	done
	_quiet=0
}
# _delta IF NAME VALUE: record VALUE less NAME's value at the last call.
_delta() {
	eval "_was=\${base_${drv}_$1_$2:-0}; base_${drv}_$1_$2=\$3"
	[ "$_quiet" = 1 ] || rec "$1.$2 $(($3 - _was))"
}
_snapshot_traffic() {
	for _c in rx_packets rx_bytes rx_errors rx_over_errors rx_dropped \
		tx_packets tx_bytes tx_errors tx_dropped tx_aborted_errors; do
		read -r _v <"/sys/class/net/$1/statistics/$_c"
		_delta "$1" "$_c" "$_v"
	done
}
_snapshot_can() {
	read -r _v <"/sys/class/net/$1/carrier" || _v=-
	rec "$1.carrier $_v"
	ip -details -statistics link show "$1" >/tmp/ip.txt
	_next=0 _berr=no
	while read -r _line; do
		case $_line in
		"can "*"state "*)
			_s=${_line#*state }
			rec "$1.state ${_s%% *}"
			case $_line in *berr-counter*) _berr=yes ;; esac ;;
		"re-started bus-errors"*) _next=1; continue ;;
		esac
		if [ $_next = 1 ]; then
			set -- "$1" $_line
			_delta "$1" restarts "$2"
			_delta "$1" bus_error "$3"
			_delta "$1" arbitration_lost "$4"
			_delta "$1" error_warning "$5"
			_delta "$1" error_passive "$6"
			_delta "$1" bus_off "$7"
			_next=0
		fi
	done </tmp/ip.txt
	rec "$1.berr_counter_shown $_berr"
}

# The error frames: candump IF with an error filter into /tmp/err-IF.txt,
# for each IF named, until errors_end.
errors_begin() {
	_err_pids=
	for _if in "$@"; do
		errors_start "$_if" "/tmp/err-$_if.txt"
		_err_pids="$_err_pids $ERR_PID"
	done
	_err_ifs=$*
}
errors_end() {
	nap 0.3
	# shellcheck disable=SC2086 # several pids
	kill $_err_pids
	wait $_err_pids 2>/dev/null || true
	for _if in $_err_ifs; do
		canon_errors "/tmp/err-$_if.txt"
		rec "$_if.errors ${ERRORS:-none}"
		rec "$_if.recovery ${RECOVERY:-none}"
	done
}

# canon_errors FILE: ERRORS = FILE's error frames, oldest first, one word
# each (class and, for CRTL, data[1] bits), a run of equal ones as one;
# CAN_ERR_CNT (whether data[6..7] hold TEC and REC) is left out.  Frames
# that report a return to a better error state (warning after passive, or
# error-active) go to RECOVERY instead, in the same form.
canon_errors() {
	ERRORS= RECOVERY= _prev= _level=0
	while read -r _ _id _ _d0 _d1 _; do
		_class=$((0x$_id & 0x1fffffff & ~0x200)) _d1=$((0x$_d1))
		_w=
		for _bit in 1:tx-timeout 2:lostarb 4:crtl 8:prot 16:trx 32:ack \
			64:busoff 128:buserror 256:restarted; do
			[ $((_class & ${_bit%%:*})) = 0 ] || _w="$_w+${_bit#*:}"
		done
		if [ $((_class & 4)) != 0 ]; then
			for _bit in 1:rx-overflow 2:tx-overflow 4:rx-warning \
				8:tx-warning 16:rx-passive 32:tx-passive 64:active; do
				[ $((_d1 & ${_bit%%:*})) = 0 ] || _w="$_w/${_bit#*:}"
			done
		fi
		_w=${_w#+}
		_w=${_w:-no-class}
		# how bad the state this frame reports is: 0 active .. 3 bus-off
		_new=-1
		[ $_class != 0 ] || _new=0
		[ $((_class & 4)) = 0 ] || [ $((_d1 & 0x40)) = 0 ] || _new=0
		[ $((_class & 4)) = 0 ] || [ $((_d1 & 0x0c)) = 0 ] || _new=1
		[ $((_class & 4)) = 0 ] || [ $((_d1 & 0x30)) = 0 ] || _new=2
		[ $((_class & 64)) = 0 ] || _new=3
		[ $((_class & 256)) = 0 ] || _level=0
		if [ $_new -ge 0 ] && [ $_new -lt $_level ]; then
			RECOVERY="$RECOVERY $_w"
		elif [ "$_w" != "$_prev" ]; then
			ERRORS="$ERRORS $_w"
		fi
		[ $_new -lt 0 ] || _level=$_new
		_prev=$_w
	done <"$1"
	ERRORS=${ERRORS# } RECOVERY=${RECOVERY# }
}

# listen IF: every frame on IF, from a local socket, into /tmp/rx-IF.txt
# (until unlisten).  Not candump -x's direction: whether an echo still
# names the socket that sent it (TX) or not (RX) depends on timing, with
# either driver.
listen() {
	dump_start "$1" 1000 "/tmp/rx-$1.txt"
	_listen_pids="${_listen_pids:-} $DUMP_PID"
}
unlisten() {
	nap 0.3
	# shellcheck disable=SC2086 # several pids
	kill $_listen_pids
	wait $_listen_pids 2>/dev/null || true
	_listen_pids=
}
# heard IF: "N ID..." of what listen IF got.
heard() {
	_n=0 _ids=
	while read -r _ _id _; do
		_n=$((_n + 1)) _ids="$_ids $_id"
	done <"/tmp/rx-$1.txt"
	rec "$1.heard $_n$_ids"
}

# ctrlmode NAME: whether the driver takes "NAME on" (can0 down).
ctrlmode() {
	if ip link set can0 type can "$1" on 2>/dev/null; then
		echo "ctrlmode.$1 yes" >>"$out"
		ip link set can0 type can "$1" off
	else
		echo "ctrlmode.$1 no" >>"$out"
	fi
}

# behaviours DRIVER: the steps, on chips bound to DRIVER, into
# /tmp/differential-DRIVER.txt.
behaviours() {
	drv=$1 out=/tmp/differential-$1.txt
	: >"$out"
	ctrlmode berr-reporting
	ctrlmode one-shot
	ctrlmode listen-only
	ctrlmode loopback
	ctrlmode triple-sampling

	step echo
	can_up can0 $rate
	can_up can1 $rate
	listen can0
	listen can1
	cansend can0 123#11
	wait_for 10 received_beyond can1 0 || fail "$1: can1 did not receive 123#11"
	cansend can1 1ABCDEF0#0102030405060708
	cansend can1 7FF#R
	cansend can1 000#
	wait_for 10 received_beyond can0 2 || fail "$1: can0 did not receive can1's frames"
	unlisten
	heard can0
	heard can1

	step loopback-off
	listen can0
	listen can1
	# cangen -x: CAN_RAW_LOOPBACK off, no other local socket gets it
	cangen -x -n 1 -I 124 -L 1 -D 22 can0
	wait_for 10 received_beyond can1 1 || fail "$1: can1 did not receive 124#22"
	unlisten
	heard can0
	heard can1
	snapshot can0 can1

	step controller-loopback
	ip link set can0 down
	ip link set can0 type can loopback on
	can_up can0 $rate
	listen can0
	listen can1
	tx0=$(if_stat can0 tx_packets)
	cansend can0 125#33
	wait_for 10 sent_beyond can0 "$tx0" || fail "$1: 125#33 not sent in loopback mode"
	unlisten
	heard can0
	heard can1
	snapshot can0 can1
	ip link set can0 down
	ip link set can0 type can loopback off

	step no-ack
	ip link set can1 down
	can_up can0 $rate
	# the queue holds the 40 frames below whatever the bus time
	ip link set can0 txqueuelen 100
	errors_begin can0
	bus_slow
	cansend can0 126#44
	wait_for 30 can_state_is can0 ERROR-PASSIVE || fail "$1: a lone can0 never went error-passive"
	# an error-passive sender's ACK errors do not count: it stays there
	nap 0.5
	snapshot can0
	step ack-again
	bus_fast
	tx0=$(if_stat can0 tx_packets)
	can_up can1 $rate
	wait_for 10 sent_beyond can0 "$tx0" || fail "$1: the pending 126#44 never went"
	# 128 - 1 - 40 is below the warning limit (96): error-active again.
	# 50 ms apart: the receiver keeps up however busy the host.
	cangen -g 50 -n 40 -I 127 -L 1 can0
	wait_for 30 can_state_is can0 ERROR-ACTIVE || fail "$1: can0 not error-active again"
	errors_end
	snapshot can0
	# can1 came up while can0 was sending: whether it took the frame
	# whose end it saw is the simulated bus's business, not the drivers'.
	snapshot -q can1

	step bus-errors
	ip link set can0 down
	ip link set can1 down
	can_up can0 $rate
	can_up can1 $rate
	errors_begin can0 can1
	bus_slow
	# 13 destroyed attempts: TEC 104 after them, 103 once the frame is
	# through (error-warning); 10 more good frames bring it below 96.
	echo 13 >"$SIM/bus_errors"
	tx0=$(if_stat can0 tx_packets)
	cansend can0 128#55
	wait_for 30 sent_beyond can0 "$tx0" || fail "$1: 128#55 never went through"
	snapshot can0 can1
	step bus-errors-after
	cangen -g 50 -n 10 -I 129 -L 1 can0
	wait_for 30 can_state_is can0 ERROR-ACTIVE || fail "$1: can0 not error-active after the bus errors"
	bus_fast
	errors_end
	snapshot can0 can1

	step bus-off
	ip link set can0 down
	can_up can0 $rate
	errors_begin can0 can1
	bus_slow
	# 32 destroyed attempts take TEC from 0 to 256: bus-off.
	echo 32 >"$SIM/bus_errors"
	cansend can0 12A#66
	wait_for 30 can_state_is can0 BUS-OFF || fail "$1: can0 never went bus-off"
	# restart-ms 0: it stays there
	nap 0.5
	snapshot -s can0
	step restart
	bus_fast
	ip link set can0 type can restart || fail "$1: restart refused"
	wait_for 10 can_state_is can0 ERROR-ACTIVE || fail "$1: can0 not error-active after restart"
	rx1=$(if_stat can1 rx_packets)
	cansend can0 12B#77
	wait_for 10 received_beyond can1 "$rx1" || fail "$1: no frame crossed after the restart"
	errors_end
	snapshot can0 can1

	step bus-off-restart-ms
	ip link set can0 down
	can_up can0 $rate restart-ms 100
	errors_begin can0
	echo 0 >"$SIM/chip0/counters"
	bus_slow
	echo 32 >"$SIM/bus_errors"
	cansend can0 12C#88
	# With restart-ms mcp251x leaves recovery to the chip, 128 x 11 bits:
	# its bus-off may pass too fast to be seen in ip.
	wait_for 30 chip0_bus_off || fail "$1: chip0 never went bus-off"
	bus_fast
	wait_for 30 can_state_is can0 ERROR-ACTIVE || fail "$1: can0 not error-active after restart-ms"
	rx1=$(if_stat can1 rx_packets)
	cansend can0 12D#99
	wait_for 10 received_beyond can1 "$rx1" || fail "$1: no frame crossed after restart-ms"
	errors_end
	snapshot can0 can1

	ip link set can0 down
	ip link set can1 down
	step end
}

# chip0_bus_off: chip0 went bus-off since its counters were cleared.
chip0_bus_off() { [ "$(sim_counter 0 bus_off)" -gt 0 ]; }

first=$VM_DRIVER
case $first in mcp2510) second=mcp251x ;; *) second=mcp2510 ;; esac
behaviours "$first"
chips_load "$second"
behaviours "$second"

# The comparison, without the keys that differ on purpose.
for d in mcp2510 mcp251x; do
	echo "differential: $d"
	sed 's/^/    /' "/tmp/differential-$d.txt"
	while read -r key value; do
		excluded "$key" || echo "$key $value"
	done <"/tmp/differential-$d.txt" >"/tmp/compared-$d.txt"
done
if ! diff -u /tmp/compared-mcp251x.txt /tmp/compared-mcp2510.txt >/tmp/diff.txt; then
	echo "differential: mcp251x (-) and mcp2510 (+) differ:"
	cat /tmp/diff.txt
	keys=$(sed -n 's/^+\([^+][^ ]*\) .*/\1/p' /tmp/diff.txt | tr '\n' ' ')
	fail "the drivers differ where they should not: $keys"
fi
echo "differential: ok"
