#!/bin/sh
# make demo: what a user of an MCP2510 on an SBC would type, against two
# simulated MCP2510s on one CAN bus in a QEMU guest running Debian's kernel.
set -eu
. /lib/rig.sh

say() {
	printf '\n### %s\n' "$*"
}

run() {
	printf '$ %s\n' "$*"
	"$@"
}

say "Two MCP2510s probed by mcp2510.ko: can0 and can1, down until configured"
run ip -brief link show type can

say "Bring both up at 125 kbit/s"
run ip link set can0 up type can bitrate 125000
run ip link set can1 up type can bitrate 125000
# The link state follows "up" up to a second later (rig.sh, wait_operstate):
# until then ip would show the interface as NO-CARRIER, state DOWN.
wait_operstate can0 || fail "can0: link state '$OPERSTATE' after up"
wait_operstate can1 || fail "can1: link state '$OPERSTATE' after up"
run ip -brief link show type can
run ip -details link show can1

say "can0 -> can1: standard, extended and remote frames"
dump_start can1 3 /tmp/can1.txt
run cansend can0 123#DEADBEEF
run cansend can0 12345678#0102030405060708
run cansend can0 321#R
dump_wait
echo "candump can1 saw:"
cat /tmp/can1.txt
expect_lines /tmp/can1.txt 3

say "can1 -> can0: a burst of 20 frames with counting payloads"
dump_start can0 20 /tmp/can0.txt
run cangen -g 10 -n 20 -I 7A0 -L 8 -D i can1
dump_wait
echo "candump can0 saw:"
cat /tmp/can0.txt
expect_lines /tmp/can0.txt 20

say "Bit timing, error state, TEC/REC and traffic statistics"
run ip -details -statistics link show can0
run ip -details -statistics link show can1

run ip link set can0 down
run ip link set can1 down
say "Demo finished: frames crossed the simulated bus both ways"
