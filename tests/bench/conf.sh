# Sourced by tests/bench/run and tests/upstream/upstream-bench: the board
# profiles, the settings a piece's boots get in /extra/bench.conf (from
# the BENCH_* variables bench.mk sets, BENCH_ENV) and a boot's timeout.

# profile NAME: a board profile of mcp2510-sim.ko (its SPI and interrupt
# costs live in the model, tests/sim/sim_spi_profile.c, and
# docs/performance.md says where each figure comes from) as "seed of the
# latency draws, bit rate of the per-frame cost bursts".
profile() {
	case $1 in
	pi | pi-rt) echo "1 500000" ;;
	slow) echo "1 125000" ;;
	*) return 1 ;;
	esac
}

# boot_timeout CONF SCALE: the timeout of one boot with bench.conf CONF
# in real seconds: the bus time of everything the guest may send (every
# RX probe and flood of the search, the TX bursts at a tenth of the bus's
# pace, lone frames a tenth of a second each besides), twice, for every
# try, plus room for a slow guest.
boot_timeout() {
	(
		# shellcheck disable=SC1090
		. "$1"
		[ -z "${LATENCY_ONLY:-}" ] || CPU_FRAMES=0 RX_BITRATES='' TX_BITRATES=
		awk -v f="$FLOOD_FRAMES" -v p="$PROBE_FRAMES" -v m="$TX_FRAMES" \
			-v c="$CPU_FRAMES" -v s="$2" -v cb="$CPU_BITRATE" -v rx="$RX_BITRATES" \
			-v tx="$TX_BITRATES" -v lf="$FRAMES" -v k="$STALL_TRIES" \
			-v lr="$COMPARE_BITRATES $SATURATION_BITRATE" 'BEGIN {
			bit = 135 * s
			t = 3 * c * bit / cb
			n = split(rx, rates, " ")
			for (i = 1; i <= n; i++)
				t += (f + p) * bit / rates[i]
			n = split(tx, rates, " ")
			for (i = 1; i <= n; i++)
				t += m * bit / rates[i] / 0.1
			n = split(lr, rates, " ")
			for (i = 1; i <= n; i++)
				t += 3 * lf * (bit / rates[i] + 0.1)
			printf "%d\n", 2 * k * t + 300
		}'
	)
}

# What bench.conf holds for every piece, and for base's and the board
# profiles' pieces: the settings a piece's figures depend on besides its
# profile and scale.  A piece measured with other settings is stale.
common_conf() {
	cat <<CONF
COMPARE_BITRATES="${BENCH_COMPARE_BITRATES:?}"
SATURATION_BITRATE=${BENCH_SATURATION_BITRATE:?}
STALL_TRIES=${BENCH_STALL_TRIES:?}
PROBE_FRAMES=${BENCH_PROBE_FRAMES:?}
TX_FRAMES=${BENCH_TX_FRAMES:?}
CONF
}
base_conf() {
	common_conf
	cat <<CONF
FRAMES=${BENCH_FRAMES:?}
FLOOD_FRAMES=${BENCH_FLOOD_FRAMES:?}
CPU_FRAMES=${BENCH_CPU_FRAMES:?}
CPU_BITRATE=125000
RX_BITRATES="${BENCH_BITRATES:?}"
TX_BITRATES="$BENCH_BITRATES"
TIME_SCALE=${BENCH_TIME_SCALE:?}
CONF
}
timed_conf() {
	common_conf
	cat <<CONF
FRAMES=${BENCH_TIMED_FRAMES:?}
FLOOD_FRAMES=${BENCH_TIMED_FLOOD_FRAMES:?}
CPU_FRAMES=${BENCH_TIMED_CPU_FRAMES:?}
RX_BITRATES="${BENCH_TIMED_RX_BITRATES:?}"
TX_BITRATES="${BENCH_TIMED_TX_BITRATES:?}"
TIME_SCALE=${BENCH_TIMED_TIME_SCALE:?}
SPI_TIME=1
CONF
}
