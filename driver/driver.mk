# driver/driver.mk: the kernel modules built from the root Kbuild.
#
#   make modules [KDIR=dir]   build against KDIR, by default the running
#                             kernel's build tree (/lib/modules/$(uname -r)/build)
#                             on any architecture; without it, stop and name
#                             the headers package to install (never installs
#                             anything); the .ko files land in
#                             build/modules/<release>/
#   make modules-rig          the same for each kernel of the QEMU rig that is
#                             there (tests/vm/kernel-info), into
#                             build/modules/<6.1|6.12|debug|rt|7.3>/
#   make modules-check        warning-free builds against Debian's 6.1 and 6.12
#                             headers (the rig's, unpacked under build/kernels
#                             by tests/vm/fetch-kernel) with W=1 and sparse
#                             (C=1), no simulator
#                             code in mcp2510.ko, and checkpatch.pl --strict
#                             on every kernel source
#   make install [KDIR=dir]   mcp2510.ko into <modules>/extra, then depmod;
#                             DESTDIR=dir (or INSTALL_MOD_PATH=dir) stages it
#                             under dir, without depmod (a package runs it on
#                             the target)
#   make uninstall [KDIR=dir] removes what make install (and
#                             make install-userspace) put there, then depmod
#   make install-dkms-source  dkms.conf and the driver's sources into
#                             $(DESTDIR)/usr/src/mcp2510-<version> (packages)
#
# Every build runs in build/kbuild/<tag>/, a tree of symlinks to the
# sources, so builds for several kernels never share objects and the
# source tree stays clean.

# The kernel make modules, install and uninstall are for unless KDIR= says
# otherwise.  tests/install/ sets these two to play a machine without headers.
MODULES_RELEASE ?= $(shell uname -r)
MODULES_KDIR_DEFAULT ?= /lib/modules/$(MODULES_RELEASE)/build
KDIR ?= $(MODULES_KDIR_DEFAULT)
# The release modules built against KDIR $(1) load into (vermagic).
kernel_release = $(shell sed -n 's/.*UTS_RELEASE "\(.*\)"/\1/p' \
		   $(1)/include/generated/utsrelease.h 2>/dev/null)

KBUILD_SOURCES := Kbuild uapi driver tests/kmod tests/sim
KBUILD_TREES := $(BUILD)/kbuild
MODULES_OUT := $(BUILD)/modules
# libelf-dev brings the libelf the kbuild tools of Debian's headers link
# against (objtool): libelf1 on Debian 12, libelf1t64 on Debian 13.
# pahole gives each module its BTF: headers that carry a vmlinux (6.12 on)
# have kbuild run it on every module it links.
KERNEL_PACKAGES := build-essential bc kmod libelf-dev pahole

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

# The package holding the build tree of kernel release $(1): Raspberry Pi
# OS names its kernels 6.12.25+rpt-rpi-2712 (bookworm on: the package is
# linux-headers-rpi-<flavour>) or 6.1.21-v8+ (bullseye and before:
# raspberrypi-kernel-headers); Debian and Ubuntu linux-headers-<release>.
headers_package = $(or \
	$(if $(findstring +rpt-rpi-,$(1)),linux-headers-rpi-$(lastword $(subst +rpt-rpi-, ,$(1)))), \
	$(if $(filter %+,$(1)),raspberrypi-kernel-headers), \
	linux-headers-$(1))

# $(call need_kdir,TARGET): one shell command that stops TARGET when KDIR
# is no kernel build tree, naming what to install.  It installs nothing: a
# plain build must not run apt-get (make deps and make check do that).
need_kdir = test -f $(KDIR)/Makefile || { \
	echo "$(1): no kernel build tree at $(KDIR)" >&2; \
	if [ "$(KDIR)" = "$(MODULES_KDIR_DEFAULT)" ]; then \
		echo "$(1): install the running kernel's headers, package $(call headers_package,$(MODULES_RELEASE))" >&2; \
		echo "$(1): (see docs/install.md), or build for another kernel with KDIR=<its build tree>" >&2; \
	else \
		echo "$(1): KDIR must be a kernel build tree (with its Makefile)" >&2; \
	fi; exit 1; }

.PHONY: modules modules-rig modules-check install uninstall modules-deps checkpatch
modules-deps:
	@$(ENSURE) $(KERNEL_PACKAGES)

modules:
	@$(call need_kdir,modules)
	$(call kbuild_modules,$(KDIR),$(call kernel_release,$(KDIR)))

