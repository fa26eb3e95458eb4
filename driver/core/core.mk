# driver/core/core.mk: the portable driver core.
#
# CORE_SRCS is compiled into the kernel module (Kbuild names the matching
# objects) and into libmcp2510; CORE_USER_SRCS only into userspace, as it
# divides 64-bit numbers.  Both relative to $(TOP).

CORE_DIR := driver/core
CORE_SRCS := $(addprefix $(CORE_DIR)/, \
	spi.c bringup.c start.c bittiming.c frame.c filter.c tx.c irq.c \
	error.c pins.c)
CORE_USER_SRCS := $(CORE_DIR)/bittiming_calc.c
CORE_HDRS := $(wildcard $(TOP)/$(CORE_DIR)/*.h)
CORE_CFLAGS := -I$(TOP)/$(CORE_DIR) -I$(TOP)/uapi

CORE_OBJ_DIR := $(BUILD)/core
CORE_OBJS := $(patsubst $(CORE_DIR)/%.c,$(CORE_OBJ_DIR)/%.o, \
	$(CORE_SRCS) $(CORE_USER_SRCS))

.PHONY: core-objs
core-objs: $(CORE_OBJS)

$(CORE_OBJ_DIR)/%.o: $(TOP)/$(CORE_DIR)/%.c $(CORE_HDRS) \
		$(TOP)/uapi/linux/can/mcp2510.h
	@mkdir -p $(dir $@)
	$(CC) $(CSTD) $(WARN) -O2 $(CORE_CFLAGS) -c $< -o $@
