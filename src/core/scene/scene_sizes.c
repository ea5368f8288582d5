/* Each coordinate's typical size (braun_scene_coordinate_sizes): what a
 * finite difference or an absolute tolerance should be measured against.
 * A program's constant 1 is 1 m, which is larger than a 1 µm mechanism
 * (braun_check_callbacks stepped 6e-6 m through it) and nothing next to a
 * 1e6 m one: the scene's own lengths are in the unit it was written in. */
#include "scene_internal.h"

/* Lengths of a body below this part of its largest are taken as points
 * that coincide (a revolute joint's two points, to the state's residual),
 * not as a size. */
#define SIZE_COINCIDE BRAUN_R(1e-6)

static braun_real dist(const braun_real *a, const braun_real *b)
{
    const braun_real dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return braun_sqrt(dx * dx + dy * dy + dz * dz);
}

/* The body's origin at q (its own coordinates' point 0: a particle's
 * position, a rigid body's centre), whose partials say which coordinates
 * are lengths. */
static void origin(const braun_scene_body *bd, int b, const braun_real *q, scene_pt *P)
{
    const braun_scene_point o = {b, 0, 0, 0};
    P->body = bd;
    P->col = bd->iq;
    P->direction = 0;
    for (int k = 0; k < 3; k++) P->vel[k] = P->cc[k] = 0;
    bd->kind->point(bd, &o, q + bd->iq, NULL, P);
}

/* The point references of an element (its POINT and BODY_POINT fields),
 * at most 4, into pts; their count. */
static int element_points(const braun_scene_field *f, const void *elem, int *pts)
{
    int k = 0;
    for (; f && f->key && k < 4; f++)
        if (f->kind == BRAUN_FIELD_POINT || f->kind == BRAUN_FIELD_BODY_POINT)
            pts[k++] = *(const int *)(const void *)((const char *)elem + f->offset);
    return k;
}

/* The largest distance between an element's points at q (0 if none of them
 * is on body b, or it has fewer than two). */
static braun_real element_length(const braun_scene *s, int b, const int *pts, int count,
                                 const braun_real *q)
{
    int touches = 0;
    for (int i = 0; i < count; i++)
        if (pts[i] >= 0 && pts[i] < s->npoints && s->points[pts[i]].body == b) touches = 1;
    if (!touches || count < 2) return 0;
    braun_real pos[4][3], len = 0;
    for (int i = 0; i < count; i++) {
        scene_pt P;
        if (pts[i] < 0 || pts[i] >= s->npoints) return 0;
        braun_scene__point(s, pts[i], q, NULL, &P);
        for (int k = 0; k < 3; k++) pos[i][k] = P.pos[k];
        for (int j = 0; j < i; j++) {
            const braun_real d = dist(pos[i], pos[j]);
            if (d > len) len = d;
        }
    }
    return len;
}

/* Body b's lengths at q — its points' distances from its origin, and the
 * lengths of the rods, joints and effects with a point on it — folded by
 * `pass`: 0 the largest, 1 the smallest above `floor`. */
static braun_real body_length(const braun_scene *s, int b, const braun_real *q, const braun_real *o,
                              int pass, braun_real floor)
{
    braun_real best = 0;
    int pts[4];
#define FOLD(len)                                                                        \
    do {                                                                                 \
        const braun_real len_ = (len);                                                   \
        if (pass == 0 ? len_ > best : len_ > floor && (best == 0 || len_ < best)) best = len_; \
    } while (0)
    for (int i = 0; i < s->npoints; i++) {
        if (s->points[i].body != b) continue;
        scene_pt P;
        braun_scene__point(s, i, q, NULL, &P);
        FOLD(dist(P.pos, o));
    }
    for (int i = 0; i < s->nrods; i++) {
        pts[0] = s->rods[i].a;
        pts[1] = s->rods[i].b;
        FOLD(element_length(s, b, pts, 2, q));
    }
    for (int i = 0; i < s->njoints; i++) {
        const braun_scene_joint *j = &s->joints[i];
        FOLD(element_length(s, b, pts, element_points(j->type->fields, j, pts), q));
    }
    for (int i = 0; i < s->neffects; i++) {
        const braun_scene_effect *e = &s->effects[i];
        FOLD(element_length(s, b, pts, element_points(e->type->fields, e, pts), q));
    }
#undef FOLD
    return best;
}

int braun_scene_coordinate_sizes(const braun_scene *s, const braun_real *q, braun_real *size)
{
    if (!s || !q || !size || s->n <= 0 || (s->nbodies > 0 && !s->bodies)) return BRAUN_ERR_ARGUMENT;
    /* Each body's length into its first coordinate's slot (every body has
     * one), then the sizes from it. */
    braun_real fallback = 0;
    for (int b = 0; b < s->nbodies; b++) {
        const braun_scene_body *bd = &s->bodies[b];
        scene_pt O;
        origin(bd, b, q, &O);
        const braun_real largest = body_length(s, b, q, O.pos, 0, 0);
        const braun_real len = body_length(s, b, q, O.pos, 1, SIZE_COINCIDE * largest);
        size[bd->iq] = len;
        if (len > 0 && (fallback == 0 || len < fallback)) fallback = len;
    }
    /* A body with no length of its own (a free particle) takes the
     * scene's smallest; a scene with none, 1. */
    if (!(fallback > 0)) fallback = 1;
    for (int b = 0; b < s->nbodies; b++) {
        const braun_scene_body *bd = &s->bodies[b];
        const braun_real len = size[bd->iq] > 0 ? size[bd->iq] : fallback;
        scene_pt O;
        origin(bd, b, q, &O);
        /* |∂O/∂q_c|: 1 for a coordinate that moves the origin (a length),
         * 0 for one that turns the body (an angle, an Euler parameter:
         * their size is 1). */
        braun_real row[BRAUN_SCENE_MAX_DOF], a2[BRAUN_SCENE_MAX_DOF] = {0};
        for (int k = 0; k < 3; k++) {
            const braun_real g[3] = {(braun_real)(k == 0), (braun_real)(k == 1), (braun_real)(k == 2)};
            for (int c = 0; c < bd->kind->dof; c++) row[c] = 0;
            bd->kind->grad(&O, g, row);
            for (int c = 0; c < bd->kind->dof; c++) a2[c] += row[c] * row[c];
        }
        for (int c = 0; c < bd->kind->dof; c++)
            size[bd->iq + c] = a2[c] > 0 ? len / braun_sqrt(a2[c]) : 1;
    }
    return BRAUN_OK;
}

/* Whether coordinate c of a body of class k is a length (braun_scene.h,
 * braun_scene_natural_sizes). */
static int is_length(const braun_scene_body_class *k, int c)
{
    return c < k->dim && c != k->angle;
}

int braun_scene_natural_sizes(const braun_scene *s, const braun_real *q, braun_real *size)
{
    if (!s || !q || !size || s->n <= 0 || (s->nbodies > 0 && !s->bodies)) return BRAUN_ERR_ARGUMENT;
    braun_real lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = BRAUN_MAXREAL;
        hi[k] = -BRAUN_MAXREAL;
    }
    for (int i = 0; i < s->npoints; i++) {
        scene_pt P;
        braun_scene__point(s, i, q, NULL, &P);
        for (int k = 0; k < 3; k++) {
            if (P.pos[k] < lo[k]) lo[k] = P.pos[k];
            if (P.pos[k] > hi[k]) hi[k] = P.pos[k];
        }
    }
    for (int b = 0; b < s->nbodies; b++) {
        const braun_scene_body *bd = &s->bodies[b];
        for (int c = 0; c < bd->kind->dof && c < 3; c++) {
            if (!is_length(bd->kind, c)) continue;
            const braun_real x = q[bd->iq + c];
            if (x < lo[c]) lo[c] = x;
            if (x > hi[c]) hi[c] = x;
        }
    }
    braun_real l2 = 0;
    for (int k = 0; k < 3; k++)
        if (hi[k] >= lo[k]) l2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    braun_real len = braun_sqrt(l2);
    if (!(len > 0) || !(len <= BRAUN_MAXREAL)) len = 1;
    for (int b = 0; b < s->nbodies; b++) {
        const braun_scene_body *bd = &s->bodies[b];
        for (int c = 0; c < bd->kind->dof; c++) size[bd->iq + c] = is_length(bd->kind, c) ? len : 1;
    }
    return BRAUN_OK;
}
