/* The builder: validates a scene description, numbers its coordinates and
 * rows, and hands out the callbacks it needs — and no others (docs/method.md
 * "What a step costs"): no nonholonomic callback without nonholonomic
 * joints (knife edges), no power callback without an effect that puts
 * energy in or out (dampers, forces, torques, motors), and a constant mass
 * matrix unless a body class's mass depends on q (rigid3d). It knows no
 * element type: every check beyond the numbers and references, every row
 * count and every callback goes through the element's class
 * (braun_scene.h). A scene is planar or spatial as a whole (s->dim). */
#include "scene_internal.h"

/* braun_model_init's bound on n, m, p: a scene with rods is always dense;
 * one without can also be handed out sparse (scene_sparse.c), so it may be
 * as large as a sparse system. */
#define MAX_ROWS_DENSE BRAUN_MAX_DENSE
#define MAX_ROWS_SPARSE BRAUN_MAX_SPARSE

int braun_scene__fail(braun_scene_error *err, int status, int element, int index,
                      const char *what)
{
    if (err) {
        err->status = status;
        err->element = element;
        err->index = index;
        err->what = what;
    }
    return status;
}

/* Finite and within BRAUN_SCENE_MAX_ABS. */
static int ok_num(braun_real x)
{
    return braun_is_finite(x) && braun_fabs(x) <= (braun_real)BRAUN_SCENE_MAX_ABS;
}

static int ok_fn(const braun_scene_fn *f)
{
    return f->kind >= BRAUN_FN_CONSTANT && f->kind <= BRAUN_FN_STEP && ok_num(f->a) &&
           ok_num(f->b) && ok_num(f->c) && ok_num(f->d);
}

/* A field of an element struct, through its descriptor. */
static int field_int(const void *elem, const braun_scene_field *f)
{
    return *(const int *)(const void *)((const char *)elem + f->offset);
}

/* The references of an element's descriptors are in range (so that the
 * class's check may follow them). */
static const char *check_refs(const braun_scene *s, const braun_scene_field *f, const void *elem,
                              const char *const *msg)
{
    for (; f && f->key; f++) {
        const int x = field_int(elem, f);
        if ((f->kind == BRAUN_FIELD_POINT || f->kind == BRAUN_FIELD_BODY_POINT) &&
            !braun_scene__ok_point_ref(s, x))
            return msg[0];
        if (f->kind == BRAUN_FIELD_BODY && !braun_scene__ok_body_ref(s, x)) return msg[1];
        if (f->kind == BRAUN_FIELD_JOINT && !(x >= 0 && x < s->njoints)) return msg[4];
    }
    return NULL;
}

/* After the class's check: the bodies of the references are what the
 * descriptors' flags ask (not the ground, a body with an angle). */
static const char *check_ref_flags(const braun_scene *s, const braun_scene_field *f,
                                   const void *elem, const char *const *msg)
{
    for (; f && f->key; f++) {
        int body;
        if (f->kind == BRAUN_FIELD_BODY) body = field_int(elem, f);
        else if (f->kind == BRAUN_FIELD_BODY_POINT) body = braun_scene__body_of(s, field_int(elem, f));
        else continue;
        if (body < 0 && (f->kind == BRAUN_FIELD_BODY_POINT || !(f->flags & BRAUN_FIELD_GROUND)))
            return msg[2];
        if (body >= 0 && (f->flags & BRAUN_FIELD_ANGLE) && !braun_scene__is_rigid(s, body))
            return msg[3];
    }
    return NULL;
}

static const char *const joint_msgs[] = {
    "joint refers to an unknown point", "joint refers to an unknown body",
    "a body of the joint cannot be the ground", "a body of the joint must be rigid (have an angle)",
    "joint refers to an unknown joint"};
static const char *const effect_msgs[] = {
    "effect refers to an unknown point", "effect refers to an unknown body",
    "a body of the effect cannot be the ground",
    "a body of the effect must be rigid (have an angle)", "effect refers to an unknown joint"};

