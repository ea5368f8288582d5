/*
 * Target entry of the demo firmware (MPS2-AN386 under QEMU): command line
 * and output through semihosting, the workspace as a static buffer whose
 * size is fixed at build time, instruction-count calibration of the timer,
 * stack high-water mark, exit status.
 */
#include <stdint.h>
#include <string.h>

#include "board.h"
#include "braun_models.h"
#include "fw_demo.h"
#include "fw_out.h"
#include "semihost.h"

/* build/firmware/<precision>/fw_sizes.h: braun_data_size() of every
 * built-in model for this target and precision, generated at build time by
 * running `sizes-header` on the emulator (mk/firmware.mk). Without it (the
 * bootstrap image that generates it) a generous buffer is used. */
#ifdef FW_HAVE_SIZES
#include "fw_sizes.h"
#define FW_WORKSPACE_BYTES FW_DATA_BYTES_MAX
#else
#define FW_WORKSPACE_BYTES 16384
#endif

/* The workspace: no heap, a static block sized for the largest built-in
 * model (8-byte aligned; braun_data_init accepts any alignment anyway). */
static union {
    unsigned char bytes[FW_WORKSPACE_BYTES];
    double align;
} workspace;

const char fw_platform_name[] = "mps2-an386";

void fw_platform_write(const char *s, size_t len)
{
    static char line[257];
    while (len) {
        size_t k = len < sizeof line - 1 ? len : sizeof line - 1;
        memcpy(line, s, k);
        line[k] = 0;
        fw_semihost_write0(line);
        s += k;
        len -= k;
    }
}

unsigned long fw_platform_ticks(void) { return fw_board_ticks(); }

/* Instructions per timer tick: a loop of exactly 2·N instructions. */
static void calibrate(void)
{
    const uint32_t n = 1u << 20;
    const uint32_t t0 = fw_board_ticks();
    fw_board_spin(n);
    const uint32_t dt = fw_board_ticks() - t0;
    fw_puts("calib");
    fw_kv_long("instructions", (long)(2 * n));
    fw_kv_long("ticks", (long)dt);
    fw_puts(" # ");
    fw_put_dec(dt ? 2.0 * (double)n / (double)dt : 0.0, 4);
    fw_puts(" instructions per tick\n");
}

#ifdef FW_HAVE_SIZES
/* The build-time figures must be what the library computes. */
static int check_sizes(void)
{
    static const struct {
        const char *name;
        size_t bytes;
    } fig[] = {FW_DATA_BYTES_TABLE};
    int bad = 0;
    for (size_t i = 0; i < sizeof fig / sizeof fig[0]; i++)
        if (fw_demo_data_size(fig[i].name) != fig[i].bytes) bad = 1;
    fw_puts("sizes_check");
    fw_kv_str("result", bad ? "mismatch" : "ok");
    fw_kv_long("models", (long)(sizeof fig / sizeof fig[0]));
    fw_kv_long("workspace_bytes", (long)sizeof workspace.bytes);
    fw_putc('\n');
    return bad;
}
#endif

int fw_board_main(void)
{
    static char cmdline[256];
    char *argv[16];
    int argc = 0;
    fw_workspace ws = {workspace.bytes, sizeof workspace.bytes};

    if (fw_semihost_cmdline(cmdline, (int)sizeof cmdline) > 0) {
        /* Words separated by spaces. QEMU puts the image name first when
         * the command line comes from -kernel/-append: skip a word ending
         * in ".elf". */
        char *p = cmdline;
        while (*p && argc < 16) {
            while (*p == ' ') *p++ = 0;
            if (!*p) break;
            argv[argc++] = p;
            while (*p && *p != ' ') p++;
        }
        if (argc > 0) {
            size_t len = strlen(argv[0]);
            if (len >= 4 && strcmp(argv[0] + len - 4, ".elf") == 0) {
                for (int i = 1; i < argc; i++) argv[i - 1] = argv[i];
                argc--;
            }
        }
    }
    int header = argc > 0 && strcmp(argv[0], "sizes-header") == 0;
    int bad = 0;
    /* `trace` runs under an instruction trace: no calibration loop (2^21
     * instructions, a million logged blocks). */
    if (!header && !(argc > 0 && strcmp(argv[0], "trace") == 0)) calibrate();
#ifdef FW_HAVE_SIZES
    if (!header) bad |= check_sizes();
#endif
    int rc = fw_demo_main(argc, argv, &ws);
    if (!header) {
        fw_puts("stack");
        fw_kv_long("size", (long)fw_board_stack_size());
        fw_kv_long("used", (long)(fw_board_stack_size() - fw_board_stack_unused()));
        fw_putc('\n');
    }
    fw_flush();
    return rc ? rc : bad;
}
