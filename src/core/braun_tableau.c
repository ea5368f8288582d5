/* Coefficients of Euler, Heun, classic RK4 and Dormand–Prince 5(4). */
#include "braun_tableau.h"

/* Coefficients rounded once, at compile time, to braun_real. */
#define R(x) ((braun_real)(x))

static const braun_tableau euler = {"euler", 1, 1, {R(0)}, {{R(0)}}, {R(1)}, {R(0)}};

static const braun_tableau heun = {
    "heun", 2, 2, {R(0), R(1)}, {{R(0)}, {R(1)}}, {R(0.5), R(0.5)}, {R(0)}};

static const braun_tableau rk4 = {
    "rk4", 4, 4, {R(0), R(0.5), R(0.5), R(1)},
    {{R(0)}, {R(0.5)}, {R(0), R(0.5)}, {R(0), R(0), R(1)}},
    {R(1.0 / 6), R(1.0 / 3), R(1.0 / 3), R(1.0 / 6)}, {R(0)}};

/* Dormand & Prince (1980), 5th-order solution, 4th-order embedded. */
static const braun_tableau dopri5 = {
    "dopri5", 7, 5, {R(0), R(1.0 / 5), R(3.0 / 10), R(4.0 / 5), R(8.0 / 9), R(1), R(1)},
    {{R(0)},
     {R(1.0 / 5)},
     {R(3.0 / 40), R(9.0 / 40)},
     {R(44.0 / 45), R(-56.0 / 15), R(32.0 / 9)},
     {R(19372.0 / 6561), R(-25360.0 / 2187), R(64448.0 / 6561), R(-212.0 / 729)},
     {R(9017.0 / 3168), R(-355.0 / 33), R(46732.0 / 5247), R(49.0 / 176), R(-5103.0 / 18656)},
     {R(35.0 / 384), R(0), R(500.0 / 1113), R(125.0 / 192), R(-2187.0 / 6784), R(11.0 / 84)}},
    {R(35.0 / 384), R(0), R(500.0 / 1113), R(125.0 / 192), R(-2187.0 / 6784), R(11.0 / 84), R(0)},
    {R(35.0 / 384 - 5179.0 / 57600), R(0), R(500.0 / 1113 - 7571.0 / 16695), R(125.0 / 192 - 393.0 / 640), R(-2187.0 / 6784 + 92097.0 / 339200), R(11.0 / 84 - 187.0 / 2100), R(-1.0 / 40)}};

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
