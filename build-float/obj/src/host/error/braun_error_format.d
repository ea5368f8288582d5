build-float/obj/src/host/error/braun_error_format.o: \
 src/host/error/braun_error_format.c include/host/braun_host.h \
 include/core/braun.h src/host/common/braun_c_locale.h
include/host/braun_host.h:
include/core/braun.h:
src/host/common/braun_c_locale.h:
