#!/bin/sh
# Build the Debian packages of debian/ as a distribution would
# (dpkg-buildpackage -us -uc -b) and check them with lintian; run by
# `make deb`.
#
# usage: tests/packaging/build-debs.sh OUTDIR
#
# The build runs on a copy of the tree in OUTDIR/mcp2510 (without build/
# and .git): dpkg-buildpackage writes its .deb, .buildinfo and .changes
# files beside the tree it builds, here into OUTDIR, never beside the
# checkout.  The build dependencies are debian/control's, as
# dpkg-checkbuilddeps reports them missing, installed through
# scripts/ensure-packages (INSTALL_DEPS=1).  A lintian error fails the
# build; its warnings are printed (docs/packaging.md justifies each).
set -eu

[ $# -eq 1 ] || { echo "usage: $0 OUTDIR" >&2; exit 2; }
top=$(cd "$(dirname "$0")/../.." && pwd)
out=$1
src=$out/mcp2510

rm -rf "$out"
mkdir -p "$src"
tar -C "$top" --exclude=./build --exclude=./.git -cf - . | tar -C "$src" -xf -
cd "$src"

# "Unmet build dependencies: debhelper-compat (= 13) dh-sequence-dkms
# ..." as names for apt (no versions, profiles or alternatives; apt takes
# the one package providing a virtual name such as debhelper-compat).
missing=$(dpkg-checkbuilddeps 2>&1 | sed -n 's/.*[Uu]nmet build dependencies: //p' |
	sed -e 's/([^)]*)//g' -e 's/<[^>]*>//g' -e 's/|[^ ]*//g')
# shellcheck disable=SC2086
"$top/scripts/ensure-packages" lintian $missing

echo "deb: dpkg-buildpackage -us -uc -b (log: $out/build.log)"
if ! dpkg-buildpackage -us -uc -b >"$out/build.log" 2>&1; then
	tail -n 40 "$out/build.log"
	echo "deb: dpkg-buildpackage failed" >&2
	exit 1
fi
cd "$out"
for deb in *.deb; do
	echo "deb: built $deb ($(dpkg-deb -c "$deb" | grep -c -v '/$') files)"
done

changes=$(ls ./*.changes)
echo "deb: lintian $(basename "$changes")"
if ! lintian --fail-on error "$changes" >lintian.txt 2>lintian.err; then
	cat lintian.txt lintian.err
	echo "deb: lintian found errors" >&2
	exit 1
fi
sed 's/^/  /' lintian.txt
echo "deb: lintian: $(grep -c '^E:' lintian.txt) errors, $(grep -c '^W:' lintian.txt) warnings"
