# driver/driver.mk: the kernel modules built from the root Kbuild.
#
#   make modules [KDIR=dir]   build against KDIR: the running kernel's build
#                             tree, else the newest /usr/src/linux-headers-*-amd64;
#                             the .ko files land in build/modules/<release>/
#   make modules-rig          the same for each kernel of the QEMU rig that is
#                             there (tests/vm/kernel-info), into
#                             build/modules/<6.1|6.12|debug|rt>/
#   make modules-check        warning-free builds against Debian's 6.1 and 6.12
#                             headers with W=1 and sparse (C=1), no simulator
#                             code in mcp2510.ko, and checkpatch.pl --strict
#                             on every kernel source
#   make install [KDIR=dir]   mcp2510.ko into <modules>/extra, then depmod
#                             (INSTALL_MOD_PATH=dir stages it under dir)
#
# Every build runs in build/kbuild/<tag>/, a tree of symlinks to the
# sources, so builds for several kernels never share objects and the
# source tree stays clean.

RUNNING_KDIR := /lib/modules/$(shell uname -r)/build
NEWEST_HEADERS = $(shell ls -d /usr/src/linux-headers-*-amd64 2>/dev/null | \
		   sort -V | tail -n 1)
KDIR ?= $(if $(wildcard $(RUNNING_KDIR)/Makefile),$(RUNNING_KDIR),$(NEWEST_HEADERS))
# The release modules built against KDIR $(1) load into (vermagic).
kernel_release = $(shell sed -n 's/.*UTS_RELEASE "\(.*\)"/\1/p' \
		   $(1)/include/generated/utsrelease.h 2>/dev/null)

KBUILD_SOURCES := Kbuild uapi driver tests/kmod tests/sim
KBUILD_TREES := $(BUILD)/kbuild
MODULES_OUT := $(BUILD)/modules
KERNEL_PACKAGES := build-essential bc kmod

# $(call kbuild_tree,DIR,SOURCES): one shell command that refreshes DIR as
# a mirror of SOURCES made of symlinks (build products and hidden files left
# out), dropping links whose source is gone.
kbuild_tree = mkdir -p $(1) && \
	(cd $(TOP) && find $(2) -type f ! -name '.*' ! -name '*.o' \
		! -name '*.ko' ! -name '*.mod' ! -name '*.mod.c' 2>/dev/null) | \
	while read -r f; do \
		mkdir -p "$(1)/$$(dirname "$$f")" && ln -sfn "$(TOP)/$$f" "$(1)/$$f"; \
	done && find $(1) -xtype l -delete

# $(call kbuild_modules,KDIR,TAG,MAKEFLAGS): build both modules for one
# kernel and publish them in build/modules/TAG/.
define kbuild_modules
	@test -f $(1)/Makefile || { \
		echo "modules: no kernel build tree at '$(1)' (set KDIR=)" >&2; exit 1; }
	@$(call kbuild_tree,$(KBUILD_TREES)/$(2),$(KBUILD_SOURCES))
	$(MAKE) -C $(1) M=$(KBUILD_TREES)/$(2) $(3) modules
	@mkdir -p $(MODULES_OUT)/$(2)
	@rm -f $(MODULES_OUT)/$(2)/*.ko
	cp $(KBUILD_TREES)/$(2)/*.ko $(MODULES_OUT)/$(2)/
endef

.PHONY: modules modules-rig modules-check install modules-deps checkpatch
modules-deps:
	@$(ENSURE) $(KERNEL_PACKAGES)
	@[ -n "$(KDIR)" ] || $(ENSURE) linux-headers-amd64

# KDIR is looked up again after modules-deps may have installed headers.
modules: modules-deps
	@$(MAKE) --no-print-directory modules-for KDIR='$(or $(KDIR),$(NEWEST_HEADERS))'

.PHONY: modules-for
modules-for:
	$(call kbuild_modules,$(KDIR),$(call kernel_release,$(KDIR)))

# The rig's kernels (tests/vm/vm.mk's VM_KERNELS when set).
RIG_KERNELS = $(or $(VM_KERNELS),6.1 6.12 rt debug)
modules-rig: modules-deps
	@set -e; for k in $(RIG_KERNELS); do \
		kdir=$$($(TOP)/tests/vm/kernel-info $$k kdir 2>/dev/null) || { \
			echo "modules-rig: rig kernel $$k not there yet, not built"; \
			continue; }; \
		$(MAKE) --no-print-directory modules-rig-one KDIR=$$kdir RIG_KERNEL=$$k; \
	done

.PHONY: modules-rig-one
modules-rig-one:
	$(call kbuild_modules,$(KDIR),$(RIG_KERNEL))

# ---- install (SBC users; DKMS uses dkms.conf at the top level) ----------

install: modules-deps
	@$(MAKE) --no-print-directory install-for KDIR='$(or $(KDIR),$(NEWEST_HEADERS))'

.PHONY: install-for
install-for:
	@test -f $(KDIR)/Makefile || { \
		echo "install: no kernel build tree at '$(KDIR)' (set KDIR=)" >&2; exit 1; }
	@$(call kbuild_tree,$(KBUILD_TREES)/install,Kbuild uapi driver)
	$(MAKE) -C $(KDIR) M=$(KBUILD_TREES)/install MCP2510_DRIVER_ONLY=1 modules
	$(MAKE) -C $(KDIR) M=$(KBUILD_TREES)/install MCP2510_DRIVER_ONLY=1 \
		INSTALL_MOD_DIR=extra modules_install
	depmod $(if $(INSTALL_MOD_PATH),-b $(INSTALL_MOD_PATH)) -a \
		$(call kernel_release,$(KDIR))

# ---- modules-check --------------------------------------------------------

# Debian's kernels the module must build for: the 6.1 ABI linux-headers-amd64
# depends on, and the newest 6.12 apt offers.
HEADERS_6_1 = $(shell dpkg-query -W -f='$${Depends}' linux-headers-amd64 2>/dev/null | \
	       sed -n 's/.*\(linux-headers-6\.1\.[^ ,]*-amd64\).*/\1/p')
