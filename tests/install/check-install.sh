#!/bin/sh
# Check what a packager and a board owner see of make modules, install,
# uninstall and dkms.conf (run by `make install-check`).
#
# usage: tests/install/check-install.sh KDIR...   (kernel build trees)
#
# - make modules with KDIR unset on a machine without the running kernel's
#   build tree (played by MODULES_KDIR_DEFAULT and MODULES_RELEASE) fails,
#   names the headers package of that kernel's distribution, and runs no
#   apt-get (stubs in PATH record any call);
# - for each KDIR: make install and install-userspace staged under a
#   temporary DESTDIR put the module and the tools there without depmod's
#   indexes, and make uninstall with the same DESTDIR leaves nothing;
# - dkms.conf's BUILD_EXCLUSIVE_CONFIG, read the way dkms reads it (each
#   CONFIG_ must be =y or =m in the kernel's .config), lets each KDIR build
#   and excludes a kernel without rx-offload.
set -eu

[ $# -ge 1 ] || { echo "usage: $0 KDIR..." >&2; exit 2; }
top=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/mcp2510-install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

. "$top/tests/lib/tally.sh"
mk() { make --no-print-directory -C "$top" "$@"; }

echo "install-check: make modules without the running kernel's headers"
mkdir -p "$tmp/stub"
for tool in apt-get apt sudo; do
	printf '#!/bin/sh\necho "%s $*" >>"%s/stub/calls"\nexit 1\n' \
		"$tool" "$tmp" >"$tmp/stub/$tool"
	chmod +x "$tmp/stub/$tool"
done
for case in "6.1.0-31-arm64 linux-headers-6.1.0-31-arm64" \
	"6.12.25+rpt-rpi-2712 linux-headers-rpi-2712" \
	"6.6.51+rpt-rpi-v8 linux-headers-rpi-v8" \
	"6.1.21-v7l+ raspberrypi-kernel-headers"; do
	release=${case% *}
	package=${case#* }
	rm -f "$tmp/stub/calls"
	if env -u KDIR PATH="$tmp/stub:$PATH" make --no-print-directory -C "$top" modules \
		MODULES_RELEASE="$release" MODULES_KDIR_DEFAULT="$tmp/no-such/build" \
		>"$tmp/out" 2>&1; then
		cat "$tmp/out"
		fail "$release: make modules succeeded without a build tree"
	elif [ -e "$tmp/stub/calls" ]; then
		cat "$tmp/out" "$tmp/stub/calls"
		fail "$release: make modules ran a package manager"
	elif ! grep -q "package $package\$" "$tmp/out"; then
		cat "$tmp/out"
		fail "$release: make modules does not name $package"
	else
		pass "$release: stops, names $package, installs nothing"
	fi
done

echo "install-check: staged install, then uninstall"
for kdir; do
	release=$(sed -n 's/.*UTS_RELEASE "\(.*\)"/\1/p' "$kdir/include/generated/utsrelease.h")
	stage="$tmp/stage-$release"
	mkdir -p "$stage"
	# A staged install must not touch the live system's modules.
	live=$(ls -l --full-time "/lib/modules/$release" "/lib/modules/$release/extra" 2>&1 || :)
	if ! mk install KDIR="$kdir" DESTDIR="$stage" >"$tmp/out" 2>&1 ||
		! mk install-userspace DESTDIR="$stage" >>"$tmp/out" 2>&1; then
		cat "$tmp/out"
		fail "$release: staged install"
		continue
	fi
	ls "$stage/lib/modules/$release/extra/mcp2510.ko"* >/dev/null 2>&1 &&
		pass "$release: mcp2510.ko in $(cd "$stage" && echo lib/modules/"$release"/extra/mcp2510.ko*)" ||
		{ find "$stage"; fail "$release: no mcp2510.ko under lib/modules/$release/extra"; }
	if find "$stage" -name 'modules.*' | grep -q .; then
		find "$stage" -name 'modules.*'
		fail "$release: staged install wrote depmod indexes"
	else
		pass "$release: no depmod indexes in the staging directory"
	fi
	if [ "$live" != "$(ls -l --full-time "/lib/modules/$release" "/lib/modules/$release/extra" 2>&1 || :)" ]; then
		fail "$release: make install DESTDIR=... changed /lib/modules/$release"
	fi
	[ -x "$stage/usr/local/bin/mcp2510ctl" ] && pass "$release: userspace installed" ||
		fail "$release: no usr/local/bin/mcp2510ctl"
	if ! mk uninstall KDIR="$kdir" DESTDIR="$stage" >"$tmp/out" 2>&1; then
		cat "$tmp/out"
		fail "$release: make uninstall"
	elif [ -n "$(find "$stage" -mindepth 1 | head -n 1)" ]; then
		find "$stage" -mindepth 1
		fail "$release: make uninstall left the above"
	else
		pass "$release: make uninstall leaves the staging directory empty"
	fi
done

echo "install-check: dkms.conf BUILD_EXCLUSIVE_CONFIG"
configs=$(sed -n 's/^BUILD_EXCLUSIVE_CONFIG="\(.*\)"$/\1/p' "$top/dkms.conf")
# excluded CONFIG: 0 when dkms would skip the kernel whose .config is CONFIG
excluded() {
	for c in $configs; do
		case $c in
		!*) grep -qE "^${c#!}=[ym]" "$1" && return 0 ;;
		*) grep -qE "^$c=[ym]" "$1" || return 0 ;;
		esac
	done
	return 1
}
if [ -z "$configs" ]; then
	fail "dkms.conf has no BUILD_EXCLUSIVE_CONFIG=\"...\" line"
else
	for kdir; do
		if excluded "$kdir/.config"; then
			fail "$(basename "$kdir"): BUILD_EXCLUSIVE_CONFIG ($configs) excludes it"
		else
			pass "$(basename "$kdir"): has $configs"
		fi
		grep -v '^CONFIG_CAN_RX_OFFLOAD=' "$kdir/.config" >"$tmp/no-offload.config"
		excluded "$tmp/no-offload.config" &&
			pass "$(basename "$kdir") without CONFIG_CAN_RX_OFFLOAD: excluded" ||
			fail "$(basename "$kdir") without CONFIG_CAN_RX_OFFLOAD: not excluded"
	done
fi

tally install-check
