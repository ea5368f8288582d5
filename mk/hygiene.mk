# Input hygiene (issue 12, item 7): gen-c's escaping of scene texts, the
# loader's time against a scene's size, special files, numeric limits,
# messages that name what failed, outputs that would overwrite each other
# or the input (tests/cli/hygiene.sh; its C-level cases are in
# tests/test_scene_hygiene.c).
TEST_SUITES += "sh tests/cli/hygiene.sh $(BUILD)/bin/braun"

.PHONY: test-hygiene
test-hygiene: $(BUILD)/bin/braun
	@sh tests/cli/hygiene.sh $(BUILD)/bin/braun
