/* Arm semihosting calls: BKPT 0xAB with the operation in r0 and a pointer
 * to its arguments in r1 (Arm "Semihosting for AArch32 and AArch64"). */
#include "semihost.h"

#define SYS_WRITE0 0x04
#define SYS_GET_CMDLINE 0x15
#define SYS_EXIT 0x18
#define SYS_EXIT_EXTENDED 0x20
#define ADP_STOPPED_APPLICATION_EXIT 0x20026

static int call(int op, void *arg)
{
    register int r0 __asm__("r0") = op;
    register void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void fw_semihost_write0(const char *s)
{
    /* The interface takes a non-const pointer; the host only reads. */
    call(SYS_WRITE0, (void *)(size_t)s);
}

int fw_semihost_cmdline(char *buf, int size)
{
    struct {
        char *buf;
        int len;
    } block = {buf, size};
    if (size <= 0) return -1;
    if (call(SYS_GET_CMDLINE, &block) != 0) {
        buf[0] = 0;
        return -1;
    }
    if (block.len < 0 || block.len >= size) block.len = size - 1;
    buf[block.len] = 0;
    return block.len;
}

void fw_semihost_exit(int status)
{
    /* Parameter block: reason, then the exit code as subcode. */
    int block[2] = {ADP_STOPPED_APPLICATION_EXIT, status};
    call(SYS_EXIT_EXTENDED, block);
    /* A host without SYS_EXIT_EXTENDED: plain SYS_EXIT (status 0 or 1). */
    call(SYS_EXIT, (void *)(size_t)(status == 0 ? ADP_STOPPED_APPLICATION_EXIT : 0x20023));
    for (;;) {
    }
}
