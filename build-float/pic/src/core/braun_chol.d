build-float/pic/src/core/braun_chol.o: src/core/braun_chol.c \
 src/core/braun_linalg.h include/core/braun.h src/core/braun_math.h \
 src/core/braun_sincos.h
src/core/braun_linalg.h:
include/core/braun.h:
src/core/braun_math.h:
src/core/braun_sincos.h:
