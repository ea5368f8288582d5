/* Coefficients of Euler, Heun, classic RK4 and Dormand–Prince 5(4). */
#include "braun_tableau.h"

static const braun_tableau euler = {"euler", 1, 1, {0}, {{0}}, {1}, {0}};

static const braun_tableau heun = {
    "heun", 2, 2, {0, 1}, {{0}, {1}}, {0.5, 0.5}, {0}};

static const braun_tableau rk4 = {
    "rk4", 4, 4, {0, 0.5, 0.5, 1},
    {{0}, {0.5}, {0, 0.5}, {0, 0, 1}},
    {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}, {0}};

/* Dormand & Prince (1980), 5th-order solution, 4th-order embedded. */
static const braun_tableau dopri5 = {
    "dopri5", 7, 5, {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1},
    {{0},
     {1.0 / 5},
     {3.0 / 40, 9.0 / 40},
     {44.0 / 45, -56.0 / 15, 32.0 / 9},
     {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
     {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
     {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0},
    {35.0 / 384 - 5179.0 / 57600, 0, 500.0 / 1113 - 7571.0 / 16695,
     125.0 / 192 - 393.0 / 640, -2187.0 / 6784 + 92097.0 / 339200,
     11.0 / 84 - 187.0 / 2100, -1.0 / 40}};

const braun_tableau *braun__tableau(braun_method method)
{
    switch (method) {
    case BRAUN_EULER: return &euler;
    case BRAUN_HEUN: return &heun;
    case BRAUN_RK4: return &rk4;
    case BRAUN_DOPRI5: return &dopri5;
    default: return 0;
    }
}

const char *braun_method_name(braun_method method)
{
    const braun_tableau *tb = braun__tableau(method);
    return tb ? tb->name : "unknown";
}

int braun_method_from_name(const char *name)
{
    if (!name) return -1;
    for (int i = BRAUN_EULER; i <= BRAUN_DOPRI5; i++) {
        const char *s = braun__tableau((braun_method)i)->name, *t = name;
        while (*s && *s == *t) s++, t++;
        if (*s == 0 && *t == 0) return i;
    }
    return -1;
}
