# dts/dts.mk: filled in by its area
