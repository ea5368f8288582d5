/* libFuzzer target: `braun run` and `braun plot` option parsing (the
 * arguments after "run" or "plot", each input parsed both ways). The input is split at NUL and newline bytes into arguments; every
 * argument vector must parse (0) or be refused with exit status 2
 * (BRAUN_CLI_USAGE) — never crash or read past an argument. --help is
 * braun_main.c's (braun_cli_help_asked): here it is an unknown option. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_cli.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { MAX_ARGS = 64 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    char *argv[MAX_ARGS + 2];
    int argc = 0;
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    char *p = text, *end = text + size;
    while (p <= end && argc < MAX_ARGS) {
        argv[argc++] = p;
        while (p < end && *p != '\0' && *p != '\n') p++;
        *p = '\0';
        p++;
    }
    argv[argc] = NULL;
    braun_cli_run_args a;
    for (int plot = 0; plot < 2; plot++) {
        int rc = braun_cli_parse_run(argc, argv, &a, plot);
        if (rc != 0 && rc != BRAUN_CLI_USAGE) abort();
    }
    free(text);
    return 0;
}
