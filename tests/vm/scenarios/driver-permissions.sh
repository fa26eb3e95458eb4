#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-kernels: 6.12
# The hardware-filter files in /sys/class/net/can0/mcp2510/ are readable by
# anyone and writable only with CAP_NET_ADMIN.  Root's shell with every
# capability but CAP_NET_ADMIN (util-linux setpriv shrinks the bounding
# set, so exec cannot give it back) gets EPERM on each file and the setting
# stays as it was; a shell holding CAP_NET_ADMIN and nothing else changes
# every file.  The interface stays down, where writes are otherwise allowed.
set -eu
. /lib/rig.sh
f=/sys/class/net/can0/mcp2510
[ -d "$f" ] || fail "no $f"

CAP_NET_ADMIN=12

# has_cap CAPS_HEX BIT: the capability set CAPS_HEX holds bit BIT.
has_cap() {
	[ $(((0x$1 >> $2) & 1)) -eq 1 ]
}

# A shell command's effective capabilities, as /proc shows them.
cap_eff() {
	setpriv "$@" sh -c 'sed -n "s/^CapEff:\t//p" /proc/self/status'
}

without=--bounding-set=-net_admin
only=--bounding-set=-all,+net_admin

# Prove the two shells are what this scenario claims they are.
eff=$(cap_eff $without)
! has_cap "$eff" $CAP_NET_ADMIN || fail "setpriv $without kept CAP_NET_ADMIN ($eff)"
has_cap "$eff" 1 && has_cap "$eff" 21 ||
	fail "setpriv $without dropped more than CAP_NET_ADMIN ($eff)"
eff=$(cap_eff $only)
[ $((0x$eff)) -eq $((1 << CAP_NET_ADMIN)) ] ||
	fail "setpriv $only left capabilities $eff"

# A valid value other than the default, for each file.
new_value() {
	case $1 in
	mask*) echo 7f0 ;;
	filter*) echo 5a5 ;;
	rxm*) echo any ;;
	rollover) echo 0 ;;
	esac
}

checked=0
for name in mask0 mask1 filter0 filter1 filter2 filter3 filter4 filter5 \
	rxm0 rxm1 rollover; do
	file=$f/$name
	[ "$(stat -c %a "$file")" = 644 ] || fail "$name has mode $(stat -c %a "$file")"
	before=$(setpriv --bounding-set=-all cat "$file") ||
		fail "$name is not readable without capabilities"
	value=$(new_value "$name")

	if setpriv $without sh -c "echo $value >$file" 2>/tmp/err; then
		fail "$name: written without CAP_NET_ADMIN"
	fi
	grep -q 'Operation not permitted' /tmp/err ||
		{ cat /tmp/err >&2; fail "$name: refused, but not with EPERM"; }
	[ "$(cat "$file")" = "$before" ] ||
		fail "$name changed to '$(cat "$file")' by a refused write"

	setpriv $only sh -c "echo $value >$file" ||
		fail "$name: not written with CAP_NET_ADMIN"
	after=$(cat "$file")
	[ "$after" != "$before" ] || fail "$name: still '$before' after writing $value"
	echo "$name: '$before' kept without CAP_NET_ADMIN, '$after' with it"

	echo "$before" >"$file"
	[ "$(cat "$file")" = "$before" ] || fail "$name: default '$before' not restored"
	checked=$((checked + 1))
done
[ "$checked" -eq 11 ] || fail "checked $checked files, expected 11"

# The defaults restored, can1 still hears everything can0 sends.
can_up can0 500000
can_up can1 500000
dump_start can1 1 /tmp/rx.txt
cansend can0 5A5#01
dump_wait
expect_lines /tmp/rx.txt 1
echo "driver-permissions: ok"
