#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param time_scale=200
# vm-kernels: 6.1
# SPI time (docs/simulator.md): off by default, when the driver's SPI
# messages cost no bus time; on, each costs at least its host overhead on
# the one SPI controller, and chipN/counters say how much (spi_busy_ns).
# Bad values are refused.  Frames from the phantom all reach the stack
# either way.  The controller sleeps until CS rises, and under TCG a
# guest's sleep overshoots by milliseconds: bus time runs 200 times slower,
# so that the overshoot stays small next to a frame.
set -eu
. /lib/rig.sh

FRAMES=20
MSG_NS=10000
CS_NS=100

flood_done() { [ "$(cat "$SIM/flood")" -eq 0 ]; }

# receive: the phantom sends $FRAMES frames to can1; all must arrive.
receive() {
	echo 0 >"$SIM/chip1/counters"
	_before=$(if_stat can1 rx_packets)
	echo "$FRAMES 100#0000000000000000 125000" >"$SIM/flood"
	wait_for 60 flood_done || fail "the flood never ended"
	sleep 1
	_got=$(($(if_stat can1 rx_packets) - _before))
	[ "$_got" -eq "$FRAMES" ] || fail "can1 received $_got of $FRAMES frames"
}

refused() {
	! { echo "$2" >"$SIM/$1"; } 2>/dev/null || fail "$1 took $2"
}

[ "$(cat "$SIM/spi_time")" -eq 0 ] || fail "SPI time is on by default"
refused spi_time 2
refused spi_msg_ns 4294967296
refused irq_latency_ns -1
[ -n "$(sim_counter 1 clock_stalls)" ] || fail "no clock_stalls counter"

can_up can1 125000

echo "== SPI time off"
receive
busy=$(sim_counter 1 spi_busy_ns)
[ "$busy" -eq 0 ] || fail "SPI time off, yet spi_busy_ns is $busy"

echo "== SPI time on"
echo $MSG_NS >"$SIM/spi_msg_ns"
echo $CS_NS >"$SIM/spi_cs_setup_ns"
echo $CS_NS >"$SIM/spi_cs_hold_ns"
echo 20000 >"$SIM/irq_latency_ns"
echo 1 >"$SIM/spi_time"
receive
busy=$(sim_counter 1 spi_busy_ns)
periods=$(sim_counter 1 spi_transfers)
echo "spi_busy_ns $busy for $periods CS periods, spi_late_ns $(sim_counter 1 spi_late_ns)"
# every frame takes at least one message, every period its setup and hold
[ "$busy" -ge $((FRAMES * MSG_NS)) ] || fail "spi_busy_ns $busy below $FRAMES messages"
[ "$busy" -ge $((periods * 2 * CS_NS)) ] || fail "spi_busy_ns $busy below $periods periods"
echo 0 >"$SIM/spi_time"

echo "== a board profile and its cost scale"
[ "$(cat "$SIM/spi_profile")" = none ] || fail "a profile is set by default"
refused spi_profile nosuch
refused spi_cost_scale_pct 5
echo pi >"$SIM/spi_profile"
[ "$(cat "$SIM/spi_time")" -eq 1 ] || fail "spi_profile pi left SPI time off"
xfer=$(cat "$SIM/spi_xfer_ns")
[ "$xfer" -gt 0 ] || fail "spi_profile pi has no per-transfer cost"
echo 200 >"$SIM/spi_cost_scale_pct"
[ "$(cat "$SIM/spi_xfer_ns")" -eq $((2 * xfer)) ] || fail "the cost scale did not double spi_xfer_ns"
receive
busy=$(sim_counter 1 spi_busy_ns)
periods=$(sim_counter 1 spi_transfers)
echo "pi x2: spi_busy_ns $busy for $periods CS periods"
# every period pays at least one transfer's set-up
[ "$busy" -ge $((periods * 2 * xfer)) ] || fail "spi_busy_ns $busy below $periods transfers"
echo none >"$SIM/spi_profile"
[ "$(cat "$SIM/spi_time")" -eq 0 ] || fail "spi_profile none left SPI time on"
echo 100 >"$SIM/spi_cost_scale_pct"
ip link set can1 down

echo "sim-spi-time: ok"
