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
#   - the CAN node is there, its oscillator within the driver's range, and
#     no enabled sibling shares its chip select;
#   - each Raspberry Pi style parameter (__overrides__) is set on its own as
#     the firmware would (dts/overlay-params.py), the result applied again,
#     and what the parameter changes read back from the merged tree with
#     fdtget; that tree passes all of the above too.
# Every dts/test/bad/*.dts must fail that same pipeline, with output that
# contains the text of its "expect:" line: failing for another reason is a
# failure too; so must every parameter use in dts/test/bad-params.  The
# binding must carry mainline's $id and state the driver's oscillator range.
set -eu

if [ $# -ne 2 ]; then
	echo "usage: $0 OUTDIR DTSCHEMA_BINDIR" >&2
	exit 2
fi
out=$1
bin=$2
here=$(cd "$(dirname "$0")" && pwd)

mkdir -p "$out/overlays" "$out/params" "$out/merged" "$out/bad" "$out/log"

passed=0
failed=0
pass() { passed=$((passed + 1)); echo "  PASS  $1"; }
fail() { failed=$((failed + 1)); echo "  FAIL  $1"; }

# The merged tree holds the disabled spidev next to the CAN node on the same
# chip select, and the base tree's "gpio" label (the Raspberry Pi's name)
# looks like a gpios property to dtc inside __symbols__: both are expected.
DUMP_FLAGS="-W no-unique_unit_address -W no-gpios_property"

# A fragment whose __overlay__ is renamed __dormant__ (off until a parameter
# turns it on) has a unit name and no reg: dtc says so, as it does for the
# Raspberry Pi's own overlays, which are built without that warning too.
# The merged tree is still checked for it.
OVERLAY_FLAGS="-W no-unit_address_vs_reg"

# The oscillator range the driver accepts (driver/core/mcp2510_core.h).
osc_limit() {
	sed -n "s/^#define MCP2510_OSC_$1_HZ[[:space:]]*\([0-9]*\).*/\1/p" \
		"$here/../driver/core/mcp2510_core.h"
}
OSC_MIN=$(osc_limit MIN)
OSC_MAX=$(osc_limit MAX)

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
	# The driver refuses an oscillator outside its range: so does this.
	clk=$(fdtget -t u "$dtb" "$found" clocks | cut -d' ' -f1)
	osc=
	for n in $(nodes "$dtb"); do
		[ "$(fdtget -t u -d none "$dtb" "$n" phandle)" = "$clk" ] || continue
		osc=$(fdtget -t u "$dtb" "$n" clock-frequency) || exit 1
	done
	[ -n "$osc" ] || { echo "no clock-frequency on the oscillator of $found"; exit 1; }
	if [ "$osc" -lt "$OSC_MIN" ] || [ "$osc" -gt "$OSC_MAX" ]; then
		echo "oscillator $osc Hz is outside the driver's $OSC_MIN-$OSC_MAX Hz"
		exit 1
	fi
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

# resolve DTB REF: the node path of REF, "&label" (the tree's __symbols__)
# or a path, which may start with an alias.
resolve() {
	case $2 in
	"&"*) fdtget "$1" /__symbols__ "${2#&}" ;;
	*) echo "$2" ;;
	esac
}

