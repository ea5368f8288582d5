build-float/obj/src/host/cli/cli_args.o: src/host/cli/cli_args.c \
 src/host/cli/braun_cli.h include/core/braun.h \
 include/host/braun_reference.h include/core/braun_models.h \
 include/core/braun.h include/host/braun_scene_file.h \
 include/core/braun_scene.h src/core/braun_math.h src/core/braun_sincos.h
src/host/cli/braun_cli.h:
include/core/braun.h:
include/host/braun_reference.h:
include/core/braun_models.h:
include/core/braun.h:
include/host/braun_scene_file.h:
include/core/braun_scene.h:
src/core/braun_math.h:
src/core/braun_sincos.h:
