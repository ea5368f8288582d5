/* Linear spring and damper between two points, along d = P_b - P_a with
 * length L = |d| and unit vector û = d/L:
 *   force on P_b  F = -(k (L - rest) + c L') û,  on P_a -F,  L' = û·d'
 *   potential     V = ½ k (L - rest)²          (energy law, Eq. 18)
 *   input power   Ė = -c L'²                   (the damper only)
 * A spring whose points coincide has no direction: the callbacks return a
 * recoverable 1 (the adaptive driver retries with a smaller step). */
#include "scene_internal.h"

typedef struct geom {
    scene_pt Pa, Pb;
    braun_real L, ux, uy, rate;
} geom;

static int measure(const braun_scene *s, const braun_scene_effect *e, const braun_real *q,
                   const braun_real *v, geom *g)
{
    braun_scene__point(s, e->a, q, v, &g->Pa);
    braun_scene__point(s, e->b, q, v, &g->Pb);
    const braun_real dx = g->Pb.pos[0] - g->Pa.pos[0], dy = g->Pb.pos[1] - g->Pa.pos[1];
    g->L = braun_sqrt(dx * dx + dy * dy);
    if (!(g->L > 0)) return 1;
    g->ux = dx / g->L;
    g->uy = dy / g->L;
    g->rate = g->ux * (g->Pb.vel[0] - g->Pa.vel[0]) + g->uy * (g->Pb.vel[1] - g->Pa.vel[1]);
    return 0;
}

int braun_scene__spring_forces(const braun_scene *s, const braun_scene_effect *e,
                               const braun_real *q, const braun_real *v, braun_real *Q)
{
    geom g;
    if (measure(s, e, q, v, &g)) return 1;
    const braun_real f = -(e->k * (g.L - e->rest) + e->c * g.rate);
    braun_scene__add_grad(&g.Pb, f * g.ux, f * g.uy, Q);
    braun_scene__add_grad(&g.Pa, -f * g.ux, -f * g.uy, Q);
    return 0;
}

int braun_scene__spring_potential(const braun_scene *s, const braun_scene_effect *e,
                                  const braun_real *q, braun_real *V, braun_real *dVdq)
{
    geom g;
    if (measure(s, e, q, NULL, &g)) return 1;
    const braun_real stretch = g.L - e->rest;
    *V = BRAUN_R(0.5) * e->k * stretch * stretch;
    if (dVdq) {
        const braun_real f = e->k * stretch;
        braun_scene__add_grad(&g.Pb, f * g.ux, f * g.uy, dVdq);
        braun_scene__add_grad(&g.Pa, -f * g.ux, -f * g.uy, dVdq);
    }
    return 0;
}

int braun_scene__spring_power(const braun_scene *s, const braun_scene_effect *e,
                              const braun_real *q, const braun_real *v, braun_real *P)
{
    geom g;
    if (measure(s, e, q, v, &g)) return 1;
    *P = -e->c * g.rate * g.rate;
    return 0;
}
