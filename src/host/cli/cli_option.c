/* The options of the commands with their own parsers (gen, gen-c), read
 * as run reads its own (cli_args.c): "--name VALUE" or "--name=VALUE",
 * each option once; a value that begins with "--" is given as --name=VALUE. */
#include <string.h>

#include "braun_cli.h"

int braun_cli_option(int argc, char **argv, int *i, char *name, size_t size, const char **val)
{
    const char *arg = argv[*i], *eq = strchr(arg, '=');
    const size_t len = eq && strncmp(arg, "--", 2) == 0 ? (size_t)(eq - arg) : strlen(arg);
    if (len >= size) return braun_cli_error("unknown option '%s' (see braun --help)", arg);
    memcpy(name, arg, len);
    name[len] = '\0';
    if (!val) return 0; /* the name alone */
    if (arg[len] == '=') *val = arg + len + 1;
    else if (*i + 1 < argc && strncmp(argv[*i + 1], "--", 2) != 0) *val = argv[++*i];
    else *val = ""; /* a following option is a forgotten value, not a file name */
    if (**val == '\0') return braun_cli_error("option %s needs a value", name);
    return 0;
}

int braun_cli_option_once(const char *canon, const char *name, const char **seen, int *nseen,
                          int cap)
{
    for (int k = 0; k < *nseen; k++)
        if (strcmp(seen[k], canon) == 0)
            return braun_cli_error("option %s given twice: give it once", name);
    if (*nseen < cap) seen[(*nseen)++] = canon;
    return 0;
}
