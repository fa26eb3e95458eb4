# mcp2510: SocketCAN driver for the Microchip MCP2510/MCP2515/MCP25625,
# its userspace port, and the simulated chip both are tested against.
#
# Every area keeps its rules in its own fragment; this file only ties them
# together and defines the targets README.md documents.

TOP := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
BUILD := $(TOP)/build
ENSURE := $(TOP)/scripts/ensure-packages

CC ?= cc
CSTD := -std=c11

# Warnings are errors in the project's own checks (make check passes
# WERROR=1 to every step), not for someone building a release with a
# compiler newer than the one the code was last checked with.
WERROR ?= 0
WARN := -Wall -Wextra $(if $(filter 1,$(WERROR)),-Werror)

# Packages are installed only by make deps, check, demo and bench (or any
# target with INSTALL_DEPS=1); other targets name what is missing and stop
# (scripts/ensure-packages).  Without dpkg nothing is checked: Buildroot,
# Yocto and other distributions bring their own dependencies.
# A sub-make keeps the decision of the make that started it: its own goals
# (demo's VMTEST_DEPS) are not the ones that decided.
ifneq ($(filter deps check demo bench,$(MAKECMDGOALS)),)
INSTALL_DEPS := 1
endif
INSTALL_DEPS ?= $(MCP2510_INSTALL_DEPS)
export MCP2510_INSTALL_DEPS := $(filter 1,$(INSTALL_DEPS))

# Quiet by default ("  CC      file"); V=1 prints every command.
V ?= 0
ifeq ($(V),1)
quiet :=
else
quiet = @printf '  %-7s %s\n' '$(1)' '$(patsubst $(TOP)/%,%,$(2))';
endif
SANITIZE := -fsanitize=address,undefined -fno-omit-frame-pointer \
	    -fno-sanitize-recover=all

# What compiling C takes: a new machine may have no compiler.  Every rule
# that runs $(CC) comes after cc-deps (or a -deps target naming these).
CC_PACKAGES := build-essential pkg-config
# Packages every host-side build and test needs.
HOST_PACKAGES := $(CC_PACKAGES) libcmocka-dev libgpiod-dev

.PHONY: all check deps cc-deps help clean distclean
all: unit-build userspace

help:
	@echo "make check     everything CI runs (installs what it needs)"
	@echo "make deps      the Debian packages builds and tests need"
	@echo "make demo      two simulated MCP2510s exchanging frames"
	@echo "make unit      cmocka suites; make unit-asan: the same under ASan/UBSan"
	@echo "make coverage  line coverage of the chip model (tests/sim)"
	@echo "make userspace libmcp2510, mcp2510ctl, mcp2510d"
	@echo "make install-userspace  them, man pages, unit (DESTDIR=, PREFIX=); make uninstall-userspace"
	@echo "make modules   kernel modules (KDIR= selects the headers)"
	@echo "make install   mcp2510.ko (DESTDIR= stages it); make uninstall"
	@echo "make deb       Debian packages in build/deb; make deb-check (root)"
	@echo "make vmtest    scenario suite in QEMU; make dt-check"
	@echo "make bench     figures against mainline, in pieces (BENCH_PROFILES=, BENCH_SCALES=, BENCH_JOBS=)"
	@echo "make bench-check  the bench report's rules on canned logs"
	@echo "make hwtest IFACES=\"can0 can1\"  the test kit on two wired CAN interfaces (root)"
	@echo "make fresh-root-check  make demo, deps and deb-check in minimal Debian 12 and 13 roots"
	@echo "make fresh-root-background  start it at idle priority; make fresh-root-await: its verdict"
	@echo "make kernels-news  is there a kernel series newer than the ones tested?"
	@echo "make clean     remove build products, keep downloads, kernels and roots"
	@echo "make distclean remove all of build/"

deps:
	@$(ENSURE) $(HOST_PACKAGES)

cc-deps:
	@$(ENSURE) $(CC_PACKAGES)

# What make clean keeps under build/: downloads, unpacked kernels, roots
# and the debug kernel, slow to fetch or make and independent of the
# sources.  Fragments add their own paths (relative to build/).
CLEAN_KEEP :=

clean:
	@$(TOP)/scripts/clean-build $(BUILD) $(CLEAN_KEEP)

distclean:
	rm -rf $(BUILD)

# $(call option_stamp,FILE,TEXT): a rule keeping TEXT in FILE, rewritten
# only when TEXT changes.  What a build option affects depends on the
# stamp holding that option, so changing the option rebuilds it.
define option_stamp
$(1): FORCE
	@mkdir -p $$(@D)
	@printf '%s\n' '$(subst ','\'',$(2))' | cmp -s - $$@ || \
		printf '%s\n' '$(subst ','\'',$(2))' >$$@
endef

.PHONY: FORCE
FORCE:

# The kernel series built and tested for, KERNEL_NEWEST among them
# (tests/matrix/matrix.mk).
include tests/matrix/kernels

# Fragments append their steps to CHECK_STEPS in the order they should run.
CHECK_STEPS :=

include tests/sim/sim.mk
include driver/core/core.mk
include userspace/userspace.mk
include tests/unit/unit.mk
include driver/driver.mk
include tests/install/install.mk
include tests/packaging/packaging.mk
include tests/build/build.mk
include tests/vm-arm64/vm-arm64.mk
include tests/kmod/kmod.mk
include tests/vm/vm.mk
include tests/hw/hw.mk
include tests/soak/soak.mk
include dts/dts.mk
include tests/fuzz/fuzz.mk
include tests/lint/lint.mk
# Late: the Debian 13 root it needs is made in the background meanwhile.
include tests/trixie/trixie.mk
include tests/bench/bench.mk
include tests/matrix/matrix.mk
include tests/upstream/upstream.mk

# Then the scenario suite on the rig kernels, so that the debug kernel's
# build (tests/vm/vm.mk) has had every other step to overlap with, and
# the patch series for mainline, whose guests overlap the fresh-root
# check's last stretch.
CHECK_STEPS += vmtest upstream-check
# Last, the fresh-root check's verdict: its roots, clones and demos run in
# the background at idle priority from the start, taking what the other
# steps leave of the cores (vmtest's guests leave some while they wait on
# simulated bus time), so that no step waits for them before vmtest.
include tests/fresh-root/fresh-root.mk

check: deps
	@set -e; check_start=$$(date +%s); for step in $(CHECK_STEPS); do \
		step_start=$$(date +%s); echo "== make $$step"; \
		$(MAKE) --no-print-directory $$step INSTALL_DEPS=1 WERROR=1; \
		echo "== make $$step: done in $$(( $$(date +%s) - step_start )) s"; \
	done; \
	echo "== make check: all steps passed in $$(( $$(date +%s) - check_start )) s ($(CHECK_STEPS))"