# The rig's kernels (tests/vm/vm.mk's VM_KERNELS when set).  A rig kernel
# may come from another Debian release than the host's: tests/vm/kbuild
# builds with the compiler its headers name (installed when missing: 6.1's
# gcc-12 on a Debian 13 host), and in the Debian 13 root when the host's C
# library is too old for its kbuild programs (7.3 on a Debian 12 host).
# Each kernel's build runs on every core: vmtest waits for these.
RIG_KERNELS = $(or $(VM_KERNELS),6.1 6.12 rt debug)
modules-rig: modules-deps
	@set -e; for k in $(RIG_KERNELS); do \
		kdir=$$($(TOP)/tests/vm/kernel-info $$k kdir 2>/dev/null) || { \
			echo "modules-rig: rig kernel $$k not there yet, not built"; \
			continue; }; \
		$(TOP)/tests/vm/kbuild $$k $(MAKE) -j$$(nproc) --no-print-directory -C $(TOP) \
			modules-rig-one KDIR=$$kdir RIG_KERNEL=$$k; \
	done

.PHONY: modules-rig-one
modules-rig-one:
	$(call kbuild_modules,$(KDIR),$(RIG_KERNEL))

# ---- install (SBC users; DKMS uses dkms.conf at the top level) ----------

# A staged install (DESTDIR or INSTALL_MOD_PATH) skips depmod: the indexes it
# would write there describe that one module and would replace the target's.
INSTALL_MOD_PATH ?= $(DESTDIR)
MOD_ROOT = $(patsubst %/,%,$(INSTALL_MOD_PATH))
# The release to uninstall from: KDIR's, or the running kernel's when its
# headers are gone already (uninstall needs no build tree).
INSTALL_RELEASE = $(or $(call kernel_release,$(KDIR)),$(if \
	$(filter $(KDIR),$(MODULES_KDIR_DEFAULT)),$(MODULES_RELEASE)))
# Where modules_install puts mcp2510.ko; kbuild compresses it (.ko.xz,
# .ko.zst, .ko.gz) when the kernel's config asks for that.
INSTALLED_MODULE_DIR = $(MOD_ROOT)/lib/modules/$(INSTALL_RELEASE)/extra
run_depmod = $(if $(MOD_ROOT),@echo "$(1): staged under $(MOD_ROOT): depmod is for the target to run",depmod -a $(INSTALL_RELEASE))

# The driver's own sources: what make install builds and DKMS needs.
DRIVER_SOURCES := Kbuild uapi driver

install:
	@$(call need_kdir,install)
	@$(call kbuild_tree,$(KBUILD_TREES)/install,$(DRIVER_SOURCES))
	$(MAKE) -C $(KDIR) M=$(KBUILD_TREES)/install MCP2510_DRIVER_ONLY=1 modules
	$(MAKE) -C $(KDIR) M=$(KBUILD_TREES)/install MCP2510_DRIVER_ONLY=1 \
		INSTALL_MOD_DIR=extra INSTALL_MOD_PATH=$(MOD_ROOT) \
		DEPMOD=true modules_install
	$(call run_depmod,install)

