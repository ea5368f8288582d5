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
    braun_real L, ux, uy, uz, rate;
} geom;

static int measure(const braun_scene *s, const braun_scene_effect *e, const braun_real *q,
                   const braun_real *v, geom *g)
{
    braun_scene__point(s, e->a, q, v, &g->Pa);
    braun_scene__point(s, e->b, q, v, &g->Pb);
    /* z terms are exact zeros in a planar scene (the planar sums, bit for bit). */
    const braun_real dx = g->Pb.pos[0] - g->Pa.pos[0], dy = g->Pb.pos[1] - g->Pa.pos[1],
                     dz = g->Pb.pos[2] - g->Pa.pos[2];
    g->L = braun_sqrt(dx * dx + dy * dy + dz * dz);
    if (!(g->L > 0)) return 1;
    g->ux = dx / g->L;
    g->uy = dy / g->L;
    g->uz = dz / g->L;
    g->rate = g->ux * (g->Pb.vel[0] - g->Pa.vel[0]) + g->uy * (g->Pb.vel[1] - g->Pa.vel[1]) +
              g->uz * (g->Pb.vel[2] - g->Pa.vel[2]);
    return 0;
}

/* row += f ∂L/∂q-direction terms: f û at P_b, -f û at P_a. */
static void push(const geom *g, braun_real f, braun_real *row)
{
    const braun_real gb[3] = {f * g->ux, f * g->uy, f * g->uz};
    const braun_real ga[3] = {-f * g->ux, -f * g->uy, -f * g->uz};
    braun_scene_pt_grad(&g->Pb, gb, row);
    braun_scene_pt_grad(&g->Pa, ga, row);
}

static int spring_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                         const braun_real *q, const braun_real *v, braun_real *Q)
{
    geom g;
    (void)t;
    if (measure(s, e, q, v, &g)) return 1;
    const braun_real f = -(e->k * (g.L - e->rest) + e->c * g.rate);
    push(&g, f, Q);
    return 0;
}

static int spring_potential(const braun_scene *s, const braun_scene_effect *e,
                            const braun_real *q, braun_real *V, braun_real *dVdq)
{
    geom g;
    if (measure(s, e, q, NULL, &g)) return 1;
    const braun_real stretch = g.L - e->rest;
    *V = BRAUN_R(0.5) * e->k * stretch * stretch;
    if (dVdq) {
        const braun_real f = e->k * stretch;
        push(&g, f, dVdq);
    }
    return 0;
}

static int spring_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                        const braun_real *q, const braun_real *v, braun_real *P)
{
    geom g;
    (void)t;
    if (measure(s, e, q, v, &g)) return 1;
    *P = -e->c * g.rate * g.rate;
    return 0;
}

/* Only a damper puts energy in or out. */
static int spring_inputs(const braun_scene_effect *e)
{
    return e->c != 0;
}

static const char *spring_check(const braun_scene *s, const braun_scene_effect *e)
{
    const char *same = braun_scene__same_body_points(s, e->a, e->b, 1);
    if (same) return same;
    if (e->k < 0 || e->c < 0 || e->rest < 0)
        return "stiffness, damping and rest length must be >= 0";
    return NULL;
}

enum { F_A, F_B, F_STIFFNESS, F_DAMPING, F_REST };

/* Scene files: a rest length left out is the initial distance. */
static void spring_defaults(const braun_scene *s, braun_scene_effect *e, unsigned given)
{
    if (!BRAUN_FIELD_GIVEN(given, F_REST)) e->rest = braun_scene_initial_distance(s, e->a, e->b);
}

static const braun_scene_field spring_fields[] = {
    [F_A] = {"a", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_effect, a), BRAUN_FIELD_REQUIRED, NULL},
    [F_B] = {"b", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_effect, b), BRAUN_FIELD_REQUIRED, NULL},
    [F_STIFFNESS] = {"stiffness", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, k),
                     BRAUN_FIELD_NONNEG, NULL},
    [F_DAMPING] = {"damping", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, c),
                   BRAUN_FIELD_NONNEG, NULL},
    [F_REST] = {"rest_length", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, rest),
                BRAUN_FIELD_NONNEG, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_spring = {
    "spring", "BRAUN_EFFECT_SPRING", spring_fields, spring_defaults, spring_check, spring_forces,
    spring_potential, spring_power, spring_inputs, 0};
