build-float/pic/src/core/braun_version.o: src/core/braun_version.c \
 include/core/braun.h
include/core/braun.h:
