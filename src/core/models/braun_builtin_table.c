/* The list of built-in models, for lookup by name and listing. */
#include <stddef.h>
#include <string.h>

#include "braun_models_internal.h"

static const braun_builtin *const table[] = {
    &braun_builtin_slider_crank,
    &braun_builtin_four_bar,
    &braun_builtin_pendulum,
};

#define TABLE_LEN ((int)(sizeof table / sizeof table[0]))

const braun_builtin *braun_builtin_at(int i)
{
    return i >= 0 && i < TABLE_LEN ? table[i] : NULL;
}

const braun_builtin *braun_builtin_find(const char *name)
{
    if (!name) return NULL;
    for (int i = 0; i < TABLE_LEN; ++i)
        if (strcmp(table[i]->name, name) == 0) return table[i];
    return NULL;
}
