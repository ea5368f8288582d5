/* MODEL on the command line -> the system to simulate. Scene files will
 * arrive here; nothing else in the tool knows how MODEL is resolved. */
#include <string.h>

#include "braun_cli.h"

static int is_scene_file(const char *arg)
{
    size_t len = strlen(arg);
    return len >= 5 && strcmp(arg + len - 5, ".json") == 0;
}

int braun_cli_find_model(const char *arg, const braun_builtin **out)
{
    *out = NULL;
    if (is_scene_file(arg))
        return braun_cli_error("scene files are not supported yet: %s", arg);
    const braun_builtin *b = braun_builtin_find(arg);
    if (!b) return braun_cli_error("unknown model '%s' (see braun list)", arg);
    *out = b;
    return 0;
}
