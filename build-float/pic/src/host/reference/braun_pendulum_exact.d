build-float/pic/src/host/reference/braun_pendulum_exact.o: \
 src/host/reference/braun_pendulum_exact.c include/host/braun_reference.h \
 include/core/braun_models.h include/core/braun.h
include/host/braun_reference.h:
include/core/braun_models.h:
include/core/braun.h:
