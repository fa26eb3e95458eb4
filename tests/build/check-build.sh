#!/bin/sh
# What a packager's build sees of the userspace port and the modules
# (run by `make build-check`):
#
# - distribution flags (dpkg-buildflags with every hardening option) are
#   used on every compile and link, after the project's, and reach the
#   binaries (BIND_NOW, RELRO, the stack protector); a staged make install
#   of the module and of the tools works with them in the environment;
# - a plain build does not make warnings errors (make check's WERROR=1
#   does); the output is one short line per file, every command with V=1;
# - changing a build option rebuilds what it affects: MCP2510_SIM=0 and
#   back, sanitizer flags and back, other CPPFLAGS; the same options twice
#   rebuild nothing;
# - a build on a system without dpkg runs no package manager; with dpkg,
#   a missing package is named and nothing installed, unless INSTALL_DEPS=1
#   (or a goal that installs, in its sub-makes too); every target that
#   compiles asks for the compiler first;
# - make clean removes products and keeps downloads, kernels and roots;
#   make distclean removes all of build/.
#
# usage: tests/build/check-build.sh KDIR   (a kernel build tree)
set -eu

[ $# -eq 1 ] || { echo "usage: $0 KDIR" >&2; exit 2; }
kdir=$1
top=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/mcp2510-build.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

. "$top/tests/lib/tally.sh"
# mk OUT ARGS...: make in the top directory, its output in $tmp/OUT.log;
# the flags of the environment are not the caller's unless it sets them.
mk() {
	log=$tmp/$1.log
	shift
	env -u CFLAGS -u CPPFLAGS -u LDFLAGS -u V -u WERROR -u INSTALL_DEPS \
		-u MCP2510_INSTALL_DEPS -u MAKEFLAGS -u MAKELEVEL \
		make --no-print-directory -j2 -C "$top" "$@" >"$log" 2>&1
}
show() { sed 's/^/  | /' "$tmp/$1.log" | tail -n 20; }
us=$tmp/us
ctl=$us/bin/mcp2510ctl

echo "build-check: distribution flags"
flags=$(DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --export=sh 2>/dev/null) || flags=
[ -n "$flags" ] || flags='export CFLAGS="-g -O2 -fstack-protector-strong -Wformat -Werror=format-security"
export CPPFLAGS="-Wdate-time -D_FORTIFY_SOURCE=2"
export LDFLAGS="-Wl,-z,relro -Wl,-z,now"'
# a marker in each, to find them on the command lines
eval "$flags"
CFLAGS="$CFLAGS -DMCP2510_MARK_CFLAGS"
CPPFLAGS="$CPPFLAGS -DMCP2510_MARK_CPPFLAGS"
LDFLAGS="$LDFLAGS -Wl,-z,now -Wl,--build-id=sha1"
if mk dist userspace US_OUT="$us" V=1 CFLAGS="$CFLAGS" CPPFLAGS="$CPPFLAGS" LDFLAGS="$LDFLAGS"; then
	# one line per command
	sed -i -e ':a' -e '/\\$/N; s/\\\n//; ta' "$tmp/dist.log"
	compiles=$(grep -c ' -c .*\.c -o ' "$tmp/dist.log" || :)
	marked=$(grep ' -c .*\.c -o ' "$tmp/dist.log" | grep -- '-O2 .*-fstack-protector-strong.*MCP2510_MARK_CFLAGS' |
		grep -c -- '-D_FORTIFY_SOURCE=2.*MCP2510_MARK_CPPFLAGS' || :)
	[ "$compiles" -gt 20 ] && [ "$marked" -eq "$compiles" ] &&
		pass "CFLAGS and CPPFLAGS on all $compiles compiles, after the project's" ||
		{ show dist; fail "CFLAGS/CPPFLAGS on $marked of $compiles compiles"; }
	links=$(grep -c -- ' -o [^ ]*/\(bin/mcp2510[a-z]*\|lib/libmcp2510\.so\.[0-9.]*\)$' "$tmp/dist.log" || :)
	linked=$(grep -- ' -o [^ ]*/\(bin/mcp2510[a-z]*\|lib/libmcp2510\.so\.[0-9.]*\)$' "$tmp/dist.log" |
		grep -c -- '-Wl,-z,relro.*--build-id=sha1' || :)
	[ "$links" -eq 3 ] && [ "$linked" -eq 3 ] && pass "LDFLAGS on the library's and both tools' links" ||
		{ show dist; fail "LDFLAGS on $linked of $links links"; }
	if grep -q -- '-Werror\( \|$\)' "$tmp/dist.log"; then
		fail "a release build uses -Werror"
	else
		pass "a release build does not make warnings errors"
	fi
	for f in "$us/lib/libmcp2510.so.0" "$ctl" "$us/bin/mcp2510d"; do
		dyn=$(readelf -d "$f")
		echo "$dyn" | grep -q 'BIND_NOW\|FLAGS.*NOW' && readelf -l "$f" | grep -q GNU_RELRO &&
			nm -D "$f" | grep -q __stack_chk_fail &&
			pass "$(basename "$f"): BIND_NOW, RELRO, stack protector" ||
			fail "$(basename "$f"): the flags did not reach it"
	done
else
	show dist
	fail "build with distribution flags"
fi
stage=$tmp/stage
if mk install install KDIR="$kdir" DESTDIR="$stage" CFLAGS="$CFLAGS" \
		CPPFLAGS="$CPPFLAGS" LDFLAGS="$LDFLAGS" &&
	mk install-us install-userspace US_OUT="$us" DESTDIR="$stage" PREFIX=/usr \
		CFLAGS="$CFLAGS" CPPFLAGS="$CPPFLAGS" LDFLAGS="$LDFLAGS" &&
	ls "$stage"/lib/modules/*/extra/mcp2510.ko* >/dev/null 2>&1 &&
	[ -x "$stage/usr/bin/mcp2510ctl" ] && ! grep -q '  CC  ' "$tmp/install-us.log"; then
	pass "staged make install and install-userspace with the flags in the environment"
else
	show install
	show install-us
	fail "staged install with distribution flags"
fi

echo "build-check: warnings and output"
if mk quiet userspace US_OUT="$tmp/quiet" && grep -q '^  CC      userspace/lib/open.c$' "$tmp/quiet.log" &&
	grep -q '^  LD      .*/bin/mcp2510ctl$' "$tmp/quiet.log" && ! grep -q ' -c ' "$tmp/quiet.log"; then
	pass "quiet by default: one line per file"
else
	show quiet
	fail "quiet output"
fi
if mk padded userspace US_OUT="$tmp/padded" CFLAGS=-Wpadded && grep -q 'warning: padding' "$tmp/padded.log"; then
	pass "new warnings (-Wpadded) do not stop a release build"
else
	show padded
	fail "a warning stopped a release build"
fi
if mk padded-werror userspace US_OUT="$tmp/padded" CFLAGS=-Wpadded WERROR=1; then
	fail "WERROR=1 let a warning through"
else
	pass "WERROR=1 (make check) makes them errors"
fi

echo "build-check: changing an option rebuilds"
sim_works() { "$ctl" --device sim selftest 2>&1 | tail -n 1 | grep -qx PASS; }
sim_refused() { "$ctl" --device sim info 2>&1 | grep -q 'cannot open sim'; }
compiled() { grep -c '^  CC  ' "$tmp/$1.log" || :; }
mk opt-plain userspace US_OUT="$us" && sim_works &&
	pass "default build: --device sim works" || { show opt-plain; fail "default build"; }
mk opt-nosim userspace US_OUT="$us" MCP2510_SIM=0 && sim_refused &&
	pass "MCP2510_SIM=0 over it: sim refused" || { show opt-nosim; fail "MCP2510_SIM=0 did not take"; }
mk opt-back userspace US_OUT="$us" && sim_works &&
	pass "back to the default: --device sim works again" || { show opt-back; fail "default after MCP2510_SIM=0"; }
mk opt-same userspace US_OUT="$us"
[ "$(compiled opt-same)" -eq 0 ] && pass "the same options again: nothing rebuilt" ||
	fail "the same options rebuilt $(compiled opt-same) files"
mk opt-asan userspace US_OUT="$us" CFLAGS="-fsanitize=address,undefined" LDFLAGS="-fsanitize=address,undefined" &&
	ldd "$ctl" | grep -q libasan && ASAN_OPTIONS=detect_leaks=0 sim_works &&
	pass "sanitizer flags: rebuilt with ASan" || { show opt-asan; fail "sanitizer flags did not take"; }
mk opt-noasan userspace US_OUT="$us" && ! ldd "$ctl" | grep -q libasan && sim_works &&
	pass "without them: rebuilt without" || { show opt-noasan; fail "ASan stayed after the flags went"; }
mk opt-cppflags userspace US_OUT="$us" CPPFLAGS=-DMCP2510_OTHER
[ "$(compiled opt-cppflags)" -gt 20 ] && pass "other CPPFLAGS: $(compiled opt-cppflags) files rebuilt" ||
	fail "other CPPFLAGS rebuilt $(compiled opt-cppflags) files"

echo "build-check: package managers"
# a PATH of every command but dpkg's and apt's, with recording stubs
mkdir -p "$tmp/nodpkg" "$tmp/stub"
for dir in /usr/local/bin /usr/bin /bin /usr/sbin /sbin; do
	for cmd in "$dir"/*; do
		name=${cmd##*/}
		case $name in dpkg*|apt*|sudo) continue ;; esac
		[ -e "$tmp/nodpkg/$name" ] || ln -s "$cmd" "$tmp/nodpkg/$name"
	done
