# The braun tool (src/host/cli): the shipped scenes beside the build's
# binary, so that `braun run four-bar.json` finds them from any directory
# (src/host/cli/cli_datadir.c: BUILD/bin/braun -> BUILD/share/braun/data),
# and the tests of `braun plot` and of the files people read (issue 15).
$(BUILD)/bin/braun: | $(BUILD)/share/braun/data
$(BUILD)/share/braun/data:
	@mkdir -p $(dir $@)
	ln -sfn $(CURDIR)/data $@

# What the plot tests use: rsvg-convert renders SVG to PNG, png_ink
# (libpng) counts what was drawn, xmllint checks the SVG, gnuplot makes the
# .png, node runs the animation page's script, script(1) gives a terminal.
PLOT_TEST_DEPS := librsvg2-bin libpng-dev libxml2-utils gnuplot-nox nodejs bsdutils
deps-plot-test:
	@tools/ensure-deps $(PLOT_TEST_DEPS)
.PHONY: deps-plot-test test-plot

PNG_INK := $(BUILD)/tests/cli/png_ink
$(PNG_INK): tests/cli/png_ink.c | deps-plot-test
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) $< -lpng -o $@

TEST_PREREQS += $(PNG_INK)
TEST_SUITES += "sh tests/cli/plot.sh $(BUILD)/bin/braun $(PNG_INK)"

test-plot: $(BUILD)/bin/braun $(PNG_INK)
	@sh tests/cli/plot.sh $(BUILD)/bin/braun $(PNG_INK)

# The README as a new user follows it: its braun commands from another
# directory, its pictures, headline figures, make targets, files and the
# install commands of tests/cli/install.sh (tests/cli/readme.sh).
TEST_SUITES += "BUILD=$(BUILD) sh tests/cli/readme.sh $(BUILD)/bin/braun"
.PHONY: test-readme
test-readme: $(BUILD)/bin/braun
	@BUILD=$(BUILD) sh tests/cli/readme.sh $(BUILD)/bin/braun
