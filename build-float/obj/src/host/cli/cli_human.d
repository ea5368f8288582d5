build-float/obj/src/host/cli/cli_human.o: src/host/cli/cli_human.c \
 src/host/cli/braun_cli.h include/core/braun.h \
 include/host/braun_reference.h include/core/braun_models.h \
 include/core/braun.h include/host/braun_scene_file.h \
 include/core/braun_scene.h
src/host/cli/braun_cli.h:
include/core/braun.h:
include/host/braun_reference.h:
include/core/braun_models.h:
include/core/braun.h:
include/host/braun_scene_file.h:
include/core/braun_scene.h:
