#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# Reproducer of upstream/mcp251x/0002 (listen-only): in listen-only mode
# the chip's RXM = 11 also takes a frame an error frame destroyed
# (DS21801 10.3; the model loads it as sent), and its sender sends it
# again.  The phantom node's 324#BEEF is destroyed once by an injected bus
# error, then a standard and an extended frame follow; can1, listen-only,
# must get each of the three once.  Mainline mcp251x programs RXM = 11 in
# every mode and gets 324#BEEF twice.
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

mcp251x_under_test

can_up can0 125000
can_up can1 125000 listen-only on
ip -details link show can1 | grep -q LISTEN-ONLY || fail "can1 is not listen-only"
echo clear >"$SIM/monitor"
echo 1 >"$SIM/bus_errors"
resent() { grep -q 'phantom 324#BEEF .* ok$' "$SIM/monitor"; }
dump_start can1 4 /tmp/lo.txt -T 3000
echo 324#BEEF >"$SIM/inject"
wait_for 10 resent || fail "the phantom's 324#BEEF was not sent again"
# Apart, so that no frame is lost to an overflow.
nap 0.2
echo 325#01 >"$SIM/inject"
nap 0.2
echo 1ABCDEF0#0203 >"$SIM/inject"
dump_wait
echo off >"$SIM/phantom"
cat "$SIM/monitor"
cat /tmp/lo.txt
grep -q 'phantom 324#BEEF .* error-' "$SIM/monitor" ||
	fail "the phantom's first 324#BEEF was not destroyed"
beef=$(grep -c '324 *\[2\] *BE EF$' /tmp/lo.txt || true)
std=$(grep -c '325 *\[1\] *01$' /tmp/lo.txt || true)
ext=$(grep -c '1ABCDEF0 *\[2\] *02 03$' /tmp/lo.txt || true)
ip -statistics link show can1
ip link set can0 down
ip link set can1 down

if [ -n "$ko" ]; then
	expect_eq "$under_test, listen-only: copies of the destroyed and resent 324#BEEF" "$beef" 1
else
	[ "$beef" -eq 2 ] ||
		fail "$under_test took 324#BEEF $beef times, not twice: the kernel has the fix"
fi
expect_eq "can1's standard frames 325#01" "$std" 1
expect_eq "can1's extended frames 1ABCDEF0#0203" "$ext" 1
echo "upstream-listen-only: $under_test took the destroyed frame $beef time(s), the others once"
