/* RK4 on the minimal-coordinate equations, in working precision. */
#include "fw_minimal.h"

#include <math.h>
#include <string.h>

#ifdef BRAUN_SINGLE
#define SIN sinf
#define COS cosf
#else
#define SIN sin
#define COS cos
#endif

int fw_minimal_init(fw_minimal *s, const braun_builtin *b)
{
    const braun_link_params *p = b->sys.user;
    /* [θ(0), θ'(0)] of each model's minimal equation (the host's oracles
     * in braun_reference.h hold the same: Fig. 1, Fig. 6, the pendulum). */
    static const double y0[3][2] = {{0.78539816339744828, 0.0},
                                    {1.5707963267948966, -1.0},
                                    {1.5707963267948966, 0.0}};
    if (strcmp(b->name, "slider-crank") == 0)
        s->kind = 0;
    else if (strcmp(b->name, "four-bar") == 0)
        s->kind = 1;
    else if (strcmp(b->name, "pendulum") == 0)
        s->kind = 2;
    else
        return -1;
    s->g_l = (braun_real)(p->g / p->l);
    s->y[0] = (braun_real)y0[s->kind][0];
    s->y[1] = (braun_real)y0[s->kind][1];
    return 0;
}

/* θ'' at (θ, θ'). */
static braun_real accel(const fw_minimal *s, braun_real th, braun_real om)
{
    switch (s->kind) {
    case 0: {
        const braun_real th2 = BRAUN_R(2.0) * th;
        return BRAUN_R(-3.0) / (BRAUN_R(5.0) - BRAUN_R(3.0) * COS(th2)) *
               (SIN(th2) * om * om + s->g_l * COS(th));
    }
    case 1:
        return -(BRAUN_R(7.0) / BRAUN_R(6.0)) * s->g_l * COS(th);
    default:
        return -s->g_l * SIN(th);
    }
}

void fw_minimal_step(fw_minimal *s, braun_real h)
{
    const braun_real hh = BRAUN_R(0.5) * h, th = s->y[0], om = s->y[1];
    const braun_real k1t = om, k1o = accel(s, th, om);
    const braun_real k2t = om + hh * k1o, k2o = accel(s, th + hh * k1t, om + hh * k1o);
    const braun_real k3t = om + hh * k2o, k3o = accel(s, th + hh * k2t, om + hh * k2o);
    const braun_real k4t = om + h * k3o, k4o = accel(s, th + h * k3t, om + h * k3o);
    s->y[0] = th + h / BRAUN_R(6.0) * (k1t + BRAUN_R(2.0) * (k2t + k3t) + k4t);
    s->y[1] = om + h / BRAUN_R(6.0) * (k1o + BRAUN_R(2.0) * (k2o + k3o) + k4o);
}
