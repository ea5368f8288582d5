# libbraun — top-level build.
#   make              build/libbraun.a, build/libbraun_host.a and build/bin/braun
#   make test         build and run every test (installs missing Debian packages)
#   make install      PREFIX=/usr/local DESTDIR=
#   make clean
# Options: BRAUN_SINGLE=1 builds braun_real = float; switching the precision
# of a BUILD rebuilds it all (BUILD/precision), BUILD=build-float keeps both.
#
# Two tiers (docs/architecture.md), one source list each:
#   core  src/core/**    C99, libm only, no stdio, no allocator: libbraun.a,
#                        the same objects for the host and for a Cortex-M
#                        (mk/firmware.mk); public headers in include/core/.
#   host  src/host/**    everything that needs an operating system: error
#                        formatting, reference oracles, scene files (jansson),
#                        scene-to-C: libbraun_host.a; the backends
#                        (mk/backends.mk): libbraun_backends.a; the CLI:
#                        build/bin/braun. Public headers in include/host/.

CC      ?= cc
AR      ?= ar
PREFIX  ?= /usr/local
DESTDIR ?=
BUILD   ?= build

WARN    := -Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes
OPT     ?= -O2 -g
CFLAGS  ?=
# Core sources see the core's headers only: a core file that includes a
# host header does not compile.
CORE_CPPFLAGS := -Iinclude/core -Isrc/core
HOST_CPPFLAGS := -Iinclude/core -Iinclude/host -Isrc/core -Isrc/host/common
CPPFLAGS_ALL := $(HOST_CPPFLAGS) $(CPPFLAGS)
ifeq ($(BRAUN_SINGLE),1)
CPPFLAGS_ALL += -DBRAUN_SINGLE
CORE_CPPFLAGS += -DBRAUN_SINGLE
endif
CFLAGS_ALL := -std=c99 $(OPT) $(WARN) $(CFLAGS)
# The precision of this build. Every object depends on $(BUILD)/precision,
# rewritten only when it changes: `make BRAUN_SINGLE=1` on a tree built in
# double rebuilt nothing, and `make install` then installed the double
# libraries and tool with pkg-config files that define BRAUN_SINGLE.
PRECISION := $(if $(filter 1,$(BRAUN_SINGLE)),float,double)
PRECISION_STAMP := $(BUILD)/precision
LDLIBS_ALL := -lm $(LDLIBS)
# Every object records the headers it read (-MMD -MP): a change to a header
# rebuilds exactly the objects that include it.
DEPFLAGS = -MMD -MP

# The core tier: libbraun.a.
CORE_SRC := $(sort $(shell find src/core -name '*.c'))
# The host tier's library (error formatting, reference oracles, scene files,
# scene-to-C; src/host/common: what they share): libbraun_host.a, with jansson.
HOST_SRC := $(sort $(wildcard src/host/common/*.c src/host/error/*.c src/host/reference/*.c \
                              src/host/scene_file/*.c src/host/gen_c/*.c \
                              src/host/check/*.c))
CLI_SRC  := $(sort $(wildcard src/host/cli/*.c))
CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/obj/%.o)
HOST_OBJ := $(HOST_SRC:%.c=$(BUILD)/obj/%.o)
CLI_OBJ  := $(CLI_SRC:%.c=$(BUILD)/obj/%.o)
HOST_DEPS := libjansson-dev
# Link order of a host program: the host library, then the core, then jansson.
HOST_LDLIBS := $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a -ljansson -lm

TEST_SRC  := $(sort $(wildcard tests/test_*.c))
TEST_BIN  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)

VERSION := $(shell sed -n 's/^\#define BRAUN_VERSION "\(.*\)"/\1/p' include/core/braun.h)

# Keep intermediate objects (test support) between runs.
.SECONDARY:

.PHONY: all lib cli test test-unit test-cli test-sanitize test-core-suites deps-test deps-host \
        install clean convergence
all: lib cli
lib: $(BUILD)/libbraun.a $(BUILD)/libbraun_host.a
cli: $(BUILD)/bin/braun

deps-host:
	@tools/ensure-deps $(HOST_DEPS)

# The stamp has a rule only when it must change (a rule that always ran
# would make make -n list every object as out of date).
ifneq ($(shell cat '$(PRECISION_STAMP)' 2>/dev/null),$(PRECISION))
$(PRECISION_STAMP): FORCE_PRECISION
	@mkdir -p $(dir $@)
	@echo $(PRECISION) > $@
.PHONY: FORCE_PRECISION
endif

$(CORE_OBJ): $(BUILD)/obj/%.o: %.c $(PRECISION_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CORE_CPPFLAGS) $(CPPFLAGS) $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

# Host objects (and everything else under obj/: tests, bench, compare).
$(BUILD)/obj/src/host/%.o: src/host/%.c $(PRECISION_STAMP) | deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

$(BUILD)/libbraun.a: $(CORE_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/libbraun_host.a: $(HOST_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

$(BUILD)/bin/braun: $(CLI_OBJ) $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(CLI_OBJ) $(LDLIBS_ALL) -o $@

# The CLI reads scene files and reports against the references.
$(BUILD)/bin/braun: LDLIBS_ALL := $(HOST_LDLIBS) $(LDLIBS_ALL)

# ---------------------------------------------------------------- tests
TEST_DEPS := libcmocka-dev

deps-test:
	@tools/ensure-deps $(TEST_DEPS) $(HOST_DEPS)

# Tests may reach into either tier's private headers (element internals,
# kernels): they test them.
TEST_CPPFLAGS = $(CPPFLAGS_ALL) -Isrc/core/scene -Isrc/core/models -Itests -Itests/systems

# Test-only systems with known solutions, linked into every test binary.
TEST_SUPPORT := $(BUILD)/obj/tests/systems/test_systems.o
$(BUILD)/obj/tests/%.o: tests/%.c $(PRECISION_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CPPFLAGS) $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

# test_noalloc counts heap calls through the linker's --wrap.
LDFLAGS_test_noalloc := -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free

$(BUILD)/tests/%: tests/%.c $(TEST_SUPPORT) $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a $(PRECISION_STAMP) | deps-test
	@mkdir -p $(dir $@)
	$(CC) $(TEST_CPPFLAGS) $(CFLAGS_ALL) $(DEPFLAGS) -MF $(BUILD)/tests/$*.d $< $(TEST_SUPPORT) \
	    $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a -lcmocka $(LDLIBS_ALL) -ljansson $(LDFLAGS_$*) -o $@

# Suites added by other parts of the project (mk/*.mk append to TEST_SUITES
# the command of a suite that ends with "N passed, M failed" or "N passed,
# M failed, K skipped", and to TEST_PREREQS what must be built first).
CORE_SUITES = "tools/run-tests $(TEST_BIN)" "sh tests/cli/run.sh $(BUILD)/bin/braun"
TEST_SUITES = $(CORE_SUITES) "BUILD=$(BUILD) sh tests/cli/install.sh" "$(MAKE) -s --no-print-directory test-sanitize"
CORE_PREREQS = $(TEST_BIN) $(BUILD)/bin/braun
TEST_PREREQS = $(CORE_PREREQS)
# The prerequisites build in parallel, one job per processor.
TEST_JOBS ?= $(shell nproc 2>/dev/null || echo 1)

# The unit and CLI tests again under AddressSanitizer + UBSan (own build dir).
SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
test-sanitize: deps-test
	@$(MAKE) --no-print-directory BUILD=build/sanitize OPT="-O1 -g $(SANITIZE)" \
	    LDLIBS="$(SANITIZE)" test-core-suites

# (prerequisites as a sub-make: mk/*.mk append to TEST_PREREQS and
# CORE_PREREQS after this point; the sanitizer run builds only what its
# core suites run — not the harness, the shared libraries or the bench)
test-core-suites:
	@$(MAKE) --no-print-directory -j$(TEST_JOBS) $(CORE_PREREQS)
	@tools/run-suites $(CORE_SUITES)

test: deps-test
	@$(MAKE) --no-print-directory -j$(TEST_JOBS) $(TEST_PREREQS)
	@tools/run-suites $(TEST_SUITES)

# Runs every unit test binary; prints one closing line "N passed, M failed, K skipped".
test-unit: $(TEST_BIN)
	@tools/run-tests $(TEST_BIN)

test-cli: $(BUILD)/bin/braun
	@sh tests/cli/run.sh $(BUILD)/bin/braun

# Observed order of convergence (docs/method.md).
convergence: $(BUILD)/bin/braun
	@sh tools/convergence.sh $(BUILD)/bin/braun

# ---------------------------------------------------------------- install
# Headers flat under include/, the three archives, pkg-config files from
# their .pc.in templates (braun, braun-host, braun-backends), the tool.
# The .pc files name no PREFIX: prefix=${pcfiledir}/../.. (relocatable).
PC_SUBST = sed -e 's|@VERSION@|$(VERSION)|g' \
               -e 's|@BACKEND_LDLIBS@|$(BACKEND_LDLIBS)|g' \
               -e 's|@BACKEND_STATIC_LDLIBS@|$(BACKEND_STATIC_LDLIBS)|g' \
               -e 's|@PRECISION_CFLAGS@|$(if $(filter float,$(PRECISION)), -DBRAUN_SINGLE,)|g'
# What is installed is of the precision the pkg-config and CMake files
# name: each archive and the tool are checked by their link names
# (braun.h: a float build's end in _float) before anything is copied.
NM ?= nm
install-check: all $(BUILD)/libbraun_backends.a
	@for f in $(BUILD)/libbraun.a $(BUILD)/libbraun_host.a $(BUILD)/libbraun_backends.a $(BUILD)/bin/braun; do \
	    if $(NM) -g --defined-only "$$f" | grep -q ' braun_[A-Za-z0-9_]*_float$$'; then p=float; else p=double; fi; \
	    [ $$p = $(PRECISION) ] || { echo "make install: $$f is built in $$p, this install is $(PRECISION);" \
	        "run make clean, then make$(if $(filter float,$(PRECISION)), BRAUN_SINGLE=1,) install" >&2; \
	        exit 1; }; done
.PHONY: install-check
# Every path quoted: PREFIX and DESTDIR may hold spaces.
install: all $(BUILD)/libbraun_backends.a install-check
	install -d "$(DESTDIR)$(PREFIX)/include" "$(DESTDIR)$(PREFIX)/lib/pkgconfig" "$(DESTDIR)$(PREFIX)/bin"
	install -m 644 include/core/*.h include/host/*.h "$(DESTDIR)$(PREFIX)/include/"
	install -m 644 $(BUILD)/libbraun.a $(BUILD)/libbraun_host.a $(BUILD)/libbraun_backends.a \
	    "$(DESTDIR)$(PREFIX)/lib/"
	install -m 755 $(BUILD)/bin/braun "$(DESTDIR)$(PREFIX)/bin/"
	for pc in braun braun-host braun-backends; do \
	    $(PC_SUBST) $$pc.pc.in > "$(DESTDIR)$(PREFIX)/lib/pkgconfig/$$pc.pc" || exit 1; done

clean:
	rm -rf $(BUILD)

# Feature areas keep their rules in mk/*.mk (scenes, compare, firmware, ...).
-include $(sort $(wildcard mk/*.mk))

# The headers each object read, recorded by -MMD.
-include $(shell find $(BUILD) -name '*.d' -not -path '$(BUILD)/sanitize/*' 2>/dev/null)
# A dependency file is only read, never made: without this empty rule make
# remade an out-of-date firmware gc_pv.d through its built-in `%: %.o` and
# the firmware's gc_%.o pattern (stem "pv.d"), compiling gc_pv.d.o with no
# FW_GC_CORRECTIONS, whose error log then failed the firmware warning check.
%.d: ;
