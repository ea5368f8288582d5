/* What a built scene must be able to compute, checked when it is loaded so
 * that a value the reader accepts either works or is refused at its
 * element with FILE:LINE:COLUMN:
 *
 *  - the mass matrix: every pivot of its Cholesky factorization must
 *    exceed n·ε·|M_jj|, its own diagonal entry, the rule of libbraun's
 *    kernels and of both backends (no change of a coordinate's unit changes
 *    it). Without rods M is block diagonal (one block per body) and the
 *    pivots are the blocks' own, exactly as the core computes them; a rod
 *    couples its ends' blocks, which are particles' (diagonal), and adds
 *    (m/6)[2 1; 1 2] ⪰ (m/6) I to its ends' entries: M ⪰ ½ diag(M), so every
 *    pivot is at least half its diagonal entry and the entry's own check
 *    decides;
 *  - every joint's rows and every effect's forces, potential and power at
 *    the initial state: a class hook that fails there (a spring whose two
 *    points coincide has no direction) or gives a non-finite value would
 *    stop the first step.
 *
 *  - a "reference" model: the scene must move as that model does, or the
 *    trajectory error a run reports against it measures nothing — the
 *    same initial state, and the same ideal (Udwadia–Kalaba) acceleration
 *    at states of the reference's own motion. A size check alone let a
 *    slider-crank scene name the four-bar (exit 0, "trajectory error" 6.7)
 *    or change its masses, gravity or starting angle.
 *
 * sj_diagnose also names the element that makes a callback fail at any
 * state, for the messages of a run (braun_scene_file_diagnose). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_reference.h"
#include "braun_c_locale.h"
#include "scene_json_internal.h"

#ifdef BRAUN_SINGLE
#define SJ_EPS FLT_EPSILON
#else
#define SJ_EPS DBL_EPSILON
#endif

/* The key of the descriptor that stores at offset, or fallback. */
static const char *field_key(const braun_scene_field *f, size_t offset, const char *fallback)
{
    for (; f && f->key; f++)
        if (f->offset == offset && f->kind == BRAUN_FIELD_REAL) return f->key;
    return fallback;
}

static void push_element(sj_reader *r, const char *array, int index)
{
    r->depth = 0;
    sj_push_key(r, array);
    sj_push_index(r, index);
}

static void who(sj_reader *r, const char *kind, const char *name, int index)
{
    if (name) snprintf(r->who, sizeof r->who, "%s '%s'", kind, name);
    else snprintf(r->who, sizeof r->who, "%s #%d", kind, index + 1);
}

