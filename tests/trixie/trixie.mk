# tests/trixie/trixie.mk: the userspace port, its unit suites and the
# modules on Debian 13 (trixie), in a root made with debootstrap.
#
#   make trixie-root    build/trixie/root: a minimal Debian 13 with the
#                       toolchain (and arm64's cross compiler), cmocka, libgpiod 2, the 6.12 kernel
#                       headers and those of the newest series the project
#                       builds for (KERNEL_NEWEST, tests/matrix/kernels) from
#                       trixie-backports, from the Debian archive the host's
#                       apt uses (tests/lib/make-root); made once, made
#                       anew when its package list or that series changes
#   make trixie-check   in that root, on this tree: make userspace, unit and
#                       unit-asan (libgpiod 2 is the root's own, so the
#                       userspace build takes the libgpiod 2 backend), then
#                       both modules against its 6.12 and its newest
#                       headers with W=1 and sparse, any warning failing
#                       the build as in modules-check (the newest kernel's
#                       kbuild tools need Debian 13's glibc: built here)
#
# The tree is mounted read-only at /src in the root and built into the
# root's /build (tests/lib/in-root), so the host's build/ is left alone.

TRIXIE_ROOT := $(BUILD)/trixie/root
# What make userspace, unit, unit-asan and the modules' W=1 C=1 build need;
# make-root adds the newest series' headers from trixie-backports.  The
# arm64 cross compiler the newest arm64 kernel names (gcc-14) builds the
# device-tree boot's modules here (tests/vm/kbuild, tests/vm-arm64).
TRIXIE_PACKAGES = build-essential make pkg-config libcmocka-dev libgpiod-dev \
	linux-headers-$(shell dpkg --print-architecture) sparse debian-archive-keyring \
	gcc-14-aarch64-linux-gnu
TRIXIE_MAKE_ROOT = $(TOP)/tests/lib/make-root --newest-headers
CLEAN_KEEP += trixie
# What runs inside: the same Makefile, building into the root's /build,
# with warnings errors when they are here (make check).
TRIXIE_MAKE := make --no-print-directory -C /src BUILD=/build WERROR=$(WERROR)

.PHONY: trixie-root trixie-root-background trixie-check trixie-inside \
	trixie-modules
trixie-root:
	@$(TRIXIE_MAKE_ROOT) $(TRIXIE_ROOT) trixie $(TRIXIE_PACKAGES)

trixie-check: trixie-root
	@$(TOP)/tests/lib/in-root --ro $(TOP):/src $(TRIXIE_ROOT) $(TRIXIE_MAKE) trixie-inside || { \
		echo "trixie-check: FAILED in the Debian 13 root (output above)" >&2; \
		exit 1; }

# ---- run inside the root (in-root), never on the host ----------------------

# The 6.12 headers package the root's linux-headers-<arch> depends on.
TRIXIE_HEADERS = $(shell dpkg-query -W -f='$${Depends}' \
	linux-headers-$$(dpkg --print-architecture) 2>/dev/null | \
	sed -n 's/.*\(linux-headers-6\.12\.[^ ,]*\).*/\1/p')
# The newest series' headers package make-root installed.
TRIXIE_HEADERS_NEWEST = $(shell dpkg-query -W -f='$${Package}\n' \
	'linux-headers-$(KERNEL_NEWEST).*-$(shell dpkg --print-architecture)' \
	2>/dev/null | grep -v -- '-common$$' | sort -V | tail -n 1)

trixie-inside:
	@[ -f /src/tests/trixie/trixie.mk ] && [ "$(BUILD)" = /build ] || { \
		echo "trixie-inside: runs in the Debian 13 root: make trixie-check" >&2; \
		exit 1; }
	@echo "== Debian $$(cat /etc/debian_version), $$(gcc --version | head -n 1), libgpiod $(US_GPIOD_VERSION)"
	@$(MAKE) -j$$(nproc) userspace unit-build unit-asan-build
	@$(MAKE) unit unit-asan
	@$(MAKE) -j$$(nproc) trixie-modules
	@echo "trixie-check: passed on Debian $$(cat /etc/debian_version): userspace (libgpiod $(US_GPIOD_VERSION) backend), $(words $(UNIT_SUITES)) unit suites plain and under ASan/UBSan, modules against $(TRIXIE_HEADERS) and $(TRIXIE_HEADERS_NEWEST) with W=1 and sparse, no warnings"

trixie-modules:
	$(call strict_build,/usr/src/$(TRIXIE_HEADERS),6.12)
	$(call strict_build,/usr/src/$(TRIXIE_HEADERS_NEWEST),$(KERNEL_NEWEST))

# The root is made in the background while the first steps run (its
# download waits on the network, its install on the disk); trixie-check
# waits for it.
trixie-root-background:
	@$(TRIXIE_MAKE_ROOT) --background $(TRIXIE_ROOT) trixie $(TRIXIE_PACKAGES)

CHECK_STEPS := trixie-root-background $(CHECK_STEPS)
CHECK_STEPS += trixie-check
