/* braun_scene_defaults: what a scene file's reader does after reading an
 * element — its class's defaults hook fills the values the file left out
 * from the initial state — for scenes written in C, where "left out" is
 * "left 0". Every reference is checked first, so that no hook follows a
 * dangling index; then vectors with BRAUN_FIELD_UNIT are normalised, and
 * bodies, joints and effects get their hooks, in that order (a joint's
 * frames need the bodies' normalised quaternions). */
#include "scene_internal.h"

static const void *field_at(const void *elem, const braun_scene_field *f)
{
    return (const char *)elem + f->offset;
}

static int ref_ok(const braun_scene *s, const braun_scene_field *f, const void *elem)
{
    const int x = *(const int *)field_at(elem, f);
    switch (f->kind) {
    case BRAUN_FIELD_POINT:
    case BRAUN_FIELD_BODY_POINT: return x >= 0 && x < s->npoints;
    case BRAUN_FIELD_BODY: return x == BRAUN_SCENE_GROUND || (x >= 0 && x < s->nbodies);
    case BRAUN_FIELD_JOINT: return x >= 0 && x < s->njoints;
    default: return 1;
    }
}

static int refs_ok(const braun_scene *s, const braun_scene_field *f, const void *elem)
{
    for (; f && f->key; f++)
        if (!ref_ok(s, f, elem)) return 0;
    return 1;
}

/* A field is "given" unless it holds only zeros (references always are;
 * a joint's drive is given when the joint is driven). */
static unsigned given_mask(const braun_scene_field *fields, const void *elem, const void *drive,
                           int driven)
{
    unsigned given = 0;
    int i = 0;
    for (const braun_scene_field *f = fields; f && f->key && i < 32; f++, i++) {
        int nonzero = 1;
        if (f->kind == BRAUN_FIELD_REAL || f->kind == BRAUN_FIELD_OFFSET) {
            const braun_real *x = field_at(elem, f);
            const int count = f->count > 0 ? f->count : 1;
            nonzero = 0;
            for (int k = 0; k < count; k++) nonzero = nonzero || x[k] != 0;
        } else if (f->kind == BRAUN_FIELD_FN) {
            const braun_scene_fn *fn = field_at(elem, f);
            nonzero = field_at(elem, f) == drive
                          ? driven
                          : fn->kind != BRAUN_FN_CONSTANT || fn->a != 0 || fn->b != 0 ||
                                fn->c != 0 || fn->d != 0;
        }
        if (nonzero) given |= 1u << i;
    }
    return given;
}

static void normalize_units(const braun_scene_field *f, void *elem)
{
    for (; f && f->key; f++)
        if (f->kind == BRAUN_FIELD_REAL && (f->flags & BRAUN_FIELD_UNIT) && f->count == 3)
            braun_scene__normalize3((braun_real *)(void *)((char *)elem + f->offset));
}

int braun_scene_defaults(braun_scene *s)
{
    if (!s || s->nbodies < 0 || s->npoints < 0 || s->njoints < 0 || s->neffects < 0 ||
        (s->nbodies && !s->bodies) || (s->npoints && !s->points) || (s->njoints && !s->joints) ||
        (s->neffects && !s->effects))
        return BRAUN_ERR_ARGUMENT;
    for (int k = 0; k < s->nbodies; k++)
        if (!s->bodies[k].kind) return BRAUN_ERR_ARGUMENT;
    for (int k = 0; k < s->npoints; k++) {
        const int b = s->points[k].body;
        if (b != BRAUN_SCENE_GROUND && !(b >= 0 && b < s->nbodies)) return BRAUN_ERR_ARGUMENT;
    }
    for (int k = 0; k < s->njoints; k++)
        if (!s->joints[k].type || !refs_ok(s, s->joints[k].type->fields, &s->joints[k]))
            return BRAUN_ERR_ARGUMENT;
    for (int k = 0; k < s->neffects; k++)
        if (!s->effects[k].type || !refs_ok(s, s->effects[k].type->fields, &s->effects[k]))
            return BRAUN_ERR_ARGUMENT;
    /* The dimension, as braun_scene_build takes it (the hooks may ask). */
    s->dim = s->nbodies > 0 && s->bodies[0].kind->dim == 3 ? 3 : 2;

    for (int k = 0; k < s->nbodies; k++) {
        braun_scene_body *b = &s->bodies[k];
        normalize_units(b->kind->fields, b);
        if (b->kind->defaults) b->kind->defaults(b, given_mask(b->kind->fields, b, NULL, 0));
    }
    for (int k = 0; k < s->njoints; k++) {
        braun_scene_joint *j = &s->joints[k];
        const unsigned given = given_mask(j->type->fields, j, &j->drive, j->driven);
        normalize_units(j->type->fields, j);
        if (j->type->defaults) j->type->defaults(s, j, given);
    }
    for (int k = 0; k < s->neffects; k++) {
        braun_scene_effect *e = &s->effects[k];
        const unsigned given = given_mask(e->type->fields, e, NULL, 0);
        normalize_units(e->type->fields, e);
        if (e->type->defaults) e->type->defaults(s, e, given);
    }
    return BRAUN_OK;
}
