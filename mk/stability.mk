# Stability suite (tests/stability/): the same source for double and float.
# The float libraries are built from the same sources into $(BUILD)/float
# (mk/float.mk).

STABILITY_BIN := $(BUILD)/tests/stability_double $(BUILD)/tests/stability_float
$(BUILD)/tests/stability_double: tests/stability/test_stability.c $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a | deps-test
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Itests $(CFLAGS_ALL) $(DEPFLAGS) -MF $@.d $< $(BUILD)/libbraun_host.a \
	    $(BUILD)/libbraun.a -lcmocka -ljansson $(LDLIBS_ALL) -o $@
$(BUILD)/tests/stability_float: tests/stability/test_stability.c $(BUILD)/float/libbraun_host.a $(BUILD)/float/libbraun.a | deps-test
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -DBRAUN_SINGLE -Itests $(CFLAGS_ALL) $(DEPFLAGS) -MF $@.d $< \
	    $(BUILD)/float/libbraun_host.a $(BUILD)/float/libbraun.a -lcmocka -ljansson $(LDLIBS_ALL) -o $@

# (TEST_PREREQS includes CORE_PREREQS: the sanitizer run needs these too)
CORE_PREREQS += $(STABILITY_BIN)
# CORE_SUITES is part of TEST_SUITES and of the sanitizer run.
CORE_SUITES += "tools/run-tests $(STABILITY_BIN)"

.PHONY: stress
# Long forms: the four-bar over 10^4 s, in double and float.
stress: $(STABILITY_BIN)
	@BRAUN_STRESS=1 tools/run-tests $(STABILITY_BIN)

# The long-run matrix (tests/stability/matrix.c): every built-in model and
# shipped scene x RK4 h = 1e-3, 5e-3, 1e-2 and DOPRI5 rtol = 1e-6, 1e-8,
# 1e-10. make stress runs it over 1000 s, the IFToMM scenes (data/iftomm)
# too, and writes the table of docs/robustness.md; make test runs the
# matrix of data/*.json over 20 s.
MATRIX_BIN := $(BUILD)/tests/stability_matrix
$(MATRIX_BIN): tests/stability/matrix.c $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a | deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) $(DEPFLAGS) -MF $@.d $< $(HOST_LDLIBS) -o $@
TEST_PREREQS += $(MATRIX_BIN)
TEST_SUITES += "$(MATRIX_BIN) --t-end 20 data"
.PHONY: stress-matrix
stress: stress-matrix
stress-matrix: $(MATRIX_BIN)
	@mkdir -p results/stability
	$(MATRIX_BIN) --t-end $(or $(MATRIX_T),1000) --iftomm --markdown results/stability/matrix.md data
