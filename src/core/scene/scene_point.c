/* Kinematics of a point of a scene: on a rigid body, a particle, or the
 * ground. Every joint, spring and force reaches q through these. */
#include "scene_internal.h"

void braun_scene__point(const braun_scene *s, int i, const braun_real *q, const braun_real *v,
                        scene_pt *P)
{
    const braun_scene_point *pt = &s->points[i];
    P->ix = -1;
    P->rigid = 0;
    P->jt[0] = P->jt[1] = 0;
    P->cc[0] = P->cc[1] = 0;
    P->vel[0] = P->vel[1] = 0;
    P->w = 0;
    if (pt->body < 0) { /* ground: world coordinates, fixed */
        P->pos[0] = pt->x;
        P->pos[1] = pt->y;
        return;
    }
    const braun_scene_body *bd = &s->bodies[pt->body];
    const int ix = bd->iq;
    P->ix = ix;
    P->pos[0] = q[ix];
    P->pos[1] = q[ix + 1];
    if (v) {
        P->vel[0] = v[ix];
        P->vel[1] = v[ix + 1];
    }
    if (bd->kind != BRAUN_BODY_RIGID) return;
    /* Rigid: P = r + R(θ)p, ∂P/∂θ = R'(θ)p = (-Rp_y, Rp_x). */
    const braun_real c = braun_cos(q[ix + 2]), sn = braun_sin(q[ix + 2]);
    const braun_real rx = c * pt->x - sn * pt->y, ry = sn * pt->x + c * pt->y;
    P->rigid = 1;
    P->pos[0] += rx;
    P->pos[1] += ry;
    P->jt[0] = -ry;
    P->jt[1] = rx;
    if (v) {
        const braun_real w = v[ix + 2];
        P->w = w;
        P->vel[0] += P->jt[0] * w;
        P->vel[1] += P->jt[1] * w;
        /* P'' = r'' + R'p ω' - R p ω²: the velocity product is -R p ω². */
        P->cc[0] = -rx * w * w;
        P->cc[1] = -ry * w * w;
    }
}

void braun_scene__add_grad(const scene_pt *P, braun_real gx, braun_real gy, braun_real *row)
{
    if (P->ix < 0) return;
    row[P->ix] += gx;
    row[P->ix + 1] += gy;
    if (P->rigid) row[P->ix + 2] += gx * P->jt[0] + gy * P->jt[1];
}

int braun_scene__angle(const braun_scene *s, int body, const braun_real *q, const braun_real *v,
                       braun_real *theta, braun_real *omega)
{
    const int col = braun_scene__theta_col(s, body);
    if (theta) *theta = col >= 0 ? q[col] : 0;
    if (omega) *omega = col >= 0 && v ? v[col] : 0;
    return col;
}

void braun_scene_point_position(const braun_scene *s, int i, const braun_real *q,
                                braun_real *xy)
{
    scene_pt P;
    braun_scene__point(s, i, q, NULL, &P);
    xy[0] = P.pos[0];
    xy[1] = P.pos[1];
}
