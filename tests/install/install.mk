# tests/install/install.mk: make modules, install, uninstall and dkms.conf
# as a packager and a board owner use them (tests/install/check-install.sh).
#
#   make install-check   a make check step; builds the driver for Debian's
#                        6.1 and 6.12 headers (driver.mk's HEADERS_6_1 and
#                        HEADERS_6_12) into a temporary staging directory

.PHONY: install-check
install-check: modules-deps userspace
	@$(ENSURE) $(HEADERS_6_1) $(HEADERS_6_12)
	@$(TOP)/tests/install/check-install.sh /usr/src/$(HEADERS_6_1) /usr/src/$(HEADERS_6_12)

CHECK_STEPS += install-check
