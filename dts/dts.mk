# dts/dts.mk: device-tree overlays, the binding, and their checks.
#
#   make dt-overlays   compile dts/*-overlay.dts to build/dts/overlays/*.dtbo
#   make install-dt-overlays   the Raspberry Pi ones (all but the generic
#                      overlays, which are edited for each board first) into
#                      $(DESTDIR)$(OVERLAYDIR), /boot/firmware/overlays
#   make dt-check      compile, apply, validate every overlay against the
#                      binding, and make sure the broken ones in
#                      dts/test/bad/ are rejected (see dts/dt-check.sh)
#
# dt-validate comes from dtschema on PyPI, pinned and installed into a venv
# under build/, so that every machine validates with the same schemas and
# prints the same messages (dts/test/bad/ matches on them).

DTS_PACKAGES := device-tree-compiler
# dt-validate's venv (dt-check only: dt-overlays needs dtc alone)
DTSCHEMA_PACKAGES := python3-venv

DTS_DIR := $(TOP)/dts
DTS_OUT := $(BUILD)/dts
DTS_OVERLAYS := $(patsubst $(DTS_DIR)/%-overlay.dts,$(DTS_OUT)/overlays/%.dtbo,\
	$(wildcard $(DTS_DIR)/*-overlay.dts))

DTSCHEMA_VERSION ?= 2026.9
DTSCHEMA_PYTHON ?= python3
DTSCHEMA_VENV := $(BUILD)/dtschema-venv
CLEAN_KEEP += dtschema-venv
DTSCHEMA_STAMP := $(DTSCHEMA_VENV)/.dtschema-$(DTSCHEMA_VERSION)

.PHONY: dt-deps dt-overlays dt-check dt-clean

dt-deps:
	@$(ENSURE) $(DTS_PACKAGES)

# Warnings fail the build: dtc reports them on stderr and exits 0.  A
# fragment switched off until a parameter turns it on (__dormant__) has a
# unit name and no reg, which dtc warns about: not a fault in an overlay
# (dts/dt-check.sh says more).
$(DTS_OUT)/overlays/%.dtbo: $(DTS_DIR)/%-overlay.dts | dt-deps
	@mkdir -p $(@D)
	@echo "  DTC     $(@F)"
	@dtc -@ -W no-unit_address_vs_reg -I dts -O dtb -o $@ $< 2>$@.log && [ ! -s $@.log ] || \
		{ cat $@.log >&2; rm -f $@ $@.log; exit 1; }
	@rm -f $@.log

dt-overlays: $(DTS_OVERLAYS)

# Where the Raspberry Pi firmware reads overlays on Raspberry Pi OS bookworm
# and later (docs/packaging.md); /boot/overlays before.
OVERLAYDIR ?= /boot/firmware/overlays
DTS_RPI_OVERLAYS := $(filter-out %-generic.dtbo,$(DTS_OVERLAYS))

.PHONY: install-dt-overlays
install-dt-overlays: $(DTS_RPI_OVERLAYS)
	install -d $(DESTDIR)$(OVERLAYDIR)
	install -m 644 $^ $(DESTDIR)$(OVERLAYDIR)/

# The stamp names the version, so changing DTSCHEMA_VERSION reinstalls.
$(DTSCHEMA_STAMP): | dt-deps
	@$(ENSURE) $(DTSCHEMA_PACKAGES)
	@echo "dt-check: installing dtschema $(DTSCHEMA_VERSION) into $(DTSCHEMA_VENV)"
	@rm -rf $(DTSCHEMA_VENV)
	@$(DTSCHEMA_PYTHON) -m venv $(DTSCHEMA_VENV)
	@$(DTSCHEMA_VENV)/bin/pip install -q --disable-pip-version-check \
		dtschema==$(DTSCHEMA_VERSION)
	@touch $@

dt-check: $(DTSCHEMA_STAMP) | dt-deps
	@rm -rf $(DTS_OUT)
	@$(DTS_DIR)/dt-check.sh $(DTS_OUT) $(DTSCHEMA_VENV)/bin

dt-clean:
	rm -rf $(DTS_OUT) $(DTSCHEMA_VENV)

CHECK_STEPS += dt-check
