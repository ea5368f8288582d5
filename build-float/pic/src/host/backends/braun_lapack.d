build-float/pic/src/host/backends/braun_lapack.o: \
 src/host/backends/braun_lapack.c include/host/braun_backends.h \
 include/core/braun.h include/core/braun_linsolver.h include/core/braun.h
include/host/braun_backends.h:
include/core/braun.h:
include/core/braun_linsolver.h:
include/core/braun.h:
