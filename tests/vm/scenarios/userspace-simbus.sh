#!/bin/sh
# vm-run: --nodes 0
# vm-kernels: 6.1
# mcp2510d and mcp2510ctl on two chips of one simulated bus that the
# processes share (sim:CHIP@BUS), with no CAN hardware and no kernel chip
# model: what cansend puts on vcan0 the daemon sends on the bus and
# mcp2510ctl dump prints; what mcp2510ctl send puts on the bus the daemon
# forwards to vcan0, where candump sees it.  Without XDG_RUNTIME_DIR the
# broker listens under /tmp/mcp2510-sim-0; once the daemon has stopped,
# its socket must be gone.
set -eu
. /lib/rig.sh

SOCK=/tmp/mcp2510-sim-0/bus1
unset XDG_RUNTIME_DIR
broker_up() { test -S "$SOCK"; }
sock_gone() { ! test -e "$SOCK"; }

ip link add dev vcan0 type vcan
ip link set vcan0 up
mcp2510d --device sim:d@bus1 --iface vcan0 2>/tmp/d.log &
D_PID=$!
wait_for 10 broker_up || { cat /tmp/d.log; fail "mcp2510d started no broker"; }
[ "$(stat -c %a /tmp/mcp2510-sim-0)" = 700 ] || fail "the socket directory is not 0700"

echo "== vcan0 -> mcp2510d's chip -> the bus -> mcp2510ctl dump"
mcp2510ctl --device sim:c@bus1 dump --count 1 --timeout 20000 >/tmp/ctl.txt &
CTL_PID=$!
nap 1
cansend vcan0 321#22
wait "$CTL_PID" || { cat /tmp/ctl.txt /tmp/d.log; fail "mcp2510ctl dump got nothing"; }
cat /tmp/ctl.txt
grep -q ' 321#22$' /tmp/ctl.txt || fail "dump printed another frame"

echo "== mcp2510ctl send -> the bus -> mcp2510d's chip -> vcan0"
candump -n 1 -T 20000 vcan0 >/tmp/vcan0.txt &
DUMP_PID=$!
nap 1
mcp2510ctl --device sim:c@bus1 --timeout 10000 send 123#11 ||
	{ cat /tmp/d.log; fail "mcp2510ctl send was not acknowledged"; }
wait "$DUMP_PID" || true
cat /tmp/vcan0.txt
grep -q '123 *\[1\] *11' /tmp/vcan0.txt || fail "vcan0 did not carry 123#11"

echo "== the broker leaves with the daemon"
test -S "$SOCK" || fail "the broker left while the daemon used it"
kill -TERM "$D_PID"
wait "$D_PID" || { cat /tmp/d.log; fail "mcp2510d exited with an error"; }
cat /tmp/d.log
wait_for 10 sock_gone || fail "the broker's socket outlived its last user"

ip link del vcan0
echo "userspace-simbus: ok"
