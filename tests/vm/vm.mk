# tests/vm/vm.mk: the QEMU rig (see docs/vm-rig.md).
#
#   make vm-kernels          fetch Debian's 6.1, 6.12 and 6.12 PREEMPT_RT,
#                            build the debug kernel
#   make vm-kernel-6.1 | vm-kernel-6.12 | vm-kernel-debug | vm-kernel-rt |
#        vm-kernel-7.3       one of them (the Debian ones: tests/vm/kernels)
#   make initramfs           base initramfs for each kernel in VM_KERNELS
#   make vmtest              the suite on every kernel in VM_KERNELS (default
#                            6.1, 6.12, rt, debug and the newest series,
#                            KERNEL_NEWEST: 7.3): what make check runs
#   make vmtest-release      the same on Debian's kernels (6.1, 6.12, rt, 7.3)
#   make vmtest-debug        the suite on the debug kernel alone, built if
#                            missing
#   make vmtest-one SCENARIO=tests/vm/scenarios/x.sh KERNEL=6.12
#   make vm-info             release, image and KDIR of each kernel
#
# Fragments whose output the guest picks up (build/modules/<kernel>/*.ko,
# build/userspace/bin) add their make target to VMTEST_DEPS; vmtest runs
# them after the kernels exist, with VM_KERNELS in the environment.  What
# only some scenarios load, and make demo does not need, goes in
# VMTEST_SUITE_DEPS.
# KDIR for a kernel: tests/vm/kernel-info 6.12 kdir; in a recipe,
# $(call vm_kdir,6.12), a shell expression (failing when it is not there).

VM_DIR := $(TOP)/tests/vm
# The Debian kernels, the debug kernel, the busybox package and libgpiod 2.
CLEAN_KEEP += kernels vm/busybox vm/gpiod2
# The debug kernel last: make check builds it in the background, and the
# Debian kernels are fetched while that build ends.
VM_KERNELS ?= 6.1 6.12 rt $(KERNEL_NEWEST) debug
VMTEST_DEPS +=
VMTEST_SUITE_DEPS +=
export VM_KERNELS

vm_kdir = $$($(VM_DIR)/kernel-info $(1) kdir)

# Small programs the scenarios run in the guest (tests/vm/guest/NAME.c),
# for what the stock tools cannot show; vm-run copies build/vm/guest-bin
# to the guest's /usr/local/bin.
VM_GUEST_BIN := $(BUILD)/vm/guest-bin
VM_GUEST_TOOLS := $(patsubst $(VM_DIR)/guest/%.c,$(VM_GUEST_BIN)/%,\
		  $(wildcard $(VM_DIR)/guest/*.c))
VMTEST_DEPS += vm-guest-tools

.PHONY: vm-guest-tools
vm-guest-tools: $(VM_GUEST_TOOLS)

$(VM_GUEST_BIN)/%: $(VM_DIR)/guest/%.c $(wildcard $(VM_DIR)/guest/*.h) | cc-deps
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(CC) $(CSTD) $(WARN) -O2 -o $@ $<

# The Debian kernels fetch-kernel unpacks (with their headers): those of
# tests/vm/kernels, the newest series put in as kernel-list does.
VM_DEBIAN_KERNELS := $(subst @NEWEST@,$(KERNEL_NEWEST),\
	$(shell awk '!/^\#/ { print $$1 }' $(VM_DIR)/kernels))

.PHONY: vm-kernels $(addprefix vm-kernel-,$(VM_DEBIAN_KERNELS)) vm-kernel-debug initramfs \
	vm-kernel-debug-background vmtest vmtest-release vmtest-debug vmtest-one \
	vm-info

vm-kernels: vm-kernel-6.1 vm-kernel-6.12 vm-kernel-debug vm-kernel-rt

$(addprefix vm-kernel-,$(VM_DEBIAN_KERNELS)):
	@$(VM_DIR)/fetch-kernel $(@:vm-kernel-%=%)

vm-kernel-debug:
	@$(VM_DIR)/build-debug-kernel

initramfs: $(addprefix vm-kernel-,$(VM_KERNELS))
	@for k in $(VM_KERNELS); do $(VM_DIR)/mkinitramfs $$k || exit 1; done

vmtest: $(addprefix vm-kernel-,$(VM_KERNELS))
	@$(MAKE) --no-print-directory $(VMTEST_DEPS) $(VMTEST_SUITE_DEPS)
	@$(VM_DIR)/vmtest -k "$(VM_KERNELS)"

vmtest-one:
	@test -n "$(SCENARIO)" || { echo "usage: make vmtest-one SCENARIO=tests/vm/scenarios/NAME.sh [KERNEL=6.1|6.12|7.3|debug|rt]"; exit 2; }
	@$(MAKE) --no-print-directory vm-kernel-$(or $(KERNEL),6.1)
	@$(MAKE) --no-print-directory $(VMTEST_DEPS) $(VMTEST_SUITE_DEPS) VM_KERNELS=$(or $(KERNEL),6.1)
	@VM_SELFTEST=0 VM_EVERY_SCENARIO=1 $(VM_DIR)/vmtest -k "$(or $(KERNEL),6.1)" $(abspath $(SCENARIO))

# can-dev as kernels before the end of 2023 have it, on the rig kernels
# made from 6.1's sources (tests/vm/old-can-dev/build).
.PHONY: old-can-dev-modules
old-can-dev-modules: modules-deps
	@set -e; ks=; for k in $(filter 6.1 debug,$(VM_KERNELS)); do \
		if $(VM_DIR)/kernel-info $$k kdir >/dev/null 2>&1; then ks="$$ks $$k"; \
		else echo "old-can-dev-modules: rig kernel $$k not there yet, not built"; fi; \
	done; [ -z "$$ks" ] || $(VM_DIR)/old-can-dev/build $$ks
VMTEST_SUITE_DEPS += old-can-dev-modules

vm-info:
	@for k in $(VM_DEBIAN_KERNELS) debug; do echo "== $$k"; $(VM_DIR)/kernel-info $$k || true; done
vmtest-release:
	@$(MAKE) --no-print-directory vmtest VM_KERNELS="6.1 6.12 rt $(KERNEL_NEWEST)"

vmtest-debug:
	@$(MAKE) --no-print-directory vmtest VM_KERNELS=debug

# make check runs vmtest after its other steps but the fresh-root verdict
# (Makefile).  The debug kernel takes some nine minutes of both cores to
# build, so make check starts that before anything else, in the background
# at nice 19: it takes what the other steps leave of the cores (the
# single-threaded ones leave a quarter), ahead of the idle fresh-root
# check, and vmtest waits for it.
vm-kernel-debug-background:
	@$(VM_DIR)/build-debug-kernel --background

CHECK_STEPS := vm-kernel-debug-background $(CHECK_STEPS)

# make demo: boot Debian's 6.1 kernel with two simulated MCP2510s and show
# ip link, cansend and candump at work.
.PHONY: demo
demo: vm-kernel-6.1
	@$(if $(strip $(VMTEST_DEPS)),$(MAKE) --no-print-directory $(VMTEST_DEPS) VM_KERNELS=6.1)
	@$(VM_DIR)/vm-run --kernel 6.1 --driver mcp2510 --nodes 2 \
		--variant mcp2510 $(VM_DIR)/demo.sh
