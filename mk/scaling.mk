# make scaling (issues 7, 13, 16): cost per step against the number of bodies
# N for every linear-algebra backend and IDA+KLU, on `braun gen chain N`, the
# redundant ladder and the spatial chain (`braun gen spatial-chain N`; no
# IDA: its harness has no rigid3d Jacobian), with fitted log-log slopes and
# the ladder's cost per body against the chain's; cost per simulated second at
# equal trajectory error at N = 1000. Writes results/scaling/ (CSV, PNG,
# scaling.md) and, with SCALING_DOCS set, the tables of docs/performance.md.
# A benchmark, not a test. `make bench` runs it too (BENCH_SCALING=0: not).
#
#   make scaling                          everything (about 4 minutes)
#   make scaling SCALING_N="10 100 1000"  SCALING_BACKENDS="dense suitesparse"
#   make scaling SCALING_MATCHED=0        without the equal-error study

SCALING_SRC := $(sort $(wildcard bench/scaling/*.c))
SCALING_OBJ := $(SCALING_SRC:%.c=$(BUILD)/obj/%.o)
SCALING_BIN := $(BUILD)/bin/braun-scaling
SCALING_OUT ?= results/scaling
SCALING_N ?= 10 20 50 100 200 500 1000 2000
SCALING_LADDER_N ?= 10 30 100 300 1000 2000
SCALING_SPATIAL_N ?= 10 20 50 100 200 500 1000
SCALING_BACKENDS ?= dense lapack suitesparse
SCALING_MATCHED ?= 1
SCALING_DOCS ?= docs/performance.md

.PHONY: scaling scaling-bin

# IDA+KLU comes from the compare harness (its objects but main()).
SCALING_CPPFLAGS = $(COMPARE_CPPFLAGS)
SCALING_PRE_LIBS = $(COMPARE_LIB_OBJ) $(COMPARE_PRE_LIBS)
SCALING_LDLIBS = $(COMPARE_LDLIBS)
$(SCALING_BIN): $(COMPARE_LIB_OBJ)

$(BUILD)/obj/bench/scaling/%.o: bench/scaling/%.c $(PRECISION_STAMP) | deps-host deps-backends
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(SCALING_CPPFLAGS) $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

$(SCALING_BIN): $(SCALING_OBJ) $(BUILD)/libbraun_host.a $(BUILD)/libbraun_backends.a $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(SCALING_OBJ) $(SCALING_PRE_LIBS) $(BUILD)/libbraun_host.a \
	    $(BACKENDS_LDLIBS) $(SCALING_LDLIBS) -ljansson -lm -o $@

scaling-bin: $(SCALING_BIN) $(BUILD)/bin/braun

# The timings assume an optimised BLAS under LAPACK and CHOLMOD: OpenBLAS,
# single-threaded (CPU time = one core's), which Debian's alternatives then
# load for -llapack -lblas. Only the study needs it, not the tests.
scaling: deps-backends
	@tools/ensure-deps libopenblas0-serial
	@$(MAKE) --no-print-directory scaling-bin
	@sh bench/scaling/run.sh --bin $(SCALING_BIN) --braun $(BUILD)/bin/braun \
	    --out $(SCALING_OUT) --n "$(SCALING_N)" --ladder-n "$(SCALING_LADDER_N)" \
	    --spatial-n "$(SCALING_SPATIAL_N)" \
	    --backends "$(SCALING_BACKENDS)" --matched $(SCALING_MATCHED) --docs "$(SCALING_DOCS)"
