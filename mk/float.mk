# The float build beside the double one, from the same sources, into
# $(BUILD)/float: the libraries (the stability suite and tests/cli/install.sh
# link them) and the tool, which tests/cli/float.sh runs in make test — what
# only a float tool answers (dopri5's minimum step, the rank tolerance's
# default in --help) was not tested anywhere.
FLOAT_OBJ := $(CORE_SRC:%.c=$(BUILD)/float/obj/%.o)
FLOAT_HOST_OBJ := $(HOST_SRC:%.c=$(BUILD)/float/obj/%.o)
FLOAT_CLI_OBJ := $(CLI_SRC:%.c=$(BUILD)/float/obj/%.o)
FLOAT_BACKEND_OBJ := $(BACKEND_SRC:%.c=$(BUILD)/float/obj/%.o)
$(FLOAT_OBJ): $(BUILD)/float/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CORE_CPPFLAGS) -DBRAUN_SINGLE $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@
$(FLOAT_HOST_OBJ) $(FLOAT_CLI_OBJ): $(BUILD)/float/obj/%.o: %.c | deps-host
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) -DBRAUN_SINGLE $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@
$(FLOAT_BACKEND_OBJ): $(BUILD)/float/obj/%.o: %.c | deps-backends
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS_ALL) $(BACKEND_CPPFLAGS) -DBRAUN_SINGLE $(CFLAGS_ALL) $(DEPFLAGS) -c $< -o $@
$(BUILD)/float/obj/src/host/backends/braun_backend_select.o: $(BUILD)/backends.flags
$(BUILD)/float/libbraun.a: $(FLOAT_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^
$(BUILD)/float/libbraun_host.a: $(FLOAT_HOST_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^
$(BUILD)/float/libbraun_backends.a: $(FLOAT_BACKEND_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^
FLOAT_LIBS := $(BUILD)/float/libbraun_backends.a $(BUILD)/float/libbraun_host.a $(BUILD)/float/libbraun.a
$(BUILD)/float/bin/braun: $(FLOAT_CLI_OBJ) $(FLOAT_LIBS) | $(BUILD)/float/share/braun/data
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $(FLOAT_CLI_OBJ) $(FLOAT_LIBS) -ljansson $(BACKEND_LDLIBS) -lm $(LDLIBS) -o $@
# The shipped scenes beside it, as for the double tool (mk/cli.mk).
$(BUILD)/float/share/braun/data:
	@mkdir -p $(dir $@)
	ln -sfn $(CURDIR)/data $@

.PHONY: test-float
test-float: $(BUILD)/float/bin/braun $(BUILD)/bin/braun
	@sh tests/cli/float.sh $(BUILD)/float/bin/braun $(BUILD)/bin/braun
TEST_PREREQS += $(BUILD)/float/bin/braun
TEST_SUITES += "sh tests/cli/float.sh $(BUILD)/float/bin/braun $(BUILD)/bin/braun"