int sj_check_mass(sj_reader *r)
{
    const braun_scene *s = &r->out->scene;
    const int n = s->n;
    double *rod = calloc((size_t)s->nbodies + 1, sizeof *rod);
    /* Each coordinate's pivot and diagonal entry. */
    double *piv = malloc(((size_t)n + 1) * sizeof *piv), *diag = malloc(((size_t)n + 1) * sizeof *diag);
    if (!rod || !piv || !diag) {
        free(rod);
        free(piv);
        free(diag);
        return sj_fail(r, SJ_AT_VALUE, "out of memory");
    }
    /* A rod adds m/3 to the diagonal of each end's block. */
    for (int k = 0; k < s->nrods; k++)
        for (int e = 0; e < 2; e++) {
            const int p = e ? s->rods[k].b : s->rods[k].a;
            const int b = p >= 0 && p < s->npoints ? s->points[p].body : -1;
            if (b >= 0 && b < s->nbodies) rod[b] += (double)s->rods[k].mass / 3;
        }
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        const int dof = b->kind->dof;
        braun_real M[BRAUN_SCENE_MAX_DOF * BRAUN_SCENE_MAX_DOF];
        double R[BRAUN_SCENE_MAX_DOF * BRAUN_SCENE_MAX_DOF];
        memset(M, 0, sizeof M);
        /* A block that depends on q (rigid3d) at the initial state. */
        if (b->kind->mass_at) b->kind->mass_at(b, r->out->q0 + b->iq, M, dof);
        else b->kind->mass(b, M, dof);
        /* Cholesky of the body's block, as braun_chol_factor computes it
         * (coupling to other blocks is zero without rods). */
        for (int i = 0; i < dof; i++) {
            double d = (double)M[i * dof + i] + rod[k];
            diag[b->iq + i] = d;
            for (int j = 0; j < i; j++) d -= R[j * dof + i] * R[j * dof + i];
            piv[b->iq + i] = d;
            const double rii = d > 0 ? sqrt(d) : 0;
            R[i * dof + i] = rii;
            for (int j = i + 1; j < dof; j++) {
                double t = (double)M[i * dof + j];
                for (int l = 0; l < i; l++) t -= R[l * dof + i] * R[l * dof + j];
                R[i * dof + j] = rii > 0 ? t / rii : 0;
            }
        }
    }
    int st = 0;
    for (int k = 0; k < s->nbodies && !st; k++) {
        const braun_scene_body *b = &s->bodies[k];
        for (int i = 0; i < b->kind->dof; i++) {
            const double p = piv[b->iq + i], mjj = diag[b->iq + i];
            const double tiny = (double)n * (double)SJ_EPS * fabs(mjj);
            if (p > tiny) continue;
            /* A planar body's angle, or a spatial body's orientation. */
            const int spatial = b->kind->dim == 3 && i >= 3;
            const int rot = i == b->kind->angle || spatial;
            const char *key = rot ? field_key(b->kind->fields,
                                              spatial ? offsetof(braun_scene_body, tensor)
                                                      : offsetof(braun_scene_body, inertia),
                                              "inertia")
                                  : field_key(b->kind->fields, offsetof(braun_scene_body, mass),
                                              "mass");
            push_element(r, "bodies", k);
            who(r, "body", r->out->body_names[k], k);
            st = sj_fail(r, SJ_AT_VALUE,
                         "%s: its %s gives the mass matrix a pivot of %g, not above "
                         "n*eps*M_jj = %g (n = %d, its diagonal entry M_jj = %g): M would be "
                         "singular to working precision",
                         r->who, key, p, tiny, n, mjj);
            break;
        }
    }
    free(rod);
    free(piv);
    free(diag);
    return st;
}

/* The two first point fields of a class's descriptors (-1: none). */
static void two_points(const braun_scene_field *f, size_t *oa, size_t *ob, const char **ka,
                       const char **kb, int *count)
{
    *count = 0;
    for (; f && f->key && *count < 2; f++) {
        if (f->kind != BRAUN_FIELD_POINT) continue;
        if ((*count)++ == 0) *oa = f->offset, *ka = f->key;
        else *ob = f->offset, *kb = f->key;
    }
}

/* ", where its points 'a' and 'b' coincide" when the element's first two
 * point fields are at one place at q. */
static void coincide(const braun_scene *s, const braun_scene_field *fields, const void *elem,
                     const braun_real *q, char *out, size_t size)
{
    size_t oa = 0, ob = 0;
    const char *ka = NULL, *kb = NULL;
    int count;
    out[0] = '\0';
    two_points(fields, &oa, &ob, &ka, &kb, &count);
    if (count < 2) return;
    const int a = *(const int *)(const void *)((const char *)elem + oa);
    const int b = *(const int *)(const void *)((const char *)elem + ob);
    if (a < 0 || b < 0 || a >= s->npoints || b >= s->npoints) return;
    braun_scene_pt Pa, Pb;
    braun_scene_pt_eval(s, a, q, NULL, &Pa);
    braun_scene_pt_eval(s, b, q, NULL, &Pb);
    if (Pa.pos[0] == Pb.pos[0] && Pa.pos[1] == Pb.pos[1] && Pa.pos[2] == Pb.pos[2])
        snprintf(out, size, ", where its points '%s' and '%s' coincide", ka, kb);
}

static int finite_all(const braun_real *x, int count)
{
    for (int i = 0; i < count; i++)
        if (!isfinite((double)x[i])) return 0;
    return 1;
}

/* The first joint or effect that fails at (t, q, v), in file order: kind
 * (BRAUN_SCENE_ELEM_JOINT, _EFFECT), index and a sentence without the
 * element's name ("its forces return 1 ..."). Q: n entries of scratch
 * (added into, never read). Returns 1 if one failed. */
