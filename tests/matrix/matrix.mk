# tests/matrix/matrix.mk: the kernel series the project is built and
# tested for, and news of newer ones.
#
#   make kernels-news   says whether Debian (trixie, trixie-backports) ships
#                       a kernel series newer than KERNEL_NEWEST in
#                       tests/matrix/kernels (tests/matrix/kernels-news);
#                       informs only, unless KERNELS_NEWS_STRICT=1, with
#                       which a newer series, or an archive it cannot ask,
#                       fails it
#
# tests/matrix/kernels names the series (KERNEL_OLDEST, KERNEL_STABLE,
# KERNEL_NEWEST) for make and for scripts; the top Makefile includes it.

.PHONY: kernels-news
kernels-news:
	@$(TOP)/tests/matrix/kernels-news $(if $(filter 1,$(KERNELS_NEWS_STRICT)),--strict)

# A few seconds, and it cannot fail make check: only a line in its log.
CHECK_STEPS += kernels-news
