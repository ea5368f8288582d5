/* The builder: validates a scene description, numbers its coordinates and
 * rows, and hands out the callbacks it needs — and no others (docs/method.md
 * "What a step costs"): no nonholonomic callback without knife edges, no
 * power callback without dampers, forces, torques or motors, no energy law
 * with driven joints, and always a constant mass matrix. */
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

static int is_rigid(const braun_scene *s, int body)
{
    return body >= 0 && body < s->nbodies && s->bodies[body].kind == BRAUN_BODY_RIGID;
}

/* Body index or the ground. */
static int ok_body_ref(const braun_scene *s, int body)
{
    return body == BRAUN_SCENE_GROUND || (body >= 0 && body < s->nbodies);
}

static int ok_point_ref(const braun_scene *s, int point)
{
    return point >= 0 && point < s->npoints;
}

static int body_of(const braun_scene *s, int point) { return s->points[point].body; }

static int check_bodies(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        const int E = BRAUN_SCENE_ELEM_BODY, A = BRAUN_ERR_ARGUMENT;
        if (b->kind != BRAUN_BODY_RIGID && b->kind != BRAUN_BODY_PARTICLE)
            return braun_scene__fail(err, A, E, k, "unknown body kind");
        if (!ok_num(b->mass) || !ok_num(b->inertia))
            return braun_scene__fail(err, A, E, k, "mass or inertia is not a finite number in range");
        for (int i = 0; i < 3; i++)
            if (!ok_num(b->q0[i]) || !ok_num(b->v0[i]))
                return braun_scene__fail(err, A, E, k, "initial state is not a finite number in range");
        if (b->kind == BRAUN_BODY_RIGID && !(b->mass > 0))
            return braun_scene__fail(err, A, E, k, "a rigid body needs a mass > 0");
        if (b->kind == BRAUN_BODY_RIGID && !(b->inertia > 0))
            return braun_scene__fail(err, A, E, k, "a rigid body needs an inertia > 0");
        if (b->kind == BRAUN_BODY_PARTICLE && b->mass < 0)
            return braun_scene__fail(err, A, E, k, "a particle's mass must be >= 0");
    }
    return BRAUN_OK;
}

static int check_points(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->npoints; k++) {
        const braun_scene_point *p = &s->points[k];
        const int E = BRAUN_SCENE_ELEM_POINT, A = BRAUN_ERR_ARGUMENT;
        if (!ok_body_ref(s, p->body)) return braun_scene__fail(err, A, E, k, "point on an unknown body");
        if (!ok_num(p->x) || !ok_num(p->y))
            return braun_scene__fail(err, A, E, k, "point coordinates are not finite numbers in range");
        if (p->body >= 0 && s->bodies[p->body].kind == BRAUN_BODY_PARTICLE &&
            (p->x != 0 || p->y != 0))
            return braun_scene__fail(err, A, E, k, "a point of a particle has no offset");
    }
    return BRAUN_OK;
}

