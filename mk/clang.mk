# make test-clang: the libraries (static and shared), the tool and the unit
# tests built with clang into $(BUILD)/clang, warnings as errors, and the
# unit tests and the input-hygiene suite (gen-c's output compiled with
# clang) run. `make CC=clang` once stopped at the version scripts
# (tools/export-map ran gcc's -fpreprocessed). Not part of make test (a
# second full build: about 1.5 minutes on 2 cores); make test checks the
# piece that broke, tools/export-map under gcc and clang
# (tests/cli/install.sh).
CLANG ?= clang
CLANG_BUILD := $(BUILD)/clang
.PHONY: test-clang
test-clang:
	@tools/ensure-deps clang
	@$(MAKE) --no-print-directory BUILD=$(CLANG_BUILD) CC=$(CLANG) CFLAGS="$(CFLAGS) -Werror" \
	    all shared $(CLANG_BUILD)/libbraun_backends.a
	@$(MAKE) --no-print-directory BUILD=$(CLANG_BUILD) CC=$(CLANG) CFLAGS="$(CFLAGS) -Werror" test-unit
	@CC=$(CLANG) sh tests/cli/hygiene.sh $(CLANG_BUILD)/bin/braun
