#!/bin/sh
# The guest half of "make bench" (tests/bench/run boots it): one simulated
# chip on the bus with the phantom node, bound to whichever driver vm-run
# loaded.  Prints one "bench: WHAT key=value..." line per measurement on the
# console for tests/bench/report.py; it asserts nothing about speed.
#
# /extra/bench.conf sets FLOOD_FRAMES (frames of an RX flood that makes a
# lossless claim), PROBE_FRAMES (frames of the probe before it),
# TX_FRAMES (frames of a TX burst), FRAMES (per latency and timestamp
# measurement, at most 256: the bus monitor), RX_BITRATES, TX_BITRATES,
# CPU_FRAMES, CPU_BITRATE, COMPARE_BITRATES and SATURATION_BITRATE
# (latency and timestamps: where every driver keeps up, and at
# saturation), TIME_SCALE (the value given to mcp2510-sim.ko),
# STALL_TRIES (see again() below) and LATENCY_ONLY (1: the latency
# measurements alone, for the PREEMPT_RT kernel).  For a board profile it
# also sets PROFILE, COST_SCALE_PCT (the profile's costs scaled, in
# percent), SPI_TIME=1 and SPI_SEED (the seed of the model's latency
# draws).
#
# Floods and bursts are counted end to end by can-flood (tests/vm/guest):
# RX at can0's socket, TX in the bus monitor, where the phantom sees them.
#
# The script stays quiet while a burst runs (one wait, no polling): under
# TCG every fork of busybox costs the guest tens of milliseconds, which
# would swamp the CPU figures of the driver.
set -eu
. /lib/rig.sh
. /extra/bench.conf

# bits of the longest 8-byte standard frame, stuffing and intermission
# included: an upper bound for how long a burst takes on the bus
FRAME_BITS_MAX=135
# the phantom's floods: frame k carries k in bytes 0-3 and, "checked",
# the CRC-32 can-flood checks in bytes 4-7
FLOOD_TEMPLATE=123#0000000000000000

# report WHAT FIELDS...: one measurement's line.  After a cpu_mark it also
# gives the bus clock's stalls since then and sets VOID to 1 if there
# were any (docs/simulator.md, "Time": the measurement is void).
# Every line ends with up=, the guest's uptime in seconds: what each
# measurement costs in real time (how long a full run takes).
report() {
	VOID=0
	read -r _up _ </proc/uptime
	if [ -n "${MARK_STALLS:-}" ]; then
		read -r _stalls <"$SIM/clock_stalls"
		_stalls=$((_stalls - MARK_STALLS))
		[ "$_stalls" -eq 0 ] || VOID=1
		echo "bench: $* stalls=$_stalls up=$_up"
		MARK_STALLS=
	else
		echo "bench: $* up=$_up"
	fi
}

# again COMMAND...: COMMAND (one measurement), tried up to STALL_TRIES
# times in all until it is not void.  report.py takes the last try of
# each; a void one is a missing figure, and make bench fails.
again() {
	_left=$((${STALL_TRIES:?} - 1))
	"$@"
	while [ "$VOID" = 1 ] && [ "$_left" -gt 0 ]; do
		_left=$((_left - 1))
		"$@"
	done
}