static int check_rods(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        const int E = BRAUN_SCENE_ELEM_ROD, A = BRAUN_ERR_ARGUMENT;
        if (!ok_point_ref(s, r->a) || !ok_point_ref(s, r->b))
            return braun_scene__fail(err, A, E, k, "rod end is not a point of the scene");
        const int ba = body_of(s, r->a), bb = body_of(s, r->b);
        if (is_rigid(s, ba) || is_rigid(s, bb))
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
    const int E = BRAUN_SCENE_ELEM_JOINT, A = BRAUN_ERR_ARGUMENT;
    if (j->type < BRAUN_JOINT_REVOLUTE || j->type > BRAUN_JOINT_ANGLE)
        return braun_scene__fail(err, A, E, k, "unknown joint type");
    if (!ok_num(j->value) || !ok_num(j->axis[0]) || !ok_num(j->axis[1]))
        return braun_scene__fail(err, A, E, k, "joint parameters are not finite numbers in range");
    if (j->driven) {
        if (j->type == BRAUN_JOINT_REVOLUTE)
            return braun_scene__fail(err, A, E, k, "a revolute joint cannot be driven");
        if (!ok_fn(&j->drive)) return braun_scene__fail(err, A, E, k, "drive is not a valid function");
        if (j->drive.kind == BRAUN_FN_STEP)
            return braun_scene__fail(err, A, E, k, "a drive must be smooth (constant, linear or sine)");
    }
    if (j->type == BRAUN_JOINT_ANGLE) {
        if (!ok_body_ref(s, j->a) || !ok_body_ref(s, j->b))
            return braun_scene__fail(err, A, E, k, "angle joint refers to an unknown body");
        if ((j->a >= 0 && !is_rigid(s, j->a)) || (j->b >= 0 && !is_rigid(s, j->b)))
            return braun_scene__fail(err, A, E, k, "angle joint needs rigid bodies (or the ground)");
        if (j->a == j->b) return braun_scene__fail(err, A, E, k, "joint connects a body to itself");
        return BRAUN_OK;
    }
    if (!ok_point_ref(s, j->a) || !ok_point_ref(s, j->b))
        return braun_scene__fail(err, A, E, k, "joint refers to an unknown point");
    if (body_of(s, j->a) == body_of(s, j->b))
        return braun_scene__fail(err, A, E, k, "joint connects a body to itself");
    if (j->type == BRAUN_JOINT_DISTANCE && !j->driven && !(j->value > 0))
        return braun_scene__fail(err, A, E, k, "distance must be > 0");
    if (j->type == BRAUN_JOINT_SLIDER || j->type == BRAUN_JOINT_PRISMATIC) {
        if (j->axis[0] == 0 && j->axis[1] == 0)
            return braun_scene__fail(err, A, E, k, "slider axis is the zero vector");
        if (body_of(s, j->a) < 0)
            return braun_scene__fail(err, A, E, k, "the sliding point is on the ground");
        const int bl = body_of(s, j->b);
        if (bl >= 0 && !is_rigid(s, bl))
            return braun_scene__fail(err, A, E, k, "the line of a slider must be on a rigid body or the "
                                      "ground");
        if (j->type == BRAUN_JOINT_PRISMATIC && !is_rigid(s, body_of(s, j->a)))
            return braun_scene__fail(err, A, E, k, "a prismatic joint's sliding body must be rigid");
    }
    return BRAUN_OK;
}

static int check_knives(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->nknives; k++) {
        const braun_scene_knife *kn = &s->knives[k];
        const int E = BRAUN_SCENE_ELEM_KNIFE, A = BRAUN_ERR_ARGUMENT;
        if (!is_rigid(s, kn->body)) return braun_scene__fail(err, A, E, k, "knife edge needs a rigid body");
        if (!ok_num(kn->x) || !ok_num(kn->y) || !ok_num(kn->dir[0]) || !ok_num(kn->dir[1]))
            return braun_scene__fail(err, A, E, k, "knife edge numbers are not finite in range");
        if (kn->dir[0] == 0 && kn->dir[1] == 0)
            return braun_scene__fail(err, A, E, k, "knife edge direction is the zero vector");
    }
    return BRAUN_OK;
}

/* Torques and motors act between a rigid body and a rigid body or ground. */
static int check_pair(const braun_scene *s, const braun_scene_effect *e)
{
    return is_rigid(s, e->a) && (e->b == BRAUN_SCENE_GROUND || is_rigid(s, e->b)) &&
           e->a != e->b;
}

