# tests/lint/lint.mk: static analysis of the C that runs outside the kernel
# glue (the glue has sparse and checkpatch in driver/driver.mk).
#
#   make lint            all three below; a make check step
#   make lint-cppcheck   cppcheck on userspace/, driver/core/, tests/sim/
#   make lint-tidy       clang-tidy on the same (tests/lint/clang-tidy.yaml)
#   make lint-analyzer   gcc -fanalyzer on userspace/ and driver/core/
#
# Any finding fails.  A finding that is wrong goes, with the reason, into
# tests/lint/cppcheck-suppressions or the check list of clang-tidy.yaml;
# a right one is fixed in the code.

LINT_DIR := tests/lint
LINT_PACKAGES := cppcheck clang-tidy gcc
LINT_JOBS ?= 2
# Relative to the top, where the rules run: suppressions name files so.
# The libgpiod backend the host's libgpiod does not build is linted apart,
# against the headers of the libgpiod under build/libgpiod (userspace.mk).
LINT_GPIOD_OTHER := $(if $(filter 2,$(US_GPIOD_MAJOR)),1,2)
LINT_US_OTHER := userspace/lib/gpio_int_v$(LINT_GPIOD_OTHER).c
LINT_US_SRCS := $(filter-out $(LINT_US_OTHER),$(patsubst $(TOP)/%,%,$(sort \
		$(wildcard $(TOP)/userspace/lib/*.c $(TOP)/userspace/tools/*.c))))
LINT_CORE_SRCS := $(CORE_SRCS) $(CORE_USER_SRCS)
LINT_SIM_SRCS := $(SIM_SRCS)
LINT_INCLUDES := -Iuapi -Idriver/core -Itests/sim -Iuserspace/include \
		 -Iuserspace/lib -Iuserspace/tools

# cppcheck: warning, performance and portability, plus style without the
# two style checks that contradict kernel style: declarations at the top
# of a block (variableScope) and "flags & BIT ? a : b" without extra
# parentheses (clarifyCalculation).
LINT_CPPCHECK_FLAGS := --std=c11 --quiet --error-exitcode=1 \
	--enable=warning,style,performance,portability \
	--suppress=variableScope --suppress=clarifyCalculation \
	--suppressions-list=$(TOP)/$(LINT_DIR)/cppcheck-suppressions \
	-j $(LINT_JOBS)

LINT_TIDY := clang-tidy --quiet --config-file=$(TOP)/$(LINT_DIR)/clang-tidy.yaml
# what the compilers see (userspace.mk, core.mk, sim.mk)
LINT_TIDY_CFLAGS := $(CSTD) $(LINT_INCLUDES)

.PHONY: lint lint-deps lint-cppcheck lint-tidy lint-analyzer
lint: lint-cppcheck lint-tidy lint-analyzer
	@echo "lint: no findings (cppcheck, clang-tidy, gcc -fanalyzer)"

lint-deps: $(US_GPIOD_DIR)/v$(LINT_GPIOD_OTHER)/pkgconfig/libgpiod.pc
	@$(ENSURE) $(LINT_PACKAGES)
LINT_OTHER_INCLUDES := $(LINT_INCLUDES) -I$(US_GPIOD_DIR)/v$(LINT_GPIOD_OTHER)/include

lint-cppcheck: | lint-deps
	@cd $(TOP) && cppcheck $(LINT_CPPCHECK_FLAGS) $(LINT_INCLUDES) \
		$(LINT_US_SRCS) $(LINT_CORE_SRCS) $(LINT_SIM_SRCS)
	@cd $(TOP) && cppcheck $(LINT_CPPCHECK_FLAGS) $(LINT_OTHER_INCLUDES) \
		$(LINT_US_OTHER)
	@echo "lint-cppcheck: $(words $(LINT_US_SRCS) $(LINT_US_OTHER) $(LINT_CORE_SRCS) $(LINT_SIM_SRCS)) files clean"

# One file per clang-tidy process, LINT_JOBS at a time: it is the slow one.
# Its output is shown only for a file with findings (it counts the
# warnings it suppressed in system headers, for every file).
# Userspace may recurse; the core and the model run on a kernel stack.
lint_tidy = cd $(TOP) && printf '%s\n' $(1) | xargs -P $(LINT_JOBS) -I '{}' \
	sh -c 'out=$$($(LINT_TIDY) $(2) "$$0" -- $(or $(3),$(LINT_TIDY_CFLAGS)) 2>&1) || \
		{ printf "%s\n" "$$out"; exit 1; }' '{}'

lint-tidy: | lint-deps
	@$(call lint_tidy,$(LINT_US_SRCS),--checks=-misc-no-recursion)
	@$(call lint_tidy,$(LINT_US_OTHER),--checks=-misc-no-recursion,$(CSTD) $(LINT_OTHER_INCLUDES))
	@$(call lint_tidy,$(LINT_CORE_SRCS) $(LINT_SIM_SRCS),)
	@echo "lint-tidy: $(words $(LINT_US_SRCS) $(LINT_US_OTHER) $(LINT_CORE_SRCS) $(LINT_SIM_SRCS)) files clean"

# The model is left out: gcc 12's analyzer loses the bound of the
# flood-frame byte loop in sim_phantom.c and reports shifts past 32 bits
# that cannot happen; cppcheck and clang-tidy cover it.
lint-analyzer: | lint-deps
	@cd $(TOP) && printf '%s\n' $(LINT_US_SRCS) $(LINT_CORE_SRCS) | \
		xargs -P $(LINT_JOBS) -I '{}' \
		gcc $(CSTD) $(WARN) -fanalyzer $(LINT_INCLUDES) -c '{}' -o /dev/null
	@cd $(TOP) && gcc $(CSTD) $(WARN) -fanalyzer $(LINT_OTHER_INCLUDES) \
		-c $(LINT_US_OTHER) -o /dev/null
	@echo "lint-analyzer: $(words $(LINT_US_SRCS) $(LINT_US_OTHER) $(LINT_CORE_SRCS)) files clean"

CHECK_STEPS += lint
