/* The one format of every error line the tool prints: "braun: <what>". */
#include <stdarg.h>
#include <stdio.h>

#include "braun_cli.h"

int braun_cli_error(const char *fmt, ...)
{
    va_list ap;
    fputs("braun: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return BRAUN_CLI_USAGE;
}
