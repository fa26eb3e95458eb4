# tests/fresh-root/fresh-root.mk: the README's first command on a new
# machine (tests/fresh-root/check, docs/fresh-root.md).
#
#   make fresh-root-check           in a minimal Debian 12 and a minimal
#                                   Debian 13 root (debootstrap minbase,
#                                   make and git), a clone of this tree's
#                                   HEAD runs make demo as root; then make
#                                   deps as a user without root fails
#                                   naming the packages, installing
#                                   nothing, and after make deps as root
#                                   that user's make userspace unit passes;
#                                   and make deb-check as root: the Debian
#                                   packages built, installed with DKMS
#                                   against the suite's own kernel headers,
#                                   used and purged
#   make fresh-root-check-bookworm  the same in the Debian 12 root alone
#   make fresh-root-check-trixie    the same in the Debian 13 root alone
#
# FRESH_ROOT_REPO= names another git tree whose HEAD is cloned instead.
# fresh-root-background starts the check in the background at idle
# priority; fresh-root-await waits for it and gives its verdict.  make
# check runs the first as its first step, so that the check takes what the
# other steps leave of the cores (and waits on the network meanwhile), and
# the second as its last, after vmtest.

FRESH_ROOT := $(TOP)/tests/fresh-root/check
FRESH_ROOT_SUITES := bookworm trixie
FRESH_ROOT_REPO ?= $(TOP)
# What make clean keeps: each suite's root and the .debs it and apt fetched.
CLEAN_KEEP += $(foreach s,$(FRESH_ROOT_SUITES),$(addprefix fresh-root/$(s)/,\
	root root.debs apt-archives))

.PHONY: fresh-root-check fresh-root-background fresh-root-await \
	$(addprefix fresh-root-check-,$(FRESH_ROOT_SUITES))
fresh-root-check:
	@$(FRESH_ROOT) --repo $(FRESH_ROOT_REPO) $(FRESH_ROOT_SUITES)

$(addprefix fresh-root-check-,$(FRESH_ROOT_SUITES)):
	@$(FRESH_ROOT) --repo $(FRESH_ROOT_REPO) $(@:fresh-root-check-%=%)

fresh-root-background:
	@$(FRESH_ROOT) --background --repo $(FRESH_ROOT_REPO) $(FRESH_ROOT_SUITES)

fresh-root-await:
	@$(FRESH_ROOT) --await --repo $(FRESH_ROOT_REPO) $(FRESH_ROOT_SUITES)

CHECK_STEPS := fresh-root-background $(CHECK_STEPS)
CHECK_STEPS += fresh-root-await
