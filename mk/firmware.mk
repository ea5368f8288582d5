# Firmware (issue 6): libbraun cross-built for a Cortex-M4F, the demo
# firmware run under QEMU (Arm MPS2 with the AN386 image), its comparison
# with the host build of the same runs, and the cost and memory figures of
# docs/firmware.md.
#
#   make firmware          build/firmware/{double,float}/: libbraun.a, demo.elf,
#                          size.txt, stack-usage.txt, gc-*.elf
#   make firmware-test     every check (part of make test; ~20 s)
#   make firmware-bench    instructions per RK4 step: emulator and callgrind
#   make firmware-long     the float study: slider-crank, h = 1e-3, 100 s
#   make firmware-profile  instructions per function of a corrected float step
#
# The library is built from the core tier's sources ($(CORE_SRC): src/core,
# the same list as the host's libbraun.a; never src/host) with its own objects per
# configuration. Missing tools are installed through tools/ensure-deps.

FW_DEPS := gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm libjansson-dev
FW_BENCH_DEPS := valgrind

FW_CC   ?= arm-none-eabi-gcc
FW_AR   ?= arm-none-eabi-ar
FW_NM   ?= arm-none-eabi-nm
FW_SIZE ?= arm-none-eabi-size
FW_OBJDUMP ?= arm-none-eabi-objdump
FW_ADDR2LINE ?= arm-none-eabi-addr2line
QEMU    ?= qemu-system-arm

FW_ARCH := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16
FW_WARN := -Wall -Wextra -Wpedantic -Wdouble-promotion -Wconversion -Wshadow \
           -Wstrict-prototypes
FW_OPT  ?= -O2 -g
# -fno-math-errno: the core never reads errno; sqrtf becomes one VSQRT.F32.
# (ISO C mode keeps -ffp-contract=off: no fused multiply-add, so the target
# rounds exactly as the host does.)
FW_CFLAGS := -std=c99 $(FW_ARCH) -ffunction-sections -fdata-sections \
             -fno-math-errno $(FW_WARN)
FW_LD_SCRIPT := firmware/board/mps2_an386.ld
# No nosys.specs and no _sbrk: anything that needs a heap or a system call
# fails to link instead of running.
FW_LDFLAGS := $(FW_ARCH) -nostartfiles --specs=nano.specs -Wl,--gc-sections \
              -T $(FW_LD_SCRIPT)
FW_LDLIBS := -Wl,--start-group -lm -lc -lgcc -Wl,--end-group
FW_QEMU_FLAGS := -M mps2-an386 -nographic \
                 -semihosting-config enable=on,target=native -icount shift=0

FW_DIR := $(BUILD)/firmware
# One short line per object unless make runs silently (make -s, make test).
FW_SAY := $(if $(findstring s,$(firstword -$(MAKEFLAGS))),@true,@echo)
# The core tier, exactly as in the host's libbraun.a: never src/host.
FW_LIB_SRC := $(CORE_SRC)
FW_DEMO_SRC := $(sort $(wildcard firmware/demo/*.c))
FW_BOARD_SRC := firmware/board/semihost.c firmware/board/board.c firmware/board/demo_scenes.c
FW_INC := -Iinclude/core -Isrc/core -Ifirmware/board -Ifirmware/demo

# Scenes the demo runs from generated C (`braun gen-c`, firmware/gen_c):
# a holonomic mechanism (the paper's slider-crank as a scene file), a
# nonholonomic one (Chaplygin sleigh, knife edge), one with energy input
# (motor, spring-damper: BRAUN_ENERGY_INPUT) and two spatial ones (rigid3d
# bodies in Euler parameters): an arm on a hinge with a bob on a ball joint
# (n = 14, m = 10) and IFToMM A04, Bricard's linkage (n = 35, 35 rows of
# rank 34: a redundant row at every step). Each is a path below data/
# without .json; the C symbol and the records' name are its base name
# (iftomm/a04-bricard: a04_bricard, "scene:a04-bricard").
FW_SCENES := slider-crank sleigh damped-motor spatial-arm iftomm/a04-bricard
FW_GEN_DIR := $(FW_DIR)/gen
fw_scene_sym = $(subst -,_,$(notdir $(1)))
FW_GEN_SRC := $(foreach s,$(FW_SCENES),$(FW_GEN_DIR)/scene_$(call fw_scene_sym,$(s)).c)

# Configurations: double and float (-O2, -fstack-usage), and, with the
# core's compile-time sizes (BRAUN_FIXED_N/ROWS, braun_linalg.h), a float
# library fixed to n = 6, rows = 5 (slider-crank, four-bar) at -O3 -flto:
# the fastest build for one model.
FW_CONFIGS := double float
FW_DEF_double :=
FW_DEF_float := -DBRAUN_SINGLE
FW_COPT_double = $(FW_OPT) -fstack-usage
FW_COPT_float = $(FW_OPT) -fstack-usage
FW_AR_double = $(FW_AR)
FW_AR_float = $(FW_AR)
# The suffix of the public link names (braun.h, "Link names").
FW_LINK_float := _float
FW_HAVE_FIXED := $(shell grep -q BRAUN_FIXED_N src/core/braun_linalg.h 2>/dev/null && echo 1)
ifeq ($(FW_HAVE_FIXED),1)
FW_CONFIGS += float-fixed
FW_DEF_float-fixed := -DBRAUN_SINGLE -DBRAUN_FIXED_N=6 -DBRAUN_FIXED_ROWS=5
FW_COPT_float-fixed = -O3 -g -flto
FW_LTO_float-fixed = -O3 -g -flto=auto
FW_AR_float-fixed = $(FW_CC)-ar
FW_LINK_float-fixed := _float
endif

.PHONY: firmware firmware-deps firmware-bench-deps firmware-test firmware-bench \
        firmware-long firmware-profile

firmware-deps:
	@tools/ensure-deps $(FW_DEPS)

firmware-bench-deps:
	@tools/ensure-deps $(FW_BENCH_DEPS)

# ---------------------------------------------------------------- per configuration
# $(1): a configuration of FW_CONFIGS
define FW_CONFIG_RULES
FW_LIB_OBJ_$(1) := $$(FW_LIB_SRC:%.c=$(FW_DIR)/$(1)/obj/%.o)
FW_DEMO_OBJ_$(1) := $$(FW_DEMO_SRC:%.c=$(FW_DIR)/$(1)/obj/%.o) \
                    $$(FW_BOARD_SRC:%.c=$(FW_DIR)/$(1)/obj/%.o) \
                    $$(FW_GEN_SRC:%.c=$(FW_DIR)/$(1)/obj/%.o)
$(FW_DIR)/$(1)/obj/firmware/board/demo_scenes.o: $(FW_GEN_DIR)/fw_scene_list.h

# Objects: compiler messages also go to OBJ.log, which firmware-test
# requires to be empty (the warning-free build of the issue).
$(FW_DIR)/$(1)/obj/%.o: %.c | firmware-deps
	@mkdir -p $$(dir $$@)
	$$(FW_SAY) "FW_CC($(1)) $$<"
	@$$(FW_CC) $$(FW_CFLAGS) $$(FW_COPT_$(1)) $$(FW_DEF_$(1)) $$(FW_INC) -I$(FW_DIR)/$(1) \
	    $$(FW_EXTRA_$$(notdir $$*)) -MMD -MP -c $$< -o $$@ 2> $$@.log; \
	    st=$$$$?; cat $$@.log >&2; exit $$$$st

$(FW_DIR)/$(1)/obj/startup.o: firmware/board/startup.S | firmware-deps
	@mkdir -p $$(dir $$@)
	$$(FW_CC) $$(FW_ARCH) -c $$< -o $$@

$(FW_DIR)/$(1)/libbraun.a: $$(FW_LIB_OBJ_$(1))
	rm -f $$@
	$$(FW_AR_$(1)) rcs $$@ $$^

# Bootstrap image without the size table: it prints the table.
$(FW_DIR)/$(1)/obj/bootstrap/demo_main.o: firmware/board/demo_main.c | firmware-deps
	@mkdir -p $$(dir $$@)
	$$(FW_CC) $$(FW_CFLAGS) $$(FW_COPT_$(1)) $$(FW_DEF_$(1)) $$(FW_INC) -MMD -MP -c $$< -o $$@

$(FW_DIR)/$(1)/sizes.elf: $(FW_DIR)/$(1)/obj/startup.o $(FW_DIR)/$(1)/obj/bootstrap/demo_main.o \
        $$(FW_DEMO_OBJ_$(1)) $(FW_DIR)/$(1)/libbraun.a $(FW_LD_SCRIPT)
	$$(FW_CC) $$(FW_LDFLAGS) $$(FW_LTO_$(1)) $$(filter %.o %.a,$$^) $$(FW_LDLIBS) -o $$@

# braun_data_size() of every built-in model and scene for this target and
# configuration, computed by the library itself on the emulator: the
# compile-time figure the demo sizes its static workspace with.
$(FW_DIR)/$(1)/fw_sizes.h: $(FW_DIR)/$(1)/sizes.elf
	$$(FW_SAY) "QEMU sizes-header > $$@"
	@{ echo "/* Generated by mk/firmware.mk: braun_data_size() per built-in model and scene ($(1), Cortex-M4F). */"; \
	   timeout 60 $$(QEMU) $$(FW_QEMU_FLAGS) -kernel $$< -append sizes-header 2>&1; } > $$@.tmp
	@grep -q '^#define FW_DATA_BYTES_MAX [0-9]' $$@.tmp || { cat $$@.tmp; rm -f $$@.tmp; exit 1; }
	@mv $$@.tmp $$@

$(FW_DIR)/$(1)/obj/firmware/board/demo_main.o: $(FW_DIR)/$(1)/fw_sizes.h

$(FW_DIR)/$(1)/demo.elf: $(FW_DIR)/$(1)/obj/startup.o $(FW_DIR)/$(1)/obj/firmware/board/demo_main.o \
        $$(FW_DEMO_OBJ_$(1)) $(FW_DIR)/$(1)/libbraun.a $(FW_LD_SCRIPT)
	$$(FW_CC) $$(FW_LDFLAGS) $$(FW_LTO_$(1)) -Wl,-Map=$$(@:.elf=.map) $$(filter %.o %.a,$$^) \
	    $$(FW_LDLIBS) -o $$@

# The demo with the fixed-step and adaptive drivers kept too: the image
# whose disassembly the check of double operations on the step path reads
# (firmware/tools/double-path.awk). Not run.
$(FW_DIR)/$(1)/path.elf: $(FW_DIR)/$(1)/obj/startup.o $(FW_DIR)/$(1)/obj/firmware/board/demo_main.o \
        $$(FW_DEMO_OBJ_$(1)) $(FW_DIR)/$(1)/libbraun.a $(FW_LD_SCRIPT)
	$$(FW_CC) $$(FW_LDFLAGS) $$(FW_LTO_$(1)) -Wl,-Map=$$(@:.elf=.map) \
	    -Wl,-u,braun_integrate$$(FW_LINK_$(1)) -Wl,-u,braun_integrate_adaptive$$(FW_LINK_$(1)) $$(filter %.o %.a,$$^) \
	    $$(FW_LDLIBS) -o $$@
endef
FW_EXTRA_demo_main := -DFW_HAVE_SIZES
FW_EXTRA_demo_scenes := -DFW_HAVE_SCENE_LIST -I$(FW_GEN_DIR)
$(foreach c,$(FW_CONFIGS),$(eval $(call FW_CONFIG_RULES,$(c))))

# ---------------------------------------------------------------- scene to C
# `braun gen-c` reads a scene file with the host's JSON reader and writes
# static C (src/host/gen_c/braun_gen_c.c); regenerated when the scene file
# or the generator changes. $(1): a scene of FW_SCENES (path below data/).
define FW_SCENE_RULES
$(FW_GEN_DIR)/scene_$(call fw_scene_sym,$(1)).c: data/$(1).json $(BUILD)/bin/braun
	@mkdir -p $$(dir $$@)
	$(BUILD)/bin/braun gen-c data/$(1).json --symbol $(call fw_scene_sym,$(1)) -o $$@
endef
$(foreach s,$(FW_SCENES),$(eval $(call FW_SCENE_RULES,$(s))))

# FW_SCENE(symbol, "name", "path below data/ without .json") per scene.
$(FW_GEN_DIR)/fw_scene_list.h: mk/firmware.mk
	@mkdir -p $(dir $@)
	@{ echo "/* Generated by mk/firmware.mk: the scenes of the demo (FW_SCENE(symbol, name, path)). */"; \
	   printf '#define FW_SCENES'; \
	   for s in $(FW_SCENES); do b=$${s##*/}; \
	       printf ' FW_SCENE(%s, "%s", "%s")' "$$(echo $$b | tr - _)" "$$b" "$$s"; done; \
	   echo; } > $@

# ---------------------------------------------------------------- double and float
# $(1): double or float
define FW_PRECISION_RULES
# The same step loop linked with different feature sets (firmware/gc):
# what each image pulls out of libbraun.a is what it costs in flash.
FW_GC_ELF_$(1) := $(foreach v,ideal pv all,$(FW_DIR)/$(1)/gc-$(v).elf)
$(FW_DIR)/$(1)/obj/gc/gc_%.o: firmware/gc/gc_main.c | firmware-deps
	@mkdir -p $$(dir $$@)
	$$(FW_SAY) "FW_CC($(1)) $$< ($$*)"
	@$$(FW_CC) $$(FW_CFLAGS) $$(FW_COPT_$(1)) $$(FW_DEF_$(1)) -DFW_GC_CORRECTIONS=$$(FW_GC_CORR_$$*) \
	    $$(FW_INC) -MMD -MP -c $$< -o $$@ 2> $$@.log; st=$$$$?; cat $$@.log >&2; exit $$$$st
$(FW_DIR)/$(1)/gc-%.elf: $(FW_DIR)/$(1)/obj/startup.o $(FW_DIR)/$(1)/obj/gc/gc_%.o \
        $(FW_DIR)/$(1)/obj/firmware/board/semihost.o $(FW_DIR)/$(1)/obj/firmware/board/board.o \
        $(FW_DIR)/$(1)/libbraun.a $(FW_LD_SCRIPT)
	$$(FW_CC) $$(FW_LDFLAGS) -Wl,-Map=$$(@:.elf=.map) $$(filter %.o %.a,$$^) $$(FW_LDLIBS) -o $$@

# Code size (Berkeley: text/data/bss) of the library objects and the images.
$(FW_DIR)/$(1)/size.txt: $(FW_DIR)/$(1)/libbraun.a $(FW_DIR)/$(1)/demo.elf $$(FW_GC_ELF_$(1))
	$$(FW_SIZE) -t $$< > $$@
	$$(FW_SIZE) $$(filter %.elf,$$^) >> $$@

# -fstack-usage of every library function, largest first.
$(FW_DIR)/$(1)/stack-usage.txt: $(FW_DIR)/$(1)/libbraun.a
	cat $$(FW_LIB_OBJ_$(1):.o=.su) | sed 's|^.*/||' | sort -t'	' -k2,2nr > $$@

# Host build of the same demo, same precision; it reads the scenes from
# their files (the JSON reader, in this precision too).
FW_HOST_SRC := $$(FW_LIB_SRC) $$(HOST_SRC) $$(FW_DEMO_SRC) \
               tests/firmware/fw_host.c
$(FW_DIR)/host-$(1)/fw_host: $$(FW_HOST_SRC) $$(wildcard include/*/*.h src/core/*.h src/core/*/*.h firmware/demo/*.h) \
        $(FW_GEN_DIR)/fw_scene_list.h | firmware-deps
	@mkdir -p $$(dir $$@)
	$$(CC) -std=c99 $$(OPT) $$(WARN) $$(FW_DEF_$(1)) $$(HOST_CPPFLAGS) -Ifirmware/demo \
	    -I$(FW_GEN_DIR) -DFW_HAVE_SCENE_LIST $$(FW_HOST_SRC) -ljansson -lm -o $$@
endef
FW_GC_CORR_ideal := 0
FW_GC_CORR_pv := 3
FW_GC_CORR_all := 7
$(foreach p,double float,$(eval $(call FW_PRECISION_RULES,$(p))))

# ---------------------------------------------------------------- host tools
$(FW_DIR)/fw_compare: tests/firmware/fw_compare.c
	@mkdir -p $(dir $@)
	$(CC) -std=c99 -D_POSIX_C_SOURCE=200809L $(OPT) $(WARN) $< -lm -o $@

$(FW_DIR)/fw_traj: tests/firmware/fw_traj.c $(BUILD)/libbraun_host.a $(BUILD)/libbraun.a
	@mkdir -p $(dir $@)
	$(CC) -std=c99 -D_POSIX_C_SOURCE=200809L $(OPT) $(WARN) $(HOST_CPPFLAGS) $< $(HOST_LDLIBS) -o $@

FW_ALL := $(foreach c,$(FW_CONFIGS),$(FW_DIR)/$(c)/libbraun.a $(FW_DIR)/$(c)/demo.elf \
              $(FW_DIR)/$(c)/path.elf) \
          $(foreach p,double float,$(FW_DIR)/$(p)/size.txt $(FW_DIR)/$(p)/stack-usage.txt \
              $(FW_GC_ELF_$(p)))
FW_TEST_PREREQS := $(FW_ALL) $(FW_DIR)/host-double/fw_host $(FW_DIR)/host-float/fw_host \
                   $(FW_DIR)/fw_compare $(FW_DIR)/fw_traj $(BUILD)/bin/braun

firmware: $(FW_ALL)

FW_ENV = QEMU="$(QEMU)" FW_NM="$(FW_NM)" FW_CC="$(FW_CC)" FW_QEMU_FLAGS="$(FW_QEMU_FLAGS)" \
         FW_OBJDUMP="$(FW_OBJDUMP)" FW_ADDR2LINE="$(FW_ADDR2LINE)" \
         FW_CONFIGS="$(FW_CONFIGS)" BRAUN="$(BUILD)/bin/braun"

firmware-test: $(FW_TEST_PREREQS)
	@$(FW_ENV) sh tests/firmware/run.sh $(FW_DIR)

# Per-step instruction counts over 2000 steps (the slider-crank passes its
# bifurcation point) on the emulator, and callgrind on the host.
firmware-bench: $(FW_TEST_PREREQS) | firmware-bench-deps
	@$(FW_ENV) sh tests/firmware/bench.sh $(FW_DIR) 2000

# The float study of the issue on its own (firmware-test runs it too).
firmware-long: $(FW_TEST_PREREQS)
	@$(FW_ENV) sh tests/firmware/long.sh $(FW_DIR)

# Instructions per function of one corrected float step (QEMU exec log).
firmware-profile: $(FW_DIR)/float/demo.elf
	@$(FW_ENV) sh tests/firmware/profile.sh $(FW_DIR)/float/demo.elf

# make test runs the firmware checks as one suite.
TEST_SUITES += "$(MAKE) -s --no-print-directory firmware-test"
# The tiers apart, and the host and firmware libbraun.a of the same objects
# (after firmware-test: it builds the firmware libraries).
TEST_SUITES += "sh tests/tiers.sh $(BUILD)"
