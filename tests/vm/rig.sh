# Helpers for scenario scripts, in the guest at /lib/rig.sh:  . /lib/rig.sh
# (POSIX sh, busybox ash).  Environment from vm-run: VM_KERNEL (6.1, 6.12,
# debug or rt), VM_NODES, VM_VARIANT, VM_DRIVER, VM_DRIVER_KO (--module's
# FILE, default mcp2510.ko), VM_SIM (1 when the simulated chips are
# loaded), VM_SIM_PARAMS (--sim-param's NAME=VALUE words).

# The helpers below start no process where a shell builtin does: on the
# debug kernel (KASAN, kmemleak and lockdep at every allocation, under TCG)
# each fork+exec costs a third of a second, and polling loops run many.

# nap SECONDS: sleep (fractions allowed) without a process: read's timeout
# on a pipe nobody writes to.
mkfifo /tmp/.rig-nap 2>/dev/null || true
exec 7<>/tmp/.rig-nap
nap() {
	read -r -t "$1" _ <&7 || true
}

# Print a failure message and exit non-zero.
fail() {
	echo "FAIL: $*" >&2
	exit 1
}

# can_up IF BITRATE [more "ip link set IF type can" arguments]: configure
# IF, bring it up, and wait until its link state says so.
can_up() {
	_if=$1 _br=$2
	shift 2
	ip link set "$_if" type can bitrate "$_br" "$@" || fail "cannot configure $_if"
	ip link set "$_if" up || fail "cannot bring $_if up"
	wait_operstate "$_if" up || fail "$_if: link state '$OPERSTATE' 10 s after up"
}

# wait_operstate IF [STATE [SECONDS]]: wait until IF's operstate reads STATE
# (default up), at most SECONDS (default 10); OPERSTATE is the last value
# read.  "ip link set IF up" returns before the link state follows: the
# carrier comes on in the driver's open, but operstate is set later by the
# kernel's linkwatch work, which runs non-urgent events at most once a
# second.  A carrier-on event counts as urgent only while the qdisc is not
# yet attached, and the work, which needs the RTNL lock the open holds,
# runs after the qdisc is: so for up to a second ip shows IF as NO-CARRIER
# and state DOWN (the second interface brought up in a row, typically).
wait_operstate() {
	_want=${2:-up}
	_polls=$((${3:-10} * 20))
	while read -r OPERSTATE <"/sys/class/net/$1/operstate" &&
		[ "$OPERSTATE" != "$_want" ]; do
		_polls=$((_polls - 1))
		[ "$_polls" -gt 0 ] || return 1
		nap 0.05
	done
	[ "$OPERSTATE" = "$_want" ]
}

# _rx_count IF: RX_COUNT = the number of receivers registered on IF, over
# all of /proc/net/can's lists.
_rx_count() {
	RX_COUNT=0
	for _list in /proc/net/can/rcvlist_*; do
		[ -r "$_list" ] || continue
		while read -r _dev _; do
			[ "$_dev" != "$1" ] || RX_COUNT=$((RX_COUNT + 1))
		done <"$_list"
	done
}

# dump_start IF[,FILTER...] N FILE [candump options]: candump -n N IF into
# FILE in the background, returning once its socket is registered (no frame
# is missed).  Stops itself after 20 s without a frame.  Collect it with
# dump_wait.
dump_start() {
	_if=$1 _n=$2 _file=$3
	shift 3
	_rx_count "${_if%%,*}"
	_before=$RX_COUNT
	candump -n "$_n" -T 20000 "$@" "$_if" >"$_file" &
	DUMP_PID=$!
	_tries=0
	while _rx_count "${_if%%,*}" && [ "$RX_COUNT" -le "$_before" ]; do
		_tries=$((_tries + 1))
		[ $_tries -le 100 ] || { nap 1; break; }
		nap 0.05
	done
}

# dump_wait: wait for the last dump_start's candump.
dump_wait() {
	wait "$DUMP_PID" || true
}

# frame_passes FROM TO ID BYTE: the frame ID#BYTE (a standard ID, one data
# byte) sent on FROM arrives on TO.  A status, for the caller to say why.
frame_passes() {
	dump_start "$2,$3:7FF" 1 /tmp/passes.txt
	cansend "$1" "$3#$4" || { kill "$DUMP_PID" 2>/dev/null; dump_wait; return 1; }
	dump_wait
	grep -q "$3 *\[1\] *$4" /tmp/passes.txt || { cat /tmp/passes.txt >&2; return 1; }
}

# expect_lines FILE N: FILE has exactly N lines, or the scenario fails.
expect_lines() {
	_got=$(wc -l <"$1")
	[ "$_got" -eq "$2" ] || { cat "$1" >&2; fail "$1: $_got lines, expected $2"; }
}

# errors_start IF FILE: record IF's error frames into FILE (until errors_stop).
errors_start() {
	_before=$(grep -c "^ *$1 " /proc/net/can/rcvlist_err || true)
	# 0~0 matches no data frame; the error mask lets every error frame in.
	candump "$1,0~0,#FFFFFFFF" >"$2" &
	ERR_PID=$!
	while [ "$(grep -c "^ *$1 " /proc/net/can/rcvlist_err || true)" -le "$_before" ]; do
		nap 0.05
	done
}
errors_stop() {
	kill "$ERR_PID"
	wait "$ERR_PID" || true
}

# error_seen FILE CLASS [CTRL]: FILE (from errors_start) holds an error
# frame with a CLASS bit in its id and, if given, all CTRL bits in data[1].
# (Debian 12's candump -e cannot decode frames that carry CAN_ERR_CNT.)
error_seen() {
	while read -r _ id _ _ d1 _; do
		[ $((0x$id & $2)) -ne 0 ] || continue
		[ $((0x$d1 & ${3:-0})) -eq $((${3:-0})) ] && return 0
	done <"$1"
	return 1
}

# The simulator's debugfs directory (docs/simulator.md).
SIM=/sys/kernel/debug/mcp2510-sim

# dlc_recv_start IF FILE: one frame from IF into FILE in the background
# (can-dlc, which shows a raw DLC above 8 as later can-utils do:
# 123#1122334455667788_E), returning once the socket is registered.
dlc_recv_start() {
	command -v can-dlc >/dev/null || fail "can-dlc is not in the guest"
	_rx_count "$1"
	_before=$RX_COUNT
	can-dlc recv "$1" 1 >"$2" &
	RECV_PID=$!
	_tries=0
	while _rx_count "$1" && [ "$RX_COUNT" -le "$_before" ]; do
		_tries=$((_tries + 1))
		[ $_tries -le 100 ] || fail "can-dlc recv $1 never registered"
		nap 0.05
	done
}

# dlc_exchange FROM TO FRAME WIRE GOT: FROM sends FRAME (can-dlc syntax);
# the bus carries WIRE from FROM's chip and TO reads GOT.
dlc_exchange() {
	: >"$SIM/monitor"
	dlc_recv_start "$2" /tmp/got.txt
	can-dlc send "$1" "$3" || fail "can-dlc send $1 $3"
	wait "$RECV_PID" || fail "$2 received nothing after $1 sent $3"
	read -r _got </tmp/got.txt
	echo "$1 sent $3, the bus carried $4, $2 read $_got"
	grep -q " chip${1#can} $4 " "$SIM/monitor" ||
		{ cat "$SIM/monitor"; fail "$1 sent $3: not $4 on the bus"; }
	[ "$_got" = "$5" ] || fail "$1 sent $3: $2 read $_got, expected $5"
}

# if_stat IF COUNTER: one of IF's interface statistics.
if_stat() {
	read -r _v <"/sys/class/net/$1/statistics/$2"
	echo "$_v"
}
# tenths A B: A / B with one decimal ("4.9").
tenths() { echo "$(($1 * 10 / $2 / 10)).$(($1 * 10 / $2 % 10))"; }
# sent_beyond IF N / received_beyond IF N: IF counted more than N frames
# sent / received.
sent_beyond() { [ "$(if_stat "$1" tx_packets)" -gt "$2" ]; }
received_beyond() { [ "$(if_stat "$1" rx_packets)" -gt "$2" ]; }

# sim_counter CHIP NAME / sim_state CHIP NAME: one line of chipN/counters
# or chipN/state.
sim_counter() {
	_field_of "$SIM/chip$1/counters" "$2"
}
sim_state() {
	_field_of "$SIM/chip$1/state" "$2"
}
# _field_of FILE KEY: the second word of FILE's line that starts with KEY.
_field_of() {
	while read -r _key _value _; do
		[ "$_key" != "$2" ] || { echo "$_value"; return 0; }
	done <"$1"
}

# ethtool_stat IF NAME: one of the driver's `ethtool -S` counters.
ethtool_stat() {
	ethtool -S "$1" | awk -v k="$2:" '$1 == k { print $2 }'
}

# expect_eq WHAT GOT WANTED: fail unless the number GOT is WANTED.
expect_eq() {
	[ "$2" -eq "$3" ] || fail "$1 is $2, expected $3"
}

# _now: NOW_S = whole seconds since boot.  uptime_s prints it.
_now() {
	read -r _up _ </proc/uptime
	NOW_S=${_up%%.*}
}
uptime_s() {
	_now
	echo "$NOW_S"
}

# wait_for SECONDS COMMAND...: poll COMMAND until it succeeds; fails
# (status 1) once SECONDS have passed.
wait_for() {
	_now
	_end=$((NOW_S + $1))
	shift
	while ! "$@"; do
		_now
		[ "$NOW_S" -lt "$_end" ] || return 1
		nap 0.2
	done
}

# can_state_is IF STATE: ip -details shows IF in STATE (ERROR-ACTIVE, ...).
can_state_is() {
	ip -details link show "$1" | grep -q "state $2 "
}

# carrier IF / operstate IF: the link's carrier (0 when IF is gone) and
# operstate, from sysfs.
carrier() { cat "/sys/class/net/$1/carrier" 2>/dev/null || echo 0; }
operstate() { cat "/sys/class/net/$1/operstate"; }
# no_carrier IF: without starting a process, so a bus-off is seen at once.
no_carrier() {
	read -r _c <"/sys/class/net/$1/carrier" 2>/dev/null || _c=0
	[ "$_c" = 0 ]
}
# on_bus IF: error-active, carrier on, operstate up.
on_bus() {
	can_state_is "$1" ERROR-ACTIVE && [ "$(carrier "$1")" = 1 ] &&
		[ "$(operstate "$1")" = up ]
}
# off_bus IF: bus-off, carrier off, operstate down.
off_bus() {
	can_state_is "$1" BUS-OFF && [ "$(carrier "$1")" = 0 ] &&
		[ "$(operstate "$1")" = down ]
}

# chips_load DRIVER: new simulated chips, as /init loads them before a
# scenario (VM_NODES chips of VM_VARIANT, VM_SIM_PARAMS), bound to DRIVER
# (mcp2510 or mcp251x) instead of VM_DRIVER: what was loaded goes first,
# so every interface, counter and error state starts anew.  For scenarios
# that compare the two drivers on the same chips in one run.
chips_load() {
	for _m in mcp2510 mcp251x mcp2510_sim; do
		[ ! -d "/sys/module/$_m" ] || rmmod "$_m" || fail "cannot unload $_m"
	done
	# shellcheck disable=SC2086 # VM_SIM_PARAMS: several NAME=VALUE words
	insmod /opt/mcp2510/modules/mcp2510-sim.ko nodes="$VM_NODES" \
		variant="$VM_VARIANT" driver="$1" ${VM_SIM_PARAMS:-} ||
		fail "cannot load mcp2510-sim.ko for $1"
	case $1 in
	mcp2510) insmod /opt/mcp2510/modules/mcp2510.ko || fail "cannot load mcp2510.ko" ;;
	mcp251x)
		if [ -n "${VM_MCP251X_KO:-}" ]; then
			insmod "$VM_MCP251X_KO" || fail "cannot load $VM_MCP251X_KO"
		else
			modprobe mcp251x || fail "cannot load mcp251x"
		fi
		;;
	*) fail "chips_load: no driver $1" ;;
	esac
	_polls=300
	while [ ! -e "/sys/class/net/can$((VM_NODES - 1))" ]; do
		_polls=$((_polls - 1))
		[ "$_polls" -gt 0 ] || fail "can$((VM_NODES - 1)) did not appear with $1"
		nap 0.1
	done
}

