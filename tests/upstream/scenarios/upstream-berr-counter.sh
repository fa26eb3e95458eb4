#!/bin/sh
# vm-run: --nodes 2 --variant mcp2515 --driver mcp251x
# Shows what upstream/mcp251x/0004 adds: TEC and REC in "ip -details link
# show" (can-dev's do_get_berr_counter).  Thirteen injected bus errors
# destroy can0's frame thirteen times before it goes through: the sender's
# TEC ends at 13 x 8 - 1 = 103, each receiver's REC at 13 - 1 = 12, as the
# chips' own counters say.  Down, an interface shows none (6.12) or
# zeros (7.3).
# Which mcp251x runs, and what it must show: mcp251x_under_test (rig.sh).
set -eu
. /lib/rig.sh

mcp251x_under_test

# berr IF: "tx N rx M" as ip shows it, empty when it shows none.
berr() {
	ip -details link show "$1" | sed -n 's/.*(berr-counter \(tx [0-9]* rx [0-9]*\)).*/\1/p'
}
# chip_berr N: the same from simulated chip N's own counters.
chip_berr() { echo "tx $(sim_state "$1" tec) rx $(sim_state "$1" rec)"; }

can_up can0 125000
can_up can1 125000
echo 13 >"$SIM/bus_errors"
tx0=$(if_stat can0 tx_packets)
cansend can0 123#5A
wait_for 30 sent_beyond can0 "$tx0" || fail "$under_test: 123#5A never went through"
shown0=$(berr can0) shown1=$(berr can1)
echo "$under_test: can0 '$shown0' (chip $(chip_berr 0)), can1 '$shown1' (chip $(chip_berr 1))"

if [ -z "$ko" ]; then
	[ -z "$shown0" ] || fail "$under_test shows the error counters: the kernel has the change"
	echo "upstream-berr-counter: $under_test shows no error counters"
	exit 0
fi
[ -n "$shown0" ] || fail "$under_test shows no error counters"
[ "$shown0" = "$(chip_berr 0)" ] && [ "$shown0" = "tx 103 rx 0" ] ||
	fail "$under_test: can0 shows $shown0, chip0 has $(chip_berr 0), expected tx 103 rx 0"
[ "$shown1" = "$(chip_berr 1)" ] && [ "$shown1" = "tx 0 rx 12" ] ||
	fail "$under_test: can1 shows $shown1, chip1 has $(chip_berr 1), expected tx 0 rx 12"
ip link set can0 down
down=$(berr can0)
[ -z "$down" ] || [ "$down" = "tx 0 rx 0" ] || fail "$under_test: can0 down shows $down"
ip link set can1 down
echo "upstream-berr-counter: $under_test shows TEC and REC as the chips count them"
