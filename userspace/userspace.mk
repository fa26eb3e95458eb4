# userspace/userspace.mk: filled in by its area
