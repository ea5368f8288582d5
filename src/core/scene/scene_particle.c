/* Particle: a point mass with coordinates x, y, its mass block diag(m, m);
 * mass 0 is allowed when rods carry it (natural coordinates). Its only
 * point is itself: P = (x, y), ∂P/∂(x, y) = I, no velocity product. */
#include "scene_internal.h"

static const char *particle_check(const braun_scene *s, const braun_scene_body *b)
{
    (void)s;
    return b->mass < 0 ? "a particle's mass must be >= 0" : NULL;
}

static void particle_mass(const braun_scene_body *b, braun_real *M, int ld)
{
    M[braun_scene__at(0, 0, ld)] += b->mass;
    M[braun_scene__at(1, 1, ld)] += b->mass;
}

/* ½ vᵀ M_b v; adds M_b v to dEdv (may be NULL). */
static braun_real particle_kinetic(const braun_scene_body *b, const braun_real *v,
                                   braun_real *dEdv)
{
    const braun_real px = b->mass * v[0], py = b->mass * v[1];
    const braun_real T = px * v[0] + py * v[1];
    if (dEdv) {
        dEdv[0] += px;
        dEdv[1] += py;
    }
    return BRAUN_R(0.5) * T;
}

static void particle_point(const braun_scene_body *b, const braun_scene_point *pt,
                           const braun_real *q, const braun_real *v, braun_scene_pt *P)
{
    (void)b;
    (void)pt;
    P->pos[0] = q[0];
    P->pos[1] = q[1];
    P->pos[2] = 0;
    if (v) {
        P->vel[0] = v[0];
        P->vel[1] = v[1];
    }
}

static void particle_grad(const braun_scene_pt *P, const braun_real *g, braun_real *row)
{
    (void)P;
    row[0] += g[0];
    row[1] += g[1];
}

static const braun_scene_field particle_fields[] = {
    {"mass", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, mass),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONNEG, NULL},
    {"position", BRAUN_FIELD_REAL, 2, offsetof(braun_scene_body, q0), BRAUN_FIELD_REQUIRED, NULL},
    {"velocity", BRAUN_FIELD_REAL, 2, offsetof(braun_scene_body, v0), 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_body_class braun_scene_body_particle = {
    "particle", "BRAUN_BODY_PARTICLE", 2, 2, -1, BRAUN_BODY_CLASS_POINT_MASS, particle_fields,
    particle_check, particle_mass, particle_kinetic, particle_point, particle_grad,
    braun_scene__weight_xy, braun_scene__gravity_potential_xy,
    NULL, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL};
