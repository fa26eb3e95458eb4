# tests/install/install.mk: make modules, install, uninstall and dkms.conf
# as a packager and a board owner use them (tests/install/check-install.sh).
#
#   make install-check   a make check step; builds the driver for Debian's
#                        6.1 and 6.12 headers (the rig's, unpacked under
#                        build/kernels) into a temporary staging directory

.PHONY: install-check
install-check: modules-deps userspace $(addprefix vm-kernel-,$(MODULES_CHECK_KERNELS))
	@$(TOP)/tests/install/check-install.sh $(foreach k,$(MODULES_CHECK_KERNELS),$(call vm_kdir,$(k)))

CHECK_STEPS += install-check