static int check_effects(braun_scene *s, braun_scene_error *err)
{
    int gravities = 0;
    s->energy_input = 0;
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        const int E = BRAUN_SCENE_ELEM_EFFECT, A = BRAUN_ERR_ARGUMENT;
        if (!ok_num(e->g[0]) || !ok_num(e->g[1]) || !ok_num(e->k) || !ok_num(e->c) ||
            !ok_num(e->rest) || !ok_num(e->tau0) || !ok_num(e->omega0) || !ok_fn(&e->f[0]) ||
            !ok_fn(&e->f[1]))
            return braun_scene__fail(err, A, E, k, "effect parameters are not finite numbers in range");
        switch (e->type) {
        case BRAUN_EFFECT_GRAVITY:
            if (++gravities > 1) return braun_scene__fail(err, A, E, k, "more than one gravity");
            break;
        case BRAUN_EFFECT_SPRING:
            if (!ok_point_ref(s, e->a) || !ok_point_ref(s, e->b))
                return braun_scene__fail(err, A, E, k, "spring refers to an unknown point");
            if (body_of(s, e->a) == body_of(s, e->b))
                return braun_scene__fail(err, A, E, k, "spring connects a body to itself");
            if (e->k < 0 || e->c < 0 || e->rest < 0)
                return braun_scene__fail(err, A, E, k, "stiffness, damping and rest length must be >= 0");
            if (e->c != 0) s->energy_input = 1;
            break;
        case BRAUN_EFFECT_TORSION:
            if (!ok_body_ref(s, e->a) || !ok_body_ref(s, e->b) ||
                (e->a >= 0 && !is_rigid(s, e->a)) || (e->b >= 0 && !is_rigid(s, e->b)))
                return braun_scene__fail(err, A, E, k, "rotational spring needs rigid bodies (or ground)");
            if (e->a == e->b) return braun_scene__fail(err, A, E, k, "rotational spring connects a body to "
                                                        "itself");
            if (e->k < 0 || e->c < 0)
                return braun_scene__fail(err, A, E, k, "stiffness and damping must be >= 0");
            if (e->c != 0) s->energy_input = 1;
            break;
        case BRAUN_EFFECT_FORCE:
            if (!ok_point_ref(s, e->a)) return braun_scene__fail(err, A, E, k, "force on an unknown point");
            if (body_of(s, e->a) < 0) return braun_scene__fail(err, A, E, k, "force on a ground point");
            s->energy_input = 1;
            break;
        case BRAUN_EFFECT_TORQUE:
            if (!check_pair(s, e))
                return braun_scene__fail(err, A, E, k, "torque needs a rigid body and a different rigid "
                                          "body or the ground");
            s->energy_input = 1;
            break;
        case BRAUN_EFFECT_MOTOR:
            if (!check_pair(s, e))
                return braun_scene__fail(err, A, E, k, "motor needs a rigid rotor and a different rigid "
                                          "stator or the ground");
            if (e->omega0 == 0) return braun_scene__fail(err, A, E, k, "motor no-load speed must not be 0");
            s->energy_input = 1;
            break;
        default: return braun_scene__fail(err, A, E, k, "unknown effect type");
        }
    }
    return BRAUN_OK;
}

/* Every coordinate must carry mass, or M is singular. */
static int check_masses(const braun_scene *s, braun_scene_error *err)
{
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        if (b->kind != BRAUN_BODY_PARTICLE || b->mass > 0) continue;
        int carried = 0;
        for (int r = 0; r < s->nrods && !carried; r++)
            carried = s->rods[r].mass > 0 &&
                      (body_of(s, s->rods[r].a) == k || body_of(s, s->rods[r].b) == k);
        if (!carried)
            return braun_scene__fail(err, BRAUN_ERR_ARGUMENT, BRAUN_SCENE_ELEM_BODY, k,
                        "particle has no mass (none of its own and no rod with mass at it)");
    }
    return BRAUN_OK;
}

