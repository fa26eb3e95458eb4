# The kit's floods (sourced by mcp2510-hwtest): can-flood's unique
# frames from one interface to the other at each bit rate, counted at the
# far side (lost, duplicated, reordered, corrupted), with what the system
# spent on them: CPU from /proc/stat, the two chips' interrupts from
# /proc/interrupts and the SPI devices' statistics from sysfs where the
# kernel keeps them.  Before them, at each bit rate, can-transit's lone
# frames give the latency from write() on one interface to recvmsg() on
# the other.

# Bits of an 8-byte standard data frame with its interframe space,
# without stuff bits: the utilisation is a lower bound.
FRAME_BITS=111

cpu_busy_total() {
	awk '$1 == "cpu" { t = 0; for (i = 2; i <= NF; i++) t += $i
		print t - $5 - $6, t; exit }' /proc/stat
}

# irqs: interrupts so far of the lines named after either chip's SPI
# device (this driver) or "mcp251x" (mainline).
irqs() {
	awk -v a="$SPI_A" -v b="$SPI_B" '$NF == a || $NF == b || $NF == "mcp251x" {
		for (i = 2; i <= NF && $i ~ /^[0-9]+$/; i++) s += $i } END { print s + 0 }' /proc/interrupts
}

# spi_stat IF NAME: a statistic of IF's SPI device, empty without one.
spi_stat() {
	f=/sys/class/net/$1/device/statistics/$2
	[ -r "$f" ] && cat "$f" || echo
}

# per_frame NOW BEFORE FRAMES: the growth per frame, two decimals; "-"
# without figures, or when they did not move (a controller that keeps
# no statistics still shows the files).
per_frame() {
	if [ -z "$1" ] || [ -z "$2" ] || [ "$1" = "$2" ] || [ "$3" -eq 0 ]; then
		echo -
		return
	fi
	awk -v a="$1" -v b="$2" -v n="$3" 'BEGIN { printf "%.2f\n", (a - b) / n }'
}

# field LINE KEY: KEY's value in a "flood: k=v ..." line.
field() { echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }

# flood FROM TO BITRATE ID: one flood, one "flood" result line.
flood() {
	FROM=$1 TO=$2 rate=$3 id=$4
	if ! pair_up "$rate"; then
		record "flood-$FROM-$rate" fail "cannot bring the pair up at $rate"
		return
	fi
	can-flood recv "$TO" "$FRAMES" -i "$id" >"$OUT/recv.txt" 2>&1 &
	rpid=$!
	wait_for 10 grep -q ready "$OUT/recv.txt" || true
	# shellcheck disable=SC2046 # two numbers
	set -- $(cpu_busy_total)
	busy0=$1 total0=$2 irq0=$(irqs) t0=$(uptime_cs)
	txm=$(spi_stat "$FROM" messages) txt=$(spi_stat "$FROM" transfers) txb=$(spi_stat "$FROM" bytes)
	rxm=$(spi_stat "$TO" messages) rxt=$(spi_stat "$TO" transfers) rxb=$(spi_stat "$TO" bytes)
	over0=$(if_stat "$TO" rx_over_errors) drop0=$(if_stat "$TO" rx_dropped)
	can-flood send "$FROM" "$FRAMES" -i "$id" >"$OUT/send.txt" 2>&1 || true
	t1=$(uptime_cs)
	wait "$rpid" || true
	# shellcheck disable=SC2046 # two numbers
	set -- $(cpu_busy_total)
	busy1=$1 total1=$2 irq1=$(irqs)
	link_down "$FROM" "$TO"
	rx=$(grep '^flood: mode=recv' "$OUT/recv.txt" || true)
	tx=$(grep '^flood: mode=send' "$OUT/send.txt" || true)
	if [ -z "$rx" ] || [ -z "$tx" ]; then
		record "flood-$FROM-$rate" fail "can-flood: $(tail -n 1 "$OUT/send.txt") / $(tail -n 1 "$OUT/recv.txt")"
		return
	fi
	got=$(field "$rx" received)
	secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { d = (b - a) / 100; printf "%.2f\n", (d > 0 ? d : 0.01) }')
	echo "flood $FROM>$TO $rate frames=$FRAMES sent=$(field "$tx" sent)" \
		"received=$got lost=$(field "$rx" lost) duplicated=$(field "$rx" duplicated)" \
		"reordered=$(field "$rx" reordered) corrupted=$(field "$rx" corrupted)" \
		"sock_drops=$(field "$rx" sock_drops)" \
		"rx_over_errors=$(($(if_stat "$TO" rx_over_errors) - over0))" \
		"rx_dropped=$(($(if_stat "$TO" rx_dropped) - drop0)) enobufs=$(field "$tx" enobufs) seconds=$secs" \
		"utilisation=$(awk -v n="$got" -v b=$FRAME_BITS -v r="$rate" -v s="$secs" \
			'BEGIN { printf "%.3f\n", n * b / r / s }')" \
		"cpu_busy_pct=$(awk -v b=$((busy1 - busy0)) -v t=$((total1 - total0)) \
			'BEGIN { printf "%.1f\n", t ? 100 * b / t : 0 }')" \
		"irqs_per_frame=$(per_frame "$irq1" "$irq0" "$got")" \
		"tx_spi_messages_per_frame=$(per_frame "$(spi_stat "$FROM" messages)" "$txm" "$FRAMES")" \
		"tx_spi_transfers_per_frame=$(per_frame "$(spi_stat "$FROM" transfers)" "$txt" "$FRAMES")" \
		"tx_spi_bytes_per_frame=$(per_frame "$(spi_stat "$FROM" bytes)" "$txb" "$FRAMES")" \
		"rx_spi_messages_per_frame=$(per_frame "$(spi_stat "$TO" messages)" "$rxm" "$got")" \
		"rx_spi_transfers_per_frame=$(per_frame "$(spi_stat "$TO" transfers)" "$rxt" "$got")" \
		"rx_spi_bytes_per_frame=$(per_frame "$(spi_stat "$TO" bytes)" "$rxb" "$got")" >>"$RESULTS"
	# Loss is a figure (a slow host loses frames at 1 Mbit/s); damage
	# to what arrives is a failure.
	damage=$(($(field "$rx" duplicated) + $(field "$rx" reordered) + $(field "$rx" corrupted)))
	summary="$got/$FRAMES received, lost $(field "$rx" lost), duplicated $(field "$rx" duplicated), reordered $(field "$rx" reordered), corrupted $(field "$rx" corrupted)"
	if [ "$damage" -eq 0 ] && [ "$(field "$tx" sent)" = "$FRAMES" ]; then
		record "flood-$FROM-$rate" pass "$summary"
	else
		record "flood-$FROM-$rate" fail "$summary, sent $(field "$tx" sent)"
	fi
}

# transit BITRATE: TRANSITS lone frames from A to B, one "transit" result
# line; a lone frame lost or damaged fails.
transit() {
	rate=$1
	if ! pair_up "$rate"; then
		record "transit-$rate" fail "cannot bring the pair up at $rate"
		return
	fi
	can-transit "$A" "$B" "$TRANSITS" -i 102 >"$OUT/transit.txt" 2>&1 || true
	link_down "$A" "$B"
	line=$(grep '^transit: ' "$OUT/transit.txt" || true)
	if [ -z "$line" ]; then
		record "transit-$rate" fail "can-transit: $(tail -n 1 "$OUT/transit.txt")"
		return
	fi
	echo "transit $A>$B $rate ${line#transit: }" >>"$RESULTS"
	summary="median $(field "$line" median_us) us, 99% $(field "$line" p99_us) us, max $(field "$line" max_us) us over $(field "$line" received)/$TRANSITS lone frames"
	if [ "$(field "$line" lost)" = 0 ] && [ "$(field "$line" damaged)" = 0 ]; then
		record "transit-$rate" pass "$summary"
	else
		record "transit-$rate" fail "$summary, lost $(field "$line" lost), damaged $(field "$line" damaged)"
	fi
}

check_floods() {
	for rate in $BITRATES; do
		transit "$rate"
	done
	for rate in $BITRATES; do
		flood "$A" "$B" "$rate" 100
		flood "$B" "$A" "$rate" 101
	done
}
