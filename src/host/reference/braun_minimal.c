/* The minimal-coordinate equations of the built-in models (Sec. 4): the
 * one-degree-of-freedom ODEs whose solutions are the paper's "numerically
 * exact" references, closed forms where they exist, and the maps from the
 * minimal state to each model's absolute coordinates. Host tier: oracles. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "braun_reference.h"

/* π in double; C99 has no M_PI. */
#define BRAUN_PI_D 3.14159265358979323846

/* ------------------------------------------------------- slider-crank */
/* Eq. 24. */
static void slider_crank_rhs(double t, const double *y, double *dydt,
                        const braun_link_params *p)
{
    (void)t;
    dydt[0] = y[1];
    dydt[1] = -3.0 / (5.0 - 3.0 * cos(2.0 * y[0]))
              * (sin(2.0 * y[0]) * y[1] * y[1] + p->g / p->l * cos(y[0]));
}

static void slider_crank_to_state(const double *y, double *q, double *v,
                             const braun_link_params *p)
{
    double h = 0.5 * p->l;
    double c = cos(y[0]), s = sin(y[0]), w = y[1];
    q[0] = h * c;
    q[1] = h * s;
    q[2] = y[0];
    q[3] = 3.0 * h * c;
    q[4] = h * s;
    q[5] = -y[0];
    v[0] = -h * s * w;
    v[1] = h * c * w;
    v[2] = w;
    v[3] = -3.0 * h * s * w;
    v[4] = h * c * w;
    v[5] = -w;
}

/* Fig. 1: released at rest with the crank at 45 degrees. */

/* Fig. 1: released at rest with the crank at 45 degrees. */
static const double slider_crank_y0[2] = {0.78539816339744828, 0.0};

/* ----------------------------------------------------------- four-bar */
/* Fig. 6 caption: θ'' + (7g/6l) cos θ = 0. */
static void four_bar_rhs(double t, const double *y, double *dydt,
                        const braun_link_params *p)
{
    (void)t;
    dydt[0] = y[1];
    dydt[1] = -7.0 * p->g / (6.0 * p->l) * cos(y[0]);
}

static const double four_bar_y0[2] = {BRAUN_PI_D / 2.0, -1.0};

/* phi = θ + π/2 turns the equation into the pendulum with w2 = 7g/(6l);
 * from the paper's state phi(0) = π, phi'(0) = -1 the linkage rotates. */
static int four_bar_exact(double t, double *y, const braun_link_params *p)
{
    double phi, dphi;
    int st = braun_pendulum_exact(7.0 * p->g / (6.0 * p->l),
                                  four_bar_y0[0] + BRAUN_PI_D / 2.0, four_bar_y0[1], t,
                                  &phi, &dphi);
    if (st < 0) return st;
    y[0] = phi - BRAUN_PI_D / 2.0;
    y[1] = dphi;
    return 0;
}

static void four_bar_to_state(const double *y, double *q, double *v,
                             const braun_link_params *p)
{
    double c = cos(y[0]), s = sin(y[0]);
    for (int i = 0; i < 3; ++i) {
        q[2 * i] = i * p->l + p->l * c;
        q[2 * i + 1] = p->l * s;
        v[2 * i] = -p->l * s * y[1];
        v[2 * i + 1] = p->l * c * y[1];
    }
}

/* Fig. 6 caption. */

/* ----------------------------------------------------------- pendulum */
static void pendulum_rhs(double t, const double *y, double *dydt,
                        const braun_link_params *p)
{
    (void)t;
    dydt[0] = y[1];
    dydt[1] = -p->g / p->l * sin(y[0]);
}

/* Released at rest from the horizontal. */
static const double pendulum_y0[2] = {BRAUN_PI_D / 2.0, 0.0};

static int pendulum_exact(double t, double *y, const braun_link_params *p)
{
    return braun_pendulum_exact(p->g / p->l, pendulum_y0[0], pendulum_y0[1], t, &y[0],
                                &y[1]);
}

static void pendulum_to_state(const double *y, double *q, double *v,
                             const braun_link_params *p)
{
    double c = cos(y[0]), s = sin(y[0]);
    q[0] = p->l * s;
    q[1] = -p->l * c;
    v[0] = p->l * c * y[1];
    v[1] = p->l * s * y[1];
}

static const braun_minimal table[] = {
    /* Eq. 24 has no closed form used here: integrated by RK4. */
    {"slider-crank", 2, slider_crank_y0, slider_crank_rhs, NULL, slider_crank_to_state},
    {"four-bar", 2, four_bar_y0, four_bar_rhs, four_bar_exact, four_bar_to_state},
    {"pendulum", 2, pendulum_y0, pendulum_rhs, pendulum_exact, pendulum_to_state},
};

const braun_minimal *braun_minimal_find(const char *name)
{
    if (!name) return NULL;
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (strcmp(table[i].name, name) == 0) return &table[i];
    return NULL;
}
