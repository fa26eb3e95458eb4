# driver/core/core.mk: filled in by its area