# check_params NAME DTBO PARAM[=VALUE]...: set the parameters as the firmware
# does (dts/overlay-params.py patches the overlay), apply the result with
# fdtoverlay, and read every setting back from the merged tree with fdtget;
# the merged tree must still validate and carry one usable CAN node.
check_params() (
	name=$1 dtbo=$2
	shift 2
	tag=$name.$(echo "$*" | tr ' =' '+-')
	patched="$out/params/$tag.dtbo"
	merged="$out/merged/$tag.dtb"
	expect="$out/log/$tag.expect"
	run "$out/log/$tag.params" "$bin/python3" "$here/overlay-params.py" apply \
		"$dtbo" "$patched" "$expect" "$@" || exit 1
	run "$out/log/$tag.apply" fdtoverlay -i "$out/base.dtb" -o "$merged" "$patched" || exit 1
	while read -r ref prop value; do
		path=$(resolve "$merged" "$ref") || { echo "$*: $ref is not in the merged tree"; exit 1; }
		case $prop in
		@name)
			got=${path##*/} ;;
		@present)
			got="(absent)"
			fdtget "$merged" "$path" "$value" >/dev/null 2>&1 && got=$value ;;
		@under)
			under=$(resolve "$merged" "$value") || exit 1
			got=$value
			case $path in "$under"/*) ;; *) got=${path%/*} ;; esac ;;
		*)
			# value is "u CELLS..." or "s STRING": fdtget's type, then data
			got="${value%% *} $(fdtget -t "${value%% *}" "$merged" "$path" "$prop")" || exit 1 ;;
		esac
		[ "$got" = "$value" ] || { echo "$*: $path $prop is '$got', expected '$value'"; exit 1; }
		echo "$*: $path $prop $value"
	done <"$expect"
	validate "$merged" || exit 1
	check_can_node "$merged" || exit 1
)

# check_overrides NAME DTBO: the overlay has the usual parameters, and each
# of its parameters, set alone (a number one below the overlay's own, or
# just named when it takes none), does what it says (check_params).
check_overrides() (
	name=$1 dtbo=$2
	run "$out/log/$name.describe" "$bin/python3" "$here/overlay-params.py" describe "$dtbo" || exit 1
	params="$out/log/$name.describe.out"
	while read -r param kind cell; do
		case $kind in
		value) check_params "$name" "$dtbo" "$param=$((cell - 1))" || exit 1 ;;
		*) check_params "$name" "$dtbo" "$param" || exit 1 ;;
		esac
	done <"$params"
	for want in oscillator interrupt speed; do
		grep -q "^$want value " "$params" || { echo "parameter $want missing"; exit 1; }
	done
)

# check_overlay NAME DTS DIR: the whole pipeline for one overlay source.
check_overlay() (
	name=$1 src=$2 dir=$3
	dtbo="$dir/$name.dtbo"
	merged="$out/merged/$name.dtb"
	# shellcheck disable=SC2086
	run "$out/log/$name.dtc" dtc -@ $OVERLAY_FLAGS -I dts -O dtb -o "$dtbo" "$src" || exit 1
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

for binding in $(find "$here/bindings" -name '*.yaml' | sort); do
	grep -q "^examples:" "$binding" || continue
	b=$(basename "$binding" .yaml)
	ex="$out/log/$b.example"
	# shellcheck disable=SC2086
	if "$bin/dt-extract-example" "$binding" >"$ex.dts" &&
		run "$ex" dtc $EXAMPLE_FLAGS -I dts -O dtb -o "$ex.dtb" "$ex.dts" &&
		validate "$ex.dtb"; then
		pass "example in ${binding#"$here"/}"
	else
		fail "example in ${binding#"$here"/}"
	fi
done

# The binding stands in for mainline's: same $id, and the oscillator range
# it states is the one the driver enforces.
binding="$here/bindings/net/can/microchip,mcp251x.yaml"
if grep -qx '$id: http://devicetree.org/schemas/net/can/microchip,mcp251x.yaml#' "$binding"; then
	pass "binding \$id is mainline's net/can/microchip,mcp251x.yaml"
else
	fail "binding \$id is not mainline's net/can/microchip,mcp251x.yaml"
fi
range="from $((OSC_MIN / 1000000)) MHz to $((OSC_MAX / 1000000)) MHz"
if [ -n "$OSC_MIN" ] && [ -n "$OSC_MAX" ] &&
	tr -s ' \n' ' ' <"$binding" | grep -q "$range"; then
	pass "binding states the driver's oscillator range ($range)"
else
	fail "binding does not state the driver's oscillator range ($range)"
fi

echo "dt-check: overlays"
count=0
for src in "$here"/*-overlay.dts; do
	name=$(basename "$src" -overlay.dts)
	count=$((count + 1))
	if check_overlay "$name" "$src" "$out/overlays" >"$out/log/$name.txt" 2>&1; then
		pass "$name ($(grep -m 1 '^CAN node' "$out/log/$name.txt" | cut -d' ' -f3-))"
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

# Two lines of one overlay, as docs/device-tree.md shows for a second chip on
# spi1: the renames keep the INT pin and oscillator nodes of each apart.
two_chips() (
	dtbo="$out/overlays/mcp2510-mcp2515.dtbo"
	for p in spi0-0 spi1-0; do
		run "$out/log/two.$p" "$bin/python3" "$here/overlay-params.py" apply \
			"$dtbo" "$out/params/two.$p.dtbo" "$out/log/two.$p.expect" "$p" || exit 1
	done
	merged="$out/merged/two-chips.dtb"
	run "$out/log/two.apply" fdtoverlay -i "$out/base.dtb" -o "$merged" \
		"$out/params/two.spi0-0.dtbo" "$out/params/two.spi1-0.dtbo" || exit 1
	validate "$merged" || exit 1
	for p in spi0-0 spi1-0; do
		case $p in spi0-0) can=/soc/spi@7e204000/can@0 ;; *) can=/soc/spi@7e215080/can@0 ;; esac
		osc=/mcp2510-mcp2515-$p-osc
		int=/soc/gpio@7e200000/mcp2510-mcp2515-$p-int
		[ "$(fdtget -t u "$merged" "$can" clocks)" = "$(fdtget -t u "$merged" "$osc" phandle)" ] ||
			{ echo "$can does not take its clock from $osc"; exit 1; }
		[ "$(fdtget -t u "$merged" "$can" pinctrl-0)" = "$(fdtget -t u "$merged" "$int" phandle)" ] ||
			{ echo "$can does not use the pin configuration $int"; exit 1; }
		echo "$can: $osc, $int"
	done
)
echo "dt-check: two chips from one overlay"
if two_chips >"$out/log/two-chips.txt" 2>&1; then
	pass "mcp2510-mcp2515 spi0-0 + mcp2510-mcp2515 spi1-0: two chips, each its own oscillator and INT pin"
else
	sed 's/^/        /' "$out/log/two-chips.txt"
	fail "mcp2510-mcp2515 spi0-0 + mcp2510-mcp2515 spi1-0"
fi

echo "dt-check: parameter uses (dts/test/bad-params: each must be rejected)"
while read -r name args; do
	case $name in "" | "#"*) continue ;; esac
	expect=${args#*expect: }
	args=${args%% expect:*}
	# shellcheck disable=SC2086
	if check_params "$name" "$out/overlays/$name.dtbo" $args >"$out/log/bad-params.txt" 2>&1; then
		fail "$name $args: accepted, should fail with: $expect"
	elif grep -qF -- "$expect" "$out/log/bad-params.txt"; then
		pass "$name $args: rejected ($expect)"
	else
		sed 's/^/        /' "$out/log/bad-params.txt"
		fail "$name $args: rejected, but not with: $expect"
	fi
done <"$here/test/bad-params"

echo "dt-check: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
