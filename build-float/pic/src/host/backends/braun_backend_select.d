build-float/pic/src/host/backends/braun_backend_select.o: \
 src/host/backends/braun_backend_select.c include/host/braun_backends.h \
 include/core/braun.h include/core/braun_linsolver.h include/core/braun.h
include/host/braun_backends.h:
include/core/braun.h:
include/core/braun_linsolver.h:
include/core/braun.h:
