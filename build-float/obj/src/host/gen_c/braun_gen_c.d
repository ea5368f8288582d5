build-float/obj/src/host/gen_c/braun_gen_c.o: \
 src/host/gen_c/braun_gen_c.c include/host/braun_scene_file.h \
 include/core/braun_scene.h include/core/braun.h \
 src/host/common/braun_c_locale.h
include/host/braun_scene_file.h:
include/core/braun_scene.h:
include/core/braun.h:
src/host/common/braun_c_locale.h:
