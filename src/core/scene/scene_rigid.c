/* Planar rigid body: coordinates x, y, θ (centre of mass, angle from the x
 * axis), the diagonal mass block diag(m, m, I) of the paper's Eq. 21, and
 * the kinematics of a body-fixed point p:
 *   P = r + R(θ) p,  ∂P/∂(x, y) = I,  ∂P/∂θ = jt = R'(θ) p = (-Rp_y, Rp_x)
 *   P' = r' + jt ω,  P'' = r'' + jt ω' + cc  with  cc = -R p ω². */
#include "scene_internal.h"

static const char *rigid_check(const braun_scene *s, const braun_scene_body *b)
{
    (void)s;
    if (!(b->mass > 0)) return "a rigid body needs a mass > 0";
    if (!(b->inertia > 0)) return "a rigid body needs an inertia > 0";
    return NULL;
}

static void rigid_mass(const braun_scene_body *b, braun_real *M, int ld)
{
    M[braun_scene__at(0, 0, ld)] += b->mass;
    M[braun_scene__at(1, 1, ld)] += b->mass;
    M[braun_scene__at(2, 2, ld)] += b->inertia;
}

/* ½ vᵀ M_b v; adds M_b v to dEdv (may be NULL). */
static braun_real rigid_kinetic(const braun_scene_body *b, const braun_real *v,
                                braun_real *dEdv)
{
    const braun_real px = b->mass * v[0], py = b->mass * v[1];
    braun_real T = px * v[0] + py * v[1];
    if (dEdv) {
        dEdv[0] += px;
        dEdv[1] += py;
    }
    const braun_real L = b->inertia * v[2];
    T += L * v[2];
    if (dEdv) dEdv[2] += L;
    return BRAUN_R(0.5) * T;
}

/* jac[0..1] = ∂P/∂θ. */
static void rigid_point(const braun_scene_body *b, const braun_scene_point *pt,
                        const braun_real *q, const braun_real *v, braun_scene_pt *P)
{
    (void)b;
    P->pos[0] = q[0];
    P->pos[1] = q[1];
    P->pos[2] = 0;
    if (v) {
        P->vel[0] = v[0];
        P->vel[1] = v[1];
    }
    braun_real c, sn;
    braun_sincos(q[2], &sn, &c);
    const braun_real rx = c * pt->x - sn * pt->y, ry = sn * pt->x + c * pt->y;
    P->pos[0] += rx;
    P->pos[1] += ry;
    P->jac[0] = -ry;
    P->jac[1] = rx;
    if (v) {
        const braun_real w = v[2];
        P->vel[0] += P->jac[0] * w;
        P->vel[1] += P->jac[1] * w;
        /* P'' = r'' + R'p ω' - R p ω²: the velocity product is -R p ω². */
        P->cc[0] = -rx * w * w;
        P->cc[1] = -ry * w * w;
    }
}

static void rigid_grad(const braun_scene_pt *P, const braun_real *g, braun_real *row)
{
    row[0] += g[0];
    row[1] += g[1];
    row[2] += g[0] * P->jac[0] + g[1] * P->jac[1];
}

static const braun_scene_field rigid_fields[] = {
    {"mass", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, mass),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_POSITIVE, NULL},
    {"inertia", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, inertia),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_POSITIVE, NULL},
    {"position", BRAUN_FIELD_REAL, 2, offsetof(braun_scene_body, q0), BRAUN_FIELD_REQUIRED, NULL},
    {"angle", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, q0) + 2 * sizeof(braun_real), 0,
     NULL},
    {"velocity", BRAUN_FIELD_REAL, 2, offsetof(braun_scene_body, v0), 0, NULL},
    {"omega", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_body, v0) + 2 * sizeof(braun_real), 0,
     NULL},
    {"points", BRAUN_FIELD_POINTS, 2, 0, 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_body_class braun_scene_body_rigid = {
    "rigid", "BRAUN_BODY_RIGID", 3, 2, 2, 0u, rigid_fields, rigid_check,
    rigid_mass, rigid_kinetic, rigid_point, rigid_grad, braun_scene__weight_xy,
    braun_scene__gravity_potential_xy,
    NULL, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL};
