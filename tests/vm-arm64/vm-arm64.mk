# tests/vm-arm64/vm-arm64.mk: the driver booted from a device tree on arm64
# (docs/arm64-dt-boot.md).
#
#   make vmtest-arm64         build what is missing, boot QEMU's arm64 "virt"
#                             machine with this project's overlay applied,
#                             probe the driver from the tree, move frames
#   make vm-arm64-kernel      the arm64 kernel only (cached)
#   make modules-arm64        mcp2510.ko and mcp2510-sim.ko for it, into
#                             build/modules/arm64/
#
# Debian's amd64 kernels have no device tree, so this is where the driver's
# OF match table, clock and interrupt lookup run.  From scratch it takes
# 5-6 minutes on two quiet cores (the kernel, cached afterwards), and
# seconds after that.

VM_ARM64_DIR := $(TOP)/tests/vm-arm64
VM_ARM64_KDIR := $(BUILD)/arm64/kernel
VM_ARM64_PACKAGES := qemu-system-arm device-tree-compiler cpio gzip

.PHONY: vmtest-arm64 vm-arm64-kernel modules-arm64 vm-arm64-deps

vm-arm64-deps:
	@$(ENSURE) $(VM_ARM64_PACKAGES)

vm-arm64-kernel:
	@$(VM_ARM64_DIR)/build-kernel >/dev/null

modules-arm64: vm-arm64-kernel modules-deps
	$(call kbuild_modules,$(VM_ARM64_KDIR),arm64,ARCH=arm64 CROSS_COMPILE=aarch64-linux-gnu-)

vmtest-arm64: vm-arm64-deps modules-arm64
	@$(VM_ARM64_DIR)/fetch-userland
	@$(VM_ARM64_DIR)/run

CHECK_STEPS += vmtest-arm64
