# tests/vm-arm64/vm-arm64.mk: the driver booted from a device tree on arm64
# (docs/arm64-dt-boot.md).
#
#   make vmtest-arm64         fetch what is missing, boot QEMU's arm64 "virt"
#                             machine with this project's overlay applied,
#                             probe the driver from the tree, move frames
#   make vm-arm64-kernel      Debian's arm64 kernel and headers only (cached)
#   make modules-arm64        mcp2510.ko and mcp2510-sim.ko for it, into
#                             build/modules/arm64/
#
# Debian's amd64 kernels have no device tree, so this is where the driver's
# OF match table, clock and interrupt lookup run.  From scratch it takes
# about a minute (downloads, and the modules cross-built), seconds after
# that.

VM_ARM64_DIR := $(TOP)/tests/vm-arm64
VM_ARM64_KDIR := $(BUILD)/arm64/kdir
CLEAN_KEEP += arm64/apt arm64/debian arm64/Image arm64/kdir arm64/sysroot \
	arm64/sysroot.stamp
VM_ARM64_PACKAGES := qemu-system-arm device-tree-compiler cpio gzip \
	gcc-aarch64-linux-gnu binutils-aarch64-linux-gnu

.PHONY: vmtest-arm64 vm-arm64-kernel modules-arm64 vm-arm64-deps

vm-arm64-deps:
	@$(ENSURE) $(VM_ARM64_PACKAGES)

vm-arm64-kernel:
	@$(VM_ARM64_DIR)/fetch-kernel >/dev/null

modules-arm64: vm-arm64-deps vm-arm64-kernel modules-deps
	$(call kbuild_modules,$(VM_ARM64_KDIR),arm64,ARCH=arm64 CROSS_COMPILE=aarch64-linux-gnu-)

vmtest-arm64: modules-arm64
	@$(VM_ARM64_DIR)/fetch-userland
	@$(VM_ARM64_DIR)/run

CHECK_STEPS += vmtest-arm64