int braun_scene_build(braun_scene *s, braun_system *sys, braun_scene_error *err)
{
    const int A = BRAUN_ERR_ARGUMENT, S = BRAUN_SCENE_ELEM_SCENE;
    braun_scene__fail(err, BRAUN_OK, S, -1, NULL);
    if (!s || !sys) return braun_scene__fail(err, A, S, -1, "no scene or no system");
    if (s->nbodies < 0 || s->npoints < 0 || s->nrods < 0 || s->njoints < 0 ||
        s->nknives < 0 || s->neffects < 0)
        return braun_scene__fail(err, A, S, -1, "negative element count");
    if ((s->nbodies && !s->bodies) || (s->npoints && !s->points) || (s->nrods && !s->rods) ||
        (s->njoints && !s->joints) || (s->nknives && !s->knives) ||
        (s->neffects && !s->effects))
        return braun_scene__fail(err, A, S, -1, "element array missing");
    int st = check_bodies(s, err);
    if (!st) st = check_points(s, err);
    if (!st) st = check_rods(s, err);
    for (int k = 0; !st && k < s->njoints; k++) st = check_joint(s, k, err);
    if (!st) st = check_knives(s, err);
    if (!st) st = check_effects(s, err);
    if (!st) st = check_masses(s, err);
    if (st) return st;

    /* Coordinates: bodies in order. Rows: rods, then joints; knife edges. */
    const long max = s->nrods > 0 ? MAX_ROWS_DENSE : MAX_ROWS_SPARSE;
    long n = 0, m = 0;
    for (int k = 0; k < s->nbodies; k++) {
        s->bodies[k].iq = (int)n;
        n += s->bodies[k].kind == BRAUN_BODY_RIGID ? 3 : 2;
        if (n > max) break;
    }
    if (n == 0) return braun_scene__fail(err, BRAUN_ERR_SIZE, S, -1, "the scene has no moving body");
    for (int k = 0; k < s->nrods && m <= max; k++) s->rods[k].row = (int)m++;
    s->driven = 0;
    for (int k = 0; k < s->njoints && m <= max; k++) {
        s->joints[k].row = (int)m;
        m += braun_scene__joint_rows(&s->joints[k]);
        s->driven += s->joints[k].driven != 0;
    }
    for (int k = 0; k < s->nknives; k++) s->knives[k].row = k;
    if (n > max || m > max || s->nknives > max)
        return braun_scene__fail(err, BRAUN_ERR_SIZE, S, -1,
                    s->nrods > 0 ? "more than 4096 coordinates or rows (a scene with rods is "
                                   "dense)"
                                 : "more than 1048576 coordinates or rows");
    s->n = (int)n;
    s->m = (int)m;
    s->p = s->nknives;
    braun_scene__system(s, sys);
    return BRAUN_OK;
}

void braun_scene__system(braun_scene *s, braun_system *sys)
{
    sys->n = s->n;
    sys->m = s->m;
    sys->p = s->p;
    /* Driven joints do work through their ideal constraint forces: the core
     * adds that power to Ė (BRAUN_CONSTRAINT_WORK), so the energy law holds. */
    sys->flags = BRAUN_MASS_CONSTANT | (s->energy_input ? BRAUN_ENERGY_INPUT : 0u) |
                 (s->driven ? BRAUN_CONSTRAINT_WORK : 0u);
    sys->mass = braun_scene__mass;
    sys->forces = braun_scene__forces;
    sys->holonomic = s->m > 0 ? braun_scene__holonomic : NULL;
    sys->nonholonomic = s->p > 0 ? braun_scene__nonholonomic : NULL;
    sys->energy = braun_scene__energy;
    sys->power = s->energy_input ? braun_scene__power : NULL;
    sys->user = s;
    sys->sparsity = NULL;
}

int braun_scene__joint_rows(const braun_scene_joint *j)
{
    const int extra = j->driven ? 1 : 0;
    switch (j->type) {
    case BRAUN_JOINT_REVOLUTE: return 2;
    case BRAUN_JOINT_SLIDER: return 1 + extra;
    case BRAUN_JOINT_PRISMATIC: return 2 + extra;
    default: return 1; /* distance, angle: the drive replaces the constant */
    }
}

void braun_scene_initial_state(const braun_scene *s, braun_real *q, braun_real *v)
{
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *b = &s->bodies[k];
        const int dim = b->kind == BRAUN_BODY_RIGID ? 3 : 2;
        for (int i = 0; i < dim; i++) {
            q[b->iq + i] = b->q0[i];
            v[b->iq + i] = b->v0[i];
        }
    }
}
