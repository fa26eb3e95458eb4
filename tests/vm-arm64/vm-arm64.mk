# tests/vm-arm64/vm-arm64.mk: the driver booted from a device tree on arm64
# (docs/arm64-dt-boot.md).
#
#   make vmtest-arm64         fetch what is missing, boot QEMU's arm64 "virt"
#                             machine with this project's overlay applied,
#                             probe the driver from the tree, move frames;
#                             once on each kernel of VM_ARM64_KERNELS
#   make vm-arm64-kernel      Debian's arm64 kernels and headers only (cached)
#   make modules-arm64        mcp2510.ko and mcp2510-sim.ko for them, into
#                             build/modules/arm64-SERIES/
#
# Debian's amd64 kernels have no device tree, so this is where the driver's
# OF match table, clock and interrupt lookup run: on the oldest series (a
# Debian 12 SBC's) and the newest (tests/matrix/kernels), whose kbuild
# programs need Debian 13's C library, so its modules are cross-built in
# the Debian 13 root (tests/vm/kbuild).  From scratch it takes a few
# minutes (downloads, and the modules cross-built), seconds after that.

VM_ARM64_DIR := $(TOP)/tests/vm-arm64
VM_ARM64_KERNELS := $(KERNEL_OLDEST) $(KERNEL_NEWEST)
CLEAN_KEEP += arm64/apt arm64/sysroot arm64/sysroot.stamp
VM_ARM64_PACKAGES := qemu-system-arm device-tree-compiler cpio gzip xz-utils \
	gcc-aarch64-linux-gnu binutils-aarch64-linux-gnu

.PHONY: vmtest-arm64 vm-arm64-kernel modules-arm64 modules-arm64-one \
	vm-arm64-deps

vm-arm64-deps:
	@$(ENSURE) $(VM_ARM64_PACKAGES)

vm-arm64-kernel:
	@for k in $(VM_ARM64_KERNELS); do \
		$(TOP)/tests/vm/fetch-kernel --arch arm64 $$k >/dev/null || exit 1; done

modules-arm64: vm-arm64-deps vm-arm64-kernel modules-deps
	@set -e; for k in $(VM_ARM64_KERNELS); do \
		kdir=$(BUILD)/kernels/arm64-$$k/kdir; \
		$(TOP)/tests/vm/kbuild $$kdir $(MAKE) --no-print-directory -C $(TOP) \
			modules-arm64-one KDIR=$$kdir ARM64_KERNEL=$$k; \
	done

modules-arm64-one:
	$(call kbuild_modules,$(KDIR),arm64-$(ARM64_KERNEL),ARCH=arm64 CROSS_COMPILE=aarch64-linux-gnu-)

# Every kernel boots, whatever the one before it gave.
vmtest-arm64: modules-arm64
	@$(VM_ARM64_DIR)/fetch-userland
	@status=0; for k in $(VM_ARM64_KERNELS); do \
		$(VM_ARM64_DIR)/run --kernel $$k || status=1; done; exit $$status

CHECK_STEPS += vmtest-arm64
