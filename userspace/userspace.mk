# userspace/userspace.mk: libmcp2510, mcp2510ctl and mcp2510d.
#
#   make userspace          build/userspace/lib/libmcp2510.a and .so (with
#                           soname), build/userspace/bin/mcp2510ctl and
#                           mcp2510d, build/userspace/libmcp2510.pc
#   make install-userspace  into $(DESTDIR)$(PREFIX) (default /usr/local)
#   make uninstall-userspace removes what install-userspace installed
#   make userspace-check    run the tools on the simulated chip and check
#                           the shared library exports only its public API
#   make userspace-gpiod2-check   the same on build/userspace-gpiod2
#
# MCP2510_SIM=0 builds the library without the chip model: the "sim"
# transport is then refused.  The driver core is compiled from core.mk's
# CORE_SRCS and CORE_USER_SRCS, the model from sim.mk's SIM_SRCS.
#
# libgpiod's major version, as pkg-config gives it, picks the INT
# backend: gpio_int_v1.c or gpio_int_v2.c.  PKG_CONFIG_PATH=<dir of a
# libgpiod.pc> builds against another libgpiod, US_OUT=<dir> into a
# directory of its own:
#
#   make userspace-gpiod2   build/userspace-gpiod2/ against the libgpiod 2
#                           that scripts/fetch-libgpiod 2 unpacks under
#                           build/libgpiod/v2 (Debian 13's packages)

US_DIR := userspace
US_OUT ?= $(BUILD)/userspace
US_OBJ := $(US_OUT)/obj
# one version, the public header's
US_VERSION := $(shell sed -n 's/^\#define MCP2510_VERSION[[:space:]]*"\(.*\)"/\1/p' \
		$(TOP)/$(US_DIR)/include/mcp2510.h)
US_SOVERSION := 0
MCP2510_SIM ?= 1
PREFIX ?= /usr/local
LIBDIR ?= $(PREFIX)/lib
MANDIR ?= $(PREFIX)/share/man
SYSTEMDUNITDIR ?= $(PREFIX)/lib/systemd/system
US_EXAMPLEDIR ?= $(PREFIX)/share/doc/mcp2510d/examples

US_PACKAGES := $(CC_PACKAGES) libgpiod-dev
US_CPPFLAGS := -I$(TOP)/$(US_DIR)/include -I$(TOP)/$(US_DIR)/lib \
	       -I$(TOP)/$(US_DIR)/tools -I$(TOP)/uapi -I$(TOP)/driver/core \
	       -I$(TOP)/tests/sim
US_CFLAGS := $(CSTD) $(WARN) -O2 -g -fPIC -fvisibility=hidden \
	     -D_FORTIFY_SOURCE=2
# A distribution's flags (CFLAGS, CPPFLAGS, LDFLAGS from the environment or
# the command line) come after the project's, so they win.
US_CFLAGS += $(CFLAGS)
US_CPPFLAGS += $(CPPFLAGS)
US_LDFLAGS := $(LDFLAGS)

# Before libgpiod-dev is installed (make deps), the version apt offers.
US_PKG_CONFIG := $(if $(PKG_CONFIG_PATH),PKG_CONFIG_PATH='$(PKG_CONFIG_PATH)') \
		 pkg-config
US_GPIOD_VERSION := $(or $(shell $(US_PKG_CONFIG) --modversion libgpiod \
			2>/dev/null),$(shell apt-cache show --no-all-versions \
			libgpiod-dev 2>/dev/null | sed -n 's/^Version: //p'))
US_GPIOD_MAJOR := $(or $(filter 1 2,$(firstword $(subst ., ,$(US_GPIOD_VERSION)))),1)
US_GPIOD_CFLAGS := $(shell $(US_PKG_CONFIG) --cflags libgpiod 2>/dev/null)
US_CFLAGS += $(US_GPIOD_CFLAGS)
US_LDLIBS := $(or $(shell $(US_PKG_CONFIG) --libs libgpiod 2>/dev/null),-lgpiod)
# the "CHIP:LINE" parsing both backends share, and one backend
us_gpio_srcs = $(addprefix $(US_DIR)/lib/,gpio_spec.c gpio_int_v$(1).c)

US_LIB_SRCS := $(addprefix $(US_DIR)/lib/,open.c config.c run.c events.c \
		inspect.c spidev.c) $(call us_gpio_srcs,$(US_GPIOD_MAJOR))
US_SIM_OBJ := $(US_OBJ)/sim-transport.o
# the in-process simulated buses and the one shared through a broker
US_SIM_SRCS := $(addprefix $(US_DIR)/lib/,sim_transport.c sim_env.c simbus_wire.c \
		simbus_connect.c simbus_broker.c simbus_client.c)
ifeq ($(MCP2510_SIM),1)
US_SIM_PARTS := $(US_SIM_SRCS) $(SIM_SRCS)
else
US_SIM_PARTS := $(US_DIR)/lib/sim_absent.c
endif
US_TOOL_SRCS := $(addprefix $(US_DIR)/tools/,cli.c cli_number.c cli_device.c \
		cli_filter.c cli_timing.c frame_text.c)
US_CTL_SRCS := $(addprefix $(US_DIR)/tools/,mcp2510ctl.c ctl.c ctl_chip.c \
		ctl_traffic.c ctl_sim.c)
US_DAEMON_SRCS := $(addprefix $(US_DIR)/tools/,mcp2510d.c bridge.c)

us_objs = $(patsubst %.c,$(US_OBJ)/%.o,$(1))
US_LIB_OBJS := $(call us_objs,$(US_LIB_SRCS) $(CORE_SRCS) $(CORE_USER_SRCS)) \
	       $(US_SIM_OBJ)
US_A := $(US_OUT)/lib/libmcp2510.a
US_SO := $(US_OUT)/lib/libmcp2510.so.$(US_VERSION)
US_SONAME := libmcp2510.so.$(US_SOVERSION)
US_CTL := $(US_OUT)/bin/mcp2510ctl
US_DAEMON := $(US_OUT)/bin/mcp2510d
US_PC := $(US_OUT)/libmcp2510.pc
US_UNIT := $(US_OUT)/mcp2510d@.service
US_MANS := $(addprefix $(US_DIR)/man/,mcp2510ctl.1 libmcp2510.3 mcp2510d.8)
US_EXAMPLES := $(addprefix $(US_DIR)/systemd/,80-mcp2510-vcan0.netdev \
		80-mcp2510-vcan0.network vcan0.conf)

.PHONY: userspace userspace-deps install-userspace userspace-check \
	userspace-gpiod2
userspace: $(US_A) $(US_SO) $(US_CTL) $(US_DAEMON) $(US_PC) $(US_UNIT)

# A libgpiod of the other major version, unpacked under build/libgpiod/vN
# (its headers in include/, its libgpiod.pc in pkgconfig/).
US_GPIOD_DIR := $(BUILD)/libgpiod
CLEAN_KEEP += libgpiod
$(US_GPIOD_DIR)/v%/pkgconfig/libgpiod.pc:
	@$(TOP)/scripts/fetch-libgpiod $* $(US_GPIOD_DIR) >/dev/null

userspace-gpiod2: $(US_GPIOD_DIR)/v2/pkgconfig/libgpiod.pc
	@$(MAKE) --no-print-directory userspace US_OUT=$(BUILD)/userspace-gpiod2 \
		PKG_CONFIG_PATH=$(US_GPIOD_DIR)/v2/pkgconfig

userspace-deps:
	@$(ENSURE) $(US_PACKAGES)

# Every object and link depends on the options it was built with: a build
# directory switched to MCP2510_SIM=0, to other flags or to another
# libgpiod rebuilds, never mixing the two.
US_OPTIONS := $(US_OUT)/options
$(eval $(call option_stamp,$(US_OPTIONS),$(CC) $(US_CFLAGS) $(US_CPPFLAGS) \
	$(US_LDFLAGS) $(US_LDLIBS) gpiod=$(US_GPIOD_VERSION) sim=$(MCP2510_SIM)))

$(US_OBJ)/%.o: $(TOP)/%.c $(US_OPTIONS) | userspace-deps
	@mkdir -p $(@D)
	$(call quiet,CC,$<)$(CC) $(US_CFLAGS) $(US_CPPFLAGS) -MMD -MP -c $< -o $@

# The transport and, when built, the model as one object of their own.
$(US_SIM_OBJ): $(call us_objs,$(US_SIM_PARTS)) $(US_OPTIONS)
	$(call quiet,LD,$@)$(LD) -r -o $@ $(filter %.o,$^)

$(US_A): $(US_LIB_OBJS)
	@mkdir -p $(@D)
	@rm -f $@
	$(call quiet,AR,$@)$(AR) rcs $@ $^

$(US_SO): $(US_LIB_OBJS)
	@mkdir -p $(@D)
	$(call quiet,LD,$@)$(CC) $(US_LDFLAGS) -shared -Wl,-soname,$(US_SONAME) \
		-Wl,--no-undefined $^ $(US_LDLIBS) -o $@
	@ln -sf $(notdir $@) $(@D)/$(US_SONAME)
	@ln -sf $(US_SONAME) $(@D)/libmcp2510.so

$(US_CTL): $(call us_objs,$(US_CTL_SRCS) $(US_TOOL_SRCS)) $(US_A)
	@mkdir -p $(@D)
	$(call quiet,LD,$@)$(CC) $(US_LDFLAGS) $^ $(US_LDLIBS) -o $@

$(US_DAEMON): $(call us_objs,$(US_DAEMON_SRCS) $(US_TOOL_SRCS)) $(US_A)
	@mkdir -p $(@D)
	$(call quiet,LD,$@)$(CC) $(US_LDFLAGS) $^ $(US_LDLIBS) -o $@

# The .pc and the unit name where install-userspace puts things.
$(eval $(call option_stamp,$(US_OUT)/prefix,$(PREFIX) $(LIBDIR)))

$(US_PC): $(TOP)/$(US_DIR)/libmcp2510.pc.in $(US_OUT)/prefix
	$(call quiet,GEN,$@)sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' \
	    -e 's|@VERSION@|$(US_VERSION)|' $< > $@

$(US_UNIT): $(TOP)/$(US_DIR)/systemd/mcp2510d@.service.in $(US_OUT)/prefix
	$(call quiet,GEN,$@)sed -e 's|@BINDIR@|$(PREFIX)/bin|' $< > $@

-include $(shell find $(US_OBJ) -name '*.d' 2>/dev/null)

install-userspace: userspace
	install -d $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(PREFIX)/bin \
		$(DESTDIR)$(PREFIX)/include/mcp2510
	install -m 644 $(US_A) $(DESTDIR)$(LIBDIR)/
	install -m 755 $(US_SO) $(DESTDIR)$(LIBDIR)/
	ln -sf $(notdir $(US_SO)) $(DESTDIR)$(LIBDIR)/$(US_SONAME)
	ln -sf $(US_SONAME) $(DESTDIR)$(LIBDIR)/libmcp2510.so
	install -m 644 $(US_PC) $(DESTDIR)$(LIBDIR)/pkgconfig/
	install -m 755 $(US_CTL) $(US_DAEMON) $(DESTDIR)$(PREFIX)/bin/
	install -m 644 $(TOP)/$(US_DIR)/include/mcp2510.h \
		$(DESTDIR)$(PREFIX)/include/
	install -m 644 $(TOP)/uapi/linux/can/mcp2510.h \
		$(DESTDIR)$(PREFIX)/include/mcp2510/registers.h
	install -d $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(MANDIR)/man3 \
		$(DESTDIR)$(MANDIR)/man8 $(DESTDIR)$(SYSTEMDUNITDIR) \
		$(DESTDIR)$(US_EXAMPLEDIR)
	$(foreach m,$(US_MANS),install -m 644 $(TOP)/$(m) \
		$(DESTDIR)$(MANDIR)/man$(subst .,,$(suffix $(m)))/ &&) true
	install -m 644 $(US_UNIT) $(DESTDIR)$(SYSTEMDUNITDIR)/
	install -m 644 $(addprefix $(TOP)/,$(US_EXAMPLES)) $(DESTDIR)$(US_EXAMPLEDIR)/

