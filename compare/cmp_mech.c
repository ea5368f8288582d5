/* A target's mechanism for the peer engines (cmp_mech.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_mech.h"
#include "cmp_mech3.h"
#ifdef CMP_HAVE_SCENES
#include "braun_scene_file.h"
#endif

void cmp_mech_free(cmp_mech *m)
{
    if (m->spatial) cmp_mech3_free(m->spatial);
    free(m->spatial);
    free(m->links);
    free(m->joints);
    free(m->forces);
    free(m->out);
    memset(m, 0, sizeof *m);
}

double cmp_mech_unwrap(double prev, double th)
{
    const double two_pi = 6.283185307179586;
    return th + two_pi * floor((prev - th) / two_pi + 0.5);
}

void cmp_mech_point(const double *pose, int l, const double *p, double *xy)
{
    if (l < 0) {
        xy[0] = p[0];
        xy[1] = p[1];
        return;
    }
    const double *s = pose + 6 * l, c = cos(s[2]), sn = sin(s[2]);
    xy[0] = s[0] + c * p[0] - sn * p[1];
    xy[1] = s[1] + sn * p[0] + c * p[1];
}

void cmp_mech_state(const cmp_mech *m, const double *pose, double *q, double *v)
{
    for (int i = 0; i < m->n; i++) {
        const cmp_mout *o = &m->out[i];
        const double *s = pose + 6 * o->link;
        if (o->kind == CMP_OUT_ANGLE) {
            q[i] = s[2] + o->offset;
            v[i] = s[5];
            continue;
        }
        /* P = c + R p, P' = c' + ω × (R p). */
        const double c = cos(s[2]), sn = sin(s[2]);
        const double rx = c * o->p[0] - sn * o->p[1], ry = sn * o->p[0] + c * o->p[1];
        if (o->kind == CMP_OUT_X) {
            q[i] = s[0] + rx;
            v[i] = s[3] - s[5] * ry;
        } else {
            q[i] = s[1] + ry;
            v[i] = s[4] + s[5] * rx;
        }
    }
}

/* ------------------------------------------------------------ growing arrays */
static int grow(void **v, int n, size_t size)
{
    if (n % 16) return 0;
    void *w = realloc(*v, (size_t)(n + 16) * size);
    if (!w) return -1;
    *v = w;
    return 0;
}

static cmp_link *new_link(cmp_mech *m)
{
    if (grow((void **)&m->links, m->nlinks, sizeof *m->links)) return NULL;
    cmp_link *l = &m->links[m->nlinks++];
    memset(l, 0, sizeof *l);
    l->parent = -1;
    l->joint = -1;
    return l;
}

static cmp_mjoint *new_joint(cmp_mech *m, int kind, const char *name)
{
    if (grow((void **)&m->joints, m->njoints, sizeof *m->joints)) return NULL;
    cmp_mjoint *j = &m->joints[m->njoints++];
    memset(j, 0, sizeof *j);
    j->kind = kind;
    snprintf(j->name, sizeof j->name, "%s", name ? name : "joint");
    return j;
}

static cmp_mforce *new_force(cmp_mech *m, int kind)
{
    if (grow((void **)&m->forces, m->nforces, sizeof *m->forces)) return NULL;
    cmp_mforce *f = &m->forces[m->nforces++];
    memset(f, 0, sizeof *f);
    f->kind = kind;
    return f;
}

#ifdef CMP_HAVE_SCENES
/* ------------------------------------------------------------ from a scene */
typedef struct conv {
    const braun_scene_file *sf;
    const braun_scene *s;
    const double *q0, *v0;
    cmp_mech *m;
    int *body_link;    /* per body: its link, -1 for a massless particle */
    int *owner_rod;    /* per body: massless particle: the rod link it is the end of */
    double *owner_end; /* per body: that end's x in the rod's frame */
    int *rod_link;     /* per rod */
    unsigned flags;    /* CMP_MECH_TORQUE, ... */
} conv;

static const char *body_name(const conv *c, int i)
{
    return c->sf->body_names && c->sf->body_names[i] ? c->sf->body_names[i] : "body";
}

static const char *joint_name(const conv *c, int i)
{
    return c->sf->joint_names && c->sf->joint_names[i] ? c->sf->joint_names[i] : "joint";
}

/* World position and velocity of scene point k at (q0, v0). */
static void point_now(const conv *c, int k, double *xy, double *vxy)
{
    braun_real pos[3], vel[3];
    braun_scene_point_state(c->s, k, c->q0, c->v0, pos, vel);
    xy[0] = pos[0];
    xy[1] = pos[1];
    vxy[0] = vel[0];
    vxy[1] = vel[1];
}

/* Scene point k as (link, point in the link's frame). */
static int resolve_point(const conv *c, int k, double *p)
{
    const braun_scene_point *pt = &c->s->points[k];
    if (pt->body == BRAUN_SCENE_GROUND) {
        p[0] = pt->x;
        p[1] = pt->y;
        return -1;
    }
    const int b = pt->body;
    if (c->body_link[b] >= 0) {
        const int point_mass = c->s->bodies[b].kind == BRAUN_BODY_PARTICLE;
        p[0] = point_mass ? 0 : pt->x;
        p[1] = point_mass ? 0 : pt->y;
        return c->body_link[b];
    }
    p[0] = c->owner_end[b];
    p[1] = 0;
    return c->owner_rod[b];
}

/* A body (angle joints, torsion, motors) as a link: -1 ground, -2 none. */
static int resolve_body(const conv *c, int b)
{
    if (b == BRAUN_SCENE_GROUND) return -1;
    if (b < 0 || b >= c->s->nbodies || c->s->bodies[b].kind != BRAUN_BODY_RIGID) return -2;
    return c->body_link[b];
}

