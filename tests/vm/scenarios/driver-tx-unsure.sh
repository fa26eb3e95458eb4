#!/bin/sh
# vm-run: --nodes 2 --variant mcp2510
# vm-kernels: debug
# An RTS whose transfer fails although it reached the chip, and the READ
# STATUS after it fails too (spi_errors_rts 2): the driver cannot tell
# whether that frame is pending.  It gives the frame up (tx_dropped) and
# keeps its buffer out of use until a READ STATUS shows it free.  The
# frames after it must wait for a buffer, never be dropped: with can1
# down nobody acknowledges, the chip keeps the given-up frame and the
# next two pending, and the fourth waits until can1 comes up and the
# buffers empty.  can0's echoes show what was sent (not the given-up
# frame: its echo went with it).
set -eu
. /lib/rig.sh

can_up can0 125000
# Byte queue limits would keep the fourth frame in the qdisc while the
# others stay pending.
echo 10000 >/sys/class/net/can0/queues/tx-0/byte_queue_limits/limit_min
dropped=$(if_stat can0 tx_dropped)
echo 2 >"$SIM/chip0/spi_errors_rts"
dump_start can0,100:700 3 /tmp/sent.txt
for i in 1 2 3 4; do
	cansend can0 "10$i#0$i" || fail "cansend 10$i"
	nap 0.2
done
expect_eq "spi_errors_rts left" "$(cat "$SIM/chip0/spi_errors_rts")" 0
expect_eq "frames given up" $(($(if_stat can0 tx_dropped) - dropped)) 1
can_up can1 125000
dump_wait
cat /tmp/sent.txt
grep -q '104 *\[1\] *04' /tmp/sent.txt || fail "the frame after the unsure one was lost"
expect_eq "frames given up" $(($(if_stat can0 tx_dropped) - dropped)) 1
echo "driver-tx-unsure: ok"
