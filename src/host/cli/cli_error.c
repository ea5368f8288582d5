/* The one format of every error line the tool prints: "braun: <what>". */
#include <stdarg.h>
#include <stdio.h>

#include "braun_cli.h"

int braun_cli_error(const char *fmt, ...)
{
    va_list ap;
    fputs("braun: ", stderr);
    va_start(ap, fmt);
    /* clang-analyzer's va_list check misfires here when clang-tidy is given
     * several files at once (not on this file alone): ap is initialized. */
    vfprintf(stderr, fmt, ap); /* NOLINT(clang-analyzer-valist.Uninitialized) */
    va_end(ap);
    fputc('\n', stderr);
    return BRAUN_CLI_USAGE;
}
