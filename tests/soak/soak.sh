#!/bin/sh
# The soak (docs/soak.md), run in the guest by "make soak": two simulated
# chips on one bus, bound to mcp2510.ko as can0 and can1, for the minutes
# named in /extra/minutes.  It works in rounds.  In each, can0 and can1
# send each other a numbered stream with cangen while the simulator's
# phantom node floods both, and one fault of the schedule strikes in the
# middle of it; then every frame is accounted for and the driver's
# statistics are held against the simulator's counters.  Between rounds,
# in turn, a chip is driven bus-off (no ACK, then bus errors) or loses its
# power and is taken down and up again.  At the end memory must be where
# it was after the first round, and a report of the figures is printed.
set -eu
. /lib/rig.sh

[ -d "$SIM" ] || fail "no $SIM"
minutes=$(cat /extra/minutes 2>/dev/null || echo 10)
BITRATE=500000
STREAM_FRAMES=1500	# per interface and round, 1 ms apart
FLOOD_FRAMES=400	# from the phantom, back to back, per round
ID0=100 ID1=200 IDP=300	# stream ids of can0, can1 and the phantom

# ---- counters ---------------------------------------------------------

# snap NAME: record every counter this soak compares as variables
# NAME_<counter>.
snap() {
	for i in 0 1; do
		for c in frames_tx frames_rx overflows spi_failed; do
			eval "${1}_c${i}_$c=\$(sim_counter $i $c)"
		done
		for s in tx_packets tx_dropped tx_errors rx_packets rx_dropped \
			rx_over_errors; do
			eval "${1}_n${i}_$s=\$(if_stat can$i $s)"
		done
	done
}

# delta NAME: the change of counter NAME between snapshots "a" and "b".
delta() {
	eval "echo \$((b_$1 - a_$1))"
}

# Totals over the whole soak, for the report.
total_sent=0 total_received=0 total_lost_rx=0 total_lost_tx=0
total_garbled=0 total_swaps=0 total_misjudged=0 total_overrun_events=0 rounds=0
faults_bus=0 faults_spi_err=0 faults_spi_corrupt=0 busoffs=0 powercuts=0

add() { eval "$1=\$(($1 + $2))"; }

# ---- receiving --------------------------------------------------------

# Sockets receiving on IF, over all of /proc/net/can's lists.
receivers() {
	cat /proc/net/can/rcvlist_* | grep -c "^ *$1 " || true
}

# tally_start IF FILE: count IF's frames per stream in FILE, ending after
# 4 s without a frame: frames per stream id, frames with any other id
# ("garbled"), frames whose stream counter came before ("dups") and frames
# older than the one before them ("swaps").
tally_start() {
	_before=$(receivers "$1")
	candump -T 4000 "$1" | awk -v a="$ID0" -v b="$ID1" -v p="$IDP" '
		BEGIN { for (i = 0; i < 256; i++) hex[sprintf("%02X", i)] = i }
		{
			id = $2; n = hex[$4] + 256 * hex[$5] + 65536 * hex[$6]
			if (id != a && id != b && id != p) { garbled++; next }
			count[id]++
			if ((id, n) in seen) dups++
			else if (id in last && n < last[id]) swaps++
			seen[id, n] = 1
			last[id] = n
		}
		END {
			printf "from_%s=%d from_%s=%d from_%s=%d ", a, count[a],
				b, count[b], p, count[p]
			printf "garbled=%d dups=%d swaps=%d\n", garbled, dups, swaps
		}' >"$2" &
	_tries=0
	while [ "$(receivers "$1")" -le "$_before" ]; do
		_tries=$((_tries + 1))
		[ $_tries -le 100 ] || fail "candump on $1 never registered"
		sleep 0.05
	done
}

# tally FILE KEY: one figure of a tally.
tally() {
	tr ' ' '\n' <"$1" | sed -n "s/^$2=//p"
}

# ---- one round of floods with a fault ----------------------------------

flood_done() { [ "$(cat "$SIM/flood")" -eq 0 ]; }

