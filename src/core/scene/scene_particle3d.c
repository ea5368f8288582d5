/* Spatial particle: a point mass with coordinates x, y, z, its mass block
 * diag(m, m, m); mass 0 is allowed when something else carries it (as for
 * planar particles). Its only point is itself: P = (x, y, z), ∂P/∂q = I, no
 * velocity product. It has no orientation, so no axis can be fixed on it. */
#include "scene_internal.h"

static const char *particle3d_check(const braun_scene *s, const braun_scene_body *b)
{
    (void)s;
    return b->mass < 0 ? "a particle's mass must be >= 0" : NULL;
}

static void particle3d_mass(const braun_scene_body *b, braun_real *M, int ld)
{
    for (int i = 0; i < 3; i++) M[braun_scene__at(i, i, ld)] += b->mass;
}

static braun_real particle3d_kinetic(const braun_scene_body *b, const braun_real *v,
                                     braun_real *dEdv)
{
    braun_real T = 0;
    for (int i = 0; i < 3; i++) {
        const braun_real pi = b->mass * v[i];
        T += pi * v[i];
        if (dEdv) dEdv[i] += pi;
    }
    return BRAUN_R(0.5) * T;
}

static void particle3d_point(const braun_scene_body *b, const braun_scene_point *pt,
                             const braun_real *q, const braun_real *v, braun_scene_pt *P)
{
    (void)b;
    (void)pt;
    for (int i = 0; i < 3; i++) {
        P->pos[i] = q[i];
        if (v) P->vel[i] = v[i];
    }
}

static void particle3d_grad(const braun_scene_pt *P, const braun_real *g, braun_real *row)
{
    (void)P;
    for (int i = 0; i < 3; i++) row[i] += g[i];
}

static void particle3d_weight(const braun_scene_body *b, const braun_real *g, braun_real *Q)
{
    for (int i = 0; i < 3; i++) Q[i] += b->mass * g[i];
}

static braun_real particle3d_gravity_potential(const braun_scene_body *b, const braun_real *g,
                                               const braun_real *q)
{
    return -(b->mass * (g[0] * q[0] + g[1] * q[1] + g[2] * q[2]));
}

static const braun_scene_field particle3d_fields[] = {
    {"mass", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, mass),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONNEG, NULL},
    {"position", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, q0), BRAUN_FIELD_REQUIRED, NULL},
    {"velocity", BRAUN_FIELD_REAL, 3, offsetof(braun_scene_body, v0), 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_body_class braun_scene_body_particle3d = {
    "particle3d", "BRAUN_BODY_PARTICLE3D", 3, 3, -1, BRAUN_BODY_CLASS_POINT_MASS,
    particle3d_fields, particle3d_check, particle3d_mass, particle3d_kinetic, particle3d_point,
    particle3d_grad, particle3d_weight, particle3d_gravity_potential,
    NULL, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL};
