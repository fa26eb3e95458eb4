#!/bin/sh
# Check the device-tree overlays and the binding (run by `make dt-check`).
#
# usage: dts/dt-check.sh OUTDIR DTSCHEMA_BINDIR
#
# For every dts/*-overlay.dts:
#   - dtc -@ compiles it without a single warning;
#   - fdtoverlay applies it to dts/test/base.dts, a made-up SoC carrying the
#     labels the overlays target;
#   - the merged tree, dumped back to .dts and recompiled, passes dt-validate
#     against dts/bindings with nothing reported (dt-validate exits 0 on
#     findings, so its output is what counts);
#   - the CAN node is there and no enabled sibling shares its chip select;
#   - Raspberry Pi style parameters (__overrides__) point at properties that
#     exist, and setting them changes those properties in the merged tree.
# Every dts/test/bad/*.dts must fail that same pipeline, with output that
# contains the text of its "expect:" line: failing for another reason is a
# failure too.
set -eu

if [ $# -ne 2 ]; then
	echo "usage: $0 OUTDIR DTSCHEMA_BINDIR" >&2
	exit 2
fi
out=$1
bin=$2
here=$(cd "$(dirname "$0")" && pwd)

mkdir -p "$out/overlays" "$out/merged" "$out/bad" "$out/log"

passed=0
failed=0
pass() { passed=$((passed + 1)); echo "  PASS  $1"; }
fail() { failed=$((failed + 1)); echo "  FAIL  $1"; }

# The merged tree holds the disabled spidev next to the CAN node on the same
# chip select, and the base tree's "gpio" label (the Raspberry Pi's name)
# looks like a gpios property to dtc inside __symbols__: both are expected.
DUMP_FLAGS="-W no-unique_unit_address -W no-gpios_property"

# dt-extract-example wraps each example in a node with #address-cells and a
# made-up interrupt controller, both of which dtc comments on.
EXAMPLE_FLAGS="-W no-avoid_unnecessary_addr_size -W no-interrupt_provider"

# run LOG CMD...: run CMD; its stdout and stderr go to LOG. Fails if CMD fails
# or prints anything on stderr (dtc and fdtoverlay warnings are errors here).
run() {
	log=$1
	shift
	if ! "$@" >"$log.out" 2>"$log.err"; then
		cat "$log.out" "$log.err"
		echo "failed: $*"
		return 1
	fi
	if [ -s "$log.err" ]; then
		cat "$log.err"
		echo "warnings from: $*"
		return 1
	fi
}

# validate DTB: dt-validate, with unmatched compatibles reported; any output
# is a finding.
validate() {
	"$bin/dt-validate" -m -s "$out/schema.json" "$1" >"$1.validate" 2>&1 || {
		cat "$1.validate"
		echo "dt-validate failed on $1"
		return 1
	}
	if [ -s "$1.validate" ]; then
		cat "$1.validate"
		echo "dt-validate findings in $1"
		return 1
	fi
}

# nodes DTB [PATH]: every node path below PATH, one a line.
nodes() (
	p=${2:-/}
	echo "$p"
	for child in $(fdtget -l "$1" "$p"); do
		if [ "$p" = / ]; then nodes "$1" "/$child"; else nodes "$1" "$p/$child"; fi
	done
)

# is_enabled DTB NODE: status absent, "okay" or "ok".
is_enabled() {
	s=$(fdtget -d okay "$1" "$2" status)
	[ "$s" = okay ] || [ "$s" = ok ]
}

# check_can_node DTB: exactly one node compatible with this binding, enabled,
# on an enabled controller, and no enabled sibling on the same chip select.
check_can_node() (
	dtb=$1
	found=
	for n in $(nodes "$dtb"); do
		compat=$(fdtget "$dtb" "$n" compatible 2>/dev/null) || continue
		case $compat in
		microchip,mcp2510* | microchip,mcp2515* | microchip,mcp25625*)
			[ -z "$found" ] || { echo "more than one CAN node: $found $n"; exit 1; }
			found=$n ;;
		esac
	done
	[ -n "$found" ] || { echo "no microchip,mcp25xx node in the merged tree"; exit 1; }
	parent=${found%/*}
	is_enabled "$dtb" "$found" || { echo "$found is disabled"; exit 1; }
	is_enabled "$dtb" "$parent" || { echo "SPI controller $parent is disabled"; exit 1; }
	cs=$(fdtget "$dtb" "$found" reg)
	for sib in $(fdtget -l "$dtb" "$parent"); do
		[ "$parent/$sib" != "$found" ] || continue
		sreg=$(fdtget "$dtb" "$parent/$sib" reg 2>/dev/null) || continue
		if [ "$sreg" = "$cs" ] && is_enabled "$dtb" "$parent/$sib"; then
			echo "$parent/$sib is still enabled on chip select $cs"
			exit 1
		fi
	done
	echo "CAN node $found on chip select $cs"
)

# override_targets DTBO PARAM: the (phandle, "prop:offset") pairs of one
# __overrides__ parameter as "PHANDLE SPEC" lines. Only the phandle + string
# form is supported (that is all these overlays use).
override_targets() {
	fdtget -t hhx "$1" /__overrides__ "$2" | awk '
	{
		n = split($0, b, " ")
		i = 1
		while (i <= n) {
			if (i + 4 > n) { print "bad"; exit }
			ph = 0
			for (k = 0; k < 4; k++) ph = ph * 256 + hex(b[i + k])
			i += 4
			s = ""
			while (i <= n && b[i] != "0") { s = s sprintf("%c", hex(b[i])); i++ }
			if (i > n || s == "") { print "bad"; exit }
			i++
			print ph, s
		}
	}
	function hex(h,   v, c, j) {
		v = 0
		for (j = 1; j <= length(h); j++) {
			c = index("0123456789abcdef", substr(h, j, 1)) - 1
			v = v * 16 + c
		}
		return v
	}'
}

# check_overrides NAME DTBO: each parameter's targets exist; setting the
# parameter (as the firmware would: patch the overlay, then apply it) shows up
# in the merged tree.
check_overrides() (
	name=$1 dtbo=$2
	params=$(fdtget -p "$dtbo" /__overrides__)
	for want in oscillator interrupt spimaxfrequency; do
		echo "$params" | grep -qx "$want" || { echo "parameter $want missing"; exit 1; }
	done
	patched="$out/overlays/$name.params.dtbo"
	cp "$dtbo" "$patched"
	expect="$out/log/$name.params.expect"
	: >"$expect"
	ovnodes=$(nodes "$dtbo")
	for param in $params; do
		targets=$(override_targets "$dtbo" "$param")
		if echo "$targets" | grep -qx bad; then
			echo "$param: not <&label>, \"prop:offset\" pairs"
			exit 1
		fi
		value=
		echo "$targets" | while read -r ph spec; do
			prop=${spec%%:*}
			off=${spec#*:}
			[ "$prop" != "$spec" ] || { echo "$param: '$spec' is not a 32-bit cell (prop:offset)"; exit 1; }
			node=
			for n in $ovnodes; do
				[ "$(fdtget -t u -d none "$dtbo" "$n" phandle)" = "$ph" ] && { node=$n; break; }
			done
			[ -n "$node" ] || { echo "$param: phandle $ph is no node of the overlay"; exit 1; }
			case $node in
			/fragment@*/__overlay__/*) ;;
			*) echo "$param: $node is outside the fragments' __overlay__ nodes"; exit 1 ;;
			esac
			cells=$(fdtget -t u "$dtbo" "$node" "$prop" 2>/dev/null) ||
				{ echo "$param: $node has no property $prop"; exit 1; }
			idx=$((off / 4))
			[ $((off % 4)) -eq 0 ] && [ "$idx" -lt "$(echo "$cells" | wc -w)" ] ||
				{ echo "$param: offset $off is outside $node/$prop ($cells)"; exit 1; }
			# One value per parameter: the first target's cell, minus one.
			[ -n "$value" ] || value=$(($(echo "$cells" | cut -d' ' -f$((idx + 1))) - 1))
			new=$(echo "$cells" | awk -v i=$((idx + 1)) -v v="$value" '{ $i = v; print }')
			# shellcheck disable=SC2086
			fdtput -t u "$patched" "$node" "$prop" $new || exit 1
			label=$(fdtget -p "$dtbo" /__symbols__ | while read -r l; do
				[ "$(fdtget "$dtbo" /__symbols__ "$l")" = "$node" ] && echo "$l"; done | head -n 1)
			[ -n "$label" ] || { echo "$param: $node has no label"; exit 1; }
			echo "$param $label $prop $new" >>"$expect"
		done || exit 1
	done
	run "$out/log/$name.params" fdtoverlay -i "$out/base.dtb" -o "$out/merged/$name.params.dtb" "$patched" || exit 1
	while read -r param label prop new; do
		path=$(fdtget "$out/merged/$name.params.dtb" /__symbols__ "$label")
		got=$(fdtget -t u "$out/merged/$name.params.dtb" "$path" "$prop")
		[ "$got" = "$new" ] || { echo "$param: $path/$prop is '$got', expected '$new'"; exit 1; }
		echo "$param -> $path $prop = <$got>"
	done <"$expect"
)

# check_overlay NAME DTS DIR: the whole pipeline for one overlay source.
check_overlay() (
	name=$1 src=$2 dir=$3
	dtbo="$dir/$name.dtbo"
	merged="$out/merged/$name.dtb"
	run "$out/log/$name.dtc" dtc -@ -I dts -O dtb -o "$dtbo" "$src" || exit 1
	run "$out/log/$name.apply" fdtoverlay -i "$out/base.dtb" -o "$merged" "$dtbo" || exit 1
	# The readable form of the result, for people; dtc checks it on the way.
	# shellcheck disable=SC2086
	run "$out/log/$name.dump" dtc $DUMP_FLAGS -I dtb -O dts -o "$out/merged/$name.dts" "$merged" || exit 1
	validate "$merged" || exit 1
	check_can_node "$merged" || exit 1
	# Raspberry Pi overlays (compatible "brcm,bcm2835") take parameters.
	if fdtget -l "$dtbo" / | grep -qx __overrides__; then
		check_overrides "$name" "$dtbo" || exit 1
	elif [ "$(fdtget -d none "$dtbo" / compatible)" = brcm,bcm2835 ]; then
		echo "Raspberry Pi overlay without __overrides__ (parameters)"
		exit 1
	fi
)

echo "dt-check: binding schemas"
if run "$out/log/doc-validate" "$bin/dt-doc-validate" "$here/bindings" "$here/test/schemas" &&
	[ ! -s "$out/log/doc-validate.out" ]; then
	pass "schemas follow the dt-schema meta-schema"
else
	cat "$out/log/doc-validate.out"
	fail "schemas follow the dt-schema meta-schema"
fi
# Rebuilt every run: a few seconds, and never stale.
run "$out/log/mk-schema" "$bin/dt-mk-schema" -j -o "$out/schema.json" \
	"$here/bindings" "$here/test/schemas" || { echo "dt-check: cannot process the schemas" >&2; exit 1; }

if run "$out/log/base" dtc -@ -I dts -O dtb -o "$out/base.dtb" "$here/test/base.dts" &&
	validate "$out/base.dtb"; then
	pass "test base tree dts/test/base.dts"
else
	fail "test base tree dts/test/base.dts"
	echo "dt-check: nothing to apply the overlays to" >&2
	exit 1
fi

for binding in "$here"/bindings/*.yaml; do
	grep -q "^examples:" "$binding" || continue
	b=$(basename "$binding" .yaml)
	ex="$out/log/$b.example"
	# shellcheck disable=SC2086
	if "$bin/dt-extract-example" "$binding" >"$ex.dts" &&
		run "$ex" dtc $EXAMPLE_FLAGS -I dts -O dtb -o "$ex.dtb" "$ex.dts" &&
		validate "$ex.dtb"; then
		pass "example in bindings/$b.yaml"
	else
		fail "example in bindings/$b.yaml"
	fi
done

echo "dt-check: overlays"
count=0
for src in "$here"/*-overlay.dts; do
	name=$(basename "$src" -overlay.dts)
	count=$((count + 1))
	if check_overlay "$name" "$src" "$out/overlays" >"$out/log/$name.txt" 2>&1; then
		pass "$name ($(grep '^CAN node' "$out/log/$name.txt" | cut -d' ' -f3-))"
	else
		sed 's/^/        /' "$out/log/$name.txt"
		fail "$name"
	fi
done
[ "$count" -gt 0 ] || fail "no overlay sources in dts/"

echo "dt-check: broken overlays (each must be rejected for its stated reason)"
for src in "$here"/test/bad/*.dts; do
	name=bad-$(basename "$src" .dts)
	expect=$(sed -n 's/.*expect: *//p' "$src" | head -n 1)
	if [ -z "$expect" ]; then
		fail "$name: no 'expect:' line"
		continue
	fi
	if check_overlay "$name" "$src" "$out/bad" >"$out/log/$name.txt" 2>&1; then
		fail "$name: accepted, should fail with: $expect"
	elif grep -qF -- "$expect" "$out/log/$name.txt"; then
		pass "$name: rejected ($expect)"
	else
		sed 's/^/        /' "$out/log/$name.txt"
		fail "$name: rejected, but not with: $expect"
	fi
done

echo "dt-check: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
