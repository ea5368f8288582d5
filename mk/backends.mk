# Optional linear-algebra backends (issue 7): build/libbraun_backends.a.
#
#   src/host/backends/braun_lapack.c       BRAUN_LAPACK=1       (liblapack-dev)
#   src/host/backends/braun_suitesparse.c  BRAUN_SUITESPARSE=1  (libsuitesparse-dev)
#   src/host/backends/braun_backend_select.c  always: names, auto selection
#
# libbraun.a never contains them (tests/backends/check-core.sh proves it).
# Both default to on for host builds; `make BRAUN_LAPACK=0 BRAUN_SUITESPARSE=0`
# builds the backend archive with the selection code alone.

BRAUN_LAPACK ?= 1
BRAUN_SUITESPARSE ?= 1

BACKEND_SRC := src/host/backends/braun_backend_select.c
BACKEND_CPPFLAGS :=
BACKEND_LDLIBS :=
BACKEND_DEPS :=
ifeq ($(BRAUN_LAPACK)$(wildcard src/host/backends/braun_lapack.c),1src/host/backends/braun_lapack.c)
BACKEND_SRC += src/host/backends/braun_lapack.c
BACKEND_CPPFLAGS += -DBRAUN_WITH_LAPACK
BACKEND_LDLIBS += -llapack -lblas
BACKEND_DEPS += liblapack-dev
endif
ifeq ($(BRAUN_SUITESPARSE)$(wildcard src/host/backends/braun_suitesparse.c),1src/host/backends/braun_suitesparse.c)
BACKEND_SRC += src/host/backends/braun_suitesparse.c
BACKEND_CPPFLAGS += -DBRAUN_WITH_SUITESPARSE -I/usr/include/suitesparse
BACKEND_LDLIBS := -lspqr -lcholmod -lsuitesparseconfig $(filter-out -llapack -lblas,$(BACKEND_LDLIBS)) -llapack -lblas
BACKEND_DEPS += libsuitesparse-dev
endif
BACKEND_OBJ := $(BACKEND_SRC:%.c=$(BUILD)/obj/%.o)
# What a static link of the backends needs (braun-backends.pc's
# Libs.private): BACKEND_LDLIBS and, transitively, every library they need
# by their shared libraries' DT_NEEDED (tools/static-libs; on Debian 12
# AMD, CAMD, COLAMD, CCOLAMD, METIS, libgomp, libgfortran, libquadmath).
# Evaluated at make install only.
BACKEND_STATIC_LDLIBS = $(if $(strip $(BACKEND_LDLIBS)),$(shell CC="$(CC)" tools/static-libs $(BACKEND_LDLIBS)))

$(BACKEND_OBJ): CPPFLAGS_ALL += $(BACKEND_CPPFLAGS)
$(BACKEND_OBJ): | deps-backends
# The flags decide what the archive holds: rebuild when they change.
$(BUILD)/obj/src/host/backends/braun_backend_select.o: $(BUILD)/backends.flags
$(BUILD)/backends.flags: FORCE_BACKEND_FLAGS
	@mkdir -p $(dir $@)
	@echo "$(BACKEND_CPPFLAGS)" | cmp -s - $@ || echo "$(BACKEND_CPPFLAGS)" > $@
.PHONY: FORCE_BACKEND_FLAGS deps-backends

deps-backends:
	@$(if $(strip $(BACKEND_DEPS)),tools/ensure-deps $(BACKEND_DEPS),true)

$(BUILD)/libbraun_backends.a: $(BACKEND_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

# Link order for programs that use backends: backends before libbraun.a.
BACKENDS_LDLIBS := $(BUILD)/libbraun_backends.a $(BUILD)/libbraun.a $(BACKEND_LDLIBS) -lm

# Tests of the backends (tests/test_backend_*.c) link them.
BACKEND_TEST_BIN := $(filter $(BUILD)/tests/test_backend_%,$(TEST_BIN))
$(BACKEND_TEST_BIN): $(BUILD)/libbraun_backends.a
# (LAPACK always: the tests compute their references with it.)
$(BACKEND_TEST_BIN): LDLIBS_ALL := $(BACKENDS_LDLIBS) -llapack -lblas $(LDLIBS_ALL)

# The CLI selects backends (--backend).
$(BUILD)/bin/braun: $(BUILD)/libbraun_backends.a
$(BUILD)/bin/braun: LDLIBS_ALL := $(BUILD)/libbraun_backends.a $(HOST_LDLIBS) $(BACKEND_LDLIBS) $(LDLIBS_ALL)

# The core stays free of the backends' libraries.
TEST_SUITES += "sh tests/backends/check-core.sh $(BUILD)/libbraun.a"
