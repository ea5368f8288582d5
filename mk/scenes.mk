# Scenes (issue 3): the planar multibody builder in libbraun.a, the host-only
# JSON reader in libbraun_scene.a, and their tests.
#
#   src/scene/*.c        firmware-friendly C99 (libm, braun.h): into libbraun.a
#   src/scene_json/*.c   host only, jansson: into build/libbraun_scene.a
#
# libbraun.a's prerequisites were expanded when the top Makefile read its
# rule, so the scene objects are added as extra prerequisites; the archive
# recipe uses $^ and picks them up.

SCENE_DEPS := libjansson-dev
SCENE_OBJ := $(patsubst %.c,$(BUILD)/obj/%.o,$(sort $(wildcard src/scene/*.c)))
SCENE_JSON_OBJ := $(patsubst %.c,$(BUILD)/obj/%.o,$(sort $(wildcard src/scene_json/*.c)))
LIB_OBJ += $(SCENE_OBJ)

$(BUILD)/libbraun.a: $(SCENE_OBJ)

$(BUILD)/libbraun_scene.a: $(SCENE_JSON_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

# The reader includes <jansson.h>: install it before compiling.
$(SCENE_JSON_OBJ): | deps-scene
deps-scene:
	@tools/ensure-deps $(SCENE_DEPS)
.PHONY: deps-scene

# Link order: the reader needs libbraun.a after it, jansson after both.
SCENE_LDLIBS := $(BUILD)/libbraun_scene.a $(BUILD)/libbraun.a -ljansson -lm

# The CLI reads scene files.
$(BUILD)/bin/braun: $(BUILD)/libbraun_scene.a
$(BUILD)/bin/braun: LDLIBS_ALL += $(SCENE_LDLIBS)

# Scene tests use the reader too.
SCENE_TEST_BIN := $(filter $(BUILD)/tests/test_scene_%,$(TEST_BIN))
$(SCENE_TEST_BIN): $(BUILD)/libbraun_scene.a tests/scene/scene_fd.h | deps-scene
$(SCENE_TEST_BIN): LDLIBS_ALL += $(SCENE_LDLIBS)

# Command-line checks of scenes: braun run/check/gen on every shipped scene.
TEST_SUITES += "sh tests/cli/scenes.sh $(BUILD)/bin/braun"

# test_scene_noalloc counts heap calls through the linker's --wrap.
LDFLAGS_test_scene_noalloc := -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free

# make install also installs the scene API (the builder is in libbraun.a)
# and the host-only reader (libbraun_scene.a: link it before libbraun.a,
# with -ljansson).
install: install-scene
install-scene: all $(BUILD)/libbraun_scene.a
	install -d $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib
	install -m 644 include/braun_scene.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 $(BUILD)/libbraun_scene.a $(DESTDIR)$(PREFIX)/lib/
.PHONY: install-scene
