# driver/driver.mk: filled in by its area
