/* The study's mechanisms as C scenes (spatial_models.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spatial_models.h"

#define PI 3.14159265358979323846

typedef struct builder {
    spatial_model *m;
    const braun_scene_body_class *rigid;
    int nb, np, nj, ne;
} builder;

/* A bar of length L, square section a, mass m along the body axis `along`
 * (0: x, 1: y, 2: z), identity orientation unless quat is given. */
static int bar(builder *b, double m, double L, double a, int along, const double *c,
               const double *quat, const double *v, const double *w)
{
    braun_scene_body *bd = &b->m->bodies[b->nb];
    memset(bd, 0, sizeof *bd);
    bd->kind = b->rigid;
    bd->mass = m;
    for (int k = 0; k < 3; k++) bd->tensor[k] = m * (L * L + a * a) / 12;
    bd->tensor[along] = m * (2 * a * a) / 12;
    for (int k = 0; k < 3; k++) bd->q0[k] = c[k];
    bd->q0[3] = 1;
    if (quat)
        for (int k = 0; k < 4; k++) bd->q0[3 + k] = quat[k];
    for (int k = 0; k < 3; k++) {
        bd->v0[k] = v ? v[k] : 0;
        bd->v0[3 + k] = w ? w[k] : 0;
    }
    return b->nb++;
}

static int particle(builder *b, double m, const double *c, const double *v)
{
    braun_scene_body *bd = &b->m->bodies[b->nb];
    memset(bd, 0, sizeof *bd);
    bd->kind = BRAUN_BODY_PARTICLE3D;
    bd->mass = m;
    for (int k = 0; k < 3; k++) bd->q0[k] = c[k], bd->v0[k] = v ? v[k] : 0;
    return b->nb++;
}

static int point(builder *b, int body, double x, double y, double z)
{
    b->m->points[b->np] = (braun_scene_point){body, x, y, z};
    return b->np++;
}

static void joint(builder *b, const braun_scene_joint_class *type, int a, int pb,
                  const double *axis)
{
    braun_scene_joint *j = &b->m->joints[b->nj++];
    memset(j, 0, sizeof *j);
    j->type = type;
    j->a = a;
    j->b = pb;
    for (int k = 0; k < 3; k++) j->axis[k] = axis ? axis[k] : 0;
}

static braun_scene_effect *effect(builder *b, const braun_scene_effect_class *type)
{
    braun_scene_effect *e = &b->m->effects[b->ne++];
    memset(e, 0, sizeof *e);
    e->type = type;
    return e;
}

static void gravity(builder *b)
{
    effect(b, BRAUN_EFFECT_GRAVITY)->g[1] = -9.81;
}

/* Bricard: joints J0..J5 at the cube's corners (0,0,0), (1,0,0), (1,1,0),
 * (1,1,1), (0,1,1), (0,0,1); bar k from J(k-1) to J(k), k = 1..5, the
 * ground the sixth link J5-J0. The axis at each corner is ⊥ both edges
 * meeting there: y, z, x, y, z, x. */
static void bricard(builder *b)
{
    static const double J[6][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, {0, 0, 1}};
    static const double axes[6][3] = {{0, 1, 0}, {0, 0, 1}, {1, 0, 0},
                                      {0, 1, 0}, {0, 0, 1}, {1, 0, 0}};
    int pa[6], pb[6];
    for (int k = 1; k <= 5; k++) {
        double c[3], d[3];
        int along = 0;
        for (int i = 0; i < 3; i++) {
            c[i] = (J[k - 1][i] + J[k][i]) / 2;
            d[i] = J[k][i] - J[k - 1][i];
            if (d[i] != 0) along = i;
        }
        const int body = bar(b, 1, 1, 0.1, along, c, NULL, NULL, NULL);
        pa[k] = point(b, body, -d[0] / 2, -d[1] / 2, -d[2] / 2);
        pb[k] = point(b, body, d[0] / 2, d[1] / 2, d[2] / 2);
    }
    const int g0 = point(b, BRAUN_SCENE_GROUND, J[0][0], J[0][1], J[0][2]);
    const int g5 = point(b, BRAUN_SCENE_GROUND, J[5][0], J[5][1], J[5][2]);
    joint(b, BRAUN_JOINT_REVOLUTE3D, pa[1], g0, axes[0]);
    for (int k = 1; k <= 4; k++) joint(b, BRAUN_JOINT_REVOLUTE3D, pb[k], pa[k + 1], axes[k]);
    joint(b, BRAUN_JOINT_REVOLUTE3D, pb[5], g5, axes[5]);
    gravity(b);
    b->m->tracked = 5;
}

static void cross(const double *a, const double *c, double *out)
{
    out[0] = a[1] * c[2] - a[2] * c[1];
    out[1] = a[2] * c[0] - a[0] * c[2];
    out[2] = a[0] * c[1] - a[1] * c[0];
}

