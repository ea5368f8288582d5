/* A spatial target's mechanism for the peer engines (cmp_mech3.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_mech.h"
#include "cmp_mech3.h"
#ifdef CMP_HAVE_SCENES
#include "braun_scene_file.h"
#endif

/* ------------------------------------------------------------ rotations */
void cmp_quat_rotate(const double *p, const double *x, double *y)
{
    const double w = p[0], a = p[1], b = p[2], c = p[3];
    y[0] = (w * w + a * a - b * b - c * c) * x[0] + 2 * (a * b - w * c) * x[1] +
           2 * (a * c + w * b) * x[2];
    y[1] = 2 * (a * b + w * c) * x[0] + (w * w - a * a + b * b - c * c) * x[1] +
           2 * (b * c - w * a) * x[2];
    y[2] = 2 * (a * c - w * b) * x[0] + 2 * (b * c + w * a) * x[1] +
           (w * w - a * a - b * b + c * c) * x[2];
}

void cmp_quat_rotate_inv(const double *p, const double *x, double *y)
{
    const double pc[4] = {p[0], -p[1], -p[2], -p[3]};
    cmp_quat_rotate(pc, x, y);
}

void cmp_quat_mul(const double *a, const double *b, double *c)
{
    const double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    const double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    const double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    const double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
    c[0] = w;
    c[1] = x;
    c[2] = y;
    c[3] = z;
}

void cmp_mech3_point0(const cmp_mech3 *m, int b, const double *p, double *P)
{
    if (b < 0) {
        memcpy(P, p, 3 * sizeof(double));
        return;
    }
    const cmp_body3 *B = &m->bodies[b];
    cmp_quat_rotate(B->quat, p, P);
    for (int k = 0; k < 3; k++) P[k] += B->pos[k];
}

void cmp_mech3_velocity0(const cmp_mech3 *m, int b, const double *P, double *v)
{
    if (b < 0) {
        v[0] = v[1] = v[2] = 0;
        return;
    }
    const cmp_body3 *B = &m->bodies[b];
    const double *w = B->omega, r[3] = {P[0] - B->pos[0], P[1] - B->pos[1], P[2] - B->pos[2]};
    v[0] = B->vel[0] + w[1] * r[2] - w[2] * r[1];
    v[1] = B->vel[1] + w[2] * r[0] - w[0] * r[2];
    v[2] = B->vel[2] + w[0] * r[1] - w[1] * r[0];
}

void cmp_mech3_free(cmp_mech3 *m)
{
    free(m->bodies);
    free(m->joints);
    free(m->forces);
    memset(m, 0, sizeof *m);
}

void cmp_mech3_state(const cmp_mech3 *m, const double *pose, double *q, double *v)
{
    for (int b = 0; b < m->nbodies; b++) {
        const double *s = pose + 13 * b;
        double *qb = q + m->bodies[b].iq, *vb = v + m->bodies[b].iq;
        if (m->bodies[b].point_mass) {
            for (int k = 0; k < 3; k++) {
                qb[k] = s[k];
                vb[k] = s[7 + k];
            }
            continue;
        }
        const double dot = s[3] * qb[3] + s[4] * qb[4] + s[5] * qb[5] + s[6] * qb[6];
        const double sg = dot < 0 ? -1 : 1;
        for (int k = 0; k < 3; k++) {
            qb[k] = s[k];
            vb[k] = s[7 + k];
        }
        for (int k = 0; k < 4; k++) qb[3 + k] = sg * s[3 + k];
        /* ṗ = ½ Eᵀ ω, E = [-e, e0 I + ẽ] (scene_rigid3d.c). */
        const double e0 = qb[3], e1 = qb[4], e2 = qb[5], e3 = qb[6];
        const double wx = s[10], wy = s[11], wz = s[12];
        vb[3] = 0.5 * (-e1 * wx - e2 * wy - e3 * wz);
        vb[4] = 0.5 * (e0 * wx + e3 * wy - e2 * wz);
        vb[5] = 0.5 * (-e3 * wx + e0 * wy + e1 * wz);
        vb[6] = 0.5 * (e2 * wx - e1 * wy + e0 * wz);
    }
}

int cmp_target_is_spatial(const cmp_target *tg)
{
#ifdef CMP_HAVE_SCENES
    const braun_scene_file *sf = tg->scene_file;
    return sf && sf->scene.dim == 3;
#else
    (void)tg;
    return 0;
#endif
}

/* ------------------------------------------------------------ the tree */
static int priority(int kind)
{
    return kind == CMP_J3_REVOLUTE || kind == CMP_J3_PRISMATIC ? 0 : kind == CMP_J3_WELD ? 1 : 2;
}

