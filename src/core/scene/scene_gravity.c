/* Uniform gravity g on every mass: bodies (through their class: the weight
 * at the centre of mass) and rod centres (half of a rod's weight at each
 * end). Conservative: the potential V = -Σ m g·r_c enters the energy law
 * (Eq. 18), Q = -∂V/∂q. At most one per scene. */
#include "scene_internal.h"

/* Adds w·(gx, gy) at the x, y columns of a rod end (nothing on the ground). */
static void add_end(const braun_scene *s, int point, braun_real w, const braun_real *g,
                    braun_real *Q)
{
    const int body = s->points[point].body;
    if (body < 0) return;
    const int i = s->bodies[body].iq;
    Q[i] += w * g[0];
    Q[i + 1] += w * g[1];
}

/* Q += sign · (generalized weight). */
static void weigh(const braun_scene *s, const braun_scene_effect *e, braun_real sign,
                  braun_real *Q)
{
    const braun_real g[3] = {sign * e->g[0], sign * e->g[1], sign * e->g[2]};
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        bd->kind->weight(bd, g, Q + bd->iq);
    }
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        const braun_real half = BRAUN_R(0.5) * r->mass;
        add_end(s, r->a, half, g, Q);
        add_end(s, r->b, half, g, Q);
    }
}

static int gravity_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                          const braun_real *q, const braun_real *v, braun_real *Q)
{
    (void)t;
    (void)q;
    (void)v;
    weigh(s, e, 1, Q);
    return 0;
}

/* V = -Σ m g·r_c; dVdq = -Q (may be NULL). */
static int gravity_potential(const braun_scene *s, const braun_scene_effect *e,
                             const braun_real *q, braun_real *Vout, braun_real *dVdq)
{
    braun_real V = 0;
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        V += bd->kind->gravity_potential(bd, e->g, q + bd->iq);
    }
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        const int ends[2] = {r->a, r->b};
        for (int j = 0; j < 2; j++) {
            const braun_scene_point *pt = &s->points[ends[j]];
            /* A ground end is fixed: its constant height only shifts E0. */
            const braun_real x = pt->body < 0 ? pt->x : q[s->bodies[pt->body].iq];
            const braun_real y = pt->body < 0 ? pt->y : q[s->bodies[pt->body].iq + 1];
            V -= BRAUN_R(0.5) * r->mass * (e->g[0] * x + e->g[1] * y);
        }
    }
    /* -∂V/∂q is exactly the generalized weight. */
    if (dVdq) weigh(s, e, -1, dVdq);
    *Vout = V;
    return 0;
}

static const char *gravity_check(const braun_scene *s, const braun_scene_effect *e)
{
    for (const braun_scene_effect *o = s->effects; o < e; o++)
        if (o->type == e->type) return "more than one gravity";
    if (s->dim == 2 && e->g[2] != 0) return "gravity in a planar scene has no z component";
    return NULL;
}

static const braun_scene_field gravity_fields[] = {
    {"g", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_effect, g),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_DIMVEC, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_gravity = {
    "gravity", "BRAUN_EFFECT_GRAVITY", gravity_fields, NULL, gravity_check, gravity_forces,
    gravity_potential, NULL, NULL, 0};
