/* Kinematics of a point of a scene: fixed on the ground, or on a body,
 * whose class computes it (scene_rigid.c, scene_particle.c). Every joint,
 * spring and force reaches q through these. */
#include <math.h> /* NAN */
#include "scene_internal.h"

/* The ground part, and the common start of a body point: body, column,
 * zero velocity and velocity product. */
static void start(const braun_scene_body *bd, scene_pt *P)
{
    P->body = bd;
    P->col = bd ? bd->iq : -1;
    P->direction = 0;
    for (int k = 0; k < 3; k++) P->vel[k] = P->cc[k] = 0;
}

void braun_scene_pt_eval(const braun_scene *s, int i, const braun_real *q, const braun_real *v,
                         scene_pt *P)
{
    const braun_scene_point *pt = &s->points[i];
    if (pt->body < 0) { /* ground: world coordinates, fixed */
        start(NULL, P);
        P->pos[0] = pt->x;
        P->pos[1] = pt->y;
        P->pos[2] = pt->z;
        return;
    }
    const braun_scene_body *bd = &s->bodies[pt->body];
    start(bd, P);
    bd->kind->point(bd, pt, q + bd->iq, v ? v + bd->iq : NULL, P);
}

void braun_scene_dir_eval(const braun_scene *s, int body, const braun_real *d,
                          const braun_real *q, const braun_real *v, scene_pt *D)
{
    if (body < 0) { /* the ground: world directions, fixed */
        start(NULL, D);
        D->direction = 1;
        for (int k = 0; k < 3; k++) D->pos[k] = d[k];
        return;
    }
    const braun_scene_body *bd = &s->bodies[body];
    start(bd, D);
    bd->kind->direction(bd, d, q + bd->iq, v ? v + bd->iq : NULL, D);
    D->direction = 1;
}

/* Point i exists and its body (if any) has a class. */
static int point_ok(const braun_scene *s, int i)
{
    if (!s || !s->points || i < 0 || i >= s->npoints) return 0;
    const int b = s->points[i].body;
    return b < 0 || (b < s->nbodies && s->bodies && s->bodies[b].kind);
}

int braun_scene_point_state(const braun_scene *s, int i, const braun_real *q,
                            const braun_real *v, braun_real *pos, braun_real *vel)
{
    scene_pt P;
    if (!point_ok(s, i) || !q || !pos) return BRAUN_ERR_ARGUMENT;
    braun_scene__point(s, i, q, v, &P);
    for (int k = 0; k < 3; k++) {
        pos[k] = P.pos[k];
        if (vel) vel[k] = P.vel[k];
    }
    return BRAUN_OK;
}

void braun_scene_pt_grad(const scene_pt *P, const braun_real *g, braun_real *row)
{
    if (!P->body) return;
    P->body->kind->grad(P, g, row + P->col);
}

int braun_scene_body_angle(const braun_scene *s, int body, const braun_real *q,
                           const braun_real *v, braun_real *theta, braun_real *omega)
{
    /* A body that does not exist, or no q to read: -1 (BRAUN_ERR_ARGUMENT)
     * and NaN, as the initial angle says (an index past the bodies read
     * beyond them). */
    if (!s || body < BRAUN_SCENE_GROUND || body >= s->nbodies ||
        (body >= 0 && (!s->bodies || !s->bodies[body].kind)) ||
        (!q && braun_scene__theta_col(s, body) >= 0)) {
        if (theta) *theta = (braun_real)NAN;
        if (omega) *omega = (braun_real)NAN;
        return BRAUN_ERR_ARGUMENT;
    }
    const int col = braun_scene__theta_col(s, body);
    if (theta) *theta = col >= 0 ? q[col] : 0;
    if (omega) *omega = col >= 0 && v ? v[col] : 0;
    return col;
}

int braun_scene_point_position(const braun_scene *s, int i, const braun_real *q, braun_real *xy)
{
    scene_pt P;
    if (!point_ok(s, i) || !q || !xy) return BRAUN_ERR_ARGUMENT;
    braun_scene__point(s, i, q, NULL, &P);
    xy[0] = P.pos[0];
    xy[1] = P.pos[1];
    return BRAUN_OK;
}

/* ------------------------------------------------------- initial state */
int braun_scene_initial_point(const braun_scene *s, int i, braun_real *pos)
{
    if (!point_ok(s, i) || !pos) return BRAUN_ERR_ARGUMENT;
    const braun_scene_point *pt = &s->points[i];
    scene_pt P;
    if (pt->body < 0) {
        pos[0] = pt->x;
        pos[1] = pt->y;
        pos[2] = pt->z;
        return BRAUN_OK;
    }
    /* The body's own coordinates are q0 (or what its class makes of
     * them): no numbering needed. */
    const braun_scene_body *bd = &s->bodies[pt->body];
    braun_real q[BRAUN_SCENE_MAX_DOF];
    const braun_real *q0 = bd->q0;
    if (bd->kind->initial) {
        braun_real v[BRAUN_SCENE_MAX_DOF];
        bd->kind->initial(bd, q, v);
        q0 = q;
    }
    start(bd, &P);
    bd->kind->point(bd, pt, q0, NULL, &P);
    for (int k = 0; k < 3; k++) pos[k] = P.pos[k];
    return BRAUN_OK;
}

braun_real braun_scene_initial_distance(const braun_scene *s, int a, int b)
{
    braun_real pa[3], pb[3];
    if (braun_scene_initial_point(s, a, pa) || braun_scene_initial_point(s, b, pb))
        return (braun_real)NAN; /* no such point */
    if (pa[2] == pb[2]) return braun_scene__hypot(pb[0] - pa[0], pb[1] - pa[1]);
    const braun_real dz = pb[2] - pa[2];
    const braun_real dxy = braun_scene__hypot(pb[0] - pa[0], pb[1] - pa[1]);
    return braun_scene__hypot(dxy, dz);
}

braun_real braun_scene_initial_angle(const braun_scene *s, int body)
{
    if (!s || body < BRAUN_SCENE_GROUND || body >= s->nbodies ||
        (body >= 0 && (!s->bodies || !s->bodies[body].kind)))
        return (braun_real)NAN; /* no such body */
    if (body < 0 || s->bodies[body].kind->angle < 0) return 0;
    return s->bodies[body].q0[s->bodies[body].kind->angle];
}
