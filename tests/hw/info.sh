# What the kit's report says of the system (sourced by mcp2510-hwtest):
# the driver bound to each interface, its version, the chip the SPI
# device was declared as, the SPI clock, the oscillator, the kernel and
# the board, from sysfs, /proc and iproute2 alone.

# be32 FILE: a device-tree cell as a number.
be32() { od -An -tu1 -v -N 4 "$1" | awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4 }'; }

board() {
	if [ -r /proc/device-tree/model ]; then
		tr -d '\0' </proc/device-tree/model
	elif [ -r /sys/class/dmi/id/product_name ]; then
		echo "$(cat /sys/class/dmi/id/sys_vendor 2>/dev/null) $(cat /sys/class/dmi/id/product_name)"
	else
		echo unknown
	fi
}

# describe IF: the "info" lines of one interface.
describe() {
	dev=/sys/class/net/$1/device
	drv=$(basename "$(readlink "$dev/driver" 2>/dev/null)" 2>/dev/null)
	# a module without a version of its own: in the kernel's tree it is
	# the kernel's; out of it (taint O), its source checksum if any
	if [ -r "/sys/module/$drv/version" ]; then
		ver=$(cat "/sys/module/$drv/version")
	elif grep -q O "/sys/module/$drv/taint" 2>/dev/null; then
		ver="out-of-tree, srcversion $(cat "/sys/module/$drv/srcversion" 2>/dev/null || echo unknown)"
	else
		ver="in-tree, $(uname -r)"
	fi
	chip=$(sed -n 's/.*\(mcp25[0-9]*\).*/\1/p' "$dev/modalias" 2>/dev/null)
	spi=$(basename "$(readlink "$dev" 2>/dev/null)" 2>/dev/null)
	hz=unknown
	[ ! -r "$dev/of_node/spi-max-frequency" ] || hz=$(be32 "$dev/of_node/spi-max-frequency")
	clock=$(ip -details link show "$1" | sed -n 's/.* clock \([0-9]*\).*/\1/p' | head -n 1)
	info "$1.driver ${drv:-none}"
	info "$1.driver_version $ver"
	info "$1.chip ${chip:-unknown}"
	info "$1.spi_device ${spi:-none}"
	info "$1.spi_max_hz $hz"
	# the CAN clock is half the oscillator on these chips
	info "$1.oscillator_hz $([ -n "$clock" ] && echo $((clock * 2)) || echo unknown)"
}

system_info() {
	info kernel "$(uname -r)"
	info machine "$(uname -m)"
	info board "$(board)"
	info cpus "$(grep -c '^processor' /proc/cpuinfo)"
	info date "$(date -u +%Y-%m-%dT%H:%M:%SZ)"
	info interfaces "$A $B"
	info frames "$FRAMES"
	info bitrates "$BITRATES"
	describe "$A"
	describe "$B"
	# shellcheck disable=SC2034 # for the other parts of the kit
	DRIVER=$(sed -n "s/^info $A.driver //p" "$RESULTS")
	CHIP=$(sed -n "s/^info $A.chip //p" "$RESULTS")
	SPI_A=$(sed -n "s/^info $A.spi_device //p" "$RESULTS")
	SPI_B=$(sed -n "s/^info $B.spi_device //p" "$RESULTS")
}
