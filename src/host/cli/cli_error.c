/* The one format of every error line the tool prints: "braun: <what>".
 * One line whatever the message carries: a scene's name or a path with a
 * newline or another control byte (a JSON "\n" escape) shows it as '?',
 * so a message can never forge a second line. */
#include <stdarg.h>
#include <stdio.h>

#include "braun_cli.h"

int braun_cli_error(const char *fmt, ...)
{
    char line[2048];
    va_list ap;
    va_start(ap, fmt);
    /* clang-analyzer's va_list check misfires here when clang-tidy is given
     * several files at once (not on this file alone): ap is initialized. */
    vsnprintf(line, sizeof line, fmt, ap); /* NOLINT(clang-analyzer-valist.Uninitialized) */
    va_end(ap);
    braun_cli_mask_controls(line);
    fprintf(stderr, "braun: %s\n", line);
    return BRAUN_CLI_USAGE;
}
