build-float/obj/src/host/backends/braun_suitesparse.o: \
 src/host/backends/braun_suitesparse.c \
 /usr/include/suitesparse/SuiteSparseQR_C.h \
 /usr/include/suitesparse/cholmod.h \
 /usr/include/suitesparse/cholmod_io64.h \
 /usr/include/suitesparse/SuiteSparse_config.h \
 /usr/include/suitesparse/cholmod_config.h \
 /usr/include/suitesparse/cholmod_core.h \
 /usr/include/suitesparse/cholmod_check.h \
 /usr/include/suitesparse/cholmod_cholesky.h \
 /usr/include/suitesparse/cholmod_partition.h \
 /usr/include/suitesparse/cholmod_camd.h \
 /usr/include/suitesparse/cholmod_supernodal.h \
 /usr/include/suitesparse/cholmod_matrixops.h \
 /usr/include/suitesparse/cholmod_modify.h \
 /usr/include/suitesparse/SuiteSparseQR_definitions.h \
 /usr/include/suitesparse/cholmod.h include/host/braun_backends.h \
 include/core/braun.h include/core/braun_linsolver.h include/core/braun.h \
 src/core/braun_math.h src/core/braun_sincos.h
/usr/include/suitesparse/SuiteSparseQR_C.h:
/usr/include/suitesparse/cholmod.h:
/usr/include/suitesparse/cholmod_io64.h:
/usr/include/suitesparse/SuiteSparse_config.h:
/usr/include/suitesparse/cholmod_config.h:
/usr/include/suitesparse/cholmod_core.h:
/usr/include/suitesparse/cholmod_check.h:
/usr/include/suitesparse/cholmod_cholesky.h:
/usr/include/suitesparse/cholmod_partition.h:
/usr/include/suitesparse/cholmod_camd.h:
/usr/include/suitesparse/cholmod_supernodal.h:
/usr/include/suitesparse/cholmod_matrixops.h:
/usr/include/suitesparse/cholmod_modify.h:
/usr/include/suitesparse/SuiteSparseQR_definitions.h:
/usr/include/suitesparse/cholmod.h:
include/host/braun_backends.h:
include/core/braun.h:
include/core/braun_linsolver.h:
include/core/braun.h:
src/core/braun_math.h:
src/core/braun_sincos.h:
