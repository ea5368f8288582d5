# make iftomm: the IFToMM multibody benchmark problems A01-A05
# (docs/iftomm.md) with libbraun's RK4 and DOPRI5 on the shipped scenes
# data/iftomm/*.json, judged against references libbraun never computes
# (compare/iftomm: closed forms, SUNDIALS IDA and GSL rk8pd on models in
# their own coordinates). Writes results/iftomm/: summary.csv, detail.csv,
# references.csv, series and plots per problem, report-section.md.
#
#   make iftomm                      every problem (tens of minutes)
#   make iftomm IFTOMM_PROBLEMS=A01,A03-0.05s
# The harness links SUNDIALS and GSL (GPL-3); libbraun.a never does.

IFTOMM_SRC := $(sort $(wildcard compare/iftomm/*.c))
IFTOMM_OBJ := $(IFTOMM_SRC:%.c=$(BUILD)/obj/%.o)
IFTOMM_LIB_OBJ := $(filter-out $(BUILD)/obj/compare/iftomm/ifm_main.o,$(IFTOMM_OBJ))
# The references alone (no libbraun): what the reference tests link.
IFTOMM_REF_OBJ := $(filter-out $(BUILD)/obj/compare/iftomm/ifm_main.o \
                    $(BUILD)/obj/compare/iftomm/ifm_braun.o,$(IFTOMM_OBJ))
IFTOMM_BIN := $(BUILD)/bin/braun-iftomm
IFTOMM_TEST := $(BUILD)/tests/iftomm/test_iftomm
IFTOMM_OUT ?= results/iftomm
IFTOMM_PROBLEMS ?=
IFTOMM_LDLIBS := -lsundials_ida -lsundials_sunlinsoldense -lsundials_sunmatrixdense \
	-lsundials_nvecserial -lgsl -lgslcblas

.PHONY: iftomm iftomm-bin

iftomm-bin: $(IFTOMM_BIN)

$(BUILD)/obj/compare/iftomm/%.o: compare/iftomm/%.c $(PRECISION_STAMP) | deps-compare deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Icompare/iftomm $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

$(IFTOMM_BIN): $(IFTOMM_OBJ) $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(IFTOMM_OBJ) $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a -ljansson \
	    $(IFTOMM_LDLIBS) $(LDLIBS_ALL) -o $@

iftomm: deps-compare
	@$(MAKE) --no-print-directory $(IFTOMM_BIN) $(BUILD)/bin/braun
	@mkdir -p $(IFTOMM_OUT)
	$(BUILD)/bin/braun gen n-four-bar 2 -o $(IFTOMM_OUT)/a02-n-four-bar-2.json
	$(IFTOMM_BIN) --out $(IFTOMM_OUT) $(if $(IFTOMM_PROBLEMS),--problems $(IFTOMM_PROBLEMS))

# ---------------------------------------------------------------- tests
$(IFTOMM_TEST): tests/iftomm/test_iftomm.c tests/test_util.h $(IFTOMM_LIB_OBJ) \
		$(BUILD)/libbraun_host.a $(BUILD)/libbraun.a | deps-test deps-compare
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Icompare/iftomm -Itests $(CFLAGS_ALL) $< $(IFTOMM_LIB_OBJ) \
	    $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a -lcmocka -ljansson $(IFTOMM_LDLIBS) \
	    $(LDLIBS_ALL) -o $@

TEST_SUITES += "tools/run-tests $(IFTOMM_TEST)" "sh tests/iftomm/cli.sh $(BUILD)/bin/braun"
TEST_PREREQS += $(IFTOMM_TEST)
