# The kit's checks of the controller's modes (sourced by mcp2510-hwtest):
# one-shot, listen-only, loopback, CC_LEN8_DLC, the modes a Classical CAN
# controller must refuse, and what only a person at the bench can do.
# $CHIP is the chip the SPI device was declared as (mcp2510, mcp2515...).

check_oneshot() {
	link_down "$A" "$B"
	if ! ip link set "$A" type can bitrate $RATE one-shot on 2>/dev/null; then
		if [ "$CHIP" = mcp2510 ]; then
			record one-shot pass "refused: the MCP2510 has no one-shot mode"
		else
			record one-shot n/a "the driver does not offer one-shot on the $CHIP"
		fi
		return
	fi
	[ "$CHIP" != mcp2510 ] || record one-shot-mcp2510 fail "one-shot accepted on an MCP2510"
	ip link set "$A" up
	tx=$(if_stat "$A" tx_packets)
	send "$A" "4AA#55"
	nap 2
	st=$(can_state "$A") tec=$(berr "$A" tx)
	if [ "$st" = ERROR-ACTIVE ] && [ "${tec:-8}" = 8 ] && [ "$(if_stat "$A" tx_packets)" = "$tx" ]; then
		record one-shot pass "one attempt without ACK: tec ${tec:-?}, not sent, no retry"
	else
		record one-shot fail "without ACK: state $st, tec ${tec:-?}, tx_packets $tx -> $(if_stat "$A" tx_packets)"
	fi
	link_down "$A"
	mode_off "$A" one-shot
}

# A listen-only node neither acknowledges nor sends.
check_listen_only() {
	link_up "$A" $RATE && link_up "$B" $RATE listen-only on ||
		{ record listen-only fail "listen-only refused: $(cat "$OUT/ip.err")"; return; }
	txb=$(if_stat "$B" tx_packets)
	send "$B" "4BB#66"
	send "$A" "4BC#77"
	if wait_for 10 is_state "$A" ERROR-PASSIVE && [ "$(if_stat "$B" tx_packets)" = "$txb" ]; then
		record listen-only pass "no ACK from the listener (the sender went error-passive), nothing sent by it"
	else
		record listen-only fail "sender $(can_state "$A"), listener tx_packets $txb -> $(if_stat "$B" tx_packets)"
	fi
	link_down "$A" "$B"
}

# Loopback mode: frames come back through the controller, none reaches
# the bus.
check_loopback_mode() {
	link_up "$B" $RATE && link_up "$A" $RATE loopback on ||
		{ record loopback-mode fail "loopback refused: $(cat "$OUT/ip.err")"; return; }
	rxa=$(if_stat "$A" rx_packets) rxb=$(if_stat "$B" rx_packets)
	send "$A" "4CC#88"
	nap 1
	da=$(($(if_stat "$A" rx_packets) - rxa)) db=$(($(if_stat "$B" rx_packets) - rxb))
	if [ $da = 1 ] && [ $db = 0 ]; then
		record loopback-mode pass "received back once, nothing on the bus"
	else
		record loopback-mode fail "received back $da, the other node got $db"
	fi
	link_down "$A" "$B"
}

check_len8_dlc() {
	command -v can-dlc >/dev/null || { record cc-len8-dlc skip "can-dlc is not installed"; return; }
	link_down "$A" "$B"
	if ! ip link set "$A" type can cc-len8-dlc on 2>/dev/null ||
		! ip link set "$B" type can cc-len8-dlc on 2>/dev/null; then
		record cc-len8-dlc n/a "the driver does not offer cc-len8-dlc"
		return
	fi
	link_up "$A" $RATE && link_up "$B" $RATE || { record cc-len8-dlc fail "cannot bring the pair up"; return; }
	can-dlc recv "$B" 2 >"$OUT/dlc.txt" 2>&1 &
	pid=$!
	nap 0.3
	can-dlc send "$A" 123#1122334455667788_E >/dev/null 2>&1 || true
	can-dlc send "$A" 124#11223344 >/dev/null 2>&1 || true
	wait "$pid" || true
	got=$(tr '\n' ' ' <"$OUT/dlc.txt")
	if [ "$got" = "123#1122334455667788_E 124#11223344 " ]; then
		record cc-len8-dlc pass "DLC 14 across and back, plain DLC 4 untouched"
	else
		record cc-len8-dlc fail "received '$got'"
	fi
	link_down "$A" "$B"
	mode_off "$A" cc-len8-dlc
	mode_off "$B" cc-len8-dlc
}

# Modes a Classical CAN controller without them must refuse.
check_refused_modes() {
	link_down "$A"
	bad=
	for mode in "fd on" "presume-ack on"; do
		# shellcheck disable=SC2086 # MODE: two words
		if ip link set "$A" type can bitrate $RATE $mode 2>/dev/null; then
			bad="$bad '$mode'"
			ip link set "$A" type can ${mode% on} off 2>/dev/null || true
		fi
	done
	[ -z "$bad" ] && record refused-modes pass "fd and presume-ack refused" ||
		record refused-modes fail "accepted:$bad"
}

# What needs a person at the bench: asked for with -i, else reported as
# not run.
check_by_hand() {
	if [ "$INTERACTIVE" != 1 ]; then
		record unplugged skip "needs a person: pull a CAN wire during traffic (run with -i)"
		return
	fi
	pair_up $RATE || { record unplugged fail "cannot bring the pair up"; return; }
	printf 'Pull CANH or CANL between the two boards, then press Enter: '
	read -r _
	send "$A" "4DD#99"
	wait_for 10 is_state "$A" ERROR-PASSIVE || wait_for 1 is_state "$A" BUS-OFF
	st=$(can_state "$A")
	printf 'Plug it back, then press Enter: '
	read -r _
	ip link set "$A" type can restart 2>/dev/null || true
	dump_start "$B" "$OUT/replug.log"
	send "$A" "4DE#AA"
	dump_stop 1
	if [ "$st" != ERROR-ACTIVE ] && grep -q '4DE#AA' "$OUT/replug.log"; then
		record unplugged pass "unplugged: $st; plugged back: traffic flows"
	else
		record unplugged fail "unplugged: $st; plugged back: $(frames "$OUT/replug.log") frames"
	fi
	link_down "$A" "$B"
}
