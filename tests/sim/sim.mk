# tests/sim/sim.mk: filled in by its area
