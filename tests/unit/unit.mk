# tests/unit/unit.mk: filled in by its area