# libgpiod's tools took another syntax with version 2, which the guest has
# where its kernel lacks the v1 ABI (tests/vm/kernel-info gpiod):
#   gpio_info CHIP                 the chip's lines
#   gpio_set CHIP OFFSET=VALUE...  set the lines, release them and return
#   gpio_get CHIP OFFSET...        the lines' values as "1 0 1"
#   gpio_chip LABEL                the gpiochip of that label (v2 takes no
#                                  labels for chips)
gpiod_v1() {
	gpiodetect --version | grep -q ' v1\.'
}
gpio_info() {
	if gpiod_v1; then gpioinfo "$1"; else gpioinfo -c "$1"; fi
}
gpio_set() {
	_chip=$1
	shift
	if gpiod_v1; then gpioset "$_chip" "$@"; else gpioset -t 0 -c "$_chip" "$@"; fi
}
gpio_get() {
	_chip=$1
	shift
	if gpiod_v1; then gpioget "$_chip" "$@"; else gpioget --numeric -c "$_chip" "$@"; fi
}
gpio_chip() {
	gpiodetect | awk -v l="[$1]" '$2 == l { print $1 }'
}

# The mcp251x under test, for make upstream-check's reproducers
# (tests/upstream/scenarios): the patched build that vm-run --module put in
# /extra and /init and chips_load load in place of the kernel's own, else
# the kernel's, whose defect a reproducer then expects to find.  Sets ko
# (the patched build, or empty) and under_test (what failures name).
mcp251x_under_test() {
	[ "$VM_SIM" = 1 ] || fail "the simulated chips are not loaded"
	ko=${VM_MCP251X_KO:-}
	under_test="the kernel's mcp251x"
	[ -z "$ko" ] || under_test=$ko
}

# burst_under_rival FRAMES BITRATE: can0 sends FRAMES sequence-numbered
# frames (can-flood, ID 123) while the phantom node puts a run of four
# frames of ID 001 on the bus after every tenth frame can-flood writes:
# each waits for the frame on the bus to end and meets can0's next one at
# the start of the next, so can0 loses arbitration to every frame of a
# run.  The runs keep pace with the burst, not with the guest's clock, so
# a slow guest (the debug kernel, or a host busy with other guests) sees
# as many as a fast one.  What the bus monitor saw of the burst
# (can-flood check, the phantom's frames another sender's) goes to
# /tmp/bus.txt.
burst_under_rival() {
	can-flood check "$1" -i 123 -o -t 5000 -f "$SIM/monitor" >/tmp/bus.txt &
	_check=$!
	wait_for 10 grep -q ready /tmp/bus.txt || fail "can-flood check did not start"
	can-flood send can0 "$1" -i 123 -r "10:$SIM/flood:4 001#00 $2" ||
		fail "can-flood send failed"
	wait "$_check" || true
	cat /tmp/bus.txt
}

# spi_mark CHIP: note chip CHIP's SPI transfers and bytes so far.
spi_mark() {
	_spi_x0=$(sim_counter "$1" spi_transfers)
	_spi_b0=$(sim_counter "$1" spi_bytes)
}
# mcp2510_traffic FROM FRAMES: can0 and can1 up at 500 kbit/s and chip0's
# SPI counts noted (spi_mark); then FROM sends FRAMES 8-byte frames 5 ms
# apart, an interrupt each.
mcp2510_traffic() {
	can_up can0 500000
	can_up can1 500000
	spi_mark 0
	cangen "$1" -n "$2" -g 5 -I 123 -L 8 -D i
}
# mcp2510_transfers_per_frame CHIP WHAT FRAMES: what the mcp251x under
# test spent on chip CHIP's SPI since spi_mark for FRAMES frames WHAT
# (received, sent), and the verdict of the MCP2510 buffer patches of
# upstream/mcp251x: one READ or WRITE for a whole buffer makes at most 8
# transfers (chip-select periods) a frame, one per register about 17.
# The module in /extra must do the first, the kernel's own the second.
mcp2510_transfers_per_frame() {
	_x=$(($(sim_counter "$1" spi_transfers) - _spi_x0))
	_b=$(($(sim_counter "$1" spi_bytes) - _spi_b0))
	_per=$(((_x + $3 - 1) / $3))
	echo "$under_test: $3 frames $2, $_x SPI transfers and $_b bytes:" \
		"$(tenths "$_x" "$3") transfers, $(tenths "$_b" "$3") bytes a frame"
	if [ -f "$ko" ]; then
		[ $_per -le 8 ] || fail "$under_test: $_per SPI transfers a frame $2, expected at most 8"
	else
		[ $_per -gt 8 ] || fail "$under_test: $_per SPI transfers a frame $2: the kernel has the change"
	fi
}
