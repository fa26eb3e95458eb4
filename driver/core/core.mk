# driver/core/core.mk: the portable driver core.
#
# CORE_SRCS is compiled into the kernel module (the root Kbuild includes
# this file for it) and into libmcp2510; CORE_USER_SRCS only into
# userspace, as it divides 64-bit numbers.  Both relative to the top.
#
#   make core-check   build the kernel part with extra warnings and prove
#                     it needs nothing from libc but memcpy/memset

CORE_DIR := driver/core
CORE_SRCS := $(addprefix $(CORE_DIR)/, \
	spi.c bringup.c start.c bittiming.c frame.c filter.c \
	tx.c tx_request.c irq.c irq_flags.c irq_rx.c irq_tx.c irq_error.c \
	error.c pins.c health.c)
CORE_USER_SRCS := $(CORE_DIR)/bittiming_calc.c

# Everything below is for the top Makefile, not for Kbuild.
ifeq ($(KERNELRELEASE),)

CORE_CPPFLAGS := -I$(TOP)/uapi -I$(TOP)/$(CORE_DIR)
CORE_ALLOWED_SYMBOLS := memcpy memset
CORE_STRICT := -Wvla -Wshadow -Wmissing-prototypes -Wstrict-prototypes \
	       -Wcast-qual -Wpointer-arith -Wundef -fno-builtin -O2
CORE_CHECK_OBJS := $(patsubst $(CORE_DIR)/%.c,$(BUILD)/core/%.o,$(CORE_SRCS))

$(BUILD)/core/%.o: $(TOP)/$(CORE_DIR)/%.c $(wildcard $(TOP)/$(CORE_DIR)/*.h) \
		$(TOP)/uapi/linux/can/mcp2510.h | cc-deps
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(CC) $(CSTD) $(WARN) $(CORE_STRICT) $(CORE_CPPFLAGS) -c $< -o $@

$(BUILD)/core/core.o: $(CORE_CHECK_OBJS)
	$(call quiet,LD,$@)$(LD) -r -o $@ $^

.PHONY: core-check
core-check: $(BUILD)/core/core.o
	@bad=$$(nm -u $< | awk '{ print $$2 }' | \
		grep -vxF $(addprefix -e ,$(CORE_ALLOWED_SYMBOLS)) || true); \
	if [ -n "$$bad" ]; then echo "core-check: the core needs:" $$bad >&2; exit 1; fi; \
	echo "core-check: the core builds clean and takes only $(CORE_ALLOWED_SYMBOLS) from outside"

CHECK_STEPS += core-check

endif
