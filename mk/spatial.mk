# make spatial-choice (issue 13): the measurement behind rigid3d's Euler
# parameters — accuracy per CPU-second of Euler parameters against natural
# coordinates on a Bricard linkage, a stiff flyball governor and a spatial
# chain of 10 bars (bench/spatial/, docs/method.md "Spatial rigid bodies").
# A benchmark, not a test. Writes results/spatial/choice.csv (about 20
# minutes on one core; SPATIAL_QUICK=1: references at h/4, one timing run).

SPATIAL_SRC := $(sort $(wildcard bench/spatial/*.c))
SPATIAL_OBJ := $(SPATIAL_SRC:%.c=$(BUILD)/obj/%.o)
SPATIAL_BIN := $(BUILD)/bin/braun-spatial-choice
SPATIAL_OUT ?= results/spatial
SPATIAL_QUICK ?= 0

.PHONY: spatial-choice

$(BUILD)/obj/bench/spatial/%.o: bench/spatial/%.c $(PRECISION_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(CORE_CPPFLAGS) -Ibench/spatial $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@

$(SPATIAL_BIN): $(SPATIAL_OBJ) $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(SPATIAL_OBJ) $(BUILD)/libbraun.a -lm -o $@

spatial-choice: $(SPATIAL_BIN)
	@mkdir -p $(SPATIAL_OUT)
	$(SPATIAL_BIN) $(if $(filter 1,$(SPATIAL_QUICK)),--quick) > $(SPATIAL_OUT)/choice.csv
	@cat $(SPATIAL_OUT)/choice.csv
