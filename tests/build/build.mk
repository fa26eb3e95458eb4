# tests/build/build.mk: the userspace port and the modules built the way a
# distribution builds them (tests/build/check-build.sh).
#
#   make build-check   a make check step: distribution flags, quiet and
#                      V=1 output, warnings and WERROR=1, rebuilds after an
#                      option changes, package managers left alone

.PHONY: build-check
build-check: modules-deps
	@$(ENSURE) $(HOST_PACKAGES) $(HEADERS_6_12) binutils
	@$(TOP)/tests/build/check-build.sh /usr/src/$(HEADERS_6_12)

CHECK_STEPS += build-check