/* An element class of the other dimension than the scene's (0: any). */
static const char *dim_msg(const braun_scene *s, int dim, const char *kind)
{
    if (dim == 0 || dim == s->dim) return NULL;
    if (kind[0] == 'j')
        return dim == 2 ? "a planar joint in a spatial scene (use its spatial counterpart)"
                        : "a spatial joint in a planar scene";
    return dim == 2 ? "a planar effect in a spatial scene (use its spatial counterpart)"
                    : "a spatial effect in a planar scene";
}

static int check_bodies(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        const braun_scene_body_class *c = b->kind;
        const int E = BRAUN_SCENE_ELEM_BODY, A = BRAUN_ERR_ARGUMENT;
        if (!c) return braun_scene__fail(err, A, E, k, "unknown body kind");
        if (!(c->mass || c->mass_at) || !(c->kinetic || c->kinetic_at) || !c->point ||
            !c->grad || !c->weight || !c->gravity_potential || c->dof < 1 ||
            c->dof > BRAUN_SCENE_MAX_DOF || (c->dim != 2 && c->dim != 3) || c->angle >= c->dof ||
            c->rows < 0 || (c->rows > 0 && !c->constraint) || (c->dim == 2 && c->rows > 0))
            return braun_scene__fail(err, A, E, k, "body class without its hooks or sizes");
        if (c->dim != s->dim)
            return braun_scene__fail(err, A, E, k, "planar and spatial bodies in one scene (a scene "
                                                   "is planar or spatial as a whole)");
        int finite = ok_num(b->mass) && ok_num(b->inertia);
        for (int i = 0; i < 6; i++) finite = finite && ok_num(b->tensor[i]);
        if (!finite)
            return braun_scene__fail(err, A, E, k, "mass or inertia is not a finite number in range");
        for (int i = 0; i < BRAUN_SCENE_MAX_DOF; i++)
            if (!ok_num(b->q0[i]) || !ok_num(b->v0[i]))
                return braun_scene__fail(err, A, E, k, "initial state is not a finite number in range");
        const char *why = c->check ? c->check(s, b) : NULL;
        if (why) return braun_scene__fail(err, A, E, k, why);
    }
    return BRAUN_OK;
}

static int check_points(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->npoints; k++) {
        const braun_scene_point *p = &s->points[k];
        const int E = BRAUN_SCENE_ELEM_POINT, A = BRAUN_ERR_ARGUMENT;
        if (!braun_scene__ok_body_ref(s, p->body))
            return braun_scene__fail(err, A, E, k, "point on an unknown body");
        if (!ok_num(p->x) || !ok_num(p->y) || !ok_num(p->z))
            return braun_scene__fail(err, A, E, k, "point coordinates are not finite numbers in range");
        if (s->dim == 2 && p->z != 0)
            return braun_scene__fail(err, A, E, k, "a point of a planar scene has z = 0");
        if (p->body < 0) continue;
        const braun_scene_body_class *c = s->bodies[p->body].kind;
        if ((c->flags & BRAUN_BODY_CLASS_POINT_MASS) && (p->x != 0 || p->y != 0 || p->z != 0))
            return braun_scene__fail(err, A, E, k, "a point of a particle has no offset");
    }
    return BRAUN_OK;
}

/* Rod ends are point masses (natural coordinates) or on the ground. */
static int point_mass(const braun_scene *s, int body)
{
    return body < 0 || (s->bodies[body].kind->flags & BRAUN_BODY_CLASS_POINT_MASS);
}

