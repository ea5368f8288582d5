build-float/obj/src/core/braun_integrate.o: src/core/braun_integrate.c \
 src/core/braun_tableau.h src/core/braun_internal.h include/core/braun.h \
 src/core/braun_dense.h src/core/braun_linalg.h src/core/braun_math.h \
 src/core/braun_sincos.h include/core/braun_linsolver.h \
 include/core/braun.h
src/core/braun_tableau.h:
src/core/braun_internal.h:
include/core/braun.h:
src/core/braun_dense.h:
src/core/braun_linalg.h:
src/core/braun_math.h:
src/core/braun_sincos.h:
include/core/braun_linsolver.h:
include/core/braun.h:
