# make bench (issue 7): what a step costs — ns (median of rounds, one
# process) and instructions (callgrind) per step and per right-hand side,
# with each correction off and on, against an unconstrained minimal-
# coordinate RK4 step; flops per step; cost at matched error from make
# compare's CSV. Writes results/bench/*.csv and the tables of
# docs/performance.md. A benchmark, not a test: nothing here is added to
# TEST_SUITES.
#
#   make bench                         everything (< 10 min on 2 busy cores)
#   make bench BENCH_TARGETS="slider-crank"  BENCH_ROUNDS=11  BENCH_VARIANTS=0
#   make bench BENCH_DOCS=             leave docs/performance.md alone
#   make bench BENCH_SCALING=0         without the large-system study
# Options: BENCH_OUT (results/bench), BENCH_ROUNDS (timing rounds, 31),
# BENCH_STEPS (steps per block, 2000), BENCH_JOBS (parallel callgrind runs, 2),
# BENCH_VARIANTS (1: also the slider-crank with other compiler flags).

BENCH_DEPS := valgrind binutils libjansson-dev
BENCH_SRC := $(sort $(wildcard bench/*.c))
# The series table of make compare (compare/series.tsv, mk/compare.mk) names
# the methods of the cost at matched error; no SUNDIALS or GSL in it.
BENCH_OBJ := $(BENCH_SRC:%.c=$(BUILD)/obj/%.o) $(BUILD)/obj/bench/cmp_series.o
BENCH_BIN := $(BUILD)/bin/braun-bench
BENCH_STATIC := $(BUILD)/bin/braun-bench-static
BENCH_OUT ?= results/bench
BENCH_ROUNDS ?= 31
BENCH_STEPS ?= 2000
BENCH_JOBS ?= 2
BENCH_VARIANTS ?= 1
BENCH_DOCS ?= docs/performance.md
# 1: also make scaling (mk/scaling.mk): cost per step against N, backends, IDA+KLU.
BENCH_SCALING ?= 1
# 1: also MuJoCo's mj_step against braun's step in one process (braun-compare's
# cost job on the paper's two mechanisms) and make firmware-bench (float and
# float-fixed, with the 100 s worst case); then results/bench/headline.csv
# (bench/headline.sh: one row per figure of issue 16, measured in this run).
BENCH_MUJOCO ?= 1
BENCH_FIRMWARE ?= 1
BENCH_TARGETS ?= slider-crank four-bar pendulum andrews $(sort $(wildcard data/*.json))

.PHONY: bench bench-bin deps-bench

deps-bench:
	@tools/ensure-deps $(BENCH_DEPS)

bench-bin: $(BENCH_BIN) $(BENCH_STATIC)

$(BUILD)/obj/bench/%.o: bench/%.c $(PRECISION_STAMP) | deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Icompare $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

$(BUILD)/obj/bench/cmp_series.o: compare/cmp_series.c $(BUILD)/gen/cmp_series.inc $(PRECISION_STAMP) | deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Icompare -I$(BUILD)/gen $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

# Not position independent: callgrind's instruction addresses are then the
# ones objdump prints (bench/flops.awk). The static twin puts libm's sin/cos
# in the same file, so their floating-point instructions are classified too.
$(BENCH_BIN): $(BENCH_OBJ) $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -no-pie $(BENCH_OBJ) $(HOST_LDLIBS) -o $@

$(BENCH_STATIC): $(BENCH_OBJ) $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -static $(BENCH_OBJ) $(HOST_LDLIBS) -o $@

bench: deps-bench
	@$(MAKE) --no-print-directory bench-bin
	@sh bench/bench.sh --bin $(BENCH_BIN) --static $(BENCH_STATIC) --out $(BENCH_OUT) \
	    --rounds $(BENCH_ROUNDS) --steps $(BENCH_STEPS) --jobs $(BENCH_JOBS) \
	    --variants $(BENCH_VARIANTS) --docs "$(BENCH_DOCS)" --build $(BUILD) \
	    --targets "$(BENCH_TARGETS)"
	@if [ "$(BENCH_SCALING)" = 1 ]; then $(MAKE) --no-print-directory scaling SCALING_DOCS="$(BENCH_DOCS)"; fi
	@if [ "$(BENCH_MUJOCO)" = 1 ]; then $(MAKE) --no-print-directory bench-mujoco; fi
	@if [ "$(BENCH_FIRMWARE)" = 1 ]; then \
	    $(MAKE) --no-print-directory firmware-bench; fi
	@sh bench/headline.sh $(BENCH_OUT) $(BENCH_OUT)/mujoco $(BUILD)/firmware $(SCALING_OUT) \
	    "$(BENCH_DOCS)"

# braun's corrected RK4 step against MuJoCo's RK4 mj_step on the same
# mechanism, in one process: the cost job of the quick study, braun only.
.PHONY: bench-mujoco
bench-mujoco: deps-compare
	@$(MAKE) --no-print-directory $(COMPARE_BIN)
	@mkdir -p $(BENCH_OUT) && MAKE="$(MAKE)" sh compare/run.sh --bin $(COMPARE_BIN) --out $(BENCH_OUT)/mujoco --study quick \
	    --jobs 1 --reps 1 --scenes "slider-crank four-bar" --methods "braun" > $(BENCH_OUT)/mujoco.log 2>&1 \
	    || { echo "bench: the MuJoCo cost job failed (see $(BENCH_OUT)/mujoco.log)" >&2; exit 1; }