done
for tool in apt-get apt sudo; do
	printf '#!/bin/sh\necho "%s $*" >>"%s/calls"\nexit 1\n' "$tool" "$tmp" >"$tmp/stub/$tool"
	chmod +x "$tmp/stub/$tool"
done
rm -f "$tmp/calls"
if PATH="$tmp/stub:$tmp/nodpkg" mk nodpkg all US_OUT="$tmp/nodpkg-us" && [ ! -e "$tmp/calls" ]; then
	pass "make without dpkg: builds, runs no package manager"
else
	show nodpkg
	cat "$tmp/calls" 2>/dev/null
	fail "make without dpkg"
fi
# dpkg that knows no package
printf '#!/bin/sh\nexit 1\n' >"$tmp/stub/dpkg-query"
chmod +x "$tmp/stub/dpkg-query"
rm -f "$tmp/calls"
if PATH="$tmp/stub:$PATH" mk missing userspace US_OUT="$tmp/missing-us"; then
	fail "a build with packages missing went on"
elif [ -e "$tmp/calls" ]; then
	cat "$tmp/calls"
	fail "a plain build ran a package manager"
elif grep -q 'missing package(s): build-essential pkg-config libgpiod-dev' "$tmp/missing.log" &&
	grep -q 'INSTALL_DEPS=1' "$tmp/missing.log"; then
	pass "a missing package is named, nothing installed"