# cpu_mark: remember the time since boot and the CPUs' summed idle time
# (/proc/uptime: nohz idle accounting, exact rather than sampled by the
# tick).  cpu_busy sets BUSY to the busy CPU time and the elapsed time
# since cpu_mark, in hundredths of a second.  Shell builtins only.
cpu_mark() {
	read -r MARK_STALLS <"$SIM/clock_stalls"
	read -r MARK_UP MARK_IDLE </proc/uptime
}
cpu_busy() {
	read -r _up _idle </proc/uptime
	# "s.hh" - "s.hh" in hundredths; the 1 keeps "08" from reading as octal
	_win=$(((${_up%.*} - ${MARK_UP%.*}) * 100 + 1${_up#*.} - 1${MARK_UP#*.}))
	_idl=$(((${_idle%.*} - ${MARK_IDLE%.*}) * 100 + 1${_idle#*.} - 1${MARK_IDLE#*.}))
	BUSY="busy_cs=$((NCPUS * _win - _idl)) window_cs=$_win"
}

# burst_seconds COUNT BITRATE: how long COUNT frames take on the bus, in
# real seconds at TIME_SCALE, plus a little.
burst_seconds() {
	awk -v n="$1" -v br="$2" -v s="$TIME_SCALE" -v b="$FRAME_BITS_MAX" \
		'BEGIN { printf "%.2f\n", n * b * s / br + 0.3 }'
}

counters() {
	tr '\n' ' ' <"$SIM/chip0/counters" | sed 's/\([a-z_]*\) \([0-9]*\) /\1=\2 /g'
}

flood_done() { [ "$(cat "$SIM/flood")" -eq 0 ]; }

# quiet_wait SECONDS COMMAND...: sleep through the expected time, then poll
# COMMAND (a slow guest) for up to a minute.
quiet_wait() {
	_s=$1
	shift
	sleep "$_s"
	wait_for 60 "$@"
}

start_at() {
	ip link set can0 down
	can_up can0 "$1"
	echo off >"$SIM/phantom"
	echo on >"$SIM/phantom"
	echo 0 >"$SIM/chip0/counters"
	echo 0 >"$SIM/monitor"
}

# idle SECONDS: the same steps as a burst of that length, without one:
# the guest's background load and the script's own forks.
idle() {
	cpu_mark
	quiet_wait "$1" flood_done
	sleep 0.5
	cpu_busy
	report idle "seconds=$1 $BUSY"
}

# counting FILE COMMAND...: COMMAND (can-flood recv or check) in the
# background, its output in FILE, once it listens; COUNTING is its pid.
counting() {
	_file=$1
	shift
	: >"$_file"
	"$@" >"$_file" &
	COUNTING=$!
	wait_for 20 first_line_is ready "$_file" || fail "$1 never listened"
}
first_line_is() { read -r _l <"$2" && [ "$_l" = "$1" ]; }

# counted FILE: once the can-flood that writes FILE ended (it exits 1
# when the flood was not lossless), sets COUNT to its count as key=value
# words without its mode and frames, and LOSSLESS to 1 or 0.
counted() {
	wait "$COUNTING" || [ $? -eq 1 ] || fail "can-flood failed: $(cat "$1")"
	COUNT=$(sed -n 's/^flood: mode=[a-z]* frames=[0-9]* //p' "$1")
	[ -n "$COUNT" ] || fail "can-flood counted nothing: $(cat "$1")"
	LOSSLESS=${COUNT#*lossless=}
	LOSSLESS=${LOSSLESS%% *}
}

# idle_ms BITRATE: can-flood's -t, no frame for this long ends a count:
# twenty frames' bus time, at least 3 s.
idle_ms() {
	awk -v br="$1" -v s="$TIME_SCALE" -v b="$FRAME_BITS_MAX" \
		'BEGIN { t = 20 * b * s * 1000 / br; printf "%d\n", t < 3000 ? 3000 : t }'
}

# rx WHAT BITRATE COUNT: the phantom floods COUNT frames back to back to
# can0 while can-flood counts them at the socket; WHAT names the
# measurement.  Sets LOSSLESS.
rx() {
	start_at "$2"
	_secs=$(burst_seconds "$3" "$2")
	counting /tmp/flood.txt can-flood recv can0 "$3" -t "$(idle_ms "$2")"
	cpu_mark
	echo "$3 $FLOOD_TEMPLATE $2 checked" >"$SIM/flood"
	# the count ends a second after the last frame (or once none came for
	# a while): what the chip holds still reaches the socket, and waiting
	# for it is one wait, not a poll
	counted /tmp/flood.txt
	cpu_busy
	wait_for 60 flood_done || fail "the flood at $2 bit/s never ended"
	report "$1" "bitrate=$2 frames=$3 seconds=$_secs $BUSY" \
		"$COUNT $(counters)"
}

# rx_search: the RX bit rates from the highest down until a flood of
# FLOOD_FRAMES is lossless: the highest bit rate without loss, assuming
# loss only grows with the bit rate (the rates below it are not flooded:
# the search has decided them).  Each rate is first probed with
# PROBE_FRAMES frames; damage there decides the rate at once, so only a
# lossless probe is followed by the full flood, and every lossless claim
# rests on FLOOD_FRAMES frames.  A flood still void after its tries ends
# the search without a result.
rx_search() {
	# shellcheck disable=SC2086
	for br in $(printf '%s\n' $RX_BITRATES | sort -rn); do
		again rx rx-probe "$br" "$PROBE_FRAMES"
		[ "$VOID" = 0 ] || break
		[ "$LOSSLESS" = 1 ] || continue
		again rx rx "$br" "$FLOOD_FRAMES"
		[ "$VOID" = 0 ] || break
		[ "$LOSSLESS" = 0 ] || return 0
	done
	[ "$VOID" = 0 ] || report rx-search-incomplete
}

# spi_time_on: the board profile's SPI and interrupt costs at its cost
# scale (docs/simulator.md, "SPI time"); they apply to messages that
# start afterwards, so before the interface comes up.
spi_time_on() {
	echo "$PROFILE" >"$SIM/spi_profile"
	echo "$COST_SCALE_PCT" >"$SIM/spi_cost_scale_pct"
	echo "$SPI_SEED" >"$SIM/spi_seed"
}

# tx WHAT BITRATE COUNT: can-flood sends COUNT unique frames as fast as
# can0 takes them; the phantom acknowledges, and a second can-flood
# counts them as the bus monitor records them.  The queue holds the
# whole burst, so the sender never waits on ENOBUFS.  The monitor keeps
# 256 records: a counter that fell behind misses some, which frames_tx
# shows (monitor_missed), and the measurement is void.
tx() {
	ip link set can0 txqueuelen $(($3 + 16))
	start_at "$2"
	_secs=$(burst_seconds "$3" "$2")
	counting /tmp/flood.txt can-flood check "$3" -f "$SIM/monitor" \
		-t "$(idle_ms "$2")"
	cpu_mark
	can-flood send can0 "$3" >/tmp/flood-send.txt ||
		fail "can-flood send at $2 bit/s: $(cat /tmp/flood-send.txt)"
	counted /tmp/flood.txt
	cpu_busy
	_sent=$(sim_counter 0 frames_tx)
	_seen=${COUNT#received=}
	_seen=${_seen%% *}
	report "$1" "bitrate=$2 frames=$3 seconds=$_secs $BUSY" \
		"$COUNT monitor_missed=$((_sent - _seen)) $(counters) $(monitor_timing)"
	[ "$_sent" -le "$_seen" ] || VOID=1
}

# percentiles FILE FIELD NAME: of column FIELD of FILE's lines (ns), the
# count, nearest-rank median and 99th percentile and the maximum, as
# NAME_n=... NAME_p50_ns=... NAME_p99_ns=... NAME_max_ns=..., and how many
# lines say "missing" (NAME_missing=...).
percentiles() {
	awk -v f="$2" -v name="$3" '$2 == "missing" { m++; next } { print $f }
		END { print m + 0 > "/tmp/percentiles.missing" }' "$1" |
		sort -n | awk -v name="$3" '{ e[NR] = $1 } END {
			n = NR
			i = int(n * 0.99); if (i < n * 0.99) i++
			printf "%s_n=%d %s_p50_ns=%d %s_p99_ns=%d %s_max_ns=%d", name, n,
				name, n ? e[int((n + 1) / 2)] : 0, name, n ? e[i] : 0,
				name, n ? e[n] : 0 }'
	echo " $3_missing=$(cat /tmp/percentiles.missing)"
}

# tx_latency BITRATE COUNT: COUNT lone frames from can0, each written once
# the previous one came back (can-latency, tests/vm/guest): from write() to
# the frame's end on the bus, ns of real time.
tx_latency() {
	start_at "$1"
	cpu_mark
	can-latency tx can0 "$2" "$SIM/monitor_times" >/tmp/latency.txt ||
		fail "can-latency tx at $1 bit/s: $(tail -n 1 /tmp/latency.txt)"
	report tx-latency "bitrate=$1 $(percentiles /tmp/latency.txt 2 lat)"
}

# rx_latency BITRATE COUNT: COUNT lone frames from the phantom, each sent
# once the previous one was received: from the frame's end on the bus to
# recvmsg() returning it (lat) and to its receive timestamp (stamp).
rx_latency() {
	start_at "$1"
	cpu_mark
	can-latency rx can0 "$2" "$SIM/inject" "$SIM/monitor_times" >/tmp/latency.txt ||
		fail "can-latency rx at $1 bit/s: $(tail -n 1 /tmp/latency.txt)"
	report rx-latency "bitrate=$1 $(percentiles /tmp/latency.txt 2 lat)" \
		"$(percentiles /tmp/latency.txt 3 stamp)"
}

# rxts BITRATE COUNT: the phantom floods COUNT frames (at most 256: the
# monitor) to can0 while can-tstamp (tests/vm/guest) takes them with their
# receive timestamps; reports how far after each frame's end on the bus
# its stamp lies (ns of real time: nearest-rank median, 99th percentile,
# maximum), and how many frames were stamped or not found on the bus.
rxts() {
	start_at "$1"
	: >/tmp/rxts.txt
	can-tstamp can0 "$2" "$SIM/monitor_times" >>/tmp/rxts.txt &
	_pid=$!
	wait_for 20 rxts_ready || fail "can-tstamp never listened"
	cpu_mark
	echo "$2 $FLOOD_TEMPLATE $1" >"$SIM/flood"
	wait "$_pid" || fail "can-tstamp failed"
	sed 1d /tmp/rxts.txt >/tmp/rxts.data
	report rxts "bitrate=$1 frames=$2 $(percentiles /tmp/rxts.data 2 err)"
}
rxts_ready() { read -r _l </tmp/rxts.txt && [ "$_l" = ready ]; }

# From chip 0's frames in the monitor (the last 256): how many, their mean
# length in bits, the span from the first start to the last start, the
# idle time between them, all in bus nanoseconds.
monitor_timing() {
	awk '$3 == "chip0" && $7 == "ok" {
		if (n == 0) first = $1
		else idle += $1 - end
		n++; bits += $6; last = $1; end = $2
	}
	END {
		printf "mon_frames=%d mon_bits=%.2f mon_span_ns=%.0f mon_idle_ns=%.0f\n",
			n, n ? bits / n : 0, last - first, idle
	}' "$SIM/monitor"
}

NCPUS=$(grep -c '^cpu[0-9]' /proc/stat)
timing=
if [ "${SPI_TIME:-0}" = 1 ]; then
	spi_time_on
	timing="profile=$PROFILE spi_profile=$PROFILE"
	timing="$timing cost_scale_pct=$COST_SCALE_PCT spi_seed=$SPI_SEED"
	for f in spi_msg_ns spi_cs_setup_ns spi_cs_hold_ns spi_ctlr_max_hz \
		irq_latency_ns irq_latency_p99_ns spi_wake_ns spi_wake_p99_ns spi_xfer_ns; do
		timing="$timing $f=$(cat "$SIM/$f")"
	done
fi
report setup "driver=$VM_DRIVER variant=$VM_VARIANT time_scale=$TIME_SCALE" \
	"frames=$FRAMES flood_frames=$FLOOD_FRAMES probe_frames=$PROBE_FRAMES" \
	"tx_frames=$TX_FRAMES cpu_frames=$CPU_FRAMES" \
	"cpu_bitrate=$CPU_BITRATE cpus=$NCPUS stall_tries=$STALL_TRIES" \
	"saturation_bitrate=$SATURATION_BITRATE" \
	"clocksource=$(cat /sys/devices/system/clocksource/clocksource0/current_clocksource)" \
	"spi_time=$(cat "$SIM/spi_time") clock_stalls=$(cat "$SIM/clock_stalls") $timing"
can_up can0 "$CPU_BITRATE"
# one frame at a time, end to end (FRAMES of each, at most 256: the
# monitor), where every driver keeps up and at saturation
for br in $COMPARE_BITRATES $SATURATION_BITRATE; do
	again tx_latency "$br" "$FRAMES"
	again rx_latency "$br" "$FRAMES"
done
if [ "${LATENCY_ONLY:-0}" = 1 ]; then
	ip link set can0 down
	report "done" "clock_stalls=$(cat "$SIM/clock_stalls")"
	exit 0
fi
# CPU and SPI cost at steady state: long bursts at a bit rate every driver
# keeps up with, and the same time without traffic to subtract.
again idle "$(burst_seconds "$CPU_FRAMES" "$CPU_BITRATE")"
again rx cpu-rx "$CPU_BITRATE" "$CPU_FRAMES"
again tx cpu-tx "$CPU_BITRATE" "$CPU_FRAMES"
# receive timestamps against the bus's end of frame in a flood, where
# every driver keeps up and at saturation
for br in $COMPARE_BITRATES $SATURATION_BITRATE; do
	again rxts "$br" "$FRAMES"
done
rx_search
for br in $TX_BITRATES; do
	again tx tx "$br" "$TX_FRAMES"
done
ip link set can0 down
# the bus clock's stalls since the module was loaded: the run is void if
# one fired (docs/simulator.md, "Time")
report "done" "clock_stalls=$(cat "$SIM/clock_stalls")"
