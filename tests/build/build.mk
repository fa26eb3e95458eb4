# tests/build/build.mk: the userspace port and the modules built the way a
# distribution builds them (tests/build/check-build.sh).
#
#   make build-check   a make check step: distribution flags, quiet and
#                      V=1 output, warnings and WERROR=1, rebuilds after an
#                      option changes, package managers left alone

.PHONY: build-check
build-check: modules-deps vm-kernel-6.12
	@$(ENSURE) $(HOST_PACKAGES) binutils
	@$(TOP)/tests/build/check-build.sh $(call vm_kdir,6.12)

CHECK_STEPS += build-check