# inject_fault ROUND: the schedule, one fault per round in turn.
inject_fault() {
	chip=$(($1 / 5 % 2))
	case $(($1 % 5)) in
	0) echo "round $1: no fault" ;;
	1) echo 20 >"$SIM/bus_errors"; add faults_bus 20
	   echo "round $1: 20 bus errors" ;;
	2) echo 3 >"$SIM/chip$chip/spi_errors"; add faults_spi_err 3
	   echo "round $1: 3 SPI errors on chip $chip" ;;
	3) echo 2 >"$SIM/chip$chip/spi_corrupt"; add faults_spi_corrupt 2
	   eval "corrupt$chip=2"
	   echo "round $1: 2 corrupted SPI periods on chip $chip" ;;
	4) echo 10 >"$SIM/bus_errors"; echo 2 >"$SIM/chip$chip/spi_errors"
	   add faults_bus 10; add faults_spi_err 2
	   echo "round $1: 10 bus errors and 2 SPI errors on chip $chip" ;;
	esac
}

# A read the SPI corrupted can make the driver misjudge what the chip did
# with its three transmit and two receive buffers, and no driver can tell
# (the bus has no checksum): per corrupted period, the figures of the
# chip's interface may be off by up to three frames.  Exact otherwise.
slack() {
	eval "echo \$((3 * corrupt$1))"
}

# within A B SLACK: A and B differ by at most SLACK.
within() {
	[ "$1" -le $(($2 + $3)) ] && [ "$2" -le $(($1 + $3)) ]
}

# check_receiver Y X: every frame sent towards canY in this round (by canX
# and by the phantom) was received or reported lost.
check_receiver() {
	y=$1 x=$2 idx=$(eval echo "\$ID$2")
	t=/tmp/tally$y
	sent=$((STREAM_FRAMES + FLOOD_FRAMES))
	got=$(($(tally $t "from_$idx") + $(tally $t "from_$IDP") + $(tally $t garbled)))
	lost_tx=$(delta "n${x}_tx_dropped")
	overflows=$(delta "c${y}_overflows")
	dropped=$(delta "n${y}_rx_dropped")
	lost=$((lost_tx + overflows + dropped))
	echo "  can$y: sent $sent = received $got + lost $lost" \
		"(can$x tx_dropped $lost_tx, overflows $overflows" \
		"in $(delta "n${y}_rx_over_errors") rx_over_errors, rx_dropped $dropped)," \
		"garbled $(tally $t garbled), out of order $(tally $t swaps)"
	slack=$(($(slack "$x") + $(slack "$y")))
	within "$sent" $((got + lost)) "$slack" || { cat $t; fail "round $round: can$y does not add up"; }
	add total_misjudged $((sent - got - lost))

	# The driver against the simulator.
	[ "$(delta "n${y}_rx_packets")" -eq "$got" ] ||
		fail "round $round: can$y rx_packets $(delta "n${y}_rx_packets"), candump $got"
	within "$(delta "n${y}_rx_packets")" $(($(delta "c${y}_frames_rx") - dropped)) "$(slack "$y")" ||
		fail "round $round: can$y rx_packets $(delta "n${y}_rx_packets"), chip stored $(delta "c${y}_frames_rx"), dropped $dropped"
	[ "$(delta "c${y}_frames_rx")" -eq $(($(delta "c${x}_frames_tx") + FLOOD_FRAMES - overflows)) ] ||
		fail "round $round: chip $y stored $(delta "c${y}_frames_rx") of $(($(delta "c${x}_frames_tx") + FLOOD_FRAMES)) frames on the bus, $overflows overflows"
	if [ "$overflows" -gt 0 ]; then
		[ "$(delta "n${y}_rx_over_errors")" -ge 1 ] ||
			fail "round $round: chip $y overflowed $overflows times, can$y reported none"
	fi
	[ "$(delta "n${y}_rx_over_errors")" -le "$overflows" ] ||
		fail "round $round: can$y reports more overruns than the chip had"
	[ "$(tally $t dups)" -eq 0 ] || { cat $t; fail "round $round: can$y received duplicates"; }
	# The driver knows which RX buffer holds the older frame; only a
	# corrupted read of the receiving chip can mislead it.
	[ "$(tally $t swaps)" -le "$(slack "$y")" ] ||
		{ cat $t; fail "round $round: can$y received $(tally $t swaps) frame(s) out of order"; }
	add total_sent "$sent"
	add total_received "$got"
	add total_lost_rx $((overflows + dropped))
	add total_lost_tx "$lost_tx"
	add total_garbled "$(tally $t garbled)"
	add total_swaps "$(tally $t swaps)"
	add total_overrun_events "$(delta "n${y}_rx_over_errors")"
}

