build-float/pic/src/host/reference/braun_elliptic.o: \
 src/host/reference/braun_elliptic.c include/host/braun_reference.h \
 include/core/braun_models.h include/core/braun.h
include/host/braun_reference.h:
include/core/braun_models.h:
include/core/braun.h:
