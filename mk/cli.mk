# The braun tool (src/host/cli): the shipped scenes beside the build's
# binary, so that `braun run four-bar.json` finds them from any directory
# (src/host/cli/cli_datadir.c: BUILD/bin/braun -> BUILD/share/braun/data).
$(BUILD)/bin/braun: | $(BUILD)/share/braun/data
$(BUILD)/share/braun/data:
	@mkdir -p $(dir $@)
	ln -sfn $(CURDIR)/data $@
