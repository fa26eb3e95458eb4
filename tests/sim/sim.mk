# tests/sim/sim.mk: the simulated MCP2510/MCP2515 and its CAN bus
# (DESIGN.md principle 2).  Other fragments link the model with
# $(SIM_SRCS) and compile against it with $(SIM_CPPFLAGS).
#
#   make sim-check   build the model with extra warnings and prove it needs
#                    nothing from libc but memcpy/memset (kernel-module safe)

SIM_DIR := tests/sim
SIM_SRCS := $(addprefix $(SIM_DIR)/,sim_chip_regs.c sim_chip_spi.c \
	    sim_chip_mode.c sim_chip_tx.c sim_chip_rx.c sim_chip_errors.c \
	    sim_chip_timing.c sim_bus.c sim_phantom.c sim_frame.c sim_spi_time.c \
	    sim_spi_profile.c)
SIM_CPPFLAGS := -I$(TOP)/uapi -I$(TOP)/driver/core -I$(TOP)/$(SIM_DIR)
# symbols the model may take from its environment (the kernel has both)
SIM_ALLOWED_SYMBOLS := memcpy memset
SIM_STRICT := -Wvla -Wshadow -Wmissing-prototypes -Wstrict-prototypes \
	      -Wcast-qual -Wpointer-arith -Wundef -fno-builtin -O2

SIM_EMPTY :=
SIM_SPACE := $(SIM_EMPTY) $(SIM_EMPTY)
SIM_CHECK_OBJS := $(patsubst $(SIM_DIR)/%.c,$(BUILD)/sim/%.o,$(SIM_SRCS))

$(BUILD)/sim/%.o: $(TOP)/$(SIM_DIR)/%.c $(wildcard $(TOP)/$(SIM_DIR)/*.h) | cc-deps
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(CC) $(CSTD) $(WARN) $(SIM_STRICT) $(SIM_CPPFLAGS) -c $< -o $@

$(BUILD)/sim/model.o: $(SIM_CHECK_OBJS)
	$(call quiet,LD,$@)$(LD) -r -o $@ $^

.PHONY: sim-check
sim-check: $(BUILD)/sim/model.o
	@bad=$$(nm -u $< | awk '{ print $$2 }' | grep -vxF -e $(subst $(SIM_SPACE), -e ,$(SIM_ALLOWED_SYMBOLS)) || true); \
	if [ -n "$$bad" ]; then echo "sim-check: the model needs:" $$bad >&2; exit 1; fi; \
	echo "sim-check: the model builds clean and takes only $(SIM_ALLOWED_SYMBOLS) from outside"

CHECK_STEPS += sim-check
