# libbraun — top-level build.
#   make              build/libbraun.a and build/bin/braun
#   make test         build and run every test (installs missing Debian packages)
#   make install      PREFIX=/usr/local DESTDIR=
#   make clean
# Options: BRAUN_SINGLE=1 builds braun_real = float.

CC      ?= cc
AR      ?= ar
PREFIX  ?= /usr/local
DESTDIR ?=
BUILD   ?= build

WARN    := -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes
OPT     ?= -O2 -g
CFLAGS  ?=
CPPFLAGS_ALL := -Iinclude -Isrc $(CPPFLAGS)
ifeq ($(BRAUN_SINGLE),1)
CPPFLAGS_ALL += -DBRAUN_SINGLE
endif
CFLAGS_ALL := -std=c99 $(OPT) $(WARN) $(CFLAGS)
LDLIBS_ALL := -lm $(LDLIBS)

# Core library: src/*.c and src/models/*.c depend on nothing but libm.
LIB_SRC := $(sort $(wildcard src/*.c) $(wildcard src/models/*.c))
# Host conveniences (allocation, message formatting): in the host library,
# never in the firmware build.
HOST_SRC := $(sort $(wildcard src/host/*.c))
CLI_SRC  := $(sort $(wildcard src/cli/*.c))
LIB_OBJ  := $(LIB_SRC:%.c=$(BUILD)/obj/%.o) $(HOST_SRC:%.c=$(BUILD)/obj/%.o)
CLI_OBJ  := $(CLI_SRC:%.c=$(BUILD)/obj/%.o)
HEADERS  := $(wildcard include/*.h) $(wildcard src/*.h) $(wildcard src/*/*.h)

TEST_SRC  := $(sort $(wildcard tests/test_*.c))
TEST_BIN  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)

# Keep intermediate objects (test support) between runs.
.SECONDARY:

.PHONY: all lib cli test test-unit test-cli test-sanitize test-core-suites deps-test install clean convergence
all: lib cli
lib: $(BUILD)/libbraun.a
cli: $(BUILD)/bin/braun

$(BUILD)/obj/%.o: %.c $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) -c $< -o $@

$(BUILD)/libbraun.a: $(LIB_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/bin/braun: $(CLI_OBJ) $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(CLI_OBJ) $(BUILD)/libbraun.a $(LDLIBS_ALL) -o $@

# ---------------------------------------------------------------- tests
TEST_DEPS := libcmocka-dev

deps-test:
	@tools/ensure-deps $(TEST_DEPS)

# Test-only systems with known solutions, linked into every test binary.
TEST_SUPPORT := $(BUILD)/obj/tests/systems/test_systems.o
$(BUILD)/obj/tests/%.o: tests/%.c tests/systems/test_systems.h $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Itests -Itests/systems $(CFLAGS_ALL) -c $< -o $@

# test_noalloc counts heap calls through the linker's --wrap.
LDFLAGS_test_noalloc := -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free

$(BUILD)/tests/%: tests/%.c tests/test_util.h tests/heap_count.h tests/heap_interpose.h $(TEST_SUPPORT) $(BUILD)/libbraun.a | deps-test
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Itests -Itests/systems $(CFLAGS_ALL) $< $(TEST_SUPPORT) $(BUILD)/libbraun.a -lcmocka $(LDLIBS_ALL) $(LDFLAGS_$*) -o $@

# Suites added by other parts of the project (mk/*.mk append to TEST_SUITES
# the command of a suite that ends with "N passed, M failed", and to
# TEST_PREREQS what must be built first).
CORE_SUITES = "tools/run-tests $(TEST_BIN)" "sh tests/cli/run.sh $(BUILD)/bin/braun"
TEST_SUITES = $(CORE_SUITES) "sh tests/cli/install.sh" "$(MAKE) -s --no-print-directory test-sanitize"
TEST_PREREQS = $(TEST_BIN) $(BUILD)/bin/braun

# The unit and CLI tests again under AddressSanitizer + UBSan (own build dir).
SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
test-sanitize: deps-test
	@$(MAKE) --no-print-directory BUILD=build/sanitize OPT="-O1 -g $(SANITIZE)" \
	    LDLIBS="$(SANITIZE)" test-core-suites

# (prerequisites as a sub-make: mk/*.mk append to TEST_PREREQS after this point)
test-core-suites:
	@$(MAKE) --no-print-directory $(TEST_PREREQS)
	@tools/run-suites $(CORE_SUITES)

test: deps-test
	@$(MAKE) --no-print-directory $(TEST_PREREQS)
	@tools/run-suites $(TEST_SUITES)

# Runs every unit test binary; prints one closing line "N passed, N failed".
test-unit: $(TEST_BIN)
	@tools/run-tests $(TEST_BIN)

test-cli: $(BUILD)/bin/braun
	@sh tests/cli/run.sh $(BUILD)/bin/braun

# Observed order of convergence (docs/method.md).
convergence: $(BUILD)/bin/braun
	@sh tools/convergence.sh $(BUILD)/bin/braun

# ---------------------------------------------------------------- install
install: all $(BUILD)/libbraun_backends.a
	install -d $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/bin
	install -m 644 include/braun.h include/braun_models.h include/braun_host.h \
	    include/braun_linsolver.h include/braun_backends.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 $(BUILD)/libbraun.a $(BUILD)/libbraun_backends.a $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(BUILD)/bin/braun $(DESTDIR)$(PREFIX)/bin/
	sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@VERSION@|$(shell sed -n 's/^#define BRAUN_VERSION "\(.*\)"/\1/p' include/braun.h)|g' \
	    braun.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/braun.pc
	printf 'prefix=%s\nlibdir=$${prefix}/lib\n\nName: braun-backends\nDescription: LAPACK and SuiteSparse backends of libbraun (braun_backends.h)\nVersion: %s\nRequires: braun\nLibs: -L$${libdir} -lbraun_backends\nLibs.private: %s\n' \
	    '$(PREFIX)' '$(shell sed -n 's/^#define BRAUN_VERSION "\(.*\)"/\1/p' include/braun.h)' '$(BACKEND_LDLIBS)' \
	    > $(DESTDIR)$(PREFIX)/lib/pkgconfig/braun-backends.pc

clean:
	rm -rf $(BUILD)

# Feature areas keep their rules in mk/*.mk (scenes, compare, firmware, ...).
-include $(sort $(wildcard mk/*.mk))
