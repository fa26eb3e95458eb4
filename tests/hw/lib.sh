# The hardware test kit's helpers (sourced by mcp2510-hwtest): how a
# result is recorded and the few questions asked of an interface through
# iproute2 and sysfs.  Nothing here knows of a simulator.
#
# A result is one line of $RESULTS:
#   check NAME pass|fail|skip|n/a DETAIL...
#   flood DIRECTION BITRATE KEY=VALUE...
#   info KEY VALUE...

nap() { sleep "$1" 2>/dev/null || sleep 1; }

# record NAME VERDICT DETAIL...: one check's result, also on the terminal.
# skip: could not be run here (never a pass); n/a: the driver does not
# offer what the check needs, which it may choose.
record() {
	_name=$1 _verdict=$2
	shift 2
	echo "check $_name $_verdict $*" >>"$RESULTS"
	printf '  %-22s %-5s %s\n' "$_name" "$_verdict" "$*"
}

info() { echo "info $*" >>"$RESULTS"; }

# if_stat IF COUNTER: a counter of IF's statistics.
if_stat() { cat "/sys/class/net/$1/statistics/$2"; }

# can_state IF: ERROR-ACTIVE, ERROR-WARNING, ERROR-PASSIVE, BUS-OFF,
# STOPPED or SLEEPING, as "ip -details" shows it.
can_state() {
	ip -details link show "$1" | sed -n 's/.*can \(<[^>]*> \)\{0,1\}state \([A-Z-]*\).*/\2/p'
}

# berr IF tx|rx: the error counter ip shows (empty when it shows none).
berr() {
	ip -details link show "$1" | sed -n "s/.*berr-counter tx \([0-9]*\) rx \([0-9]*\).*/\1 \2/p" |
		{ read -r _tx _rx || true; [ "$2" = tx ] && echo "${_tx:-}" || echo "${_rx:-}"; }
}

# can_stat IF NAME: one of the CAN statistics ip -details -statistics
# shows (re-started bus-errors arbit-lost error-warn error-pass bus-off).
can_stat() {
	ip -details -statistics link show "$1" | awk -v want="$2" '
		$1 == "re-started" { for (i = 1; i <= NF; i++) col[$i] = i; getline
			print $(col[want]); exit }'
}

uptime_cs() { awk '{ printf "%d\n", $1 * 100 }' /proc/uptime; }

# wait_for SECONDS COMMAND...: until COMMAND succeeds, polled every 50 ms
# (by the clock: on a slow machine a poll itself takes time).
wait_for() {
	_until=$(($(uptime_cs) + $1 * 100))
	shift
	until "$@"; do
		[ "$(uptime_cs)" -lt "$_until" ] || return 1
		nap 0.05
	done
}

is_state() { [ "$(can_state "$1")" = "$2" ]; }
operstate_is() { [ "$(cat "/sys/class/net/$1/operstate")" = "$2" ]; }
at_least() { [ "$(if_stat "$1" "$2")" -ge "$3" ]; }

# link_down IF...: down, whatever the state.
link_down() {
	for _if in "$@"; do
		ip link set "$_if" down 2>/dev/null || true
	done
}

# link_up IF BITRATE [OPTION...]: configured from scratch (every mode
# off, no automatic restart) and up; fails when the driver refuses.
link_up() {
	_if=$1 _br=$2
	shift 2
	ip link set "$_if" down 2>/dev/null || true
	ip link set "$_if" type can bitrate "$_br" restart-ms 0 loopback off \
		listen-only off triple-sampling off "$@" 2>"$OUT/ip.err" || return 1
	ip link set "$_if" up 2>"$OUT/ip.err" || return 1
	wait_for 10 operstate_is "$_if" up
}

# mode_off IF MODE: MODE off, ignoring a driver that never offered it.
mode_off() { ip link set "$1" type can "$2" off 2>/dev/null || true; }

# pair_up BITRATE: both interfaces up at BITRATE with every mode off.
pair_up() {
	for _if in "$A" "$B"; do
		link_down "$_if"
		mode_off "$_if" one-shot
		mode_off "$_if" cc-len8-dlc
		link_up "$_if" "$1" || return 1
	done
}

# dump_start IF[,FILTER...] FILE [candump OPTION...]: candump -L of IF
# into FILE in the background; DUMP is its process.
dump_start() {
	_if=$1 _file=$2
	shift 2
	candump -L "$@" "$_if" >"$_file" 2>/dev/null &
	DUMP=$!
	nap 0.2
}

dump_stop() {
	nap "${1:-0.5}"
	kill "$DUMP" 2>/dev/null || true
	wait "$DUMP" 2>/dev/null || true
}

# frames FILE: how many frames a candump -L file holds.
frames() { grep -c '#' "$1" || true; }
