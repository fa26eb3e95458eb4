#!/bin/sh
# vm-run: --nodes 1 --variant mcp2510 --sim-param time_scale=200 --timeout 600
# vm-run: --nodes 1 --variant mcp2515 --sim-param time_scale=200 --timeout 600
# vm-kernels: 6.1
# SPI messages are not atomic (docs/simulator.md, "SPI"): with the pi
# board profile at twice its costs, bus time runs on between the
# chip-select periods of one message, so phantom frames land between the
# release of a receive buffer and the READ STATUS after it in the same
# message (chip0/counters spi_gap_frames).  The receive order holds all
# the same: every frame arrives in order, and one missing was dropped by
# the chip with its buffers full and the overflow reported.  Bus time runs
# 200 times slower than real time, as in the bench's board profiles.
set -eu
. /lib/rig.sh

FRAMES=600
BITRATE=500000

flood_done() { [ "$(cat "$SIM/flood")" -eq 0 ]; }

# in_order FILE SENT: the flood's sequence numbers (the first four data
# bytes, little-endian) in candump FILE rise, none at or past SENT.
in_order() {
	awk -v n="$2" '
		function hex(s,  i, v) {
			v = 0
			for (i = 1; i <= length(s); i++)
				v = v * 16 + index("0123456789ABCDEF", substr(s, i, 1)) - 1
			return v
		}
		{
			seq = hex($7 $6 $5 $4)
			if (NR > 1 && seq <= prev) {
				printf "frame %d: seq %d after %d\n", NR, seq, prev | "cat >&2"
				exit 1
			}
			prev = seq
		}
		END { if (prev >= n) exit 1 }' "$1"
}

echo pi >"$SIM/spi_profile"
echo 200 >"$SIM/spi_cost_scale_pct"
echo 1 >"$SIM/spi_seed"
[ "$(cat "$SIM/spi_time")" -eq 1 ] || fail "spi_profile pi left SPI time off"
can_up can0 "$BITRATE"
echo 0 >"$SIM/chip0/counters"
over_before=$(if_stat can0 rx_over_errors)

dump_start can0 "$FRAMES" /tmp/gap.txt -T 60000
echo "$FRAMES 100#0000000000000000 $BITRATE" >"$SIM/flood"
wait_for 300 flood_done || fail "the flood never ended"
sleep 2
kill "$DUMP_PID" 2>/dev/null || true
dump_wait

got=$(wc -l </tmp/gap.txt)
gap=$(sim_counter 0 spi_gap_frames)
ovf=$(sim_counter 0 overflows)
echo "$got of $FRAMES frames, $gap stored between two periods of a message, $ovf overflows"
[ "$gap" -gt 0 ] || fail "no frame landed between the periods of a message"
in_order /tmp/gap.txt "$FRAMES" || fail "frames out of order"
[ $((got + ovf)) -eq "$FRAMES" ] || fail "$got received and $ovf dropped of $FRAMES"
if [ "$ovf" -gt 0 ]; then
	[ "$(if_stat can0 rx_over_errors)" -gt "$over_before" ] ||
		fail "the chip dropped $ovf frames, the driver reported none"
fi
echo none >"$SIM/spi_profile"
[ "$(cat "$SIM/spi_time")" -eq 0 ] || fail "spi_profile none left SPI time on"
ip link set can0 down
echo "sim-spi-gap: ok"
