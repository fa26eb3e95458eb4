# tests/soak/soak.mk: the long run of mcp2510.ko under floods and faults
# (docs/soak.md).  Not part of make check.
#
#   make soak [SOAK_MINUTES=10]   boot Debian's 6.1 kernel with two simulated
#                                 chips and run tests/soak/soak.sh for that long
#
# vm-run's timeout is the soak's length plus room for the boot, the last
# rounds and the kernel log.

SOAK_MINUTES ?= 10
SOAK_DIR := $(BUILD)/soak

.PHONY: soak
soak: vm-kernel-6.1
	@case '$(SOAK_MINUTES)' in ''|*[!0-9]*) \
		echo "soak: SOAK_MINUTES takes whole minutes" >&2; exit 2;; esac
	@$(if $(strip $(VMTEST_DEPS)),$(MAKE) --no-print-directory $(VMTEST_DEPS) VM_KERNELS=6.1)
	@mkdir -p $(SOAK_DIR)/extra
	@echo $(SOAK_MINUTES) >$(SOAK_DIR)/extra/minutes
	@$(VM_DIR)/vm-run --kernel 6.1 --driver mcp2510 --nodes 2 --variant mcp2510 \
		--add $(SOAK_DIR)/extra --timeout $$(($(SOAK_MINUTES) * 60 + 300)) \
		--logs $(SOAK_DIR)/soak $(TOP)/tests/soak/soak.sh
