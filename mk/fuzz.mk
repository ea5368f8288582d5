# Coverage-guided fuzzing with libFuzzer (clang), under AddressSanitizer and
# UBSan: the scene reader/builder (fuzz_scene), the CLI's option parsing
# (fuzz_args), the C generator (fuzz_gen_c: texts never leave their
# comments) and the adaptive driver's options (fuzz_adaptive: bounded by
# max_steps, BRAUN_OK only with a finite state at t_end).
#   make fuzz            each target for FUZZ_SECONDS (default 30) from its
#                        seed corpus in tests/fuzz/corpus_*; part of make test
#                        (15 s per target there)
#   make fuzz-regress    replay the corpora and tests/fuzz/regressions/ only
# A crash leaves its input in $(BUILD)/fuzz/; copy it to
# tests/fuzz/regressions/TARGET/ (scene, args, gen_c, adaptive) so it is
# replayed from then on.
FUZZ_SECONDS ?= 30
FUZZ_CC := clang
FUZZ_COMMON := -g -O1 -fno-sanitize-recover=all \
               $(HOST_CPPFLAGS) -Isrc/host/cli -std=c99 -D_POSIX_C_SOURCE=200809L
FUZZ_FLAGS := -fsanitize=fuzzer,address,undefined $(FUZZ_COMMON)
FUZZ_LIB_SRC = $(CORE_SRC) $(HOST_SRC)
FUZZ_CLI_SRC = src/host/cli/cli_args.c src/host/cli/cli_option.c src/host/cli/cli_error.c src/host/cli/cli_usage.c \
               src/host/cli/cli_real.c src/host/cli/cli_text.c

# Every source is compiled once with coverage and sanitizers
# (fuzzer-no-link) and the four targets link the objects they need: the
# library's ~100 files were compiled four times before (70 s of make test).
FUZZ_OBJ_FLAGS := -fsanitize=fuzzer-no-link,address,undefined $(FUZZ_COMMON)
FUZZ_OBJ = $(patsubst %.c,$(BUILD)/fuzz/obj/%.o,$(1))
$(BUILD)/fuzz/obj/%.o: %.c | deps-fuzz
	@mkdir -p $(dir $@)
	@$(FUZZ_CC) $(FUZZ_OBJ_FLAGS) -MMD -MP -c $< -o $@
# (their -MMD files are read by the Makefile's include of $(BUILD)/**/*.d)

$(BUILD)/fuzz/fuzz_scene: $(call FUZZ_OBJ,tests/fuzz/fuzz_scene.c $(FUZZ_LIB_SRC))
	$(FUZZ_CC) $(FUZZ_FLAGS) $^ -ljansson -lm -o $@
$(BUILD)/fuzz/fuzz_args: $(call FUZZ_OBJ,tests/fuzz/fuzz_args.c $(FUZZ_CLI_SRC) $(CORE_SRC))
	$(FUZZ_CC) $(FUZZ_FLAGS) $^ -lm -o $@
$(BUILD)/fuzz/fuzz_gen_c: $(call FUZZ_OBJ,tests/fuzz/fuzz_gen_c.c $(FUZZ_LIB_SRC))
	$(FUZZ_CC) $(FUZZ_FLAGS) $^ -ljansson -lm -o $@
$(BUILD)/fuzz/fuzz_adaptive: $(call FUZZ_OBJ,tests/fuzz/fuzz_adaptive.c $(CORE_SRC))
	$(FUZZ_CC) $(FUZZ_FLAGS) $^ -lm -o $@

deps-fuzz:
	@tools/ensure-deps clang libclang-rt-14-dev libjansson-dev

FUZZ_BIN := $(BUILD)/fuzz/fuzz_scene $(BUILD)/fuzz/fuzz_args $(BUILD)/fuzz/fuzz_gen_c \
            $(BUILD)/fuzz/fuzz_adaptive
.PHONY: fuzz fuzz-regress deps-fuzz
fuzz: $(FUZZ_BIN)
	@sh tools/fuzz-run $(BUILD)/fuzz $(FUZZ_SECONDS)
fuzz-regress: $(FUZZ_BIN)
	@sh tools/fuzz-run $(BUILD)/fuzz 0

# make test fuzzes each target for 15 s (make fuzz: FUZZ_SECONDS, 30): the
# suite is one of the two longest of make test.
TEST_SUITES += "$(MAKE) -s --no-print-directory fuzz FUZZ_SECONDS=15"
