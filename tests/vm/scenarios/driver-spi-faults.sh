#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515
# vm-kernels: rt debug
# SPI faults under mcp2510.ko, from the simulator's per-chip fault files:
# failed SPI messages (spi_errors) and corrupted MISO (spi_corrupt) while
# the interface opens, while a frame is loaded, while an interrupt is
# handled and while the interface closes; then a power loss of the chip.
# The driver says what went wrong in the kernel log, never crashes or
# leaks (vm-run's checks, kmemleak on the debug kernel), and at the latest
# after the next ifdown/ifup the interface works again.  The MCP2515 is
# used because its SPI instructions (READ RX BUFFER, LOAD TX BUFFER, READ
# STATUS) give more paths to fail than the MCP2510's, which the other
# scenarios use.
set -eu
. /lib/rig.sh

show() { ip -details -statistics link show "$1"; }

# log_mark: remember the end of the kernel log; log_since PATTERN: a line
# written after the mark matches PATTERN.
log_mark() { LOG_LINES=$(dmesg | wc -l); }
log_since() {
	dmesg | tail -n +$((LOG_LINES + 1)) | grep -E "$1"
}

# faults_done CHIP: every SPI failure armed for CHIP has happened.
faults_done() { [ "$(cat "$SIM/chip$1/spi_errors")" -eq 0 ]; }

# crosses FROM TO ID: a new frame from FROM reaches TO.
crosses() {
	dump_start "$2,$3:7FF" 1 /tmp/x.txt
	cansend "$1" "$3#$(printf '%02X' "$SEQ")"
	dump_wait
	grep -q "$3 *\[1\] *$(printf '%02X' "$SEQ")" /tmp/x.txt
	_ok=$?
	SEQ=$((SEQ + 1))
	return $_ok
}
SEQ=1

# works: after ifdown/ifup of both, frames cross both ways.
works() {
	ip link set can0 down
	ip link set can1 down
	can_up can0 500000
	can_up can1 500000
	crosses can0 can1 101 || { show can0; show can1; fail "can0 -> can1 broken after $1"; }
	crosses can1 can0 102 || { show can0; show can1; fail "can1 -> can0 broken after $1"; }
}

ip link set can0 type can bitrate 500000
ip link set can1 type can bitrate 500000

echo "== spi_errors while opening"
log_mark
echo 1000 >"$SIM/chip0/spi_errors"
if ip link set can0 up 2>/dev/null; then
	fail "can0 came up although its chip did not answer"
fi
log_since 'can0: cannot start the chip' || fail "no log line for the failed open"
[ "$(cat "$SIM/chip0/spi_errors")" -lt 1000 ] || fail "the fault was never hit"
echo 0 >"$SIM/chip0/spi_errors"
ip link set can0 up || fail "can0 does not come up once SPI works"
can_up can1 500000
crosses can0 can1 110 || fail "no traffic after the failed open"

echo "== spi_errors while loading a frame"
tx_dropped=$(if_stat can0 tx_dropped)
# The driver looks at an idle chip once a second (two SPI transfers) and
# shrugs off a failed look: arm a few failures, so that the load meets
# one whatever the timing (cansend may take a second to start on the
# debug kernel).
echo 5 >"$SIM/chip0/spi_errors"
cansend can0 120#01
wait_for 15 faults_done 0 || fail "the armed SPI failures were never hit"
[ "$(if_stat can0 tx_dropped)" -eq $((tx_dropped + 1)) ] ||
	fail "can0 tx_dropped $(if_stat can0 tx_dropped), expected $((tx_dropped + 1))"
crosses can0 can1 121 || fail "can0 stuck after a failed load"

echo "== spi_errors while handling an interrupt"
log_mark
# can1's interrupt passes fail while failures are left; INT stays
# asserted, so the frame is fetched by the first pass that works.  Armed
# once candump listens, which takes seconds on the debug kernel.
dump_start can1,130:7FF 1 /tmp/irq.txt
echo 5 >"$SIM/chip1/spi_errors"
cansend can0 130#AA
dump_wait
grep -q '130 *\[1\] *AA' /tmp/irq.txt || fail "the frame behind a failed interrupt pass was lost"
wait_for 15 faults_done 1 || fail "the armed SPI failures were never hit"
log_since 'can1: interrupt handling failed' || {
	dmesg | tail -n 5
	fail "no log line for the failed interrupt pass (chip1: $(sim_counter 1 spi_failed) failed)"
}
crosses can0 can1 131 || fail "can1 stuck after a failed interrupt pass"

echo "== spi_errors while closing"
echo 3 >"$SIM/chip0/spi_errors"
ip link set can0 down || fail "ifdown failed"
echo 0 >"$SIM/chip0/spi_errors"
works "a failed close"

echo "== spi_corrupt in each phase"
echo 2 >"$SIM/chip0/spi_corrupt"
ip link set can0 down
ip link set can0 up 2>/dev/null || echo "can0 refused to open on corrupted replies"
echo 0 >"$SIM/chip0/spi_corrupt"
works "corruption while opening"
echo 1 >"$SIM/chip0/spi_corrupt"
cansend can0 140#01
sleep 1
echo 0 >"$SIM/chip0/spi_corrupt"
works "corruption while loading"
echo 1 >"$SIM/chip1/spi_corrupt"
cansend can0 150#01
sleep 1
echo 0 >"$SIM/chip1/spi_corrupt"
works "corruption in an interrupt pass"
echo 2 >"$SIM/chip0/spi_corrupt"
ip link set can0 down
echo 0 >"$SIM/chip0/spi_corrupt"
works "corruption while closing"

echo "== power loss"
log_mark
echo 0 >"$SIM/chip0/power"
cansend can0 160#01 || true
cansend can0 161#02 || true
wait_for 10 log_since 'can0:' || { dmesg | tail; fail "the driver logged nothing about the dead chip"; }
log_since 'can0:'
echo 1 >"$SIM/chip0/power"
works "a power loss"
for chip in 0 1; do
	[ "$(sim_counter $chip spi_mode_errors)" -eq 0 ] || fail "chip$chip: wrong SPI mode"
done
ip link set can0 down
ip link set can1 down
echo "driver-spi-faults: ok"
