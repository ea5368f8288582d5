build-float/obj/src/host/cli/braun_main.o: src/host/cli/braun_main.c \
 include/host/braun_backends.h include/core/braun.h \
 include/core/braun_linsolver.h include/core/braun.h \
 src/host/cli/braun_cli.h include/host/braun_reference.h \
 include/core/braun_models.h include/host/braun_scene_file.h \
 include/core/braun_scene.h
include/host/braun_backends.h:
include/core/braun.h:
include/core/braun_linsolver.h:
include/core/braun.h:
src/host/cli/braun_cli.h:
include/host/braun_reference.h:
include/core/braun_models.h:
include/host/braun_scene_file.h:
include/core/braun_scene.h:
