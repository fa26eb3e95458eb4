# The kit's black-box checks (sourced by mcp2510-hwtest): what a user
# can see of a driver through iproute2, can-utils and sockets, on two
# interfaces $A and $B on one bus.  Each check_* records its verdicts
# (lib.sh) and leaves both interfaces down.

RATE=500000

# send IF FRAME: cansend, failures recorded by the caller's checks.
send() { cansend "$1" "$2" 2>/dev/null || true; }

check_link() {
	if ! link_up "$A" $RATE; then
		record link fail "$A would not come up: $(cat "$OUT/ip.err")"
		return
	fi
	st=$(can_state "$A")
	link_down "$A"
	if [ "$st" = ERROR-ACTIVE ] && wait_for 5 operstate_is "$A" down; then
		record link pass "up: $st, down: $(can_state "$A")"
	else
		record link fail "up: state '$st', down: operstate $(cat "/sys/class/net/$A/operstate")"
	fi
}

check_bitrates() {
	bad=
	for r in 125000 250000 500000 1000000; do
		pair_up $r || { bad="$bad $r(refused)"; continue; }
		ip -details link show "$A" | grep -q "bitrate $r " || bad="$bad $r(shown)"
		dump_start "$B" "$OUT/rate.log"
		send "$A" "1AB#$(printf '%08X' $r)"
		dump_stop
		grep -q "1AB#$(printf '%08X' $r)" "$OUT/rate.log" || bad="$bad $r(no frame)"
	done
	link_down "$A" "$B"
	[ -z "$bad" ] && record bitrates pass "125k 250k 500k 1M set, shown, crossed" ||
		record bitrates fail "failed at:$bad"
	if ip link set "$A" type can bitrate 3000000 2>/dev/null; then
		record bitrate-refused fail "3 Mbit/s accepted"
	else
		record bitrate-refused pass "3 Mbit/s refused"
	fi
}

# Local sockets get a sent frame once, as the echo of its transmission;
# the interface counts it as sent, not received; no echo without an ACK.
check_echo() {
	pair_up $RATE || { record echo fail "cannot bring the pair up"; return; }
	rx=$(if_stat "$A" rx_packets) tx=$(if_stat "$A" tx_packets)
	dump_start "$A" "$OUT/echo-a.log"
	echo "$DUMP" >"$OUT/dump-a.pid"
	dump_start "$B" "$OUT/echo-b.log"
	send "$A" "5A5#0102"
	dump_stop
	kill "$(cat "$OUT/dump-a.pid")" 2>/dev/null || true
	na=$(frames "$OUT/echo-a.log") nb=$(frames "$OUT/echo-b.log")
	drx=$(($(if_stat "$A" rx_packets) - rx)) dtx=$(($(if_stat "$A" tx_packets) - tx))
	if [ "$na" = 1 ] && [ "$nb" = 1 ] && [ $drx = 0 ] && [ $dtx = 1 ]; then
		record echo pass "one echo, one frame across, tx_packets +1, rx_packets +0"
	else
		record echo fail "echoes $na, across $nb, tx_packets +$dtx, rx_packets +$drx"
	fi
	link_down "$B"
	dump_start "$A" "$OUT/noack.log"
	send "$A" "5A6#03"
	dump_stop 1
	n=$(frames "$OUT/noack.log")
	[ "$n" = 0 ] && record echo-needs-ack pass "no echo while nobody acknowledges" ||
		record echo-needs-ack fail "$n echoes of a frame nobody acknowledged"
	link_down "$A"
}

# The four CAN_RAW_LOOPBACK x CAN_RAW_RECV_OWN_MSGS cases (can-echo).
check_sockopts() {
	if ! command -v can-echo >/dev/null; then
		record loopback-sockopts skip "can-echo is not installed"
		return
	fi
	pair_up $RATE || { record loopback-sockopts fail "cannot bring the pair up"; return; }
	can-echo "$A" >"$OUT/sockopts.txt" 2>&1 || true
	link_down "$A" "$B"
	cat >"$OUT/sockopts.want" <<'TXT'
loopback=0 recv_own=0 sender: - listener: -
loopback=0 recv_own=1 sender: - listener: -
loopback=1 recv_own=0 sender: - listener: 120 121 122
loopback=1 recv_own=1 sender: 130c 131c 132c listener: 130 131 132
TXT
	if cmp -s "$OUT/sockopts.want" "$OUT/sockopts.txt"; then
		record loopback-sockopts pass "4 cases as the socket options ask"
	else
		record loopback-sockopts fail "$(tr '\n' ';' <"$OUT/sockopts.txt")"
	fi
}

# Socket filters: id/mask (an 8-digit id is extended) and inverted.
check_filters() {
	pair_up $RATE || { record filters fail "cannot bring the pair up"; return; }
	dump_start "$B,123:7FF,12345678:1FFFFFFF" "$OUT/filter.log"
	echo "$DUMP" >"$OUT/dump-b.pid"
	dump_start "$B,123~7FF" "$OUT/inverse.log"
	for f in 123#01 124#02 12345678#03 00000123#04; do send "$A" "$f"; done
	dump_stop
	kill "$(cat "$OUT/dump-b.pid")" 2>/dev/null || true
	link_down "$A" "$B"
	got=$(sed 's/.* //' "$OUT/filter.log" | tr '\n' ' ')
	inv=$(sed 's/.* //' "$OUT/inverse.log" | tr '\n' ' ')
	# A mask of 7FF does not look at the EFF flag: 00000123 matches 123.
	if [ "$got" = "123#01 12345678#03 00000123#04 " ] && [ "$inv" = "124#02 12345678#03 " ]; then
		record filters pass "id/mask and inverted filters"
	else
		record filters fail "filtered: '$got', inverted: '$inv'"
	fi
}

# A lone sender: no ACK, error-passive (TEC 128), and once the other
# node is back the pending frame arrives and good frames bring the
# sender back to error-active.
check_no_ack() {
	pair_up $RATE || { record no-ack fail "cannot bring the pair up"; return; }
	link_down "$B"
	send "$A" "2AA#11"
	if wait_for 10 is_state "$A" ERROR-PASSIVE; then
		tec=$(berr "$A" tx)
		record no-ack pass "error-passive, tec ${tec:-not shown}"
	else
		record no-ack fail "state $(can_state "$A"), tec $(berr "$A" tx)"
	fi
	tx=$(if_stat "$A" tx_packets)
	link_up "$B" $RATE
	if wait_for 5 at_least "$A" tx_packets $((tx + 1)); then
		record no-ack-pending pass "the pending frame went once the other node came up"
	else
		record no-ack-pending fail "tx_packets stays $tx"
	fi
	can-flood send "$A" 40 -i 2AB >/dev/null 2>&1 || true
	if wait_for 5 is_state "$A" ERROR-ACTIVE; then
		record error-recovery pass "error-active again after 40 good frames"
	else
		record error-recovery fail "state $(can_state "$A"), tec $(berr "$A" tx) after 40 good frames"
	fi
	link_down "$A" "$B"
}

restarted_since() { [ "$(can_stat "$A" re-started)" -gt "$1" ]; }
inflight_zero() { [ "$(cat "$1/inflight")" -eq 0 ]; }

# Bus-off without a simulator: the other node at another bit rate
# destroys every frame.  Manual restart, then restart-ms.
check_busoff() {
	link_up "$A" $RATE && link_up "$B" 250000 || { record bus-off fail "cannot bring the pair up"; return; }
	off=$(can_stat "$A" bus-off)
	send "$A" "3BB#22"
	if ! wait_for 10 is_state "$A" BUS-OFF; then
		record bus-off fail "state $(can_state "$A") with a node at 250 kbit/s"
		link_down "$A" "$B"
		return
	fi
	record bus-off pass "bus-off against a node at 250 kbit/s (bus-off count $off -> $(can_stat "$A" bus-off))"
	link_up "$B" $RATE
	dump_start "$B" "$OUT/restart.log"
	if ip link set "$A" type can restart 2>"$OUT/ip.err" && wait_for 5 is_state "$A" ERROR-ACTIVE; then
		send "$A" "3BC#33"
		dump_stop
		grep -q '3BC#33' "$OUT/restart.log" && record restart pass "manual restart, traffic flows" ||
			record restart fail "restarted, but no frame across"
	else
		dump_stop 0
		record restart fail "restart: $(cat "$OUT/ip.err") state $(can_state "$A")"
	fi
	link_down "$A"
	check_restart_ms
	link_down "$A" "$B"
}

# restart-ms 100 against the same fault: can-dev is told of the bus-off
# and restarts the interface by itself (restart-ms-reported), and once
# the rates agree traffic flows without a manual restart.
check_restart_ms() {
	link_up "$A" $RATE restart-ms 100 && link_up "$B" 250000 ||
		{ record restart-ms fail "cannot bring the pair up"; return; }
	restarts=$(can_stat "$A" re-started)
	send "$A" "3BD#44"
	if wait_for 10 restarted_since "$restarts"; then
		record restart-ms-reported pass "bus-off reported and restarted by can-dev ($(can_stat "$A" re-started) times)"
	else
		record restart-ms-reported fail "no bus-off reported and no restart counted in 10 s (state $(can_state "$A"))"
	fi
	link_up "$B" $RATE
	dump_start "$B" "$OUT/restart-ms.log"
	send "$A" "3BE#55"
	# The state that follows depends on the error counters the restart
	# left: a chip that recovered by itself keeps its TEC.
	dump_stop 2
	if grep -q '3BE#55' "$OUT/restart-ms.log" && ! is_state "$A" BUS-OFF; then
		record restart-ms pass "traffic flows once the rates agree, no manual restart (state $(can_state "$A"))"
	else
		record restart-ms fail "state $(can_state "$A") once the rates agree, $(frames "$OUT/restart-ms.log") frames across"
	fi
}

check_bql() {
	q=/sys/class/net/$A/queues/tx-0/byte_queue_limits
	[ -r "$q/inflight" ] || { record bql skip "no byte_queue_limits in sysfs"; return; }
	pair_up $RATE || { record bql fail "cannot bring the pair up"; return; }
	can-flood send "$A" 300 -i 2BC >/dev/null 2>&1 || true
	if [ "$(cat "$q/limit")" -eq 0 ]; then
		record bql n/a "the driver does not report bytes in flight (limit 0 after 300 frames)"
	elif wait_for 5 inflight_zero "$q"; then
		record bql pass "inflight back to 0 after 300 frames (limit $(cat "$q/limit"))"
	else
		record bql fail "inflight $(cat "$q/inflight") after 300 frames"
	fi
	link_down "$A" "$B"
}

# monotonic FILE: candump -L's timestamps never go back.
monotonic() {
	awk '{ t = substr($1, 2, length($1) - 2) + 0; if (NR > 1 && t < last) bad++; last = t }
		END { exit !(NR > 0 && bad == 0) }' "$1"
}

check_timestamps() {
	pair_up $RATE || { record timestamps fail "cannot bring the pair up"; return; }
	dump_start "$B" "$OUT/ts-rx.log"
	echo "$DUMP" >"$OUT/dump-b.pid"
	dump_start "$A" "$OUT/ts-echo.log"
	can-flood send "$A" 200 -i 2CD >/dev/null 2>&1 || true
	dump_stop
	kill "$(cat "$OUT/dump-b.pid")" 2>/dev/null || true
	link_down "$A" "$B"
	if monotonic "$OUT/ts-rx.log" && monotonic "$OUT/ts-echo.log"; then
		record timestamps pass "$(frames "$OUT/ts-rx.log") received, $(frames "$OUT/ts-echo.log") echoes in order of time"
	else
		record timestamps fail "receive or echo timestamps go back in time"
	fi
}
