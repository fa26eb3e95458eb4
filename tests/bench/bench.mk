# tests/bench/bench.mk: make bench, figures rather than tests
# (docs/performance.md).  Not part of make check: it asserts nothing.
#
#   make bench [BENCH_PROFILES="base pi pi-rt slow"] [BENCH_SCALES="50 100 200"]
#              [BENCH_JOBS=4] [BENCH_RT_PROFILES=pi-rt] [BENCH_RT_SCALES=100]
#              [BENCH_FRAMES=100] [BENCH_FLOOD_FRAMES=1000]
#              [BENCH_PROBE_FRAMES=200] [BENCH_TX_FRAMES=300]
#              [BENCH_CPU_FRAMES=1000]
#              [BENCH_TIME_SCALE=10] [BENCH_BITRATES="10000 ... 1000000"]
#              [BENCH_TIMED_FRAMES=100] [BENCH_TIMED_FLOOD_FRAMES=1000]
#              [BENCH_TIMED_CPU_FRAMES=200] [BENCH_TIMED_TIME_SCALE=200]
#              [BENCH_TIMED_RX_BITRATES="50000 ... 1000000"]
#              [BENCH_TIMED_TX_BITRATES="125000 500000 1000000"]
#              [BENCH_STALL_TRIES=3]
#              [BENCH_COMPARE_BITRATES="125000 250000"]
#              [BENCH_SATURATION_BITRATE=1000000]
#
# Boots Debian's 6.1 kernel four times per piece (mcp2510.ko and mainline
# mcp251x, each on a simulated MCP2510 and MCP2515), BENCH_JOBS at a time:
# "base" with SPI that takes no time (and the userspace port's bench on the
# host), "pi", "pi-rt" and "slow" with the simulator's SPI time set to a
# board's costs, one piece per cost scale (in percent); the pieces of
# BENCH_RT_PROFILES at BENCH_RT_SCALES boot Debian's 6.12 PREEMPT_RT kernel
# four more times for the latency figures alone.  Prints tables and writes
# build/bench/summary.json and the figures and plot of docs/performance.md
# from every piece in build/bench, earlier runs' included, so a full set
# can be gathered in pieces; fails when a figure is missing (a measurement
# the bus clock stalled across in each of its tries) or a piece is stale
# (measured on other sources or with other settings).

BENCH_OUT := $(BUILD)/bench
BENCH_PROFILES ?= base pi pi-rt slow
BENCH_JOBS ?= 4
BENCH_RT_PROFILES ?= pi-rt
BENCH_RT_SCALES ?= 100
BENCH_PROBE_FRAMES ?= 200
BENCH_TX_FRAMES ?= 300
BENCH_FRAMES ?= 100
BENCH_FLOOD_FRAMES ?= 1000
BENCH_CPU_FRAMES ?= 1000
BENCH_TIME_SCALE ?= 10
BENCH_BITRATES ?= 10000 20000 50000 100000 125000 250000 500000 800000 1000000
BENCH_TIMED_FRAMES ?= 100
BENCH_TIMED_FLOOD_FRAMES ?= 1000
BENCH_TIMED_CPU_FRAMES ?= 200
BENCH_TIMED_TIME_SCALE ?= 200
BENCH_TIMED_RX_BITRATES ?= 50000 100000 125000 250000 500000 800000 1000000
BENCH_TIMED_TX_BITRATES ?= 125000 500000 1000000
BENCH_SCALES ?= 50 100 200
BENCH_STALL_TRIES ?= 3
BENCH_COMPARE_BITRATES ?= 125000 250000
BENCH_SATURATION_BITRATE ?= 1000000
BENCH_PACKAGES := gnuplot-nox python3

# The settings of a boot's /extra/bench.conf (tests/bench/conf.sh), for
# tests/bench/run and make upstream-bench.
BENCH_ENV = BENCH_PROBE_FRAMES=$(BENCH_PROBE_FRAMES) \
	BENCH_TX_FRAMES=$(BENCH_TX_FRAMES) BENCH_FRAMES=$(BENCH_FRAMES) \
	BENCH_FLOOD_FRAMES=$(BENCH_FLOOD_FRAMES) \
	BENCH_TIMED_FLOOD_FRAMES=$(BENCH_TIMED_FLOOD_FRAMES) \
	BENCH_STALL_TRIES=$(BENCH_STALL_TRIES) \
	BENCH_COMPARE_BITRATES="$(BENCH_COMPARE_BITRATES)" \
	BENCH_SATURATION_BITRATE=$(BENCH_SATURATION_BITRATE) \
	BENCH_CPU_FRAMES=$(BENCH_CPU_FRAMES) BENCH_TIME_SCALE=$(BENCH_TIME_SCALE) \
	BENCH_BITRATES="$(BENCH_BITRATES)" BENCH_TIMED_FRAMES=$(BENCH_TIMED_FRAMES) \
	BENCH_TIMED_CPU_FRAMES=$(BENCH_TIMED_CPU_FRAMES) \
	BENCH_TIMED_TIME_SCALE=$(BENCH_TIMED_TIME_SCALE) \
	BENCH_TIMED_RX_BITRATES="$(BENCH_TIMED_RX_BITRATES)" \
	BENCH_TIMED_TX_BITRATES="$(BENCH_TIMED_TX_BITRATES)"

.PHONY: bench
bench: vm-kernel-6.1 vm-kernel-rt
	@$(ENSURE) $(BENCH_PACKAGES)
	@$(MAKE) --no-print-directory modules-rig userspace vm-guest-tools \
		VM_KERNELS="6.1 rt"
	@$(BENCH_ENV) BENCH_OUT=$(BENCH_OUT) BENCH_PROFILES="$(BENCH_PROFILES)" \
		BENCH_JOBS=$(BENCH_JOBS) BENCH_RT_PROFILES="$(BENCH_RT_PROFILES)" \
		BENCH_RT_SCALES="$(BENCH_RT_SCALES)" BENCH_SCALES="$(BENCH_SCALES)" \
		BENCH_DOC=$(TOP)/docs/performance.md \
		$(TOP)/tests/bench/run

# The report's counting and stall rules on canned guest lines
# (tests/bench/test_report.py) and its pieces: merged across runs, stale
# ones refused, the before/after table (tests/bench/test_pieces.py): a few
# seconds, no QEMU.
.PHONY: bench-check
bench-check:
	@$(ENSURE) python3
	@python3 $(TOP)/tests/bench/test_report.py
	@python3 $(TOP)/tests/bench/test_pieces.py
CHECK_STEPS += bench-check
