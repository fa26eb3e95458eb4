#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp2510 --sim-param time_scale=10 --sim-param rx_corrupt_every=50 --timeout 500
# vm-kernels: 6.1
# The hardware test kit notices a broken receive path: the simulated
# chips flip a bit of every 50th frame they receive (mcp2510-sim.ko's
# rx_corrupt_every, a test-only fault), which to the kit looks like a
# driver that damages frames.  The kit must fail and its report must say
# which floods carried corrupted frames.  One bit rate is enough.
set -eu
. /lib/rig.sh

umount /sys/kernel/debug
trap 'mount -t debugfs debugfs /sys/kernel/debug' EXIT

status=0
KIT_FRAMES=200 KIT_BITRATES=125000 mcp2510-hwtest -o /tmp/kit can0 can1 || status=$?
[ $status -eq 1 ] || fail "the kit exited with $status on a broken receive path, expected 1"
grep '^check flood-' /tmp/kit/results.txt
for dir in can0 can1; do
	grep -q "^check flood-$dir-125000 fail .*corrupted [1-9]" /tmp/kit/results.txt ||
		fail "the flood from $dir does not report corrupted frames"
done
grep -q '"verdict": "fail"' /tmp/kit/summary.json || fail "the summary's verdict is not fail"
grep -q '"corrupted": [1-9]' /tmp/kit/summary.json || fail "the summary holds no corrupted frames"
echo "hwtest-kit-broken: ok"