# check_sender X: cangen's frames all ended as transmitted or dropped, and
# the driver's count of transmitted frames is the chip's.
check_sender() {
	x=$1
	[ $(($(delta "n${x}_tx_packets") + $(delta "n${x}_tx_dropped"))) -eq "$STREAM_FRAMES" ] ||
		fail "round $round: can$x tx_packets $(delta "n${x}_tx_packets") + tx_dropped $(delta "n${x}_tx_dropped") != $STREAM_FRAMES"
	within "$(delta "n${x}_tx_packets")" "$(delta "c${x}_frames_tx")" "$(slack "$x")" ||
		fail "round $round: can$x tx_packets $(delta "n${x}_tx_packets"), chip sent $(delta "c${x}_frames_tx")"
}

flood_round() {
	corrupt0=0 corrupt1=0
	restarts0=$(restarts can0) restarts1=$(restarts can1)
	snap a
	tally_start can0 /tmp/tally0
	tally_start can1 /tmp/tally1
	cangen can0 -x -g 1 -p 200 -n $STREAM_FRAMES -I $ID0 -L 8 -D i &
	gen0=$!
	cangen can1 -x -g 1 -p 200 -n $STREAM_FRAMES -I $ID1 -L 8 -D i &
	gen1=$!
	echo "$FLOOD_FRAMES $IDP#00000000" >"$SIM/flood"
	sleep 1
	[ "$round" -gt "$rounds" ] || inject_fault "$round"
	wait "$gen0" || fail "round $round: cangen on can0 failed"
	wait "$gen1" || fail "round $round: cangen on can1 failed"
	wait_for 60 flood_done || fail "round $round: the phantom's flood never ended"
	wait # the tallies, 4 s after the last frame
	snap b
	echo 0 >"$SIM/bus_errors"
	# No fault of a round takes TEC to 256: a restart means the driver
	# reported a bus-off the chip never had (a corrupted EFLG believed).
	for i in 0 1; do
		[ "$(restarts can$i)" -eq "$(eval echo "\$restarts$i")" ] ||
			fail "round $round: can$i went bus-off and restarted"
	done
	check_sender 0
	check_sender 1
	check_receiver 1 0
	check_receiver 0 1
}

# ---- faults between rounds ---------------------------------------------

restarts() {
	ip -details -statistics link show "$1" |
		awk '/re-started bus-errors/ { getline; print $1 }'
}
restarted_since() { [ "$(restarts "$1")" -gt "$2" ]; }

# bus_off X: canX sends a frame nobody acknowledges until it is
# error-passive, then bus errors drive it bus-off; restart-ms brings it
# back.  The frame ends transmitted or dropped, nothing else.
bus_off() {
	x=$1
	snap a
	before=$(restarts "can$x")
	echo 1 >"$SIM/no_ack"
	cansend "can$x" 7FF#B0
	wait_for 30 can_state_is "can$x" ERROR-PASSIVE || fail "can$x never went error-passive"
	echo 1000 >"$SIM/bus_errors"
	wait_for 30 restarted_since "can$x" "$before" || fail "can$x never restarted after bus-off"
	echo 0 >"$SIM/bus_errors"
	echo 0 >"$SIM/no_ack"
	wait_for 30 can_state_is "can$x" ERROR-ACTIVE || true
	snap b
	[ $(($(delta "n${x}_tx_packets") + $(delta "n${x}_tx_dropped"))) -eq 1 ] ||
		fail "bus-off of can$x: the frame neither sent nor dropped"
	echo "bus-off of can$x: restarted, its frame $( [ "$(delta "n${x}_tx_dropped")" -eq 1 ] && echo dropped || echo sent)"
	add busoffs 1
}

# power_cut X: chip X loses power with frames waiting to go out, comes
# back, and canX is taken down and up: the waiting frames are reported
# dropped and the next round finds the chip working.
power_cut() {
	x=$1
	snap a
	echo 0 >"$SIM/chip$x/power"
	queued=0
	for n in 1 2 3; do
		! cansend "can$x" "7F$n#0$n" || queued=$((queued + 1))
	done
	sleep 1
	echo 1 >"$SIM/chip$x/power"
	ip link set "can$x" down
	can_up "can$x" $BITRATE restart-ms 100
	snap b
	echo "power cut on chip $x: $queued frames queued, tx_packets $(delta "n${x}_tx_packets"), tx_dropped $(delta "n${x}_tx_dropped")"
	[ "$(delta "n${x}_tx_packets")" -eq 0 ] || fail "power cut: can$x claims frames sent by a chip without power"
	[ "$(delta "n${x}_tx_dropped")" -eq "$queued" ] ||
		fail "power cut: can$x dropped $(delta "n${x}_tx_dropped") of the $queued frames it took"
	add powercuts 1
}

# ---- memory --------------------------------------------------------------

meminfo() {
	sync
	echo 3 >/proc/sys/vm/drop_caches
	awk -v k="$1:" '$1 == k { print $2 }' /proc/meminfo
}

# ---- the soak ------------------------------------------------------------

can_up can0 $BITRATE restart-ms 100
can_up can1 $BITRATE restart-ms 100
echo "soak: $minutes minutes, $STREAM_FRAMES frames each way and $FLOOD_FRAMES phantom frames per round at $BITRATE bit/s"

round=0 rounds=1000000
flood_round # warm-up: caches and slabs settle before the baseline
avail_before=$(meminfo MemAvailable)
slab_before=$(meminfo Slab)
end=$(($(uptime_s) + minutes * 60))
while [ "$(uptime_s)" -lt "$end" ]; do
	round=$((round + 1))
	flood_round
	case $((round % 4)) in
	1) bus_off 0 ;;
	2) power_cut 1 ;;
	3) bus_off 1 ;;
	0) power_cut 0 ;;
	esac
done
rounds=$round

# Once more without faults: whatever the faults did, traffic is whole.
round=$((round + 1))
echo "round $round: no fault (the last)"
flood_round

avail_after=$(meminfo MemAvailable)
slab_after=$(meminfo Slab)
ip -details -statistics link show can0
ip -details -statistics link show can1

echo "== soak report"
echo "rounds:          $rounds with faults, 2 without"
echo "frames sent:     $total_sent (both directions, streams and phantom)"
echo "received:        $total_received (garbled by SPI corruption: $total_garbled; out of order: $total_swaps)"
echo "lost on receive: $total_lost_rx (chip overflows, reported in $total_overrun_events rx_over_errors; rx_dropped)"
echo "lost on send:    $total_lost_tx (tx_dropped)"
echo "misjudged:       $total_misjudged (sent - received - lost, in rounds with SPI corruption)"
echo "faults:          $faults_bus bus errors, $faults_spi_err SPI errors, $faults_spi_corrupt corrupted SPI periods, $busoffs bus-offs, $powercuts power cuts"
echo "MemAvailable:    $avail_before kB -> $avail_after kB"
echo "Slab:            $slab_before kB -> $slab_after kB"
[ $((total_received + total_lost_rx + total_lost_tx + total_misjudged)) -eq "$total_sent" ] ||
	fail "the totals do not add up"
# A leak of one skb per frame would be tens of MiB; noise is well under 4.
[ $((avail_before - avail_after)) -lt 4096 ] || fail "MemAvailable fell by $((avail_before - avail_after)) kB"
[ $((slab_after - slab_before)) -lt 2048 ] || fail "Slab grew by $((slab_after - slab_before)) kB"
echo "soak: ok"
