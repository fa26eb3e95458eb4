# tests/unit/unit.mk: the cmocka suites.
#
#   make unit        build build/unit/<suite> for every suite and run them all
#   make unit-asan   the same under ASan/UBSan, in build/unit-asan/
#   make coverage    the same with --coverage in build/coverage/, then the
#                    line coverage of the chip model (tests/sim/*.c)
#
# Adding a suite is one line here, plus its source list when it links more
# than tests/unit/<suite>.c:
#
#   UNIT_SUITES += test_core_tx
#   test_core_tx_SRCS := driver/core/tx.c $(UNIT_SIM_SRCS)
#
# Paths are relative to the top directory.  $(UNIT_SIM_SRCS) is the chip
# model with the SPI/frame helpers of tests/unit/sim_helpers.h.
# A failing test fails make, after every suite has run.

UNIT_DIR := tests/unit
UNIT_CFLAGS := $(CSTD) $(WARN) -g -I$(TOP)/uapi -I$(TOP)/driver/core \
	       -I$(TOP)/tests/sim -I$(TOP)/$(UNIT_DIR)
UNIT_LDLIBS := -lcmocka
UNIT_SIM_SRCS := $(SIM_SRCS) $(UNIT_DIR)/sim_helpers.c

# ---- suites -------------------------------------------------------------
UNIT_SUITES += test_sim_spi
test_sim_spi_SRCS := $(UNIT_SIM_SRCS)
UNIT_SUITES += test_sim_bus
test_sim_bus_SRCS := $(UNIT_SIM_SRCS)
UNIT_SUITES += test_sim_errors
test_sim_errors_SRCS := $(UNIT_SIM_SRCS)
UNIT_SUITES += test_sim_modes
test_sim_modes_SRCS := $(UNIT_SIM_SRCS)
UNIT_SUITES += test_sim_timing
test_sim_timing_SRCS := $(UNIT_SIM_SRCS)
UNIT_SUITES += test_sim_spi_model
test_sim_spi_model_SRCS := $(UNIT_SIM_SRCS)
# the simulated SPI controller's kernel-free layer (tests/kmod/kmod_logic.c)
UNIT_SUITES += test_kmod_logic
test_kmod_logic_SRCS := tests/kmod/kmod_logic.c $(UNIT_SIM_SRCS)
# can-flood's counting (tests/vm/guest/flood_count.h)
UNIT_SUITES += test_flood_count

# the portable driver core over the chip model (tests/unit/core_harness.h)
UNIT_CORE_SRCS := $(CORE_SRCS) $(CORE_USER_SRCS) $(SIM_SRCS) \
	$(UNIT_DIR)/core_harness.c
UNIT_SUITES += test_core_bittiming
test_core_bittiming_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_frame
test_core_frame_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_filter
test_core_filter_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_bringup
test_core_bringup_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_tx
test_core_tx_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_irq
test_core_irq_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_error
test_core_error_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_health
test_core_health_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_spi_time
test_core_spi_time_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_core_spi_gap
test_core_spi_gap_SRCS := $(UNIT_CORE_SRCS)
UNIT_SUITES += test_userspace_text
test_userspace_text_SRCS := $(US_UNIT_TEXT_SRCS)
UNIT_SUITES += test_userspace_transport
test_userspace_transport_SRCS := $(US_UNIT_TRANSPORT_SRCS)
UNIT_SUITES += test_userspace_gpio_v2
test_userspace_gpio_v2_SRCS := $(US_UNIT_GPIO_V2_SRCS)
UNIT_SUITES += test_userspace_lib
test_userspace_lib_SRCS := $(US_UNIT_LIB_SRCS)
UNIT_SUITES += test_userspace_simbus
test_userspace_simbus_SRCS := $(US_UNIT_LIB_SRCS)
UNIT_SUITES += test_userspace_ctl
test_userspace_ctl_SRCS := $(US_UNIT_CTL_SRCS)
UNIT_SUITES += test_userspace_bridge
test_userspace_bridge_SRCS := $(US_UNIT_BRIDGE_SRCS)

# ---- rules (no need to touch these to add a suite) ------------------------
UNIT_FLAVOURS := unit unit-asan coverage
UNIT_FLAGS_unit :=
UNIT_FLAGS_unit-asan := $(SANITIZE)
UNIT_FLAGS_coverage := --coverage -O0

# objects of suite $(2) in flavour $(1)
unit_objs = $(patsubst %.c,$(BUILD)/$(1)/obj/%.o,$(UNIT_DIR)/$(2).c $($(2)_SRCS))

define UNIT_FLAVOUR_RULES
$(eval $(call option_stamp,$(BUILD)/$(1)/options,$(CC) $(UNIT_CFLAGS) \
	$(UNIT_FLAGS_$(1)) $(UNIT_LDLIBS)))

$(BUILD)/$(1)/obj/%.o: $(TOP)/%.c $(BUILD)/$(1)/options | unit-deps
	@mkdir -p $$(@D)
	$$(call quiet,CC,$$<)$$(CC) $$(UNIT_CFLAGS) $$(UNIT_FLAGS_$(1)) -MMD -MP -c $$< -o $$@

.PHONY: $(1)-build
$(1)-build: $(addprefix $(BUILD)/$(1)/,$(UNIT_SUITES))
endef

define UNIT_SUITE_RULES
$(BUILD)/$(1)/$(2): $(call unit_objs,$(1),$(2)) | unit-deps
	$$(call quiet,LD,$$@)$$(CC) $$(UNIT_FLAGS_$(1)) $$^ $$(UNIT_LDLIBS) -o $$@
-include $(patsubst %.o,%.d,$(call unit_objs,$(1),$(2)))
endef

$(foreach f,$(UNIT_FLAVOURS),$(eval $(call UNIT_FLAVOUR_RULES,$(f))))
$(foreach f,$(UNIT_FLAVOURS),$(foreach s,$(UNIT_SUITES),\
	$(eval $(call UNIT_SUITE_RULES,$(f),$(s)))))

# every suite runs; make fails at the end if one did
unit_run = fail=; for t in $(UNIT_SUITES); do \
		$(BUILD)/$(1)/$$t || fail="$$fail $$t"; \
	done; \
	if [ -n "$$fail" ]; then echo "$(1): FAILED:$$fail" >&2; exit 1; fi; \
	echo "$(1): all suites passed ($(words $(UNIT_SUITES)) suites)"

.PHONY: unit unit-asan coverage unit-deps
unit-deps:
	@$(ENSURE) $(CC_PACKAGES) libcmocka-dev

unit: unit-build
	@$(call unit_run,unit)

# Exported, for the suites to see them.  A pointer kept past its frame's
# return is caught on every compiler: newer ASan runtimes check that by
# default, older ones only when asked.
unit-asan: unit-asan-build
	@export ASAN_OPTIONS=detect_leaks=1:detect_stack_use_after_return=1 \
		UBSAN_OPTIONS=print_stacktrace=1; \
		$(call unit_run,unit-asan)

COVERAGE_SIM_SRCS := $(SIM_SRCS)
coverage: coverage-build
	@find $(BUILD)/coverage -name '*.gcda' -delete
	@$(call unit_run,coverage)
	@command -v gcovr >/dev/null 2>&1 || $(ENSURE) gcovr
	@cd $(TOP) && gcovr --root $(TOP) $(addprefix --filter ,$(COVERAGE_SIM_SRCS)) \
		--object-directory $(BUILD)/coverage $(BUILD)/coverage

CHECK_STEPS += unit unit-asan