static void governor(builder *b)
{
    const double W[3] = {0, 2 * PI, 0}, alpha = 30 * PI / 180, rho = 3000;
    const double mb = rho * 1 * 0.01 * 0.01, ms = rho * 0.1 * 0.1 * 0.1;
    double c[3], v[3];
    /* shaft along y, 0 .. 1 */
    c[0] = 0, c[1] = 0.5, c[2] = 0;
    cross(W, c, v);
    const int shaft = bar(b, mb, 1, 0.01, 1, c, NULL, v, W);
    const int s_bottom = point(b, shaft, 0, -0.5, 0), s_top = point(b, shaft, 0, 0.5, 0);
    const int s_c = point(b, shaft, 0, 0, 0);
    int tops[2], mids[2], ends[2];
    for (int side = 0; side < 2; side++) {
        const double sg = side ? -1 : 1;
        const double d[3] = {sg * sin(alpha), -cos(alpha), 0};
        /* body x along d: a turn about z by atan2(d_y, d_x) */
        const double phi = atan2(d[1], d[0]);
        const double quat[4] = {cos(phi / 2), 0, 0, sin(phi / 2)};
        for (int i = 0; i < 3; i++) c[i] = (i == 1 ? 1 : 0) + 0.5 * d[i];
        cross(W, c, v);
        const int arm = bar(b, mb, 1, 0.01, 0, c, quat, v, W);
        tops[side] = point(b, arm, -0.5, 0, 0);
        mids[side] = point(b, arm, 0, 0, 0);
        ends[side] = point(b, arm, 0.5, 0, 0);
    }
    c[0] = 0, c[1] = 1 - 2 * 0.5 * cos(alpha), c[2] = 0;
    cross(W, c, v);
    const int slider = bar(b, ms, 0.1, 0.1, 1, c, NULL, v, W);
    const int sl_c = point(b, slider, 0, 0, 0);
    int masses[2];
    for (int side = 0; side < 2; side++) {
        const double sg = side ? -1 : 1;
        const double e[3] = {sg * sin(alpha), 1 - cos(alpha), 0};
        cross(W, e, v);
        masses[side] = point(b, particle(b, 5, e, v), 0, 0, 0);
    }
    const double Y[3] = {0, 1, 0}, Z[3] = {0, 0, 1};
    joint(b, BRAUN_JOINT_REVOLUTE3D, s_bottom, point(b, BRAUN_SCENE_GROUND, 0, 0, 0), Y);
    for (int side = 0; side < 2; side++) {
        joint(b, BRAUN_JOINT_REVOLUTE3D, tops[side], s_top, Z);
        joint(b, BRAUN_JOINT_SPHERICAL, ends[side], masses[side], NULL);
    }
    joint(b, BRAUN_JOINT_PRISMATIC3D, sl_c, s_c, Y);
    for (int side = 0; side < 2; side++) {
        braun_scene_effect *e = effect(b, BRAUN_EFFECT_SPRING);
        e->a = mids[side];
        e->b = sl_c;
        e->k = 8e5;
        e->c = 4e4;
        e->rest = 0.5;
    }
    gravity(b);
    b->m->tracked = b->nb;
}

/* hinged: revolute joints about z instead of spherical ones, turning
 * about z (a planar chain in 3-D). */
static void chain(builder *b, int N, int hinged)
{
    const double W[3] = {0, hinged ? 0 : 1, hinged ? 1 : 0}, Z[3] = {0, 0, 1};
    int prev = point(b, BRAUN_SCENE_GROUND, 0, 0, 0);
    for (int k = 0; k < N; k++) {
        double c[3] = {k + 0.5, 0, 0}, v[3];
        cross(W, c, v);
        const int body = bar(b, 1, 1, 0.1, 0, c, NULL, v, W);
        joint(b, hinged ? BRAUN_JOINT_REVOLUTE3D : BRAUN_JOINT_SPHERICAL,
              point(b, body, -0.5, 0, 0), prev, hinged ? Z : NULL);
        prev = point(b, body, 0.5, 0, 0);
    }
    gravity(b);
    b->m->tracked = N;
}

int spatial_model_make(spatial_model *m, const char *name, int N,
                       const braun_scene_body_class *rigid, braun_system *sys)
{
    const int cap = N > 8 ? N + 8 : 16;
    memset(m, 0, sizeof *m);
    m->bodies = calloc((size_t)cap, sizeof *m->bodies);
    m->points = calloc((size_t)(3 * cap), sizeof *m->points);
    m->joints = calloc((size_t)cap, sizeof *m->joints);
    m->effects = calloc(8, sizeof *m->effects);
    if (!m->bodies || !m->points || !m->joints || !m->effects) return -1;
    builder b = {m, rigid, 0, 0, 0, 0};
    if (strcmp(name, "bricard") == 0) bricard(&b);
    else if (strcmp(name, "governor") == 0) governor(&b);
    else if (strcmp(name, "chain") == 0) chain(&b, N, 0);
    else if (strcmp(name, "hinge-chain") == 0) chain(&b, N, 1);
    else return -1;
    braun_scene *s = &m->scene;
    s->nbodies = b.nb, s->bodies = m->bodies;
    s->npoints = b.np, s->points = m->points;
    s->njoints = b.nj, s->joints = m->joints;
    s->neffects = b.ne, s->effects = m->effects;
    braun_scene_error err;
    if (braun_scene_defaults(s) || braun_scene_build(s, sys, &err)) {
        fprintf(stderr, "%s: build failed: element %d #%d: %s\n", name, err.element, err.index,
                err.what ? err.what : "?");
        return -1;
    }
    return 0;
}

void spatial_model_free(spatial_model *m)
{
    free(m->bodies);
    free(m->points);
    free(m->joints);
    free(m->effects);
}