else
	show missing
	fail "the missing packages are not named"
fi
PATH="$tmp/stub:$PATH" mk missing-install userspace US_OUT="$tmp/missing-us" INSTALL_DEPS=1 || :
grep -q 'apt-get .*install .*pkg-config libgpiod-dev' "$tmp/calls" 2>/dev/null &&
	pass "INSTALL_DEPS=1 installs them" || { show missing-install; fail "INSTALL_DEPS=1 did not run apt-get"; }
# Every target that compiles asks for the compiler first: a new machine
# has none.  Built in a scratch BUILD, stopped by apt-get's stub.
for target in sim-check core-check unit-build userspace vm-guest-tools; do
	rm -f "$tmp/calls"
	PATH="$tmp/stub:$PATH" mk "cc-$target" "$target" BUILD="$tmp/cc" INSTALL_DEPS=1 || :
	grep -q 'apt-get .*install .*build-essential' "$tmp/calls" 2>/dev/null &&
		pass "make $target INSTALL_DEPS=1 installs the compiler" ||
		{ show "cc-$target"; fail "make $target INSTALL_DEPS=1 did not ask for build-essential"; }
done
# A goal that installs (make demo) keeps doing so in the sub-make it
# starts for VMTEST_DEPS: a rig of stubs makes the rest of it a no-op.
mkdir -p "$tmp/vm"
cp "$top/tests/vm/kernels" "$tmp/vm/"
for tool in fetch-kernel vm-run; do
	printf '#!/bin/sh\nexit 0\n' >"$tmp/vm/$tool"
	chmod +x "$tmp/vm/$tool"
done
rm -f "$tmp/calls"
PATH="$tmp/stub:$PATH" mk demo-sub demo VM_DIR="$tmp/vm" VMTEST_DEPS=userspace-deps BUILD="$tmp/demo" || :
grep -q 'apt-get .*install .*libgpiod-dev' "$tmp/calls" 2>/dev/null &&
	pass "make demo installs what its sub-make needs" ||
	{ show demo-sub; fail "make demo's sub-make did not install libgpiod-dev"; }

echo "build-check: make clean and distclean"
# A scratch build/ with what make clean keeps and what it removes.
b=$tmp/clean
kept="kernels/6.1/release kernels/apt/bookworm/status kernels/debug/stamp
libgpiod/v2/pkgconfig/libgpiod.pc kernels/arm64-7.3/release arm64/apt/status
trixie/root/etc/debian_version vm/busybox/bin/busybox"
products="userspace/bin/mcp2510ctl unit/test_core_tx modules/6.1/mcp2510.ko
vm/6.1/initramfs.cpio.gz arm64/initramfs.cpio.gz checkpatch/report.txt"
for f in $kept $products; do
	mkdir -p "$b/${f%/*}" && : >"$b/$f"
done
mk clean clean BUILD="$b"
gone=
for f in $kept; do [ -e "$b/$f" ] || gone="$gone $f"; done
left=
for f in $products; do [ ! -e "$b/$f" ] || left="$left $f"; done
[ -z "$gone" ] && pass "make clean keeps downloads, kernels and roots" ||
	{ show clean; fail "make clean removed:$gone"; }
[ -z "$left" ] && [ ! -e "$b/userspace" ] && pass "make clean removes build products" ||
	{ show clean; fail "make clean left:$left"; }
mk distclean distclean BUILD="$b"
[ ! -e "$b" ] && pass "make distclean removes all of build/" || fail "make distclean left $b"

tally build-check