# Exactly what install-userspace installs; make uninstall runs it.  In a
# staging directory (DESTDIR) the directories it made go too, once empty.
.PHONY: uninstall-userspace
uninstall-userspace:
	rm -f $(addprefix $(DESTDIR)$(LIBDIR)/,$(notdir $(US_A) $(US_SO)) \
		$(US_SONAME) libmcp2510.so pkgconfig/$(notdir $(US_PC))) \
		$(addprefix $(DESTDIR)$(PREFIX)/bin/,$(notdir $(US_CTL) $(US_DAEMON))) \
		$(DESTDIR)$(PREFIX)/include/mcp2510.h \
		$(DESTDIR)$(PREFIX)/include/mcp2510/registers.h \
		$(foreach m,$(US_MANS),$(DESTDIR)$(MANDIR)/man$(subst .,,$(suffix $(m)))/$(notdir $(m))) \
		$(DESTDIR)$(SYSTEMDUNITDIR)/$(notdir $(US_UNIT)) \
		$(addprefix $(DESTDIR)$(US_EXAMPLEDIR)/,$(notdir $(US_EXAMPLES)))
	@[ -z "$(DESTDIR)" ] || for d in $(LIBDIR)/pkgconfig $(PREFIX)/bin \
			$(PREFIX)/include/mcp2510 $(MANDIR)/man1 $(MANDIR)/man3 \
			$(MANDIR)/man8 $(SYSTEMDUNITDIR) $(US_EXAMPLEDIR); do \
		while [ -n "$$d" ] && rmdir "$(DESTDIR)$$d" 2>/dev/null; do d=$${d%/*}; done; \
	done

# systemd-analyze verify checks that the unit's commands exist: procps
# brings its ExecReload's /bin/kill.
userspace-check: userspace
	@$(ENSURE) can-utils binutils groff-base systemd procps
	@$(TOP)/$(US_DIR)/check-userspace $(US_OUT) $(TOP)/$(US_DIR)/include/mcp2510.h

# the same checks on the libgpiod 2 build
.PHONY: userspace-gpiod2-check
userspace-gpiod2-check: userspace-gpiod2
	@$(MAKE) --no-print-directory userspace-check \
		US_OUT=$(BUILD)/userspace-gpiod2 \
		PKG_CONFIG_PATH=$(US_GPIOD_DIR)/v2/pkgconfig

CHECK_STEPS += userspace-check userspace-gpiod2-check

# The rig copies build/userspace/{bin,lib} into the guest, and the
# libgpiod 2 build of mcp2510ctl with its libgpiod: build them first.
VMTEST_DEPS += userspace userspace-gpiod2

# ---- the cmocka suites of tests/unit/unit.mk ----------------------------
# Source lists the suites' lines in unit.mk name.  Their sources need the
# userspace include paths, and the transport suites link with the system
# calls and libgpiod wrapped by their mocks (and without the chip model):
# test_userspace_transport has libgpiod 1's backend, test_userspace_gpio_v2
# libgpiod 2's, each built against the headers of its libgpiod (the host's,
# or the one under build/libgpiod when the host has the other).
US_UNIT_LIB_SRCS := $(US_LIB_SRCS) $(CORE_SRCS) $(CORE_USER_SRCS) \
		    $(US_SIM_SRCS) $(SIM_SRCS)
US_UNIT_TEXT_SRCS := $(US_TOOL_SRCS) $(US_UNIT_LIB_SRCS)
us_unit_transport_srcs = $(filter-out %/gpio_spec.c %/gpio_int_v$(US_GPIOD_MAJOR).c,\
			$(US_LIB_SRCS)) $(call us_gpio_srcs,$(1)) \
			$(CORE_SRCS) $(CORE_USER_SRCS) $(US_DIR)/lib/sim_absent.c
US_UNIT_TRANSPORT_SRCS := $(call us_unit_transport_srcs,1)
US_UNIT_GPIO_V2_SRCS := $(call us_unit_transport_srcs,2)
US_UNIT_CTL_SRCS := $(filter-out %/mcp2510ctl.c,$(US_CTL_SRCS)) \
		    $(US_UNIT_TEXT_SRCS)

US_UNIT_BRIDGE_SRCS := $(US_DIR)/tools/bridge.c $(US_UNIT_LIB_SRCS)
US_UNIT_OBJS := $(patsubst $(TOP)/%.c,%.o,$(wildcard \
			$(TOP)/tests/unit/test_userspace_*.c \
			$(TOP)/tests/unit/userspace_*.c)) \
		$(patsubst %.c,%.o,$(sort $(US_LIB_SRCS) \
			$(US_SIM_SRCS) $(US_DIR)/lib/sim_absent.c \
			$(US_TOOL_SRCS) $(US_CTL_SRCS) $(US_DAEMON_SRCS) \
			$(call us_gpio_srcs,1) $(call us_gpio_srcs,2)))
$(addprefix $(BUILD)/%/obj/,$(US_UNIT_OBJS)): UNIT_CFLAGS += \
	-I$(TOP)/$(US_DIR)/include -I$(TOP)/$(US_DIR)/lib -I$(TOP)/$(US_DIR)/tools

# The objects that include gpiod.h, by libgpiod major version.
US_UNIT_GPIOD_OBJS_1 := $(US_DIR)/lib/gpio_int_v1.o \
			tests/unit/test_userspace_transport.o
US_UNIT_GPIOD_OBJS_2 := $(US_DIR)/lib/gpio_int_v2.o \
			tests/unit/test_userspace_gpio_v2.o
define US_UNIT_GPIOD_HEADERS
ifneq ($(1),$(US_GPIOD_MAJOR))
unit-deps: $(US_GPIOD_DIR)/v$(1)/pkgconfig/libgpiod.pc
$(addprefix $(BUILD)/%/obj/,$(US_UNIT_GPIOD_OBJS_$(1))): UNIT_CFLAGS += \
	-I$(US_GPIOD_DIR)/v$(1)/include
else
$(addprefix $(BUILD)/%/obj/,$(US_UNIT_GPIOD_OBJS_$(1))): UNIT_CFLAGS += \
	$(US_GPIOD_CFLAGS)
endif
endef
$(foreach v,1 2,$(eval $(call US_UNIT_GPIOD_HEADERS,$(v))))

US_WRAPPED := open close ioctl gpiod_chip_open_lookup gpiod_chip_close \
	gpiod_chip_get_line gpiod_chip_find_line gpiod_line_find \
	gpiod_line_get_chip \
	gpiod_line_request_falling_edge_events gpiod_line_release \
	gpiod_line_get_value gpiod_line_event_wait gpiod_line_event_read \
	gpiod_line_event_get_fd
US_WRAPPED_V2 := open close ioctl scandir gpiod_is_gpiochip_device \
	gpiod_chip_open gpiod_chip_close gpiod_chip_get_info \
	gpiod_chip_info_get_label gpiod_chip_info_free \
	gpiod_chip_get_line_offset_from_name \
	gpiod_line_settings_new gpiod_line_settings_free \
	gpiod_line_settings_set_direction gpiod_line_settings_set_edge_detection \
	gpiod_line_config_new gpiod_line_config_free \
	gpiod_line_config_add_line_settings \
	gpiod_request_config_new gpiod_request_config_free \
	gpiod_request_config_set_consumer gpiod_chip_request_lines \
	gpiod_line_request_release gpiod_line_request_get_value \
	gpiod_line_request_wait_edge_events gpiod_line_request_read_edge_events \
	gpiod_line_request_get_fd gpiod_edge_event_buffer_new \
	gpiod_edge_event_buffer_free
US_EMPTY :=
US_COMMA := ,
us_wrap = -Wl$(US_COMMA)$(subst $(US_EMPTY) $(US_EMPTY),$(US_COMMA),$(addprefix --wrap=,$(1)))
$(BUILD)/%/test_userspace_transport: UNIT_LDLIBS += $(call us_wrap,$(US_WRAPPED))
$(BUILD)/%/test_userspace_gpio_v2: UNIT_LDLIBS += $(call us_wrap,$(US_WRAPPED_V2))
$(BUILD)/%/test_userspace_text $(BUILD)/%/test_userspace_lib \
$(BUILD)/%/test_userspace_simbus \
$(BUILD)/%/test_userspace_ctl $(BUILD)/%/test_userspace_bridge: UNIT_LDLIBS += $(US_LDLIBS)
