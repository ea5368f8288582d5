build-float/pic/src/host/scene_file/scene_json_read.o: \
 src/host/scene_file/scene_json_read.c include/core/braun_models.h \
 include/core/braun.h src/host/common/braun_c_locale.h \
 src/host/scene_file/scene_json_internal.h \
 include/host/braun_scene_file.h include/core/braun_scene.h
include/core/braun_models.h:
include/core/braun.h:
src/host/common/braun_c_locale.h:
src/host/scene_file/scene_json_internal.h:
include/host/braun_scene_file.h:
include/core/braun_scene.h:
