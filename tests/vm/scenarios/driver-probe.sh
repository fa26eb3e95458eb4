#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-run: --nodes 2 --variant mcp2515
# vm-run: --nodes 2 --variant mcp25625
# vm-kernels: rt debug
# What mcp2510.ko shows once it has probed two simulated chips: the
# binding and module aliases, the CAN core's view (bit-timing limits,
# supported control modes: one-shot only on the MCP2515 and MCP25625), ethtool (identity, register dump: the chip
# sleeps while the interface is down), and the hardware-filter files with
# their rules (defaults, parsing, EINVAL keeps the old value, EBUSY while up).
set -eu
. /lib/rig.sh

# Binding and module aliases.
for dev in can0 can1; do
	drv=$(basename "$(readlink "/sys/class/net/$dev/device/driver")")
	[ "$drv" = mcp2510 ] || fail "$dev is bound to '$drv'"
done
aliases=$(modinfo -F alias /opt/mcp2510/modules/mcp2510.ko)
echo "$aliases"
for alias in spi:mcp2510 spi:mcp2515 spi:mcp25625 \
	'of:N\*T\*Cmicrochip,mcp2510' 'of:N\*T\*Cmicrochip,mcp2515' \
	'of:N\*T\*Cmicrochip,mcp25625'; do
	echo "$aliases" | grep -qx "$alias" || fail "no module alias $alias"
done

# The CAN core sees the chip's bit-timing limits and clock.
details=$(ip -details link show can0)
echo "$details"
echo "$details" | grep -q 'mcp2510: tseg1 3..16 tseg2 2..8 sjw 1..4 brp 1..64 brp_inc 1' ||
	echo "$details" | grep -q 'mcp2510: tseg1 3..16 tseg2 2..8 sjw 1..4 brp 1..64 brp-inc 1' ||
	fail "bit-timing limits not reported"
echo "$details" | grep -q 'state STOPPED' || fail "can0 not STOPPED while down"

# Supported control modes; one-shot is an MCP2515 feature.
for mode in "loopback on" "listen-only on" "triple-sampling on" "berr-reporting on"; do
	# shellcheck disable=SC2086
	ip link set can0 type can bitrate 125000 $mode || fail "refused $mode"
	ip link set can0 type can $(echo "$mode" | sed 's/ on$/ off/')
done
if [ "$VM_VARIANT" = mcp2510 ]; then
	if ip link set can0 type can bitrate 125000 one-shot on 2>/dev/null; then
		fail "an MCP2510 accepted one-shot"
	fi
else
	ip link set can0 type can bitrate 125000 one-shot on || fail "refused one-shot"
	ip link set can0 type can one-shot off
fi

# The MTU is classical CAN's, down or up: can_change_mtu() refuses CAN FD's
# where it exists, can-dev's MTU range (6.18 on) everything else.
mtu() { cat /sys/class/net/can0/mtu; }
for state in down up; do
	[ "$state" = down ] || ip link set can0 up type can bitrate 125000
	! ip link set can0 mtu 72 2>/dev/null || fail "MTU 72 accepted while $state"
	ip link set can0 mtu 16 || fail "MTU 16 refused while $state"
	[ "$(mtu)" -eq 16 ] || fail "MTU $(mtu) while $state"
done
ip link set can0 down

# ethtool: identity and the 128-byte register dump.
ethtool -i can0 | tee /tmp/drvinfo
grep -qx 'driver: mcp2510' /tmp/drvinfo || fail "ethtool driver name"
grep -qx "bus-info: $(basename "$(readlink /sys/class/net/can0/device)")" /tmp/drvinfo || fail "ethtool bus-info"
ethtool -d can0 raw on >/tmp/regs
[ "$(wc -c </tmp/regs)" -eq 128 ] || fail "register dump is $(wc -c </tmp/regs) bytes"
# canstat ADDR: CANSTAT.OPMOD (bits 7-5) from a fresh dump.
opmod() {
	ethtool -d "$1" raw on | od -An -tu1 -v -j 14 -N 1 | awk '{ print int($1 / 32) }'
}
[ "$(opmod can0)" -eq 1 ] || fail "chip not asleep while can0 is down (OPMOD $(opmod can0))"
ip link set can0 up type can bitrate 500000
[ "$(opmod can0)" -eq 0 ] || fail "chip not in normal mode while can0 is up (OPMOD $(opmod can0))"
ip link set can0 down
[ "$(opmod can0)" -eq 1 ] || fail "chip not asleep again after down"

# Hardware filters: defaults accept everything.
f=/sys/class/net/can0/mcp2510
names="mask0 mask1 filter0 filter1 filter2 filter3 filter4 filter5 rxm0 rxm1 rollover"
for name in $names; do
	[ -f "$f/$name" ] || fail "no $f/$name"
	eval "default_$name=\$(cat $f/$name)"
	echo "$name: $(cat $f/$name)"
done
[ "$(cat $f/mask0)" = 0 ] && [ "$(cat $f/mask1)" = 0 ] || fail "masks not 0 by default"
[ "$(cat $f/rxm0)" = filtered ] && [ "$(cat $f/rxm1)" = filtered ] || fail "rxm defaults"
[ "$(cat $f/rollover)" = 1 ] || fail "rollover default"

# writes ATTR VALUE EXPECTED: VALUE is accepted and reads back as EXPECTED.
writes() {
	echo "$2" >"$f/$1" || fail "$1 refused '$2'"
	[ "$(cat "$f/$1")" = "$3" ] || fail "$1 reads '$(cat "$f/$1")' after '$2'"
}
# refuses ATTR VALUE ERROR: VALUE fails with ERROR and the old value stays.
refuses() {
	old=$(cat "$f/$1")
	if err=$(sh -c "echo '$2' >'$f/$1'" 2>&1); then
		fail "$1 accepted '$2'"
	fi
	echo "$err" | grep -q "$3" || fail "$1 '$2': '$err', expected $3"
	[ "$(cat "$f/$1")" = "$old" ] || fail "$1 changed by a refused write"
}
writes mask0 7ff 7ff
writes mask1 1fffffffx 1fffffffx
writes filter0 123 123
writes filter5 1abcdefx 1abcdefx
writes rxm0 std std
writes rxm1 any any
writes rollover 0 0
refuses filter1 800 'Invalid argument'
refuses filter2 20000000x 'Invalid argument'
refuses mask0 xyz 'Invalid argument'
refuses rxm0 all 'Invalid argument'
refuses rollover 2 'Invalid argument'
ip link set can0 up type can bitrate 125000
refuses mask0 0 'busy'
ip link set can0 down
# Back to the defaults.
for name in $names; do
	eval "value=\$default_$name"
	writes "$name" "$value" "$value"
done
echo "driver-probe: ok"