static int first_failure(const braun_scene *s, braun_real t, const braun_real *q,
                         const braun_real *v, braun_real *Q, int *element, int *index, char *what,
                         size_t size)
{
    char where[128];
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        const braun_scene_joint_class *c = j->type;
        const int rows = c->rows(j);
        braun_real phi[16], b[16], bv[16];
        if (rows < 1 || rows > 16) continue;
        const int rc = c->eval(s, j, t, q, v, phi, NULL, c->nonholonomic ? NULL : b, bv);
        const int bad = rc != 0 || !finite_all(phi, rows) || !finite_all(bv, rows) ||
                        (!c->nonholonomic && !finite_all(b, rows));
        if (!bad) continue;
        coincide(s, c->fields, j, q, where, sizeof where);
        *element = BRAUN_SCENE_ELEM_JOINT;
        *index = k;
        if (rc) braun__c_snprintf(what, size, "its rows (eval hook) return %d at t = %g%s", rc, (double)t, where);
        else braun__c_snprintf(what, size, "its rows are not finite at t = %g%s", (double)t, where);
        return 1;
    }
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        const braun_scene_effect_class *c = e->type;
        const char *hook = NULL;
        int rc = 0;
        braun_real V = 0, P = 0;
        if (c->forces && (rc = c->forces(s, e, t, q, v, Q)) != 0) hook = "forces";
        else if (c->potential && ((rc = c->potential(s, e, q, &V, NULL)) != 0 || !isfinite((double)V)))
            hook = "potential";
        else if (c->power && (!c->inputs || c->inputs(e)) &&
                 ((rc = c->power(s, e, t, q, v, &P)) != 0 || !isfinite((double)P)))
            hook = "power";
        if (!hook) continue;
        coincide(s, c->fields, e, q, where, sizeof where);
        *element = BRAUN_SCENE_ELEM_EFFECT;
        *index = k;
        if (rc) braun__c_snprintf(what, size, "its %s hook returns %d at t = %g%s", hook, rc, (double)t, where);
        else braun__c_snprintf(what, size, "its %s hook is not finite at t = %g%s", hook, (double)t, where);
        return 1;
    }
    return 0;
}

int sj_check_initial(sj_reader *r)
{
    const braun_scene *s = &r->out->scene;
    braun_real *Q = calloc((size_t)s->n + 1, sizeof *Q);
    if (!Q) return sj_fail(r, SJ_AT_VALUE, "out of memory");
    int element = 0, index = 0;
    char what[256];
    const int failed = first_failure(s, 0, r->out->q0, r->out->v0, Q, &element, &index, what,
                                     sizeof what);
    free(Q);
    if (!failed) return 0;
    const int joint = element == BRAUN_SCENE_ELEM_JOINT;
    push_element(r, joint ? "joints" : "effects", index);
    who(r, joint ? "joint" : "effect", joint ? r->out->joint_names[index] : r->out->effect_names[index],
        index);
    return sj_fail(r, SJ_AT_VALUE, "%s (%s) cannot be evaluated at the initial state: %s", r->who,
                   joint ? s->joints[index].type->name : s->effects[index].type->name, what);
}

/* A system's ideal acceleration at any state: a data block of its own,
 * every correction off (braun_eval is then the Udwadia–Kalaba
 * acceleration), made once for all the states compared. */
typedef struct {
    braun_model model;
    braun_data d;
    void *buf;
    braun_real *qdot;
    int ready;
} ideal_eval;

static int ideal_open(ideal_eval *e, const braun_system *sys)
{
    memset(e, 0, sizeof *e);
    int st = braun_model_init(&e->model, sys);
    if (st) return st;
    e->model.opt.corrections = BRAUN_CORRECT_NONE;
    const size_t bytes = braun_data_size(&e->model);
    e->buf = bytes ? malloc(bytes) : NULL;
    e->qdot = calloc((size_t)sys->n + 1, sizeof *e->qdot);
    st = e->buf && e->qdot ? braun_data_init(&e->d, &e->model, e->buf, bytes) : BRAUN_ERR_BUFFER;
    e->ready = !st;
    return st;
}

static void ideal_close(ideal_eval *e)
{
    if (e->ready) braun_data_release(&e->d);
    free(e->qdot);
    free(e->buf);
}

/* The largest |a_i − b_i| relative to max(|a|∞, |b|∞, floor), and its i. */
static double rel_gap(int n, const braun_real *a, const braun_real *b, double floor, int *at)
{
    double scale = floor, gap = 0;
    for (int i = 0; i < n; i++) {
        if (fabs((double)a[i]) > scale) scale = fabs((double)a[i]);
        if (fabs((double)b[i]) > scale) scale = fabs((double)b[i]);
    }
    *at = 0;
    for (int i = 0; i < n; i++) {
        const double e = fabs((double)a[i] - (double)b[i]);
        if (e > gap || e != e) gap = e, *at = i;
    }
    return gap / scale;
}

/* A function of time that is not one value (a constant, or a ramp, sine
 * or step that does not move). */
static int varies(const braun_scene_fn *f)
{
    switch (f->kind) {
    case BRAUN_FN_CONSTANT: return 0;
    case BRAUN_FN_LINEAR: return f->b != 0;
    case BRAUN_FN_SINE: return f->b != 0 && f->c != 0;
    case BRAUN_FN_STEP: return f->a != f->b;
    default: return 1;
    }
}

/* The first field of an element that is a function of time that varies
 * (its key in *key), or 0. */
static int time_dependent(const braun_scene_field *fields, const void *elem, const char **key)
{
    for (int i = 0; fields && fields[i].key; i++)
        if (fields[i].kind == BRAUN_FIELD_FN &&
            varies((const braun_scene_fn *)(const void *)((const char *)elem + fields[i].offset))) {
            *key = fields[i].key;
            return 1;
        }
    return 0;
}

int sj_check_reference(sj_reader *r, const braun_builtin *b)
{
    const braun_scene_file *sf = r->out;
    const int n = b->sys.n;
    /* Round-off apart: a scene written as the model (its decimal literals,
     * its other coordinates' formulas) agrees to ~1e-13 (tests); a slip
     * of the physics is O(1). */
    const double tol = sqrt(SJ_EPS);
    braun_reference ref;
    const int has_ref = braun_reference_init(&ref, b, 0) == 0;
    /* The reference's own states: its start, then along its motion. */
    static const double times[] = {0.0, 0.1, 0.37, 1.0};
    const int count = has_ref ? (int)(sizeof times / sizeof times[0]) : 1;
    double *qd = calloc(4 * (size_t)n + 1, sizeof *qd), *vd = qd ? qd + n : NULL;
    braun_real *q = calloc(4 * (size_t)n + 1, sizeof *q), *v = q ? q + n : NULL;
    braun_real *a_ref = q ? v + n : NULL, *a_scene = q ? a_ref + n : NULL;
    ideal_eval model, scene;
    const int sa = ideal_open(&model, &b->sys), sb = ideal_open(&scene, &sf->sys);
    int rc = 0;
    char why[320] = "";
    /* The built-in models do not depend on time: a scene whose forces or
     * drives do cannot be one of them at every time, and the sampled times
     * below would miss a step at t = 2 (a 100 N force switched on there
     * loaded, and its trajectory error measured nothing). */
    const braun_scene *sc = &sf->scene;
    for (int k = 0; !rc && k < sc->njoints + sc->neffects; k++) {
        const int joint = k < sc->njoints, i = joint ? k : k - sc->njoints;
        const char *key = NULL;
        const braun_scene_field *fields = joint ? sc->joints[i].type->fields : sc->effects[i].type->fields;
        const void *elem = joint ? (const void *)&sc->joints[i] : (const void *)&sc->effects[i];
        if (!time_dependent(fields, elem, &key)) continue;
        const char *name = joint ? (sf->joint_names ? sf->joint_names[i] : NULL)
                                 : (sf->effect_names ? sf->effect_names[i] : NULL);
        if (name)
            snprintf(why, sizeof why, "%s '%.60s' (%s): its '%s' varies with time, and the model "
                     "does not depend on time", joint ? "joint" : "effect", name,
                     joint ? sc->joints[i].type->name : sc->effects[i].type->name, key);
        else
            snprintf(why, sizeof why, "%s #%d (%s): its '%s' varies with time, and the model does "
                     "not depend on time", joint ? "joint" : "effect", i + 1,
                     joint ? sc->joints[i].type->name : sc->effects[i].type->name, key);
        rc = -1;
    }
    if (rc) {
    } else if (!qd || !q) {
        snprintf(why, sizeof why, "out of memory");
        rc = -1;
    } else if (sa || sb) {
        snprintf(why, sizeof why, "the %s cannot be evaluated (%s)", sa ? "model" : "scene",
                 braun_status_str(sa ? sa : sb));
        rc = -1;
    }
    for (int k = 0; !rc && k < count; k++) {
        if (has_ref) {
            if (braun_reference_eval(&ref, times[k], qd, vd)) {
                braun__c_snprintf(why, sizeof why, "its reference cannot be evaluated at t = %g", times[k]);
                rc = -1;
                break;
            }
            for (int i = 0; i < n; i++) q[i] = (braun_real)qd[i], v[i] = (braun_real)vd[i];
        } else {
            for (int i = 0; i < n; i++) q[i] = b->q0[i], v[i] = b->v0[i];
        }
        int at = 0;
        if (k == 0) {
            /* The reference starts from the model's initial state. */
            int at_v = 0;
            const int pos = !(rel_gap(n, q, sf->q0, 1, &at) <= tol);
            if (pos || !(rel_gap(n, v, sf->v0, 1, &at_v) <= tol)) {
                if (!pos) at = at_v;
                braun__c_snprintf(why, sizeof why, "its initial %s[%d] is %.9g, the scene's %.9g (the reference "
                         "starts where the model does)", pos ? "q" : "v", at,
                         (double)(pos ? q : v)[at], (double)(pos ? sf->q0 : sf->v0)[at]);
                rc = -1;
                break;
            }
        }
        const int ea = braun_eval(&model.d, (braun_real)times[k], q, v, 1, model.qdot, a_ref);
        const int eb = ea ? 0 : braun_eval(&scene.d, (braun_real)times[k], q, v, 1, scene.qdot, a_scene);
        if (ea || eb) {
            braun__c_snprintf(why, sizeof why, "the %s cannot be evaluated at the reference's state at t = %g (%s)",
                     ea ? "model" : "scene", times[k], braun_status_str(ea ? ea : eb));
            rc = -1;
            break;
        }
        if (!(rel_gap(n, a_ref, a_scene, 1e-300, &at) <= tol)) {
            braun__c_snprintf(why, sizeof why, "at its state at t = %g its acceleration q''[%d] is %.9g, the "
                     "scene's %.9g (the masses, forces or constraints differ)", times[k], at,
                     (double)a_ref[at], (double)a_scene[at]);
            rc = -1;
        }
    }
    ideal_close(&model);
    ideal_close(&scene);
    free(qd);
    free(q);
    if (!rc) return 0;
    r->depth = 0;
    sj_push_key(r, "reference");
    return sj_fail(r, SJ_AT_VALUE, "scene: field 'reference': '%s' does not move as this scene: %s",
                   b->name, why);
}

int braun_scene_file_diagnose(const braun_scene_file *sf, braun_real t, const braun_real *q,
                              const braun_real *v, char *msg, size_t size)
{
    if (msg && size) msg[0] = '\0';
    if (!sf || !q) return -1; /* nothing to evaluate: not "nothing fails" */
    const braun_scene *s = &sf->scene;
    braun_real *Q = calloc((size_t)s->n + 1, sizeof *Q);
    if (!Q) return -1;
    int element = 0, index = 0;
    char what[256];
    const int failed = first_failure(s, t, q, v, Q, &element, &index, what, sizeof what);
    free(Q);
    if (!failed || !msg || !size) return failed;
    const int joint = element == BRAUN_SCENE_ELEM_JOINT;
    const char *name = joint ? sf->joint_names[index] : sf->effect_names[index];
    const char *type = joint ? s->joints[index].type->name : s->effects[index].type->name;
    if (name) snprintf(msg, size, "%s '%s' (%s): %s", joint ? "joint" : "effect", name, type, what);
    else snprintf(msg, size, "%s #%d (%s): %s", joint ? "joint" : "effect", index + 1, type, what);
    for (char *c = msg; *c; c++)
        if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
    return 1;
}
