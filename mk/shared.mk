# Shared libraries, the CMake package and the rest of `make install`
# (issue 15). The archives (libbraun.a for firmware and static links) stay;
# beside them:
#   BUILD/libbraun.so.V           the core          soname libbraun.so.MAJOR.MINOR
#   BUILD/libbraun_host.so.V      scene files, ...  soname libbraun_host.so.MAJOR.MINOR
#   BUILD/libbraun_backends.so.V  LAPACK, SuiteSparse
# from position-independent objects of the same sources (BUILD/pic/), each
# exporting exactly the public API it defines (tools/export-map: declared
# in include/core/*.h or include/host/*.h; braun__* and the kernels stay
# inside) under the symbol version BRAUN_MAJOR.MINOR. In 0.x every minor
# version may change the ABI, so the soname carries it.
# make install adds them, lib/cmake/braun/braunConfig.cmake and its
# version file (imported targets braun::braun, braun::scene,
# braun::backends), the shipped scenes (share/braun/data, which the
# installed braun finds), the examples and the documentation.

VERSION_MAJOR := $(word 1,$(subst ., ,$(VERSION)))
VERSION_MINOR := $(word 2,$(subst ., ,$(VERSION)))
SOVERSION := $(VERSION_MAJOR).$(VERSION_MINOR)
PUBLIC_HEADERS := $(sort $(wildcard include/core/*.h include/host/*.h))

PIC_CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/pic/%.o)
PIC_HOST_OBJ := $(HOST_SRC:%.c=$(BUILD)/pic/%.o)
PIC_BACKEND_OBJ := $(BACKEND_SRC:%.c=$(BUILD)/pic/%.o)
PIC_FLAGS := -fPIC

$(PIC_CORE_OBJ): $(BUILD)/pic/%.o: %.c $(PRECISION_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CORE_CPPFLAGS) $(CPPFLAGS) $(CFLAGS_ALL) $(PIC_FLAGS) $(DEPFLAGS) -c $< -o $@
$(PIC_HOST_OBJ): $(BUILD)/pic/%.o: %.c $(PRECISION_STAMP) | deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) $(PIC_FLAGS) $(DEPFLAGS) -c $< -o $@
$(PIC_BACKEND_OBJ): $(BUILD)/pic/%.o: %.c $(PRECISION_STAMP) | deps-backends
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(BACKEND_CPPFLAGS) $(CFLAGS_ALL) $(PIC_FLAGS) $(DEPFLAGS) -c $< -o $@
$(BUILD)/pic/src/host/backends/braun_backend_select.o: $(BUILD)/backends.flags

# The version scripts: exactly the public symbols each library defines.
$(BUILD)/%.map: $(BUILD)/%.a $(PUBLIC_HEADERS) tools/export-map tools/strip-comments
	CC="$(CC)" tools/export-map BRAUN_$(SOVERSION) $< $(PUBLIC_HEADERS) > $@.tmp && mv $@.tmp $@

so_ldflags = -shared -Wl,--no-undefined -Wl,-soname,$(1).so.$(SOVERSION) \
             -Wl,--version-script=$(BUILD)/$(1).map
# BUILD/libX.so.V, with the links libX.so.MAJOR.MINOR (the soname) and libX.so.
define so_links
	ln -sf $(notdir $@) $(BUILD)/$(1).so.$(SOVERSION)
	ln -sf $(1).so.$(SOVERSION) $(BUILD)/$(1).so
endef

$(BUILD)/libbraun.so.$(VERSION): $(PIC_CORE_OBJ) $(BUILD)/libbraun.map
	$(CC) $(CFLAGS_ALL) $(call so_ldflags,libbraun) $(PIC_CORE_OBJ) -lm $(LDLIBS) -o $@
	$(call so_links,libbraun)
$(BUILD)/libbraun_host.so.$(VERSION): $(PIC_HOST_OBJ) $(BUILD)/libbraun_host.map \
                                      $(BUILD)/libbraun.so.$(VERSION)
	$(CC) $(CFLAGS_ALL) $(call so_ldflags,libbraun_host) $(PIC_HOST_OBJ) -L$(BUILD) -lbraun -ljansson -lm $(LDLIBS) -o $@
	$(call so_links,libbraun_host)
$(BUILD)/libbraun_backends.so.$(VERSION): $(PIC_BACKEND_OBJ) $(BUILD)/libbraun_backends.map \
                                          $(BUILD)/libbraun.so.$(VERSION)
	$(CC) $(CFLAGS_ALL) $(call so_ldflags,libbraun_backends) $(PIC_BACKEND_OBJ) -L$(BUILD) -lbraun $(BACKEND_LDLIBS) -lm \
	    $(LDLIBS) -o $@
	$(call so_links,libbraun_backends)

SHARED_LIBS := $(BUILD)/libbraun.so.$(VERSION) $(BUILD)/libbraun_host.so.$(VERSION) \
               $(BUILD)/libbraun_backends.so.$(VERSION)
.PHONY: shared install-shared install-cmake install-data uninstall
shared: $(SHARED_LIBS)
lib: $(BUILD)/libbraun.so.$(VERSION) $(BUILD)/libbraun_host.so.$(VERSION)

# ---------------------------------------------------------------- install
LIBDIR := $(DESTDIR)$(PREFIX)/lib
install: install-shared install-cmake install-data
install-shared: $(SHARED_LIBS) install-check
	install -d "$(LIBDIR)"
	for l in libbraun libbraun_host libbraun_backends; do \
	    install -m 755 $(BUILD)/$$l.so.$(VERSION) "$(LIBDIR)/" && \
	    ln -sf $$l.so.$(VERSION) "$(LIBDIR)/$$l.so.$(SOVERSION)" && \
	    ln -sf $$l.so.$(SOVERSION) "$(LIBDIR)/$$l.so" || exit 1; done
	@# The loader's cache, when installing into the system itself as root.
	@if [ -z "$(DESTDIR)" ] && [ "$$(id -u)" = 0 ] && command -v ldconfig > /dev/null; then \
	    ldconfig; fi

SIZEOF_POINTER := $(shell $(CC) -dM -E -x c /dev/null 2>/dev/null | sed -n 's/^\#define __SIZEOF_POINTER__ //p')
# CMake list of the backends' libraries: "-lspqr -llapack" -> "spqr;lapack;".
BACKEND_CMAKE_LIBS = $(subst $(eval) ,,$(foreach l,$(BACKEND_LDLIBS),$(patsubst -l%,%,$(l));))
CMAKE_SUBST = sed -e 's|@VERSION@|$(VERSION)|g' -e 's|@SOVERSION@|$(SOVERSION)|g' \
                  -e 's|@VERSION_MAJOR@|$(VERSION_MAJOR)|g' -e 's|@VERSION_MINOR@|$(VERSION_MINOR)|g' \
                  -e 's|@BACKEND_LIBS@|$(BACKEND_CMAKE_LIBS)|g' \
                  -e 's|@BACKEND_LIBS_TEXT@|$(or $(BACKEND_LDLIBS),nothing for the backends)|g' \
                  -e 's|@SIZEOF_VOID_P@|$(SIZEOF_POINTER)|g' \
                  -e 's|@PRECISION_DEFINES@|$(if $(filter float,$(PRECISION)),BRAUN_SINGLE,)|g'
install-cmake: cmake/braunConfig.cmake.in cmake/braunConfigVersion.cmake.in install-check
	install -d "$(LIBDIR)/cmake/braun"
	$(CMAKE_SUBST) cmake/braunConfig.cmake.in > "$(LIBDIR)/cmake/braun/braunConfig.cmake"
	$(CMAKE_SUBST) cmake/braunConfigVersion.cmake.in > "$(LIBDIR)/cmake/braun/braunConfigVersion.cmake"

SHARE := $(DESTDIR)$(PREFIX)/share
install-data: install-check
	install -d "$(SHARE)/braun/data/iftomm" "$(SHARE)/braun/examples" "$(SHARE)/doc/braun"
	install -m 644 data/*.json "$(SHARE)/braun/data/"
	install -m 644 data/iftomm/*.json "$(SHARE)/braun/data/iftomm/"
	install -m 644 examples/*.c examples/CMakeLists.txt examples/Makefile "$(SHARE)/braun/examples/"
	install -m 644 README.md CHANGELOG.md docs/*.md "$(SHARE)/doc/braun/"

uninstall:
	for h in $(notdir $(PUBLIC_HEADERS)); do rm -f "$(DESTDIR)$(PREFIX)/include/$$h"; done
	for l in libbraun libbraun_host libbraun_backends; do \
	    rm -f "$(LIBDIR)/$$l.a" "$(LIBDIR)/$$l.so" "$(LIBDIR)/$$l.so.$(SOVERSION)" \
	          "$(LIBDIR)/$$l.so.$(VERSION)"; done
	rm -f "$(LIBDIR)/pkgconfig/braun.pc" "$(LIBDIR)/pkgconfig/braun-host.pc" "$(LIBDIR)/pkgconfig/braun-backends.pc"
	rm -rf "$(LIBDIR)/cmake/braun" "$(SHARE)/braun" "$(SHARE)/doc/braun"
	rm -f "$(DESTDIR)$(PREFIX)/bin/braun"

# Installed, the libraries export exactly their maps and the examples build
# and run against a DESTDIR installation with pkg-config and with CMake,
# statically and dynamically (tests/cli/install.sh, in make test).
TEST_PREREQS += $(SHARED_LIBS)
# (libmetis-dev: -lmetis in braun-backends.pc's Libs.private, which lists
# only what the linker finds; Debian 12 ships it without libmetis.a)
INSTALL_TEST_DEPS := cmake pkgconf binutils libmetis-dev
deps-test: deps-install-test
deps-install-test:
	@tools/ensure-deps $(INSTALL_TEST_DEPS)
.PHONY: deps-install-test

# The ABI of the public headers against the record of this minor version
# (tests/abi/check.sh); after a new minor version, `make abi-record`
# writes the new record (tools/abi-record: x86-64, gcc).
TEST_SUITES += "sh tests/abi/check.sh"
.PHONY: abi-record
abi-record:
	CC=gcc tools/abi-record include/core include/host > tests/abi/abi-$(SOVERSION).txt
