# Stability suite (tests/stability/): the same source for double and float.
# The float library is built from the same sources into $(BUILD)/float.
FLOAT_OBJ := $(LIB_SRC:%.c=$(BUILD)/float/obj/%.o)
$(BUILD)/float/obj/%.o: %.c $(HEADERS)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -DBRAUN_SINGLE $(CFLAGS_ALL) -c $< -o $@
$(BUILD)/float/libbraun.a: $(FLOAT_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

STABILITY_BIN := $(BUILD)/tests/stability_double $(BUILD)/tests/stability_float
$(BUILD)/tests/stability_double: tests/stability/test_stability.c tests/test_util.h $(BUILD)/libbraun.a | deps-test
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -Itests $(CFLAGS_ALL) $< $(BUILD)/libbraun.a -lcmocka $(LDLIBS_ALL) -o $@
$(BUILD)/tests/stability_float: tests/stability/test_stability.c tests/test_util.h $(BUILD)/float/libbraun.a | deps-test
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -DBRAUN_SINGLE -Itests $(CFLAGS_ALL) $< $(BUILD)/float/libbraun.a -lcmocka $(LDLIBS_ALL) -o $@

TEST_PREREQS += $(STABILITY_BIN)
# CORE_SUITES is part of TEST_SUITES and of the sanitizer run.
CORE_SUITES += "tools/run-tests $(STABILITY_BIN)"

.PHONY: stress
# Long forms: the four-bar over 10^4 s, in double and float.
stress: $(STABILITY_BIN)
	@BRAUN_STRESS=1 tools/run-tests $(STABILITY_BIN)
