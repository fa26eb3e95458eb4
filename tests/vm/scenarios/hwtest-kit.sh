#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510 --sim-param time_scale=10 --timeout 500
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x --sim-param time_scale=10 --timeout 500
# vm-kernels: 6.1
# vm-every-line: yes
# The hardware test kit as a board runs it: mcp2510-hwtest, installed as
# make install-userspace installs it, on can0 and can1 of two simulated
# chips, with the simulator's debugfs unmounted so that the kit sees
# nothing a board would not have.  Both drivers on the oldest and the
# newest kernel: mainline mcp251x is the kernel's own.  Every check passes or is reported as
# not run or not offered, the report names the driver bound, and the
# JSON summary holds the floods.  Mainline mcp251x fails one check, as it
# should: with restart-ms set it never tells can-dev of a bus-off, so
# nothing is reported or restarted (docs/differences-from-mcp251x.md).
# It may fail a flood too, by reordering alone: it takes RXB0 before RXB1
# without asking which holds the older frame, which a frame arriving in
# RXB0 while RXB1 waits turns around; how often depends on timing.
# Floods are short here (KIT_FRAMES); a board runs the full counts.  Bus time runs 10 times slower than real
# time, so 1 Mbit/s is within what a TCG guest keeps up with.
set -eu
. /lib/rig.sh

umount /sys/kernel/debug
trap 'mount -t debugfs debugfs /sys/kernel/debug' EXIT
[ ! -e "$SIM" ] || fail "the simulator's debugfs is still visible"

expected='' want_status=0 verdict=pass
[ "$VM_DRIVER" = mcp2510 ] || expected='restart-ms-reported ' want_status=1 verdict=fail

frames=200 status=0
KIT_FRAMES=$frames KIT_TRANSITS=50 mcp2510-hwtest -o /tmp/kit can0 can1 || status=$?
cat /tmp/kit/summary.json
failed=$(sed -n 's/^check \([^ ]*\) fail .*/\1/p' /tmp/kit/results.txt | grep -v '^flood-' | tr '\n' ' ')
# The series of upstream/mcp251x (make upstream-check's module) keeps
# the order (0001).
if [ "$VM_DRIVER" = mcp2510 ] || [ -n "$VM_MCP251X_KO" ]; then
	! grep -q '^check flood-[^ ]* fail' /tmp/kit/results.txt || fail "a flood failed"
else
	! grep '^check flood-[^ ]* fail' /tmp/kit/results.txt | grep -v "duplicated 0, reordered [1-9][0-9]*, corrupted 0, sent $frames\$" ||
		fail "a flood failed with more than reordering"
fi
[ "$failed" = "$expected" ] || fail "failed checks: '$failed', expected '$expected'"
[ $status -eq $want_status ] || fail "the kit exited with $status, expected $want_status"
grep -q "^  \"$VM_DRIVER\": {" /tmp/kit/summary.json || fail "the report does not name $VM_DRIVER"
grep -q "\"verdict\": \"$verdict\"" /tmp/kit/summary.json || fail "the summary's verdict is not $verdict"
[ "$(grep -c '^flood ' /tmp/kit/results.txt)" -eq 6 ] || fail "not six floods in the results"
[ "$(grep -c '^transit .* lost=0 damaged=0 ' /tmp/kit/results.txt)" -eq 3 ] ||
	fail "not three latency runs without loss in the results"
grep -q '"latency_us": {"125000": {"median": [0-9]' /tmp/kit/summary.json ||
	fail "the summary has no latency"
echo "hwtest-kit: ok"
