build-float/pic/src/host/reference/braun_andrews_ref.o: \
 src/host/reference/braun_andrews_ref.c include/host/braun_reference.h \
 include/core/braun_models.h include/core/braun.h
include/host/braun_reference.h:
include/core/braun_models.h:
include/core/braun.h:
