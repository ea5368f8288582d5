build-float/obj/src/host/check/braun_callback_check.o: \
 src/host/check/braun_callback_check.c include/host/braun_host.h \
 include/core/braun.h src/host/common/braun_c_locale.h
include/host/braun_host.h:
include/core/braun.h:
src/host/common/braun_c_locale.h:
