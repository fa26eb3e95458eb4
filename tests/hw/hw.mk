# tests/hw/hw.mk: the hardware test kit (docs/hardware-testing.md).
#
#   make hwtest IFACES="can0 can1" [KIT_FRAMES=20000] [KIT_TRANSITS=1000]
#        [KIT_BITRATES="125000 500000 1000000"] [KIT_CHECKS="..."] [HWTEST_OUT=DIR]
#	runs tests/hw/mcp2510-hwtest on two CAN interfaces of this machine
#	(root; a board with two chips on one bus), with the kit's programs
#	(can-flood, can-transit, can-echo, can-dlc from tests/vm/guest)
#	built first
#   make hwtest-broken-modules  mcp2510.ko broken on purpose, for the
#	rig's proof that the kit fails on a broken driver (tests/hw/broken)
#   make install-hwtest   mcp2510-hwtest into $(DESTDIR)$(PREFIX)/bin, its
#	scripts and programs (private: generic names) into
#	$(PREFIX)/lib/mcp2510-hwtest; part of make install-userspace
#
# The rig runs the installed copy: vm-run copies build/vm/guest-root,
# where this installs it, into the guest (tests/vm/scenarios/hwtest-kit.sh).

HW_DIR := $(TOP)/tests/hw
HW_SCRIPTS := $(addprefix $(HW_DIR)/,lib.sh info.sh checks.sh modes.sh floods.sh report.awk)
# The kit's programs are built with the userspace tools (make userspace,
# with a distribution's flags), so that installing compiles nothing.
HW_BIN := $(US_OUT)/hwtest
HW_PROGRAMS := $(addprefix $(HW_BIN)/,can-flood can-transit can-echo can-dlc)
HW_LIB = $(PREFIX)/lib/mcp2510-hwtest
VM_GUEST_ROOT := $(BUILD)/vm/guest-root

.PHONY: hwtest install-hwtest uninstall-hwtest hwtest-rig
hwtest: $(HW_PROGRAMS)
	@[ -n "$(IFACES)" ] || { echo 'make hwtest: say which interfaces: IFACES="can0 can1"'; exit 2; }
	PATH="$(HW_BIN):$$PATH" $(if $(KIT_FRAMES),KIT_FRAMES=$(KIT_FRAMES)) \
		$(if $(KIT_TRANSITS),KIT_TRANSITS=$(KIT_TRANSITS)) \
		$(if $(KIT_BITRATES),KIT_BITRATES="$(KIT_BITRATES)") \
		$(if $(KIT_CHECKS),KIT_CHECKS="$(KIT_CHECKS)") \
		$(HW_DIR)/mcp2510-hwtest $(if $(HWTEST_OUT),-o $(HWTEST_OUT)) $(IFACES)

userspace: $(HW_PROGRAMS)

$(HW_BIN)/%: $(VM_DIR)/guest/%.c $(wildcard $(VM_DIR)/guest/*.h) $(US_OPTIONS) | cc-deps
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(CC) $(CSTD) $(WARN) -O2 -g $(CFLAGS) $(CPPFLAGS) $(LDFLAGS) -o $@ $<

install-hwtest: $(HW_PROGRAMS)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(HW_LIB)
	install -m 755 $(HW_DIR)/mcp2510-hwtest $(DESTDIR)$(PREFIX)/bin/
	install -m 755 $(HW_PROGRAMS) $(DESTDIR)$(HW_LIB)/
	install -m 644 $(HW_SCRIPTS) $(DESTDIR)$(HW_LIB)/

uninstall-hwtest:
	rm -f $(DESTDIR)$(PREFIX)/bin/mcp2510-hwtest
	rm -rf $(DESTDIR)$(HW_LIB)

install-userspace: install-hwtest
uninstall-userspace: uninstall-hwtest

# The kit as a board has it, for the rig's guest.
hwtest-rig: $(HW_PROGRAMS)
	@rm -rf $(VM_GUEST_ROOT)
	@$(MAKE) --no-print-directory install-hwtest DESTDIR=$(VM_GUEST_ROOT) PREFIX=/usr/local >/dev/null
VMTEST_DEPS += hwtest-rig

# The driver broken on purpose (tests/hw/broken/*.patch), which the kit
# must find fault with (tests/vm/scenarios/hwtest-kit-broken.sh), for the
# kernels that scenario runs on: the oldest and the newest series.  A
# patched copy of the driver's sources per kernel and patch, built where
# the rig's modules are (tests/vm/kbuild).
.PHONY: hwtest-broken-modules
hwtest-broken-modules: modules-deps
	@set -e; for k in $(filter $(KERNEL_OLDEST) $(KERNEL_NEWEST),$(RIG_KERNELS)); do \
		$(VM_DIR)/kernel-info $$k kdir >/dev/null 2>&1 || { \
			echo "hwtest-broken-modules: rig kernel $$k not there yet, not built"; \
			continue; }; \
		$(HW_DIR)/broken/build $$k $(wildcard $(HW_DIR)/broken/*.patch); \
	done
VMTEST_SUITE_DEPS += hwtest-broken-modules
KERNEL_PATCHES += $(wildcard $(HW_DIR)/broken/*.patch)
