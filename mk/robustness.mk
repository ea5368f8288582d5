# Tools that find what tests miss (issue: robustness). All part of make test.
#   make lint           cppcheck + clang-tidy on the library and the tool
#   make test-valgrind  memcheck on a subset of the tests and a CLI run
LINT_SRC = $(CORE_SRC) $(HOST_SRC) $(CLI_SRC) \
	$(BACKEND_SRC)
# The backends' headers are system headers to the linters (SuiteSparse's
# macros trip clang-tidy's checks); their code is compiled as built.
LINT_FLAGS = -std=c99 $(HOST_CPPFLAGS) -isystem /usr/include/suitesparse $(BACKEND_CPPFLAGS:-I/usr/include/suitesparse=)

.PHONY: lint test-valgrind
lint:
	@tools/ensure-deps cppcheck clang-tidy
	@cppcheck --enable=warning,style,performance,portability --std=c99 --inline-suppr \
	    --error-exitcode=1 -q $(HOST_CPPFLAGS) $(filter -D%,$(BACKEND_CPPFLAGS)) $(LINT_SRC) \
	    && echo "ok - cppcheck clean" || { echo "not ok - cppcheck"; exit 1; }
	@clang-tidy -quiet $(LINT_SRC) -- $(LINT_FLAGS) $(CPPFLAGS) >$(BUILD)/clang-tidy.log 2>&1 \
	    && echo "ok - clang-tidy clean (.clang-tidy)" || { grep -E "error:|warning:" $(BUILD)/clang-tidy.log; echo "not ok - clang-tidy"; exit 1; }
	@echo "2 passed, 0 failed"

VALGRIND_TESTS = $(BUILD)/tests/test_core $(BUILD)/tests/test_errors $(BUILD)/tests/test_linalg \
	$(BUILD)/tests/test_sparse_core $(filter $(BUILD)/tests/test_backend_%,$(TEST_BIN))
# The suitesparse backend's long runs (95 of its 138 s under memcheck) are
# left to the native and ASan runs (BRAUN_TEST_SKIP, a cmocka pattern; the
# other binaries ignore it).
VALGRIND_SKIP = *redundant_*
test-valgrind: $(VALGRIND_TESTS) $(BUILD)/bin/braun
	@tools/ensure-deps valgrind
	@pass=0; fail=0; \
	skip="$(VALGRIND_SKIP)"; export BRAUN_TEST_SKIP="$$skip"; \
	for t in $(VALGRIND_TESTS) "$(BUILD)/bin/braun run four-bar --dt 1e-2 --t-end 2" \
	         "$(BUILD)/bin/braun run slider-crank --dt 1e-2 --t-end 1 --corrections bogus" \
	         "$(BUILD)/bin/braun run data/chain-5.json --backend suitesparse --dt 1e-2 --t-end 1"; do \
	    if valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \
	        $$t >$(BUILD)/valgrind.log 2>&1 || [ $$? -ne 99 ]; then \
	        if grep -q "ERROR SUMMARY: [1-9]" $(BUILD)/valgrind.log; then echo "not ok - memcheck $$t"; fail=$$((fail+1)); \
	        else case $$t in *suitesparse) note=" (tests $$skip left to the native and ASan runs)" ;; *) note="" ;; esac; \
	             echo "ok - memcheck clean: $$t$$note"; pass=$$((pass+1)); fi; \
	    else echo "not ok - memcheck $$t"; cat $(BUILD)/valgrind.log; fail=$$((fail+1)); fi; \
	done; echo "$$pass passed, $$fail failed"; [ $$fail -eq 0 ]

TEST_SUITES += "$(MAKE) -s --no-print-directory lint" "$(MAKE) -s --no-print-directory test-valgrind"
# The generic kernels' length dispatch off and partial (BRAUN_SMALL_MAX).
TEST_SUITES += "sh tests/core/small_max.sh $(BUILD)"
