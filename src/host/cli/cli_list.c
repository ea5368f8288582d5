/* braun list: the built-in models, one line each (name, n, m, p, description). */
#include "braun_cli.h"

int braun_cli_list(void)
{
    const braun_builtin *b;
    for (int i = 0; (b = braun_builtin_at(i)) != NULL; i++)
        printf("%-14s n=%d m=%d p=%d  %s\n", b->name, b->sys.n, b->sys.m, b->sys.p,
               b->description ? b->description : "");
    const braun_cli_target *t;
    for (int i = 0; (t = braun_cli_extra_at(i)) != NULL; i++)
        printf("%-14s n=%d m=%d p=%d  %s\n", t->name, t->sys.n, t->sys.m, t->sys.p,
               t->description ? t->description : "");
    return fflush(stdout) == 0 ? 0 : BRAUN_CLI_FAILED;
}
