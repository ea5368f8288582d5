/*
 * Arm semihosting (the debug-agent interface QEMU implements with
 * -semihosting-config enable=on): console output, the command line given
 * with -append, and the exit status. Bare-metal only.
 */
#ifndef FW_SEMIHOST_H
#define FW_SEMIHOST_H

#include <stddef.h>

/* Print a NUL-terminated string on the host console (SYS_WRITE0). */
void fw_semihost_write0(const char *s);

/* Copy the command line into buf (size bytes, NUL-terminated); returns its
 * length, or -1 if the host has none (SYS_GET_CMDLINE). */
int fw_semihost_cmdline(char *buf, int size);

/* End the emulation with this exit status (SYS_EXIT_EXTENDED with
 * ADP_Stopped_ApplicationExit: QEMU exits with `status`). */
void fw_semihost_exit(int status) __attribute__((noreturn));

#endif