# The module, and the directories install made when nothing else is in them
# (never lib/modules itself nor anything above the staging directory).
uninstall: uninstall-userspace
	@[ -n "$(INSTALL_RELEASE)" ] || { \
		echo "uninstall: which kernel? KDIR=$(KDIR) is no kernel build tree" >&2; exit 1; }
	rm -f $(addprefix $(INSTALLED_MODULE_DIR)/mcp2510.ko,"" .xz .zst .gz)
	@d=$(INSTALLED_MODULE_DIR); while [ "$$d" != "$(MOD_ROOT)/lib/modules" ] && \
		rmdir "$$d" 2>/dev/null; do d=$${d%/*}; done; \
	for d in "$(MOD_ROOT)/lib/modules" "$(MOD_ROOT)/lib"; do \
		[ -z "$(MOD_ROOT)" ] || rmdir "$$d" 2>/dev/null || break; done
	$(call run_depmod,uninstall)

# dkms.conf and the sources it builds from (no tests, no build products) in
# $(DESTDIR)/usr/src/mcp2510-<version>, where DKMS looks for them: what a
# package ships, where `dkms add .` would copy the whole checkout.
DKMS_VERSION := $(shell sed -n 's/^PACKAGE_VERSION="\(.*\)"$$/\1/p' $(TOP)/dkms.conf)
DKMS_SOURCE_DIR = $(DESTDIR)/usr/src/mcp2510-$(DKMS_VERSION)

.PHONY: install-dkms-source
install-dkms-source:
	@cd $(TOP) && find $(DRIVER_SOURCES) -type f \( -name '*.[ch]' \
		-o -name Kbuild -o -name core.mk \) | sort | while read -r f; do \
		install -D -m 644 "$$f" "$(DKMS_SOURCE_DIR)/$$f" || exit 1; done
	install -m 644 $(TOP)/dkms.conf $(DKMS_SOURCE_DIR)/

# ---- modules-check --------------------------------------------------------

# Debian's kernels the module must build for: the rig's 6.1 and 6.12, with
# the headers fetch-kernel unpacked under build/kernels (vm.mk's vm_kdir).
MODULES_CHECK_KERNELS := 6.1 6.12

# Sources checkpatch reads: everything compiled into a kernel module here.
KERNEL_SOURCES = $(sort $(wildcard $(TOP)/driver/*.[ch] $(TOP)/driver/core/*.[ch] \
		   $(TOP)/tests/kmod/*.[ch]))

CHECKPATCH_DIR := $(BUILD)/checkpatch
CHECKPATCH := $(CHECKPATCH_DIR)/checkpatch.pl

# From Debian's linux-source-6.1, fetched into build/kernels/source.
$(CHECKPATCH):
	@$(ENSURE) xz-utils perl
	mkdir -p $(CHECKPATCH_DIR)
	tar -xJf $$($(TOP)/tests/vm/fetch-linux-source) -C $(CHECKPATCH_DIR) --strip-components=2 \
		--wildcards '*/scripts/checkpatch.pl' '*/scripts/spelling.txt' \
		'*/scripts/const_structs.checkpatch'
	touch $@

# Patches of kernel code that other fragments keep (tests/hw/hw.mk's
# broken builds of the driver), read as patches: from standard input, as
# checkpatch reads a file git tracks as source whatever its name.
KERNEL_PATCHES :=

# checkpatch exits 1 on findings; anything else means it did not run.
checkpatch: $(CHECKPATCH)
	@cd $(TOP) && { $(CHECKPATCH) --strict --no-tree --terse --show-types \
		-f $(patsubst $(TOP)/%,%,$(KERNEL_SOURCES)) \
		> $(CHECKPATCH_DIR)/report.txt; [ $$? -le 1 ]; }
	@cd $(TOP) && for p in $(patsubst $(TOP)/%,%,$(KERNEL_PATCHES)); do \
		$(CHECKPATCH) --strict --no-tree --no-signoff --terse --show-types - \
			<$$p >$(CHECKPATCH_DIR)/patch.txt; [ $$? -le 1 ] || exit 1; \
		sed "s|^-:|$$p:|" $(CHECKPATCH_DIR)/patch.txt >>$(CHECKPATCH_DIR)/report.txt; \
	done
	@if grep -q ': \(ERROR\|WARNING\|CHECK\):' $(CHECKPATCH_DIR)/report.txt; then \
		grep ': \(ERROR\|WARNING\|CHECK\):' $(CHECKPATCH_DIR)/report.txt; \
		echo "checkpatch: findings above" >&2; exit 1; fi
	@echo "checkpatch --strict: clean ($(words $(KERNEL_SOURCES)) files, $(words $(KERNEL_PATCHES)) patches)"

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

# $(call strict_build,KDIR,TAG): a full build with W=1 and sparse on every
# file against the kernel build tree KDIR, in a fresh tree of its own
# (several people may run this at once); any compiler, sparse or modpost
# warning fails it.  TAG names the kernel in messages.
define strict_build
	@kdir=$(1); [ -f "$$kdir/Makefile" ] || { \
		echo "modules-check: no $(2) kernel build tree at '$$kdir'" >&2; exit 1; }; \
	echo "== $(2): W=1 C=1, KDIR=$$kdir"; \
	mkdir -p $(KBUILD_TREES); \
	tree=$$(mktemp -d $(KBUILD_TREES)/check-$(2).XXXXXX); \
	log=$$tree.log; \
	$(call kbuild_tree,$$tree,$(KBUILD_SOURCES)) && \
	if ! $(MAKE) -C $$kdir M=$$tree W=1 C=1 modules >$$log 2>&1; then \
		cat $$log; echo "modules-check: $(2) build failed" >&2; exit 1; fi; \
	if grep -q 'warning:\|error:\|WARNING:\|ERROR:' $$log; then \
		grep 'warning:\|error:\|WARNING:\|ERROR:' $$log; \
		echo "modules-check: $(2) build not clean (log: $$log)" >&2; exit 1; fi; \
	$(call sim_free,$$tree); \
	rm -rf $$tree $$log
	@echo "$(2): no warnings, no simulator code in mcp2510.ko"
endef

modules-check: modules-deps $(addprefix vm-kernel-,$(MODULES_CHECK_KERNELS))
	@$(ENSURE) sparse
	@$(MAKE) --no-print-directory modules-check-build
	@$(MAKE) --no-print-directory checkpatch

.PHONY: modules-check-build
modules-check-build:
	$(call strict_build,$(call vm_kdir,6.1),6.1)
	$(call strict_build,$(call vm_kdir,6.12),6.12)

CHECK_STEPS += modules-check
# The rig boots what modules-rig leaves in build/modules/<kernel>/.
VMTEST_DEPS += modules-rig
