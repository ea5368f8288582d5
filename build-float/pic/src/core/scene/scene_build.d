build-float/pic/src/core/scene/scene_build.o: \
 src/core/scene/scene_build.c src/core/scene/scene_internal.h \
 src/core/braun_math.h include/core/braun.h src/core/braun_sincos.h \
 include/core/braun_scene.h include/core/braun.h
src/core/scene/scene_internal.h:
src/core/braun_math.h:
include/core/braun.h:
src/core/braun_sincos.h:
include/core/braun_scene.h:
include/core/braun.h:
