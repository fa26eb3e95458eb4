# tests/packaging/packaging.mk: the Debian packages of debian/.
#
#   make version-check   the header's MCP2510_VERSION (US_VERSION), the one
#                        version, is also dkms.conf's and debian/changelog's
#   make deb             build the four packages from a copy of the tree
#                        into build/deb/ and run lintian on them
#                        (tests/packaging/build-debs.sh)
#   make deb-check       as root: install them with apt, let DKMS build the
#                        driver for an installed kernel's headers
#                        (DEB_KERNEL=<release>, by default the newest),
#                        use them, purge them, and find nothing left
#                        (tests/packaging/check-debs.sh)

DEB_OUT := $(BUILD)/deb
DEB_KERNEL ?=
DEB_CHANGELOG_VERSION := $(shell sed -n '1s/^[^ ]* (\([^)-]*\).*/\1/p' \
			   $(TOP)/debian/changelog)

.PHONY: version-check deb deb-check
version-check:
	@for v in "dkms.conf $(DKMS_VERSION)" \
		"debian/changelog $(DEB_CHANGELOG_VERSION)"; do \
		[ "$${v#* }" = "$(US_VERSION)" ] || { \
			echo "version-check: $${v% *} says '$${v#* }', mcp2510.h says '$(US_VERSION)'" >&2; \
			exit 1; }; \
	done
	@echo "version-check: mcp2510.h, dkms.conf and debian/changelog say $(US_VERSION)"

deb: version-check
	@$(ENSURE) dpkg-dev
	@$(TOP)/tests/packaging/build-debs.sh $(DEB_OUT)

deb-check: deb
	@$(TOP)/tests/packaging/check-debs.sh $(DEB_OUT) $(DEB_KERNEL)

CHECK_STEPS += version-check