int cmp_mech3_tree(cmp_mech3 *m, char *why, size_t whysize)
{
    const int nb = m->nbodies;
    char *seen = calloc((size_t)nb + 1, 1);
    if (!seen) {
        snprintf(why, whysize, "out of memory");
        return -1;
    }
#define SEEN(b) ((b) < 0 || seen[b])
    for (int i = 0; i < nb; i++) m->bodies[i].parent = m->bodies[i].joint = -1;
    for (int j = 0; j < m->njoints; j++) m->joints[j].tree = 0;
    for (int done = 0; done < nb;) {
        int best = -1, child = -1;
        for (int j = 0; j < m->njoints; j++) {
            const cmp_joint3 *J = &m->joints[j];
            if (J->tree || SEEN(J->a) == SEEN(J->b)) continue;
            if (best < 0 || priority(J->kind) < priority(m->joints[best].kind)) {
                best = j;
                child = SEEN(J->a) ? J->b : J->a;
            }
        }
        if (best < 0) {
            /* No joint reaches an unseen body from the seen ones: the
             * first unseen body is a free root. */
            for (int i = 0; i < nb; i++)
                if (!seen[i]) {
                    seen[i] = 1;
                    done++;
                    break;
                }
            continue;
        }
        cmp_joint3 *J = &m->joints[best];
        J->tree = 1;
        m->bodies[child].joint = best;
        m->bodies[child].parent = child == J->a ? J->b : J->a;
        seen[child] = 1;
        done++;
    }
#undef SEEN
    free(seen);
    return 0;
}

void cmp_mech3_order(const cmp_mech3 *m, int *order)
{
    if (m->nbodies > 0)
        cmp_parents_first(m->nbodies, &m->bodies[0].parent, sizeof *m->bodies, order);
}

/* ------------------------------------------------------------ from a scene */
#ifdef CMP_HAVE_SCENES
static int grow(void **v, int n, size_t size)
{
    if (n % 16) return 0;
    void *w = realloc(*v, (size_t)(n + 16) * size);
    if (!w) return -1;
    *v = w;
    return 0;
}

static const char *name_of(const char **names, int i, const char *fallback)
{
    return names && names[i] ? names[i] : fallback;
}

/* Scene point k as (body, point in the body's frame); -2: not a rigid3d. */
static int resolve(const braun_scene *s, const int *body_of, int k, double *p)
{
    const braun_scene_point *pt = &s->points[k];
    p[0] = pt->x;
    p[1] = pt->y;
    p[2] = pt->z;
    if (pt->body == BRAUN_SCENE_GROUND) return -1;
    return body_of[pt->body];
}

static int convert(const braun_scene_file *sf, const double *q0, const double *v0, cmp_mech3 *m,
                   int *body_of, char *why, size_t whysize)
{
    const braun_scene *s = &sf->scene;
    for (int i = 0; i < s->nbodies; i++) {
        const braun_scene_body *b = &s->bodies[i];
        body_of[i] = -2;
        const int point = b->kind == BRAUN_BODY_PARTICLE3D;
        if ((b->kind != BRAUN_BODY_RIGID3D && !point) || !(b->mass > 0)) {
            snprintf(why, whysize, "body '%s' (%s%s) has no counterpart in the peer model yet",
                     name_of(sf->body_names, i, "body"), b->mass > 0 ? "" : "massless ",
                     b->kind->name);
            return -1;
        }
        if (grow((void **)&m->bodies, m->nbodies, sizeof *m->bodies)) goto oom;
        cmp_body3 *B = &m->bodies[m->nbodies];
        memset(B, 0, sizeof *B);
        body_of[i] = m->nbodies++;
        snprintf(B->name, sizeof B->name, "%s", name_of(sf->body_names, i, "body"));
        B->mass = b->mass;
        B->point_mass = point;
        B->iq = b->iq;
        B->parent = B->joint = -1;
        const double *q = q0 + b->iq, *v = v0 + b->iq;
        if (point) {
            for (int k = 0; k < 3; k++) {
                B->pos[k] = q[k];
                B->vel[k] = v[k];
            }
            B->quat[0] = 1;
            continue;
        }
        for (int k = 0; k < 6; k++) B->inertia[k] = b->tensor[k];
        const double norm = sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);
        for (int k = 0; k < 3; k++) {
            B->pos[k] = q[k];
            B->vel[k] = v[k];
        }
        for (int k = 0; k < 4; k++) B->quat[k] = q[3 + k] / norm;
        /* ω = 2 E(p) ṗ/|p|² (scene_rigid3d.c), with e = p/|p|: 2 E(e) ṗ/|p|. */
        const double *e = B->quat, *d = v + 3;
        B->omega[0] = 2 * (-e[1] * d[0] + e[0] * d[1] - e[3] * d[2] + e[2] * d[3]) / norm;
        B->omega[1] = 2 * (-e[2] * d[0] + e[3] * d[1] + e[0] * d[2] - e[1] * d[3]) / norm;
        B->omega[2] = 2 * (-e[3] * d[0] - e[2] * d[1] + e[1] * d[2] + e[0] * d[3]) / norm;
    }
    if (s->nrods > 0) {
        snprintf(why, whysize, "rods have no counterpart in the spatial peer model yet");
        return -1;
    }
    for (int i = 0; i < s->njoints; i++) {
        const braun_scene_joint *sj = &s->joints[i];
        const char *jn = name_of(sf->joint_names, i, "joint");
        int kind;
        if (sj->type == BRAUN_JOINT_SPHERICAL) kind = CMP_J3_SPHERICAL;
        else if (sj->type == BRAUN_JOINT_REVOLUTE3D && !sj->driven) kind = CMP_J3_REVOLUTE;
        else if (sj->type == BRAUN_JOINT_WELD) kind = CMP_J3_WELD;
        else if (sj->type == BRAUN_JOINT_PRISMATIC3D && !sj->driven) kind = CMP_J3_PRISMATIC;
        else {
            snprintf(why, whysize, "joint '%s' (%s%s) has no counterpart in the spatial peer model yet",
                     jn, sj->driven ? "driven " : "", sj->type->name);
            return -1;
        }
        if (grow((void **)&m->joints, m->njoints, sizeof *m->joints)) goto oom;
        cmp_joint3 *J = &m->joints[m->njoints++];
        memset(J, 0, sizeof *J);
        J->kind = kind;
        snprintf(J->name, sizeof J->name, "%s", jn);
        J->a = resolve(s, body_of, sj->a, J->pa);
        J->b = resolve(s, body_of, sj->b, J->pb);
        for (int k = 0; k < 3; k++) {
            J->axis[k] = sj->axis[k];
            J->axis_b[k] = sj->axis_b[k];
        }
        if (kind == CMP_J3_PRISMATIC) {
            /* The line's axis is on b's body; a's frame sees it turned by
             * their (fixed) relative orientation. */
            const double *qa = J->a >= 0 ? m->bodies[J->a].quat : NULL;
            const double *qb = J->b >= 0 ? m->bodies[J->b].quat : NULL;
            double w[3];
            if (qb) cmp_quat_rotate(qb, sj->axis, w);
            else memcpy(w, sj->axis, sizeof w);
            if (qa) cmp_quat_rotate_inv(qa, w, J->axis);
            else memcpy(J->axis, w, sizeof w);
            memcpy(J->axis_b, sj->axis, sizeof w);
        }
        if (J->a == J->b) {
            snprintf(why, whysize, "joint '%s' connects a body to itself", jn);
            return -1;
        }
        if (kind != CMP_J3_SPHERICAL && ((J->a >= 0 && m->bodies[J->a].point_mass) ||
                                         (J->b >= 0 && m->bodies[J->b].point_mass))) {
            snprintf(why, whysize, "joint '%s' (%s) holds the orientation of a particle3d, which has none",
                     jn, sj->type->name);
            return -1;
        }
    }
    for (int i = 0; i < s->neffects; i++) {
        const braun_scene_effect *se = &s->effects[i];
        if (grow((void **)&m->forces, m->nforces, sizeof *m->forces)) goto oom;
        cmp_force3 *F = &m->forces[m->nforces];
        memset(F, 0, sizeof *F);
        if (se->type == BRAUN_EFFECT_GRAVITY) {
            F->kind = CMP_F3_GRAVITY;
            for (int k = 0; k < 3; k++) F->g[k] = se->g[k];
        } else if (se->type == BRAUN_EFFECT_SPRING) {
            F->kind = CMP_F3_SPRING;
            F->a = resolve(s, body_of, se->a, F->pa);
            F->b = resolve(s, body_of, se->b, F->pb);
            F->k = se->k;
            F->c = se->c;
            F->rest = se->rest;
        } else if (se->type == BRAUN_EFFECT_TORSION3D &&
                   s->joints[se->a].type == BRAUN_JOINT_REVOLUTE3D) {
            F->kind = CMP_F3_TORSION;
            F->joint = se->a;
            F->k = se->k;
            F->c = se->c;
            F->rest = se->rest;
        } else {
            snprintf(why, whysize, "effect '%s' (%s) has no counterpart in the spatial peer model yet",
                     name_of(sf->effect_names, i, "effect"), se->type->name);
            return -1;
        }
        m->nforces++;
    }
    m->n = s->n;
    return 0;
oom:
    snprintf(why, whysize, "out of memory");
    return -1;
}
#endif

int cmp_mech3_for_target(const cmp_target *tg, cmp_mech3 *m, char *why, size_t whysize)
{
    memset(m, 0, sizeof *m);
#ifdef CMP_HAVE_SCENES
    if (!cmp_target_is_spatial(tg)) {
        snprintf(why, whysize, "'%s' is not a spatial scene", tg->name);
        return -1;
    }
    const braun_scene_file *sf = tg->scene_file;
    int *body_of = malloc(((size_t)sf->scene.nbodies + 1) * sizeof(int));
    int rc = -1;
    if (!body_of) snprintf(why, whysize, "out of memory");
    else rc = convert(sf, tg->q0, tg->v0, m, body_of, why, whysize);
    free(body_of);
    if (rc) cmp_mech3_free(m);
    return rc;
#else
    (void)tg;
    snprintf(why, whysize, "peer models need the scene library");
    return -1;
#endif
}