static int check_rods(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        const int E = BRAUN_SCENE_ELEM_ROD, A = BRAUN_ERR_ARGUMENT;
        if (s->dim != 2) return braun_scene__fail(err, A, E, k, "rods are planar only");
        if (!braun_scene__ok_point_ref(s, r->a) || !braun_scene__ok_point_ref(s, r->b))
            return braun_scene__fail(err, A, E, k, "rod end is not a point of the scene");
        const int ba = braun_scene__body_of(s, r->a), bb = braun_scene__body_of(s, r->b);
        if (!point_mass(s, ba) || !point_mass(s, bb))
            return braun_scene__fail(err, A, E, k, "rod end is on a rigid body (natural coordinates need "
                                      "particles or ground points)");
        if (ba < 0 && bb < 0) return braun_scene__fail(err, A, E, k, "rod has both ends on the ground");
        if (ba == bb) return braun_scene__fail(err, A, E, k, "rod has both ends on the same particle");
        if (!ok_num(r->mass) || r->mass < 0)
            return braun_scene__fail(err, A, E, k, "rod mass must be a finite number >= 0");
        if (!ok_num(r->length) || !(r->length > 0))
            return braun_scene__fail(err, A, E, k, "rod length must be a finite number > 0");
    }
    return BRAUN_OK;
}

static int check_joint(const braun_scene *s, int k, braun_scene_error *err)
{
    const braun_scene_joint *j = &s->joints[k];
    const braun_scene_joint_class *c = j->type;
    const int E = BRAUN_SCENE_ELEM_JOINT, A = BRAUN_ERR_ARGUMENT;
    if (!c) return braun_scene__fail(err, A, E, k, "unknown joint type");
    if (!c->rows || !c->eval) return braun_scene__fail(err, A, E, k, "joint class without rows or eval");
    int finite = ok_num(j->value);
    for (int i = 0; i < 3; i++)
        finite = finite && ok_num(j->axis[i]) && ok_num(j->axis_b[i]) && ok_num(j->ref_a[i]) &&
                 ok_num(j->ref_b[i]);
    if (!finite)
        return braun_scene__fail(err, A, E, k, "joint parameters are not finite numbers in range");
    const char *why = dim_msg(s, c->dim, "joint");
    if (!why) why = check_refs(s, c->fields, j, joint_msgs);
    if (!why && c->check) why = c->check(s, j);
    if (why) return braun_scene__fail(err, A, E, k, why);
    if (j->driven) {
        if (!ok_fn(&j->drive)) return braun_scene__fail(err, A, E, k, "drive is not a valid function");
        if (j->drive.kind == BRAUN_FN_STEP)
            return braun_scene__fail(err, A, E, k, "a drive must be smooth (constant, linear or sine)");
    }
    why = check_ref_flags(s, c->fields, j, joint_msgs);
    if (why) return braun_scene__fail(err, A, E, k, why);
    if (c->rows(j) < 1) return braun_scene__fail(err, A, E, k, "joint class gives no rows");
    return BRAUN_OK;
}

static int check_effects(braun_scene *s, braun_scene_error *err)
{
    s->energy_input = 0;
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        const braun_scene_effect_class *c = e->type;
        const int E = BRAUN_SCENE_ELEM_EFFECT, A = BRAUN_ERR_ARGUMENT;
        if (!c) return braun_scene__fail(err, A, E, k, "unknown effect type");
        if (!ok_num(e->g[0]) || !ok_num(e->g[1]) || !ok_num(e->g[2]) || !ok_num(e->k) ||
            !ok_num(e->c) || !ok_num(e->rest) || !ok_num(e->tau0) || !ok_num(e->omega0) ||
            !ok_fn(&e->f[0]) || !ok_fn(&e->f[1]) || !ok_fn(&e->f[2]))
            return braun_scene__fail(err, A, E, k, "effect parameters are not finite numbers in range");
        const char *why = dim_msg(s, c->dim, "effect");
        if (!why) why = check_refs(s, c->fields, e, effect_msgs);
        if (!why && c->check) why = c->check(s, e);
        if (!why) why = check_ref_flags(s, c->fields, e, effect_msgs);
        if (why) return braun_scene__fail(err, A, E, k, why);
        if (c->power && (!c->inputs || c->inputs(e))) s->energy_input = 1;
    }
    return BRAUN_OK;
}

/* Every coordinate must carry mass, or M is singular. One pass over the
 * rods marks the bodies a rod with mass ends on (in the bodies' iq, which
 * the numbering below overwrites), one over the bodies asks. */
static int check_masses(braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->nbodies; k++) s->bodies[k].iq = 0;
    for (int r = 0; r < s->nrods; r++) {
        if (!(s->rods[r].mass > 0)) continue;
        const int ends[2] = {braun_scene__body_of(s, s->rods[r].a),
                             braun_scene__body_of(s, s->rods[r].b)};
        for (int e = 0; e < 2; e++)
            if (ends[e] >= 0) s->bodies[ends[e]].iq = 1;
    }
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        if (b->mass > 0 || b->iq) continue;
        return braun_scene__fail(err, BRAUN_ERR_ARGUMENT, BRAUN_SCENE_ELEM_BODY, k,
                                 "particle has no mass (none of its own and no rod with mass at it)");
    }
    return BRAUN_OK;
}

void braun_scene__joint_bodies(const braun_scene *s, const braun_scene_joint *j, int body[2])
{
    body[0] = body[1] = BRAUN_SCENE_GROUND;
    if (j->type->bodies) {
        j->type->bodies(s, j, body);
        return;
    }
    int k = 0;
    for (const braun_scene_field *f = j->type->fields; f && f->key && k < 2; f++) {
        if (f->kind == BRAUN_FIELD_BODY) body[k++] = field_int(j, f);
        else if (f->kind == BRAUN_FIELD_POINT || f->kind == BRAUN_FIELD_BODY_POINT)
            body[k++] = braun_scene__body_of(s, field_int(j, f));
    }
}

int braun_scene_build(braun_scene *s, braun_system *sys, braun_scene_error *err)
{
    const int A = BRAUN_ERR_ARGUMENT, S = BRAUN_SCENE_ELEM_SCENE;
    braun_scene__fail(err, BRAUN_OK, S, -1, NULL);
    if (!s || !sys) return braun_scene__fail(err, A, S, -1, "no scene or no system");
    if (s->nbodies < 0 || s->npoints < 0 || s->nrods < 0 || s->njoints < 0 || s->neffects < 0)
        return braun_scene__fail(err, A, S, -1, "negative element count");
    if ((s->nbodies && !s->bodies) || (s->npoints && !s->points) || (s->nrods && !s->rods) ||
        (s->njoints && !s->joints) || (s->neffects && !s->effects))
        return braun_scene__fail(err, A, S, -1, "element array missing");
    /* The scene's dimension is its first body's (check_bodies asks the
     * others to agree). */
    s->dim = s->nbodies > 0 && s->bodies[0].kind && s->bodies[0].kind->dim == 3 ? 3 : 2;
    int st = check_bodies(s, err);
    if (!st) st = check_points(s, err);
    if (!st) st = check_rods(s, err);
    for (int k = 0; !st && k < s->njoints; k++) st = check_joint(s, k, err);
    if (!st) st = check_effects(s, err);
    if (!st) st = check_masses(s, err);
    if (st) return st;

    /* Coordinates: bodies in order. Rows of Φ_q: rods, then holonomic
     * joints in order; of Φ_v: nonholonomic joints in order. */
    const long max = s->nrods > 0 ? MAX_ROWS_DENSE : MAX_ROWS_SPARSE;
    long n = 0, m = 0, p = 0;
    for (int k = 0; k < s->nbodies; k++) {
        s->bodies[k].iq = (int)n;
        n += s->bodies[k].kind->dof;
        if (n > max) break;
    }
    if (n == 0) return braun_scene__fail(err, BRAUN_ERR_SIZE, S, -1, "the scene has no moving body");
    for (int k = 0; k < s->nrods && m <= max; k++) s->rods[k].row = (int)m++;
    s->driven = 0;
    for (int k = 0; k < s->njoints && m <= max && p <= max; k++) {
        braun_scene_joint *j = &s->joints[k];
        long *rows = j->type->nonholonomic ? &p : &m;
        j->row = (int)*rows;
        *rows += j->type->rows(j);
        s->driven += j->driven != 0;
    }
    for (int k = 0; k < s->nbodies && m <= max; k++) {
        s->bodies[k].row = (int)m;
        m += s->bodies[k].kind->rows;
    }
    if (n > max || m > max || p > max)
        return braun_scene__fail(err, BRAUN_ERR_SIZE, S, -1,
                    s->nrods > 0 ? "more than 4096 coordinates or rows (a scene with rods is "
                                   "dense)"
                                 : "more than 1048576 coordinates or rows");
    s->n = (int)n;
    s->m = (int)m;
    s->p = (int)p;
    braun_scene__system(s, sys);
    return BRAUN_OK;
}

/* A body's initial coordinates and velocities (its class's dof of each,
 * into q and v): its class's own rule (a rigid3d's normalised quaternion
 * and its rate from ω), else q0 and v0 as given. */
static void body_initial(const braun_scene_body *b, braun_real *q, braun_real *v)
{
    if (b->kind->initial) {
        b->kind->initial(b, q, v);
        return;
    }
    for (int i = 0; i < b->kind->dof; i++) {
        q[i] = b->q0[i];
        v[i] = b->v0[i];
    }
}

void braun_scene__system(braun_scene *s, braun_system *sys)
{
    sys->n = s->n;
    sys->m = s->m;
    sys->p = s->p;
    /* Driven joints do work through their ideal constraint forces, which the
     * core adds to Ė unless a system is scleronomic: a scene without drives
     * says so (the core then skips that work and checks b_q = 0). */
    int constant = 1;
    for (int k = 0; k < s->nbodies && constant; k++) constant = s->bodies[k].kind->mass_at == NULL;
    sys->flags = (constant ? BRAUN_MASS_CONSTANT : 0u) |
                 (s->energy_input ? BRAUN_ENERGY_INPUT : 0u) | (s->driven ? 0u : BRAUN_SCLERONOMIC);
    sys->mass = braun_scene__mass;
    sys->forces = braun_scene__forces;
    sys->holonomic = s->m > 0 ? braun_scene__holonomic : NULL;
    sys->nonholonomic = s->p > 0 ? braun_scene__nonholonomic : NULL;
    sys->energy = braun_scene__energy;
    sys->power = s->energy_input ? braun_scene__power : NULL;
    sys->user = s;
    sys->sparsity = NULL;
    sys->q_scale = NULL;
    if (s->q_scale) {
        /* The initial state into the storage, then the sizes over it
         * (braun_scene_natural_sizes reads all of q before it writes). */
        for (int k = 0; k < s->nbodies; k++) {
            braun_real v[BRAUN_SCENE_MAX_DOF];
            body_initial(&s->bodies[k], s->q_scale + s->bodies[k].iq, v);
        }
        if (braun_scene_natural_sizes(s, s->q_scale, s->q_scale) == BRAUN_OK) sys->q_scale = s->q_scale;
    }
}

int braun_scene_initial_state(const braun_scene *s, braun_real *q, braun_real *v)
{
    if (!s || !q || !v || s->n <= 0 || (s->nbodies > 0 && !s->bodies)) return BRAUN_ERR_ARGUMENT;
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        if (!b->kind || b->iq < 0 || b->iq + b->kind->dof > s->n) return BRAUN_ERR_ARGUMENT;
    }
    for (int k = 0; k < s->nbodies; k++) body_initial(&s->bodies[k], q + s->bodies[k].iq, v + s->bodies[k].iq);
    return BRAUN_OK;
}
