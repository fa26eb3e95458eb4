#!/bin/sh
# Install the packages `make deb` built, use them, purge them, and find
# nothing of them left (run by `make deb-check`, as root).
#
# usage: tests/packaging/check-debs.sh DEBDIR [RELEASE]
#
# - apt-get install of the four packages (without recommends, so that no
#   other kernel's headers come along);
# - DKMS builds mcp2510.ko for kernel RELEASE: by default the newest whose
#   linux-headers-<release> package is installed (with INSTALL_DEPS=1 and
#   none there, linux-headers-<arch> is installed first).  No kernel of
#   that release needs to run, nor systemd: a chroot will do;
# - modinfo of the result, the tools' --version and the simulated chip's
#   self test, a program built with pkg-config, the man pages;
# - apt-get purge: every path the packages brought that was not there
#   before, and anything named *mcp2510* that DKMS or a maintainer script
#   made (outside /tmp and /var/tmp), is gone.
set -eu

[ $# -ge 1 ] && [ $# -le 2 ] || { echo "usage: $0 DEBDIR [RELEASE]" >&2; exit 2; }
top=$(cd "$(dirname "$0")/../.." && pwd)
debdir=$(cd "$1" && pwd)
release=${2:-}
ensure=$top/scripts/ensure-packages
[ "$(id -u)" -eq 0 ] || { echo "deb-check: run as root: it installs and purges packages" >&2; exit 1; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/mcp2510-debs.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
. "$top/tests/lib/tally.sh"
apt() { DEBIAN_FRONTEND=noninteractive apt-get -o DPkg::Lock::Timeout=900 -y -q "$@"; }
# run LOG COMMAND...: the command's output in $tmp/LOG, shown if it fails
run() { log=$tmp/$1; shift; "$@" >"$log" 2>&1 || { sed 's/^/  | /' "$log"; return 1; }; }

"$ensure" dkms kmod man-db pkg-config

headers_release() {
	dpkg-query -W -f='${Status} ${Package}\n' 'linux-headers-*' 2>/dev/null |
		sed -n 's/^install ok installed linux-headers-//p' | while read -r r; do
			[ -f "/lib/modules/$r/build/Makefile" ] && echo "$r"
		done | sort -V | tail -n 1
}
if [ -z "$release" ]; then
	release=$(headers_release)
	[ -n "$release" ] || { "$ensure" "linux-headers-$(dpkg --print-architecture)"; release=$(headers_release); }
	[ -n "$release" ] || { echo "deb-check: no linux-headers-<release> package installed" >&2; exit 1; }
fi

debs='' pkgs=''
for d in "$debdir"/*.deb; do
	case $d in *-dbgsym_*) continue ;; esac
	debs="$debs $d" pkgs="$pkgs $(dpkg-deb -f "$d" Package)"
	version=$(dpkg-deb -f "$d" Version)
done
pkgs=${pkgs# }
echo "deb-check: $pkgs $version, DKMS for $release"

# A run that stopped half-way may have left them installed.
installed=$(for p in $pkgs; do dpkg-query -W -f='${Status} ${Package}\n' "$p" 2>/dev/null; done |
	sed -n 's/^install ok installed //p' | tr '\n' ' ')
# shellcheck disable=SC2086
[ -z "$installed" ] || { echo "deb-check: purging $installed first"; apt purge $installed >/dev/null; }

# What the packages bring that is not there yet, and what is named after
# the driver before they come.
for d in $debs; do dpkg-deb --fsys-tarfile "$d" | tar -t; done |
	sed -e 's|^\./|/|' -e 's|/$||' | grep -v '^/*$' | sort -u >"$tmp/brought"
existing() { while read -r p; do if [ -e "$p" ] || [ -L "$p" ]; then echo "$p"; fi; done; }
existing <"$tmp/brought" | comm -23 "$tmp/brought" - >"$tmp/new"
named() {
	find /usr /etc /boot /opt /srv /var /lib/modules/ -path /var/tmp -prune -o \
		-name '*mcp2510*' -print 2>/dev/null | sort -u
}
named >"$tmp/named-before"

echo "deb-check: apt-get install"
# shellcheck disable=SC2086
run install apt install --no-install-recommends $debs && pass "apt-get install ./*.deb" ||
	fail "apt-get install ./*.deb"
for p in $pkgs; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' &&
		pass "$p installed" || fail "$p not installed"
done
src=/usr/src/mcp2510-$version
[ -f "$src/dkms.conf" ] && [ -f "$src/Kbuild" ] && [ ! -e "$src/tests" ] &&
	pass "$src: dkms.conf, Kbuild, no tests" || fail "$src: not as DKMS wants it"
ls /boot/firmware/overlays/mcp2510-can0.dtbo >/dev/null 2>&1 &&
	pass "overlays in /boot/firmware/overlays" || fail "no /boot/firmware/overlays/mcp2510-can0.dtbo"

echo "deb-check: dkms install mcp2510/$version -k $release"
run dkms dkms install "mcp2510/$version" -k "$release" &&
	dkms status "mcp2510/$version" -k "$release" | grep -q ': installed' &&
	pass "DKMS built and installed mcp2510.ko for $release" || fail "DKMS for $release"
file=$(modinfo -k "$release" -F filename mcp2510 2>/dev/null || :)
vermagic=$(modinfo -k "$release" -F vermagic mcp2510 2>/dev/null || :)
echo "  modinfo: $file"
echo "  vermagic: $vermagic"
case $file in
/lib/modules/"$release"/updates/dkms/mcp2510.ko*) pass "modinfo finds it where DKMS puts it" ;;
*) fail "modinfo -k $release mcp2510: '$file'" ;;
esac
[ "${vermagic%% *}" = "$release" ] && pass "built for $release" || fail "vermagic '$vermagic'"
modinfo -k "$release" -F alias mcp2510 | grep -q 'microchip,mcp2515' &&
	pass "device-tree aliases (microchip,mcp2515)" || fail "no microchip,mcp2515 alias"

echo "deb-check: the tools, the library, the man pages"
for tool in mcp2510ctl mcp2510d; do
	out=$($tool --version 2>&1 || :)
	[ "$out" = "$tool $version" ] && pass "$out" || fail "$tool --version: '$out'"
done
[ "$(mcp2510ctl --device sim selftest 2>&1 | tail -n 1)" = PASS ] &&
	pass "mcp2510ctl --device sim selftest: PASS" || fail "mcp2510ctl selftest"
printf '#include <stdio.h>\n#include <mcp2510.h>\nint main(void) { puts(mcp2510_version()); return 0; }\n' >"$tmp/prog.c"
# shellcheck disable=SC2046
run cc cc -o "$tmp/prog" "$tmp/prog.c" $(pkg-config --cflags --libs libmcp2510) &&
	[ "$("$tmp/prog")" = "$version" ] && pass "a program built with pkg-config runs" ||
	fail "a program built with pkg-config"
for page in mcp2510ctl mcp2510d libmcp2510; do
	path=$(man -w "$page" 2>/dev/null || :)
	case $path in /usr/share/man/*) ;; *) fail "man -w $page: '$path'"; continue ;; esac
	MANWIDTH=80 man -l "$path" 2>"$tmp/man.err" | grep -q '^NAME' && [ ! -s "$tmp/man.err" ] &&
		pass "man $page: $path renders" || { cat "$tmp/man.err"; fail "man -l $path"; }
done

echo "deb-check: apt-get purge"
# shellcheck disable=SC2086
run purge apt purge $pkgs && pass "apt-get purge $pkgs" || fail "apt-get purge"
for p in $pkgs; do
	case $(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || :) in
	"" | *not-installed) pass "$p purged" ;;
	*) fail "$p still known to dpkg" ;;
	esac
done
left=$(existing <"$tmp/new")
[ -z "$left" ] && pass "nothing the packages brought is left ($(wc -l <"$tmp/new") paths)" ||
	{ echo "$left"; fail "left behind by the packages"; }
left=$(named | comm -13 "$tmp/named-before" -)
[ -z "$left" ] && pass "nothing named *mcp2510* in /usr /etc /boot /opt /srv /var /lib/modules" ||
	{ echo "$left"; fail "left behind by DKMS or the packages"; }
modinfo -k "$release" mcp2510 >/dev/null 2>&1 && fail "modinfo still finds mcp2510" ||
	pass "modinfo -k $release no longer finds mcp2510"

tally deb-check
