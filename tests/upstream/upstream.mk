# tests/upstream/upstream.mk: the patch series for mainline mcp251x
# (upstream/mcp251x/: fixes and features, each with its reproducer on the
# rig).
#
#   make upstream-check   the series, patch by patch, on the mcp251x.c of
#                         the newest kernel source Debian ships
#                         (linux-source-$(KERNEL_NEWEST), trixie-backports):
#                         checkpatch.pl --strict on each patch file, W=1
#                         C=1 builds against the rig's 6.12 and newest
#                         headers at each step, each patch's reproducer
#                         failing before its patch and passing after it on
#                         the rig's 6.12 kernel, and all of them with the
#                         whole series on 6.12 and the newest kernel
#                         (tests/upstream/upstream-check says how)
#   make upstream-bench [UPSTREAM_BENCH_STEPS="0 12"] [UPSTREAM_BENCH_PROFILE=pi]
#              [UPSTREAM_BENCH_SCALE=100] [UPSTREAM_BENCH_JOBS=2]
#                         make bench's figures for mcp251x with the modules
#                         of those steps of the series (default: the first
#                         and the last; make upstream-check builds them),
#                         on both chips: a table, no verdict
#
# It installs what it needs, as make check does, which runs it after
# vmtest; it downloads Debian's whole kernel source package once for one
# file and checkpatch.pl.

UPSTREAM_DIR := $(TOP)/tests/upstream
# The pristine file and checkpatch.pl, fetched once per Debian version.
CLEAN_KEEP += upstream/source

ifneq ($(filter upstream-check upstream-bench,$(MAKECMDGOALS)),)
export MCP2510_INSTALL_DEPS := 1
endif

.PHONY: upstream-check
upstream-check: vm-kernel-6.12 vm-kernel-$(KERNEL_NEWEST)
	@$(MAKE) --no-print-directory $(VMTEST_DEPS) VM_KERNELS="6.12 $(KERNEL_NEWEST)"
	@$(UPSTREAM_DIR)/upstream-check

UPSTREAM_BENCH_PROFILE ?= pi
UPSTREAM_BENCH_SCALE ?= 100
UPSTREAM_BENCH_JOBS ?= 2
.PHONY: upstream-bench
upstream-bench: vm-kernel-6.12
	@$(ENSURE) python3
	@$(MAKE) --no-print-directory modules-rig userspace vm-guest-tools VM_KERNELS=6.12
	@$(BENCH_ENV) BENCH_JOBS=$(UPSTREAM_BENCH_JOBS) \
		UPSTREAM_BENCH_STEPS="$(UPSTREAM_BENCH_STEPS)" \
		UPSTREAM_BENCH_PROFILE=$(UPSTREAM_BENCH_PROFILE) \
		UPSTREAM_BENCH_SCALE=$(UPSTREAM_BENCH_SCALE) \
		$(UPSTREAM_DIR)/upstream-bench
