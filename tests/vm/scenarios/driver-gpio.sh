#!/bin/sh
# vm-run: --nodes 2 --sim-param gpio_controller=1
# vm-kernels: 6.12 rt debug
# The chip's spare pins as a gpiochip when the firmware marks the device
# gpio-controller: gpioinfo shows the driver's five lines with their fixed
# directions, gpioset drives RX0BF/RX1BF (the simulated pins follow, and
# keep their level across the reset of an ifup), a failed SPI write of a
# pin reaches the caller or the log, gpioget reads the TXnRTS inputs as the
# simulator drives them.
set -eu
. /lib/rig.sh

expect() { # WHAT GOT WANTED
	[ "$2" = "$3" ] || fail "$1 is '$2', expected '$3'"
}

# The gpiochip is labelled with the SPI device's name (6.12: spi-<node>).
dev=$(sim_state 0 spi_device)
chip=$(gpio_chip "$dev")
[ -n "$chip" ] || { gpiodetect; fail "no gpiochip labelled $dev"; }
gpiodetect | grep "^$chip " | grep -q '(5 lines)' || fail "$chip has not 5 lines"
gpio_info "$chip" | tee /tmp/info
n=0
for want in "RX0BF output" "RX1BF output" "TX0RTS input" "TX1RTS input" "TX2RTS input"; do
	name=${want% *} dir=${want#* }
	grep -q "line *$n:[[:space:]]*\"$name\"[[:space:]].*$dir" /tmp/info || fail "line $n is not $name, $dir"
	n=$((n + 1))
done

echo "== gpioset drives RX0BF and RX1BF"
for line in 0 1; do
	pin=rx${line}bf
	expect "$pin at start" "$(sim_state 0 $pin)" 1
	gpio_set "$chip" $line=0
	expect "$pin after gpioset $line=0" "$(sim_state 0 $pin)" 0
	expect "chip1 $pin" "$(sim_state 1 $pin)" 1
	gpio_set "$chip" $line=1
	expect "$pin after gpioset $line=1" "$(sim_state 0 $pin)" 1
done
gpio_set "$chip" 0=0 1=1
can_up can0 125000
expect "rx0bf after ifup's chip reset" "$(sim_state 0 rx0bf)" 0
expect "rx1bf after ifup's chip reset" "$(sim_state 0 rx1bf)" 1
ip link set can0 down
expect "rx0bf after ifdown" "$(sim_state 0 rx0bf)" 0

echo "== a failed write of RX0BF is not swallowed"
# gpio-set requests line 0 at 1, then sets it to 0 with the SPI message
# failing.  Where gpiolib's .set returns an error the caller gets it; on
# kernels whose .set returns nothing the driver can only log it.
dmesg -c >/dev/null
st=0
out=$(gpio-set "/dev/$chip" 0 1 0 "$SIM/chip0/spi_errors" 1) || st=$?
echo "$out"
echo 0 >"$SIM/chip0/spi_errors"
case $st in
0)
	# %pe prints the number where CONFIG_SYMBOLIC_ERRNAME is off (debug).
	dmesg | grep -Eq "setting RX0BF failed: (-EIO|-5)$" ||
		fail "the failed write was neither returned nor logged" ;;
1) [ "$out" = "set: failed: Input/output error" ] || fail "gpio-set: $out" ;;
*) fail "gpio-set could not run: $out" ;;
esac
expect "rx0bf after the failed write" "$(sim_state 0 rx0bf)" 1

echo "== gpioget reads TX0RTS-TX2RTS"
expect "TXnRTS idle" "$(gpio_get "$chip" 2 3 4)" "1 1 1"
for levels in 6:"0 1 1" 5:"1 0 1" 3:"1 1 0" 0:"0 0 0"; do
	echo "${levels%%:*}" >$SIM/chip0/rts
	expect "TXnRTS with rts=${levels%%:*}" "$(gpio_get "$chip" 2 3 4)" "${levels#*:}"
done
echo 7 >$SIM/chip0/rts

echo "== only gpio-controller devices have a gpiochip"
[ "$(gpiodetect | grep -c '\[spi')" -eq 2 ] || { gpiodetect; fail "not one gpiochip per chip"; }
echo "driver-gpio: ok"