static int convert(conv *c, char *why, size_t whysize)
{
    const braun_scene *s = c->s;
    cmp_mech *m = c->m;
    if (s->dim != 2) {
        snprintf(why, whysize, "a spatial scene: its peer model is cmp_mech3.h's");
        return -1;
    }
    /* Links: bodies with mass, then rods. */
    for (int i = 0; i < s->nbodies; i++) {
        const braun_scene_body *b = &s->bodies[i];
        const double *q = c->q0 + b->iq, *v = c->v0 + b->iq;
        c->body_link[i] = -1;
        c->owner_rod[i] = -1;
        if (b->kind == BRAUN_BODY_PARTICLE && !(b->mass > 0)) continue;
        if (b->kind != BRAUN_BODY_RIGID && b->kind != BRAUN_BODY_PARTICLE) {
            snprintf(why, whysize, "body '%s' (%s) has no counterpart in the peer model",
                     body_name(c, i), b->kind->name);
            return -1;
        }
        cmp_link *l = new_link(m);
        if (!l) goto oom;
        c->body_link[i] = m->nlinks - 1;
        snprintf(l->name, sizeof l->name, "%s", body_name(c, i));
        l->mass = b->mass;
        l->x = q[0];
        l->y = q[1];
        l->vx = v[0];
        l->vy = v[1];
        if (b->kind == BRAUN_BODY_RIGID) {
            l->inertia = b->inertia;
            l->th = q[2];
            l->w = v[2];
        } else {
            l->point_mass = 1;
        }
    }
    for (int r = 0; r < s->nrods; r++) {
        const braun_scene_rod *rod = &s->rods[r];
        double pa[2], pb[2], va[2], vb[2];
        point_now(c, rod->a, pa, va);
        point_now(c, rod->b, pb, vb);
        cmp_link *l = new_link(m);
        if (!l) goto oom;
        c->rod_link[r] = m->nlinks - 1;
        snprintf(l->name, sizeof l->name, "rod%d", r);
        const double dx = pb[0] - pa[0], dy = pb[1] - pa[1], d2 = dx * dx + dy * dy;
        l->mass = rod->mass;
        l->inertia = rod->mass * rod->length * rod->length / 12.0;
        l->x = 0.5 * (pa[0] + pb[0]);
        l->y = 0.5 * (pa[1] + pb[1]);
        l->th = atan2(dy, dx);
        l->vx = 0.5 * (va[0] + vb[0]);
        l->vy = 0.5 * (va[1] + vb[1]);
        l->w = (dx * (vb[1] - va[1]) - dy * (vb[0] - va[0])) / d2;
        /* A massless particle is the end of the first rod that reaches it. */
        const int ends[2] = {rod->a, rod->b};
        for (int e = 0; e < 2; e++) {
            const int body = s->points[ends[e]].body;
            if (body >= 0 && c->body_link[body] < 0 && c->owner_rod[body] < 0) {
                c->owner_rod[body] = c->rod_link[r];
                c->owner_end[body] = (e ? 0.5 : -0.5) * rod->length;
            }
        }
    }
    for (int i = 0; i < s->nbodies; i++)
        if (c->body_link[i] < 0 && c->owner_rod[i] < 0) {
            snprintf(why, whysize, "massless particle '%s' is on no rod", body_name(c, i));
            return -1;
        }
    /* A rod's ends: pinned to what they meet (unless they are that point's owner). */
    for (int r = 0; r < s->nrods; r++) {
        const braun_scene_rod *rod = &s->rods[r];
        const int ends[2] = {rod->a, rod->b};
        for (int e = 0; e < 2; e++) {
            const int body = s->points[ends[e]].body;
            const double x_end = (e ? 0.5 : -0.5) * rod->length;
            if (body >= 0 && c->owner_rod[body] == c->rod_link[r] && c->owner_end[body] == x_end)
                continue;
            cmp_mjoint *j = new_joint(m, CMP_MJ_REVOLUTE, "rod end");
            if (!j) goto oom;
            snprintf(j->name, sizeof j->name, "rod%d.%c", r, e ? 'b' : 'a');
            j->a = c->rod_link[r];
            j->pa[0] = x_end;
            j->b = resolve_point(c, ends[e], j->pb);
        }
    }
    for (int i = 0; i < s->njoints; i++) {
        const braun_scene_joint *sj = &s->joints[i];
        cmp_mjoint *j = NULL;
        const char *what = NULL;
        if (sj->type == BRAUN_JOINT_REVOLUTE) {
            if (!(j = new_joint(m, CMP_MJ_REVOLUTE, joint_name(c, i)))) goto oom;
            j->a = resolve_point(c, sj->a, j->pa);
            j->b = resolve_point(c, sj->b, j->pb);
        } else if (sj->type == BRAUN_JOINT_DISTANCE) {
            if (sj->driven) what = "a driven distance";
            else {
                if (!(j = new_joint(m, CMP_MJ_DISTANCE, joint_name(c, i)))) goto oom;
                j->a = resolve_point(c, sj->a, j->pa);
                j->b = resolve_point(c, sj->b, j->pb);
                j->length = sj->value;
            }
        } else if (sj->type == BRAUN_JOINT_SLIDER) {
            if (sj->driven) what = "a driven slider";
            else {
                if (!(j = new_joint(m, CMP_MJ_SLIDER, joint_name(c, i)))) goto oom;
                j->a = resolve_point(c, sj->a, j->pa);
                j->b = resolve_point(c, sj->b, j->pb);
                const double u = hypot(sj->axis[0], sj->axis[1]);
                j->axis[0] = sj->axis[0] / u;
                j->axis[1] = sj->axis[1] / u;
            }
        } else if (sj->type == BRAUN_JOINT_ANGLE) {
            if (!(j = new_joint(m, CMP_MJ_ANGLE, joint_name(c, i)))) goto oom;
            j->a = resolve_body(c, sj->a);
            j->b = resolve_body(c, sj->b);
            j->value = sj->value;
            j->driven = sj->driven;
            j->drive = sj->drive;
            if (j->a == -2 || j->b == -2) what = "an angle joint of a body without angle";
        } else if (sj->type == BRAUN_JOINT_KNIFE) {
            if (!(j = new_joint(m, CMP_MJ_KNIFE, joint_name(c, i)))) goto oom;
            j->a = resolve_point(c, sj->a, j->pa);
            const double u = hypot(sj->axis[0], sj->axis[1]);
            j->axis[0] = sj->axis[0] / u;
            j->axis[1] = sj->axis[1] / u;
            j->b = -1;
        } else {
            what = sj->type->name;
        }
        if (what) {
            snprintf(why, whysize, "joint '%s' (%s) has no counterpart in the peer model",
                     joint_name(c, i), what);
            return -1;
        }
    }
    for (int i = 0; i < s->neffects; i++) {
        const braun_scene_effect *se = &s->effects[i];
        cmp_mforce *f;
        if (se->type == BRAUN_EFFECT_GRAVITY) {
            if (!(f = new_force(m, CMP_MF_GRAVITY))) goto oom;
            f->g[0] = se->g[0];
            f->g[1] = se->g[1];
        } else if (se->type == BRAUN_EFFECT_SPRING) {
            if (!(f = new_force(m, CMP_MF_SPRING))) goto oom;
            f->a = resolve_point(c, se->a, f->pa);
            f->b = resolve_point(c, se->b, f->pb);
            f->k = se->k;
            f->c = se->c;
            f->rest = se->rest;
        } else if (se->type == BRAUN_EFFECT_TORSION || se->type == BRAUN_EFFECT_MOTOR) {
            if (!(f = new_force(m, se->type == BRAUN_EFFECT_MOTOR ? CMP_MF_MOTOR : CMP_MF_TORSION)))
                goto oom;
            f->a = resolve_body(c, se->a);
            f->b = resolve_body(c, se->b);
            f->k = se->k;
            f->c = se->c;
            f->rest = se->rest;
            f->tau0 = se->tau0;
            f->omega0 = se->omega0;
            if (f->a == -2 || f->b == -2) {
                snprintf(why, whysize, "effect %d (%s) acts on a body without angle", i,
                         se->type->name);
                return -1;
            }
        } else if (se->type == BRAUN_EFFECT_TORQUE &&
                   ((c->flags & CMP_MECH_TORQUE) || se->f[0].kind == BRAUN_FN_CONSTANT)) {
            if (!(f = new_force(m, CMP_MF_TORQUE))) goto oom;
            f->a = resolve_body(c, se->a);
            f->b = resolve_body(c, se->b);
            f->f = se->f[0];
            if (f->a == -2 || f->b == -2) {
                snprintf(why, whysize, "effect %d (%s) acts on a body without angle", i,
                         se->type->name);
                return -1;
            }
        } else {
            snprintf(why, whysize, "effect %d (%s) has no counterpart in the peer model", i,
                     se->type->name);
            return -1;
        }
    }
    /* libbraun's coordinates from the links. */
    m->n = s->n;
    m->out = calloc((size_t)s->n, sizeof *m->out);
    if (!m->out) goto oom;
    for (int i = 0; i < s->nbodies; i++) {
        const braun_scene_body *b = &s->bodies[i];
        cmp_mout *o = m->out + b->iq;
        const int l = c->body_link[i] >= 0 ? c->body_link[i] : c->owner_rod[i];
        o[0].kind = CMP_OUT_X;
        o[1].kind = CMP_OUT_Y;
        o[0].link = o[1].link = l;
        if (c->body_link[i] < 0) o[0].p[0] = o[1].p[0] = c->owner_end[i];
        if (b->kind == BRAUN_BODY_RIGID) {
            o[2].kind = CMP_OUT_ANGLE;
            o[2].link = l;
        }
    }
    return 0;
oom:
    snprintf(why, whysize, "out of memory");
    return -1;
}

static int from_scene(const braun_scene_file *sf, const double *q0, const double *v0,
                      unsigned flags, cmp_mech *m, char *why, size_t whysize)
{
    const braun_scene *s = &sf->scene;
    conv c;
    memset(&c, 0, sizeof c);
    c.sf = sf;
    c.s = s;
    c.q0 = q0;
    c.v0 = v0;
    c.m = m;
    c.flags = flags;
    const size_t nb = (size_t)s->nbodies + 1, nr = (size_t)s->nrods + 1;
    c.body_link = malloc(nb * sizeof(int));
    c.owner_rod = malloc(nb * sizeof(int));
    c.owner_end = malloc(nb * sizeof(double));
    c.rod_link = malloc(nr * sizeof(int));
    int rc = -1;
    if (c.body_link && c.owner_rod && c.owner_end && c.rod_link) rc = convert(&c, why, whysize);
    else snprintf(why, whysize, "out of memory");
    free(c.body_link);
    free(c.owner_rod);
    free(c.owner_end);
    free(c.rod_link);
    if (rc) cmp_mech_free(m);
    return rc;
}
#endif

int cmp_mech_for_target(const cmp_target *tg, cmp_mech *m, char *why, size_t whysize)
{
    return cmp_mech_for_target_ex(tg, 0, m, why, whysize);
}

int cmp_mech_for_target_ex(const cmp_target *tg, unsigned flags, cmp_mech *m, char *why,
                           size_t whysize)
{
    memset(m, 0, sizeof *m);
#ifdef CMP_HAVE_SCENES
    if (tg->scene_file) return from_scene(tg->scene_file, tg->q0, tg->v0, flags, m, why, whysize);
    if (!tg->builtin) {
        snprintf(why, whysize, "'%s' is not a scene: no peer model%s", tg->name,
                 strcmp(tg->name, "andrews") == 0 ? " (the peers run it as the scene a03-andrews)" : "");
        return -1;
    }
    /* A built-in model through the scene file that reproduces it. */
    char path[128], err[512];
    snprintf(path, sizeof path, "data/%s.json", tg->name);
    braun_scene_file *f = braun_scene_load(path, err, sizeof err);
    if (!f) {
        snprintf(why, whysize, "no scene file for '%s': %s", tg->name, err);
        return -1;
    }
    int same = f->sys.n == tg->sys.n;
    for (int i = 0; same && i < tg->sys.n; i++)
        same = fabs((double)f->q0[i] - tg->q0[i]) <= 1e-12 && fabs((double)f->v0[i] - tg->v0[i]) <= 1e-12;
    int rc = -1;
    if (!same) snprintf(why, whysize, "%s does not start where the built-in '%s' does", path, tg->name);
    else rc = from_scene(f, tg->q0, tg->v0, flags, m, why, whysize);
    braun_scene_free(f);
    return rc;
#else
    (void)flags;
    snprintf(why, whysize, "peer models need the scene library");
    return -1;
#endif
}

/* ------------------------------------------------------------ the tree */
static int priority(int kind)
{
    return kind == CMP_MJ_SLIDER ? 0 : kind == CMP_MJ_REVOLUTE ? 1 : kind == CMP_MJ_DISTANCE ? 2 : -1;
}

static const char *kind_name(int kind)
{
    static const char *const names[] = {"revolute", "slider", "distance", "angle", "knife edge"};
    return kind >= 0 && kind <= CMP_MJ_KNIFE ? names[kind] : "?";
}

int cmp_mech_tree(cmp_mech *m, unsigned closable, const char *peer, char *why, size_t whysize)
{
    const int nl = m->nlinks;
    char *seen = calloc((size_t)nl + 1, 1);
    if (!seen) {
        snprintf(why, whysize, "out of memory");
        return -1;
    }
#define SEEN(l) ((l) < 0 || seen[l])
    for (int i = 0; i < nl; i++) m->links[i].parent = m->links[i].joint = -1;
    for (int j = 0; j < m->njoints; j++) m->joints[j].tree = 0;
    for (int done = 0; done < nl;) {
        int best = -1, child = -1;
        for (int j = 0; j < m->njoints; j++) {
            const cmp_mjoint *J = &m->joints[j];
            const int pr = priority(J->kind);
            if (pr < 0 || J->tree) continue;
            int c = -1;
            if (J->kind == CMP_MJ_SLIDER) {
                if (SEEN(J->b) && !SEEN(J->a)) c = J->a;
            } else if (SEEN(J->a) != SEEN(J->b)) {
                c = SEEN(J->a) ? J->b : J->a;
            }
            if (c < 0) continue;
            if (best < 0 || pr < priority(m->joints[best].kind)) best = j, child = c;
        }
        if (best >= 0) {
            cmp_mjoint *J = &m->joints[best];
            J->tree = 1;
            m->links[child].joint = best;
            m->links[child].parent = child == J->a ? J->b : J->a;
            seen[child] = 1;
        } else {
            /* No joint reaches further: the first link left is a free root. */
            int l = 0;
            while (seen[l]) l++;
            seen[l] = 1;
        }
        done++;
    }
#undef SEEN
    free(seen);
    for (int j = 0; j < m->njoints; j++) {
        const cmp_mjoint *J = &m->joints[j];
        if (J->tree) continue;
        if (J->kind == CMP_MJ_ANGLE) {
            /* On the revolute tree joint between its two links. */
            int ok = 0;
            for (int l = 0; l < nl && !ok; l++) {
                const cmp_link *L = &m->links[l];
                ok = L->joint >= 0 && m->joints[L->joint].kind == CMP_MJ_REVOLUTE &&
                     ((l == J->b && L->parent == J->a) || (l == J->a && L->parent == J->b));
            }
            if (ok && J->driven && J->drive.kind != BRAUN_FN_LINEAR &&
                J->drive.kind != BRAUN_FN_CONSTANT)
                ok = 0;
            if (!ok) {
                snprintf(why, whysize,
                         "%s: angle joint '%s' is not on a revolute joint of the tree, or its "
                         "drive is not linear in time", peer, J->name);
                return -1;
            }
            continue;
        }
        if (!(closable & CMP_MJ_BIT(J->kind))) {
            snprintf(why, whysize, "%s cannot close a loop with a %s joint ('%s')", peer,
                     kind_name(J->kind), J->name);
            return -1;
        }
    }
    return 0;
}

void cmp_parents_first(int n, const int *parent, size_t stride, int *order)
{
    /* An item after the chain of its parents. */
    int k = 0;
    char *placed = calloc((size_t)n + 1, 1);
    if (!placed) {
        for (int i = 0; i < n; i++) order[i] = i;
        return;
    }
#define PARENT(i) (*(const int *)(const void *)((const char *)parent + (size_t)(i) * stride))
    while (k < n) {
        const int k0 = k;
        for (int i = 0; i < n; i++) {
            const int p = PARENT(i);
            if (!placed[i] && (p < 0 || placed[p])) {
                placed[i] = 1;
                order[k++] = i;
            }
        }
        if (k == k0) break; /* a cycle: not a tree */
    }
#undef PARENT
    free(placed);
}

void cmp_mech_order(const cmp_mech *m, int *order)
{
    if (m->nlinks > 0) cmp_parents_first(m->nlinks, &m->links[0].parent, sizeof *m->links, order);
}

/* The revolute tree joint between links a and b, its child, and the sign
 * of θ_b - θ_a in the hinge's coordinate (child - parent). -1 if none. */
int cmp_mech_hinge(const cmp_mech *m, int a, int b, int *child, int *sign)
{
    for (int l = 0; l < m->nlinks; l++) {
        const cmp_link *L = &m->links[l];
        if (L->joint < 0 || m->joints[L->joint].kind != CMP_MJ_REVOLUTE) continue;
        if (l == b && L->parent == a) {
            *child = l;
            *sign = 1;
            return L->joint;
        }
        if (l == a && L->parent == b) {
            *child = l;
            *sign = -1;
            return L->joint;
        }
    }
    return -1;
}

