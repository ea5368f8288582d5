build-float/pic/src/core/models/braun_builtin_table.o: \
 src/core/models/braun_builtin_table.c \
 src/core/models/braun_models_internal.h include/core/braun.h \
 include/core/braun_models.h include/core/braun.h src/core/braun_math.h \
 src/core/braun_sincos.h
src/core/models/braun_models_internal.h:
include/core/braun.h:
include/core/braun_models.h:
include/core/braun.h:
src/core/braun_math.h:
src/core/braun_sincos.h:
