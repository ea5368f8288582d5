# make compare: libbraun against SUNDIALS IDA, Baumgarte and exact references
# (docs/compare.md). The harness links SUNDIALS and GSL (GPL-3); libbraun.a
# never does.
#
#   make compare                  the default study -> results/compare/
#   make compare SCENES="four-bar" METHODS="braun ida-ggl"
#   make compare-quick            a short version -> results/compare-quick/
#   make -j4 compare              4 runs at a time (one process per run)
#   make compare-jobs             the study as a run list, one self-contained command per
#                                 line (results/compare/jobs/prepare.txt, runs.txt) for GNU
#                                 parallel or a Slurm array; then make compare-merge
# Options: COMPARE_JOBS (runs at a time without -j, default 2; 1: serial),
# COMPARE_REPS (best of K CPU times, default 3), COMPARE_OUT.
# The recipes that call compare/run.sh are marked `+`: its sub-make takes
# part in this make's jobserver (and runs under make -n too; run.sh then
# only says so).

# The peers (issue 14): MuJoCo 2.2.2 (C API) and Simbody 3.7 (a C++ adapter,
# compare/cmp_simbody.cpp); GNU parallel runs exported run lists.
COMPARE_DEPS := libsundials-dev libgsl-dev gnuplot-nox libsuitesparse-dev libmujoco-dev \
	libsimbody-dev parallel
COMPARE_SRC := $(sort $(wildcard compare/*.c))
COMPARE_OBJ := $(COMPARE_SRC:%.c=$(BUILD)/obj/%.o)
# Everything but main(), for the harness tests.
COMPARE_LIB_OBJ := $(filter-out $(BUILD)/obj/compare/cmp_main.o,$(COMPARE_OBJ))
COMPARE_HDR := $(wildcard compare/*.h)
# The series table (compare/series.tsv) as C initializers, for
# compare/cmp_series.c (here and in braun-bench, mk/bench.mk).
CMP_SERIES_INC := $(BUILD)/gen/cmp_series.inc
COMPARE_CPPFLAGS := -Icompare -I$(BUILD)/gen -I/usr/include/suitesparse \
	-DCMP_HAVE_MUJOCO -DCMP_HAVE_SIMBODY
COMPARE_LDLIBS := -lsundials_ida -lsundials_sunlinsolklu -lsundials_sunlinsoldense \
	-lsundials_sunmatrixsparse -lsundials_sunmatrixdense -lsundials_nvecserial \
	-lklu -lgsl -lgslcblas -lmujoco
# The Simbody adapter is a plugin the harness dlopen()s with RTLD_DEEPBIND
# (compare/cmp_simbody_plugin.h: Simbody's CPodes and SUNDIALS 6 share 101
# C symbol names, so the harness must not link Simbody). Only the plugin
# links -lSimTK*; compare/cmp_simbody_host.c loads it from this path.
CXX ?= g++
COMPARE_CXXFLAGS := -std=c++17 $(OPT) -Wall -Wextra -Wpedantic -isystem /usr/include/simbody \
	-fPIC -fvisibility=hidden
COMPARE_SB_PLUGIN := $(BUILD)/lib/cmp_simbody.so
COMPARE_SB_LDLIBS := -lSimTKsimbody -lSimTKmath -lSimTKcommon
COMPARE_BIN := $(BUILD)/bin/braun-compare
COMPARE_TEST := $(BUILD)/tests/compare/test_compare
COMPARE_OUT ?= results/compare
COMPARE_JOBS ?= 2
COMPARE_REPS ?= 3
SCENES ?=
METHODS ?=

.PHONY: compare compare-quick compare-jobs compare-merge deps-compare compare-bin

deps-compare:
	@tools/ensure-deps $(COMPARE_DEPS)

compare-bin: $(COMPARE_BIN)

$(BUILD)/obj/compare/%.o: compare/%.c $(PRECISION_STAMP) | deps-compare deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(COMPARE_CPPFLAGS) $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

# The Simbody adapter is C++ (Simbody has no C API), built as the plugin.
# Its files: the planar model and the run (cmp_simbody.cpp), the spatial
# model (cmp_simbody3.cpp).
COMPARE_SB_OBJ := $(BUILD)/obj/compare/pic/cmp_simbody.o $(BUILD)/obj/compare/pic/cmp_simbody3.o
$(BUILD)/obj/compare/pic/%.o: compare/%.cpp $(PRECISION_STAMP) | deps-compare deps-host
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS_ALL) $(COMPARE_CPPFLAGS) $(COMPARE_CXXFLAGS) $(CXXFLAGS) $(DEPFLAGS) -c $< -o $@

$(COMPARE_SB_PLUGIN): $(COMPARE_SB_OBJ)
	@mkdir -p $(dir $@)
	$(CXX) -shared -Wl,-z,defs $(COMPARE_SB_OBJ) $(COMPARE_SB_LDLIBS) $(LDLIBS) -o $@

$(BUILD)/obj/compare/cmp_simbody_host.o: COMPARE_CPPFLAGS += \
	-DCMP_SIMBODY_PLUGIN_PATH='"$(abspath $(COMPARE_SB_PLUGIN))"'

$(CMP_SERIES_INC): compare/series.tsv compare/series.awk
	@mkdir -p $(dir $@)
	awk -f compare/series.awk -v out=c compare/series.tsv > $@.tmp && mv $@.tmp $@
$(BUILD)/obj/compare/cmp_series.o: $(CMP_SERIES_INC)

$(COMPARE_BIN): $(COMPARE_OBJ) $(BUILD)/libbraun.a $(COMPARE_SB_PLUGIN)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(COMPARE_OBJ) $(COMPARE_PRE_LIBS) $(BUILD)/libbraun.a $(COMPARE_LDLIBS) \
	    $(LDLIBS_ALL) -o $@

compare: deps-compare
	@$(MAKE) --no-print-directory $(COMPARE_BIN)
	+@MAKE="$(MAKE)" sh compare/run.sh --bin $(COMPARE_BIN) --out $(COMPARE_OUT) --study default \
	    --jobs $(COMPARE_JOBS) --reps $(COMPARE_REPS) --scenes "$(SCENES)" --methods "$(METHODS)"

compare-quick: deps-compare
	@$(MAKE) --no-print-directory $(COMPARE_BIN)
	+@MAKE="$(MAKE)" sh compare/run.sh --bin $(COMPARE_BIN) --out results/compare-quick --study quick \
	    --jobs $(COMPARE_JOBS) --reps $(COMPARE_REPS) --scenes "$(SCENES)" --methods "$(METHODS)"

# The study as a run list (docs/compare.md, "Beyond one machine"): run
# $(COMPARE_OUT)/jobs/prepare.txt, then runs.txt, anywhere that sees this
# directory; then compare-merge assembles the CSV files and the report.
compare-jobs: deps-compare
	@$(MAKE) --no-print-directory $(COMPARE_BIN)
	@sh compare/run.sh --list --bin $(COMPARE_BIN) --out $(COMPARE_OUT) --study $(or $(COMPARE_STUDY),default) \
	    --reps $(COMPARE_REPS) --scenes "$(SCENES)" --methods "$(METHODS)"

compare-merge:
	@sh compare/run.sh --merge --bin $(COMPARE_BIN) --out $(COMPARE_OUT)

# ---------------------------------------------------------------- tests
# Harness tests need SUNDIALS and GSL, so they are not tests/test_*.c (those
# link libbraun.a and cmocka only).
$(COMPARE_TEST): tests/compare/test_compare.c tests/compare/test_proj_ref.h tests/test_util.h $(COMPARE_LIB_OBJ) \
		$(BUILD)/libbraun.a | deps-test deps-compare
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(COMPARE_CPPFLAGS) -Itests $(CFLAGS_ALL) $< $(COMPARE_LIB_OBJ) \
	    $(COMPARE_PRE_LIBS) $(BUILD)/libbraun.a -lcmocka $(COMPARE_LDLIBS) $(LDLIBS_ALL) -o $@

TEST_SUITES += "tools/run-tests $(COMPARE_TEST)" "sh tests/compare/quick.sh $(COMPARE_BIN)"
TEST_SUITES += "sh tests/compare/parallel.sh $(COMPARE_BIN)"
# The run list (compare/run.sh --list) under GNU parallel, merged.
TEST_SUITES += "sh tests/compare/jobs.sh $(COMPARE_BIN)"
# The series table's three readers: the report, plot.sh and braun-bench.
TEST_SUITES += "sh tests/compare/series.sh $(COMPARE_BIN) $(BENCH_BIN)"
# The report's claims and summary, and the plots' legends and titles, say
# what the study ran (made-up CSV files).
TEST_SUITES += "sh tests/compare/evidence.sh $(COMPARE_BIN)"
TEST_PREREQS += $(COMPARE_TEST) $(COMPARE_BIN) $(BENCH_BIN)

# The Simbody adapter's tests (tests/compare/test_simbody.c): the pendulum
# against its exact solution, the initial-state map, failures as rows,
# refusals; with `run TARGET T SETTING...` the driver of the hand
# measurements in docs/compare.md ("Simbody").
COMPARE_SB_TEST := $(BUILD)/tests/compare/test_simbody
$(COMPARE_SB_TEST): tests/compare/test_simbody.c tests/compare/test_proj_ref.h tests/test_util.h $(COMPARE_HDR) \
		$(COMPARE_LIB_OBJ) $(BUILD)/libbraun.a $(COMPARE_SB_PLUGIN) | deps-test deps-compare
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(COMPARE_CPPFLAGS) -Itests $(CFLAGS_ALL) $< $(COMPARE_LIB_OBJ) \
	    $(COMPARE_PRE_LIBS) $(BUILD)/libbraun.a -lcmocka $(COMPARE_LDLIBS) $(LDLIBS_ALL) -o $@

TEST_SUITES += "tools/run-tests $(COMPARE_SB_TEST)"
TEST_PREREQS += $(COMPARE_SB_TEST) $(COMPARE_SB_PLUGIN)

# Scene files and Andrews' mechanism become targets (the host library).
COMPARE_CPPFLAGS += -DCMP_HAVE_SCENES
COMPARE_PRE_LIBS := $(BUILD)/libbraun_host.a
COMPARE_LDLIBS += -ljansson
$(COMPARE_BIN) $(COMPARE_TEST) $(COMPARE_SB_TEST): $(BUILD)/libbraun_host.a

# ---------------------------------------------------------------- IDA + KLU (issue 7)
# braun-ida-run SCENE T RTOL: one IDA+KLU run with its counts and CPU time
# (analytic, colored or column finite-difference Jacobian), and
# test_ida_jac: the analytic Jacobian against finite differences.
COMPARE_IDA_RUN := $(BUILD)/bin/braun-ida-run
COMPARE_JAC_TEST := $(BUILD)/tests/compare/test_ida_jac

.PHONY: compare-ida-run
compare-ida-run: $(COMPARE_IDA_RUN)

$(COMPARE_IDA_RUN): compare/tools/ida_run.c $(COMPARE_HDR) $(COMPARE_LIB_OBJ) \
		$(BUILD)/libbraun.a | deps-compare
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(COMPARE_CPPFLAGS) $(CFLAGS_ALL) $< $(COMPARE_LIB_OBJ) \
	    $(COMPARE_PRE_LIBS) $(BUILD)/libbraun.a $(COMPARE_LDLIBS) $(LDLIBS_ALL) -o $@

$(COMPARE_JAC_TEST): tests/compare/test_ida_jac.c tests/test_util.h $(COMPARE_HDR) \
		$(COMPARE_LIB_OBJ) $(BUILD)/libbraun.a | deps-test deps-compare
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(COMPARE_CPPFLAGS) -Itests $(CFLAGS_ALL) $< $(COMPARE_LIB_OBJ) \
	    $(COMPARE_PRE_LIBS) $(BUILD)/libbraun.a -lcmocka $(COMPARE_LDLIBS) $(LDLIBS_ALL) -o $@

TEST_SUITES += "tools/run-tests $(COMPARE_JAC_TEST)"
TEST_PREREQS += $(COMPARE_JAC_TEST) $(COMPARE_IDA_RUN)
$(COMPARE_IDA_RUN) $(COMPARE_JAC_TEST): $(BUILD)/libbraun_host.a