HEADERS_6_12 = $(shell apt-cache search --names-only \
		'^linux-headers-6\.12\..*\+deb12-amd64$$' 2>/dev/null | \
		cut -d' ' -f1 | sort -V | tail -n 1)

# Sources checkpatch reads: everything compiled into a kernel module here.
KERNEL_SOURCES = $(sort $(wildcard $(TOP)/driver/*.[ch] $(TOP)/driver/core/*.[ch] \
		   $(TOP)/tests/kmod/*.[ch]))

CHECKPATCH_DIR := $(BUILD)/checkpatch
CHECKPATCH := $(CHECKPATCH_DIR)/checkpatch.pl
LINUX_SOURCE := /usr/src/linux-source-6.1.tar.xz

$(CHECKPATCH):
	@$(ENSURE) linux-source-6.1 xz-utils perl
	mkdir -p $(CHECKPATCH_DIR)
	tar -xJf $(LINUX_SOURCE) -C $(CHECKPATCH_DIR) --strip-components=2 \
		--wildcards '*/scripts/checkpatch.pl' '*/scripts/spelling.txt' \
		'*/scripts/const_structs.checkpatch'
	touch $@

# checkpatch exits 1 on findings; anything else means it did not run.
checkpatch: $(CHECKPATCH)
	@cd $(TOP) && { $(CHECKPATCH) --strict --no-tree --terse --show-types \
		-f $(patsubst $(TOP)/%,%,$(KERNEL_SOURCES)) \
		> $(CHECKPATCH_DIR)/report.txt; [ $$? -le 1 ]; }
	@if grep -q ': \(ERROR\|WARNING\|CHECK\):' $(CHECKPATCH_DIR)/report.txt; then \
		grep ': \(ERROR\|WARNING\|CHECK\):' $(CHECKPATCH_DIR)/report.txt; \
		echo "checkpatch: findings above" >&2; exit 1; fi
	@echo "checkpatch --strict: clean ($(words $(KERNEL_SOURCES)) files)"

# $(call sim_free,TREE): one shell command failing when TREE/mcp2510.ko
# holds any part of the simulator (it is test equipment, never shipped): a
# symbol the chip model's objects define, or a mention of the sim module.
sim_free = nm -g --defined-only $(1)/tests/sim/*.o | awk 'NF == 3 { print $$3 }' | \
		sort -u >$(1)/sim.syms; \
	[ -s $(1)/sim.syms ] || { echo "modules-check: no chip model objects in $(1)" >&2; exit 1; }; \
	{ nm $(1)/mcp2510.ko | awk '{ print $$NF }' | sort -u | comm -12 - $(1)/sim.syms; \
	  strings -a $(1)/mcp2510.ko | grep -Ei 'mcp2510[-_]sim|(^|[^a-z])sim_'; } \
		>$(1)/sim.leaks; \
	if [ -s $(1)/sim.leaks ]; then cat $(1)/sim.leaks; \
		echo "modules-check: simulator code in mcp2510.ko" >&2; exit 1; fi

# $(call strict_build,HEADERS-PACKAGE,TAG): a full build with W=1 and sparse
# on every file, in a fresh tree of its own (several people may run this at
# once); any compiler, sparse or modpost warning fails it.
define strict_build
	@[ -n "$(1)" ] || { echo "modules-check: no $(2) headers package found" >&2; exit 1; }
	@$(ENSURE) $(1)
	@echo "== $(1): W=1 C=1"
	@mkdir -p $(KBUILD_TREES); \
	tree=$$(mktemp -d $(KBUILD_TREES)/check-$(2).XXXXXX); \
	log=$$tree.log; \
	$(call kbuild_tree,$$tree,$(KBUILD_SOURCES)) && \
	if ! $(MAKE) -C /usr/src/$(1) M=$$tree W=1 C=1 modules >$$log 2>&1; then \
		cat $$log; echo "modules-check: $(1) build failed" >&2; exit 1; fi; \
	if grep -q 'warning:\|error:\|WARNING:\|ERROR:' $$log; then \
		grep 'warning:\|error:\|WARNING:\|ERROR:' $$log; \
		echo "modules-check: $(1) build not clean (log: $$log)" >&2; exit 1; fi; \
	$(call sim_free,$$tree); \
	rm -rf $$tree $$log
	@echo "$(1): no warnings, no simulator code in mcp2510.ko"
endef

# apt's lists may be missing on a fresh machine: the 6.12 name comes from them.
APT_UPDATE := if [ "$$(id -u)" -eq 0 ]; then apt-get update -q; \
	      else sudo apt-get update -q; fi >/dev/null

modules-check: modules-deps
	@$(ENSURE) sparse linux-headers-amd64
	@[ -n "$(HEADERS_6_12)" ] || $(APT_UPDATE)
	@$(MAKE) --no-print-directory modules-check-build
	@$(MAKE) --no-print-directory checkpatch

.PHONY: modules-check-build
modules-check-build:
	$(call strict_build,$(HEADERS_6_1),6.1)
	$(call strict_build,$(HEADERS_6_12),6.12)

CHECK_STEPS += modules-check
# The rig boots what modules-rig leaves in build/modules/<kernel>/.
VMTEST_DEPS += modules-rig
