# tests/kmod/kmod.mk: mcp2510-sim.ko, the chip model behind a virtual SPI
# controller (docs/simulator.md).
#
# The module is built with the driver from the root Kbuild: "make modules"
# and "make modules-rig" put it in build/modules/<kernel>/, where
# tests/vm/vm-run loads it, and "make modules-check" holds it to W=1, sparse
# and checkpatch --strict on 6.1 and 6.12.
#
#   make sim-vmtest [VM_KERNELS="6.1 6.12 debug"]
#                    the simulator's own scenarios (tests/vm/scenarios/sim-*.sh)

.PHONY: sim-vmtest
sim-vmtest:
	@$(MAKE) --no-print-directory $(addprefix vm-kernel-,$(VM_KERNELS)) modules-rig
	@$(TOP)/tests/vm/vmtest -k "$(VM_KERNELS)" $(wildcard $(TOP)/tests/vm/scenarios/sim-*.sh)
