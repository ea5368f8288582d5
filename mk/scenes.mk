# Scenes (issue 3): the planar multibody builder is core (src/core/scene,
# in libbraun.a); scene files and scene-to-C are host (src/host/scene_file,
# src/host/gen_c, in libbraun_host.a). This file adds their tests.

# Scene tests read scene files.
SCENE_TEST_BIN := $(filter $(BUILD)/tests/test_scene_%,$(TEST_BIN))
$(SCENE_TEST_BIN): tests/scene/scene_fd.h

# Command-line checks of scenes: braun run/check/gen on every shipped scene.
TEST_SUITES += "sh tests/cli/scenes.sh $(BUILD)/bin/braun"

# test_scene_noalloc counts heap calls through the linker's --wrap.
LDFLAGS_test_scene_noalloc := -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free

# (kept for make targets that still name it)
deps-scene: deps-host
.PHONY: deps-scene
