build-float/pic/src/core/braun_vec.o: src/core/braun_vec.c \
 src/core/braun_linalg.h include/core/braun.h src/core/braun_math.h \
 src/core/braun_sincos.h
src/core/braun_linalg.h:
include/core/braun.h:
src/core/braun_math.h:
src/core/braun_sincos.h:
