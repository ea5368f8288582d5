build-float/pic/src/host/scene_file/scene_json_underflow.o: \
 src/host/scene_file/scene_json_underflow.c \
 src/host/scene_file/scene_json_internal.h include/core/braun_models.h \
 include/core/braun.h include/host/braun_scene_file.h \
 include/core/braun_scene.h
src/host/scene_file/scene_json_internal.h:
include/core/braun_models.h:
include/core/braun.h:
include/host/braun_scene_file.h:
include/core/braun_scene.h:
