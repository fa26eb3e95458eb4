# Receive timestamp checks for scenario scripts, in the guest at
# /lib/rx-timestamps.sh, after /lib/rig.sh: driver-rx-timestamp's, which
# make upstream-check's upstream-rx-timestamp runs on mcp251x.  can1
# receives from the phantom node.  Failures name $under_test when set.

STAMP_FRAMES=60

# stamps_offered IF: ethtool -T offers software receive stamps on IF and
# claims no hardware ones (the chip has no clock).
stamps_offered() {
	ethtool -T "$1" >/tmp/tsinfo.txt || fail "ethtool -T $1 failed"
	grep -q "software-receive" /tmp/tsinfo.txt ||
		{ cat /tmp/tsinfo.txt; fail "software receive stamps not offered"; }
	! grep -q "hardware-receive" /tmp/tsinfo.txt ||
		{ cat /tmp/tsinfo.txt; fail "hardware stamps claimed for host clock stamps"; }
}

# stamp_burst BITRATE TIME_SCALE: STAMP_FRAMES frames back to back from
# the phantom to can1, each stamp not before the end of its frame on the
# bus (the simulator's monitor_times), before recvmsg() returned it and
# not before the stamp of the frame before, in SO_TIMESTAMPNS and in
# candump -t a; sets STORED and LOST (frames the chip stored and lost).
stamp_burst() {
	can_up can1 "$1"
	echo "$2" >"$SIM/time_scale"
	echo 0 >"$SIM/chip1/counters"
	echo clear >"$SIM/monitor"
	dump_start can1 "$STAMP_FRAMES" /tmp/dump.txt -t a
	: >/tmp/ts.txt
	can-tstamp can1 "$STAMP_FRAMES" "$SIM/monitor_times" >>/tmp/ts.txt &
	TS_PID=$!
	wait_for 20 ts_ready || fail "can-tstamp never listened"
	echo "$STAMP_FRAMES 100#00000000 $1" >"$SIM/flood"
	wait "$TS_PID" || fail "can-tstamp failed"
	# it stopped 3 s after the last frame: candump has them all too (and
	# has ended by itself if that was all STAMP_FRAMES)
	kill "$DUMP_PID" 2>/dev/null || true
	dump_wait
	ip link set can1 down

	STORED=$(sim_counter 1 frames_rx)
	LOST=$(sim_counter 1 overflows)
	echo "$1 bit/s, time_scale $2: chip stored $STORED, lost $LOST to full buffers"
	stamps_honest
	sort -n -k2 /tmp/err.txt | awk '{ e[NR] = $2 } END {
		printf "stamp - end of frame: median %d us, max %d us\n",
		       e[int((NR + 1) / 2)] / 1000, e[NR] / 1000 }'
	sort -n -k3 /tmp/err.txt | awk '{ e[NR] = $3 } END {
		printf "recvmsg - stamp: median %d us\n", e[int((NR + 1) / 2)] / 1000 }'

	# candump -t a: (SECONDS.MICROSECONDS) never decreasing; both parts are
	# zero-padded, so the digits compare as strings (busybox awk takes a
	# number with a leading 0 for octal)
	[ "$(wc -l </tmp/dump.txt)" -eq "$STORED" ] ||
		{ cat /tmp/dump.txt; fail "candump got $(wc -l </tmp/dump.txt) of $STORED frames"; }
	tr -d '()' </tmp/dump.txt | awk '{ split($1, t, "[.]"); k = t[1] "" t[2]
		if (NR > 1 && k < last) { print "back in time: " p; print "          to: " $0; bad = 1 }
		last = k; p = $0 } END { exit bad }' ||
		fail "${under_test:+$under_test: }candump -t a timestamps go back"
}
ts_ready() { read -r _l </tmp/ts.txt && [ "$_l" = ready ]; }

# stamps_honest: can-tstamp's lines in /tmp/ts.txt (after its "ready"),
# one for each of the STORED frames can1's chip stored, each stamp not
# before the end of its frame, before recvmsg() returned it and not
# before the stamp of the frame before; the lines go to /tmp/err.txt.
stamps_honest() {
	sed 1d /tmp/ts.txt >/tmp/err.txt
	_got=$(wc -l </tmp/err.txt)
	[ "$_got" -eq "$STORED" ] || { cat /tmp/ts.txt; fail "got $_got stamped frames of $STORED"; }
	! grep -q missing /tmp/err.txt || { cat /tmp/ts.txt; fail "a frame not on the bus"; }
	# FRAME STAMP-END RECV-STAMP STAMP-PREV, in ns
	awk '$2 < 0 { print "stamped before its end of frame: " $0; bad = 1 }
	     $3 <= 0 { print "stamped after recvmsg() returned it: " $0; bad = 1 }
	     $4 < 0 { print "stamp earlier than the frame before: " $0; bad = 1 }
	     END { exit bad }' /tmp/err.txt || fail "${under_test:+$under_test: }dishonest timestamps"
}

# stamp_bursts: stamp_burst faster than the guest takes frames (both
# buffers fill and overflow), then slow enough for the driver to take
# many frames, a pass at a time (the debug kernel is several times
# slower).
stamp_bursts() {
	stamp_burst 500000 1
	[ "$LOST" -gt 0 ] || fail "no overflow: both buffers were never full (guest too fast?)"
	_scale=4
	[ "$VM_KERNEL" != debug ] || _scale=20
	stamp_burst 125000 "$_scale"
	[ "$STORED" -ge 10 ] || fail "only $STORED frames stored: too few passes to judge"
}

# stamp_isolated: frames one at a time, with SPI messages that cost
# SPI_MSG_NS each.  The chip is read (flags, then the buffer: two
# messages at least) before a frame can be queued, so a stamp taken by
# the stack, or by the
# driver once it has read the frame, is 2 * SPI_MSG_NS after the end of
# frame at least; the time INT fired is not.  The first frame follows
# the chip's reset at start, which leaves its pass nothing to go on: it
# is stamped after the flags read, so it is left out.  Fails (status 1)
# when a stamp is not within 2 * SPI_MSG_NS of the end of its frame.
SPI_MSG_NS=50000000
stamp_isolated() {
	echo "$SPI_MSG_NS" >"$SIM/spi_msg_ns"
	echo 0 >"$SIM/irq_latency_ns"
	echo 1 >"$SIM/spi_time"
	can_up can1 125000
	echo 1 >"$SIM/time_scale"
	echo clear >"$SIM/monitor"
	: >/tmp/ts.txt
	can-tstamp can1 6 "$SIM/monitor_times" >>/tmp/ts.txt &
	TS_PID=$!
	wait_for 20 ts_ready || fail "can-tstamp never listened"
	for i in 0 1 2 3 4 5; do
		echo "200#0$i 125000" >"$SIM/inject"
		nap 0.5
	done
	wait "$TS_PID" || fail "can-tstamp failed"
	ip link set can1 down
	echo 0 >"$SIM/spi_time"
	sed '1,2d' /tmp/ts.txt >/tmp/err.txt
	cat /tmp/err.txt
	[ "$(wc -l </tmp/err.txt)" -eq 5 ] || { cat /tmp/ts.txt; fail "lone frames lost"; }
	awk -v lim=$((2 * SPI_MSG_NS)) '$2 < 0 || $2 >= lim {
		print "not stamped when INT fired: " $0; bad = 1 } END { exit bad }' \
		/tmp/err.txt
}

# stamp_paced: lone frames at uneven gaps of two to six SPI messages of
# SPI_MSG_NS, so that some come while the IRQ thread is busy with the one
# before and some just after it is done: on an edge-triggered line the
# hard handler then also fires during a run of the thread, and the time
# it notes belongs to a frame that run reads, not to the first frame of
# the next run.  Every stamp honest, as stamp_burst checks them.
STAMP_GAPS="0.11 0.16 0.27 0.13 0.29 0.12 0.21 0.14 0.26 0.17 0.11 0.28 0.15 0.23 0.12 0.30 0.18 0.25 0.13 0.20"
stamp_paced() {
	echo "$SPI_MSG_NS" >"$SIM/spi_msg_ns"
	echo 0 >"$SIM/irq_latency_ns"
	echo 1 >"$SIM/spi_time"
	can_up can1 125000
	echo 1 >"$SIM/time_scale"
	echo 0 >"$SIM/chip1/counters"
	echo clear >"$SIM/monitor"
	: >/tmp/ts.txt
	can-tstamp can1 $(($(echo $STAMP_GAPS | wc -w) + 1)) "$SIM/monitor_times" >>/tmp/ts.txt &
	TS_PID=$!
	wait_for 20 ts_ready || fail "can-tstamp never listened"
	echo "300#00 125000" >"$SIM/inject"
	_n=0
	for _gap in $STAMP_GAPS; do
		nap "$_gap"
		_n=$((_n + 1))
		printf '300#%02X 125000\n' "$_n" >"$SIM/inject"
	done
	wait "$TS_PID" || fail "can-tstamp failed"
	ip link set can1 down
	echo 0 >"$SIM/spi_time"
	STORED=$(sim_counter 1 frames_rx)
	echo "paced frames at gaps of $STAMP_GAPS s, SPI messages of $((SPI_MSG_NS / 1000000)) ms: chip stored $STORED"
	stamps_honest
}
