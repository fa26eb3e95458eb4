#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510 --sim-param time_scale=50
# vm-run: --nodes 2 --variant mcp2515 --sim-param time_scale=50
# vm-kernels: rt debug
# Error states and bus-off in mcp2510.ko, with berr-reporting on.  can0
# sends a frame nobody acknowledges: each ACK error costs it 8 in TEC until
# it is error-passive, where an unacknowledged transmitter stays.  Then the
# simulator destroys its frames until it is bus-off.  Each state comes with
# an error frame and is counted once, bus errors are reported.  Bus time
# runs 50 times slower than real time so that, at 125 kbit/s, the guest
# sees error-warning before the next errors push TEC past it.  With
# restart-ms 0 can0 stays bus-off until "ip link set can0 type can
# restart"; with restart-ms it restarts by itself; afterwards frames flow
# again between can0 and can1.
set -eu
. /lib/rig.sh

show() { ip -details -statistics link show "$1"; }

# The "re-started bus-errors arbit-lost error-warn error-pass bus-off"
# numbers of ip -details -statistics, as "name=value" words.
can_stats() {
	show "$1" | awk '/re-started bus-errors/ { getline; print "restarts=" $1,
		"bus_errors=" $2, "arbit_lost=" $3, "warn=" $4, "passive=" $5,
		"bus_off=" $6 }'
}
can_stat() { can_stats "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"; }

CAN_ERR_CRTL=0x4 CAN_ERR_BUSOFF=0x40 CAN_ERR_BUSERROR=0x80
CAN_ERR_CRTL_TX_WARNING=0x08 CAN_ERR_CRTL_TX_PASSIVE=0x20

restarted() { [ "$(can_stat can0 restarts)" -ge 1 ]; }

echo "== error-passive without ACK, bus-off under bus errors, manual restart"
can_up can0 125000 berr-reporting on
can_up can1 125000
errors_start can0 /tmp/err0.txt
echo 1 >"$SIM/no_ack"
cansend can0 123#11
wait_for 30 can_state_is can0 ERROR-PASSIVE || { show can0; fail "can0 never went error-passive"; }
echo 1000 >"$SIM/bus_errors"
wait_for 30 can_state_is can0 BUS-OFF || { show can0; fail "can0 never went bus-off"; }
echo 0 >"$SIM/bus_errors"
echo 0 >"$SIM/no_ack"
errors_stop
show can0
can_stats can0
[ "$(can_stat can0 bus_errors)" -gt 0 ] || fail "no bus errors counted"
[ "$(can_stat can0 warn)" -eq 1 ] || fail "error-warning not counted once"
[ "$(can_stat can0 passive)" -eq 1 ] || fail "error-passive not counted once"
[ "$(can_stat can0 bus_off)" -eq 1 ] || fail "bus-off not counted once"
error_seen /tmp/err0.txt $CAN_ERR_BUSERROR || { cat /tmp/err0.txt; fail "no bus-error frame"; }
error_seen /tmp/err0.txt $CAN_ERR_CRTL $CAN_ERR_CRTL_TX_WARNING ||
	{ cat /tmp/err0.txt; fail "no error-warning frame"; }
error_seen /tmp/err0.txt $CAN_ERR_CRTL $CAN_ERR_CRTL_TX_PASSIVE ||
	{ cat /tmp/err0.txt; fail "no error-passive frame"; }
error_seen /tmp/err0.txt $CAN_ERR_BUSOFF || { cat /tmp/err0.txt; fail "no bus-off frame"; }
# restart-ms 0: it stays off the bus.
sleep 1
can_state_is can0 BUS-OFF || fail "can0 left bus-off by itself"
ip link set can0 type can restart || fail "manual restart refused"
can_state_is can0 ERROR-ACTIVE || { show can0; fail "can0 not error-active after restart"; }
[ "$(can_stat can0 restarts)" -eq 1 ] || fail "restart not counted"

echo "== bus-off with restart-ms"
ip link set can0 down
can_up can0 125000 restart-ms 100
echo 1000 >"$SIM/bus_errors"
cansend can0 123#22
wait_for 30 restarted || { show can0; fail "no automatic restart after bus-off"; }
echo 0 >"$SIM/bus_errors"
ip link set can0 down
ip link set can1 down

echo "== traffic again"
can_up can0 125000
can_up can1 125000
dump_start can1 1 /tmp/one.txt
cansend can0 456#C0FFEE
dump_wait
grep -q '456 *\[3\] *C0 FF EE' /tmp/one.txt || fail "no traffic after the errors"
can_state_is can0 ERROR-ACTIVE || fail "can0 not error-active after clean traffic"
show can0
show can1
echo "driver-busoff: ok"
