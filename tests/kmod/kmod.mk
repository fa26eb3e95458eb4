# tests/kmod/kmod.mk: filled in by its area
