build-float/obj/src/core/braun_status.o: src/core/braun_status.c \
 include/core/braun.h
include/core/braun.h:
