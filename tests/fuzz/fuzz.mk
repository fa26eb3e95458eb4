# tests/fuzz/fuzz.mk: libFuzzer targets under ASan and UBSan (clang).
#
#   make fuzz                   run every target for FUZZ_SECONDS (60) each
#   make fuzz FUZZ_SECONDS=600  longer
#   make fuzz-<target>          one target, e.g. make fuzz-sim_spi
#   make fuzz-smoke             every target for FUZZ_SMOKE_SECONDS (5):
#                               a make check step
#   make fuzz-build             only build them
#
# Targets (tests/fuzz/fuzz_<target>.c; docs/fuzzing.md has the details):
#   sim_spi        the chip model's SPI decoder, two chips and a peer
#   core_hostile   the core's interrupt loop, bring-up and modes against
#                  a chip answering with fuzzer-chosen bytes
#   frame_text     the cansend-syntax parser and the candump formatter
#   filter_text    the filter-id and receive-mode parsers
#   bittiming      the CNF encoder and the bit-timing calculator
#
# Every run starts from the committed seeds in tests/fuzz/corpus/<target>/
# and keeps what it finds in build/fuzz/corpus/<target>/, so runs build on
# each other.  A failing input lands in build/fuzz/artifacts/<target>/ and
# fails make; the log of each run is build/fuzz/logs/<target>.log.

FUZZ_DIR := tests/fuzz
FUZZ_OUT := $(BUILD)/fuzz
FUZZ_CC := clang
FUZZ_PACKAGES := clang libclang-rt-14-dev
FUZZ_SECONDS ?= 60
FUZZ_SMOKE_SECONDS := 5
FUZZ_SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all \
		 -fno-omit-frame-pointer
FUZZ_CFLAGS := $(CSTD) $(WARN) -g -O1 $(FUZZ_SANITIZE) \
	       -fsanitize=fuzzer-no-link \
	       -I$(TOP)/uapi -I$(TOP)/driver/core -I$(TOP)/tests/sim \
	       -I$(TOP)/userspace/tools -I$(TOP)/$(FUZZ_DIR)
# A hang is a finding: no input may take this long.
FUZZ_RUN_FLAGS := -timeout=10 -rss_limit_mb=2048 -print_final_stats=1

FUZZ_TARGETS := sim_spi core_hostile frame_text filter_text bittiming

fuzz_sim_spi_SRCS := $(SIM_SRCS) $(FUZZ_DIR)/fuzz_input.c
fuzz_core_hostile_SRCS := $(CORE_SRCS) $(SIM_SRCS) $(FUZZ_DIR)/fuzz_input.c \
			  $(FUZZ_DIR)/fuzz_hostile_chip.c
fuzz_frame_text_SRCS := userspace/tools/frame_text.c
fuzz_filter_text_SRCS := $(CORE_SRCS)
fuzz_bittiming_SRCS := $(CORE_SRCS) $(CORE_USER_SRCS) $(FUZZ_DIR)/fuzz_input.c

# Text targets: nothing interesting is longer than a line.
fuzz_frame_text_FLAGS := -max_len=64
fuzz_filter_text_FLAGS := -max_len=32
fuzz_bittiming_FLAGS := -max_len=32

fuzz_bin = $(FUZZ_OUT)/fuzz_$(1)
fuzz_objs = $(patsubst %.c,$(FUZZ_OUT)/obj/%.o,$(FUZZ_DIR)/fuzz_$(1).c \
		$(fuzz_$(1)_SRCS))
fuzz_dict = $(wildcard $(TOP)/$(FUZZ_DIR)/dict/$(1).dict)

.PHONY: fuzz fuzz-smoke fuzz-build fuzz-deps $(addprefix fuzz-,$(FUZZ_TARGETS))

fuzz-deps:
	@$(ENSURE) $(FUZZ_PACKAGES)

$(FUZZ_OUT)/obj/%.o: $(TOP)/%.c | fuzz-deps
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -MMD -MP -c $< -o $@

define FUZZ_TARGET_RULES
$(call fuzz_bin,$(1)): $(call fuzz_objs,$(1)) | fuzz-deps
	$(FUZZ_CC) $(FUZZ_SANITIZE) -fsanitize=fuzzer $$^ -o $$@
-include $(patsubst %.o,%.d,$(call fuzz_objs,$(1)))

fuzz-$(1): $(call fuzz_bin,$(1))
	@$$(call fuzz_run,$(1),$(FUZZ_SECONDS))
endef
$(foreach t,$(FUZZ_TARGETS),$(eval $(call FUZZ_TARGET_RULES,$(t))))

fuzz-build: $(foreach t,$(FUZZ_TARGETS),$(call fuzz_bin,$(t)))

# Run target $(1) for $(2) seconds; print its statistics, or the end of
# its log when it found something.
fuzz_run = mkdir -p $(FUZZ_OUT)/corpus/$(1) $(FUZZ_OUT)/artifacts/$(1) \
		$(FUZZ_OUT)/logs; \
	log=$(FUZZ_OUT)/logs/$(1).log; \
	if $(call fuzz_bin,$(1)) $(FUZZ_RUN_FLAGS) $(fuzz_$(1)_FLAGS) \
		-max_total_time=$(2) \
		-artifact_prefix=$(FUZZ_OUT)/artifacts/$(1)/ \
		$(addprefix -dict=,$(call fuzz_dict,$(1))) \
		$(FUZZ_OUT)/corpus/$(1) $(TOP)/$(FUZZ_DIR)/corpus/$(1) \
		>$$log 2>&1; then \
		awk -v t=$(1) -v corp=$$(ls $(FUZZ_OUT)/corpus/$(1) | wc -l) \
		  '/^stat::number_of_executed_units/ { runs = $$2 } \
		   /^stat::average_exec_per_sec/ { rate = $$2 } \
		   END { printf "fuzz %-13s %9d runs %7d/s, corpus %d\n", \
			t, runs, rate, corp }' $$log; \
	else \
		tail -n 40 $$log; \
		echo "fuzz-$(1): FAILED, input in $(FUZZ_OUT)/artifacts/$(1)/" >&2; \
		exit 1; \
	fi

fuzz: fuzz-build
	@fail=; for t in $(FUZZ_TARGETS); do \
		$(MAKE) --no-print-directory fuzz-$$t || fail="$$fail $$t"; \
	done; \
	if [ -n "$$fail" ]; then echo "fuzz: FAILED:$$fail" >&2; exit 1; fi

fuzz-smoke: fuzz-build
	@fail=; for t in $(FUZZ_TARGETS); do \
		$(MAKE) --no-print-directory fuzz-$$t \
			FUZZ_SECONDS=$(FUZZ_SMOKE_SECONDS) || fail="$$fail $$t"; \
	done; \
	if [ -n "$$fail" ]; then echo "fuzz-smoke: FAILED:$$fail" >&2; exit 1; fi

CHECK_STEPS += fuzz-smoke
