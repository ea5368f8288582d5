/* The scene file reader: from a jansson tree to the element arrays of a
 * braun_scene (docs/scene-format.md). Every check names the element and
 * the field and, through the reader's path, the file position. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_models.h"
#include "scene_json_internal.h"

/* ------------------------------------------------------------ helpers */

static void set_who(sj_reader *r, const char *kind, const char *name, int index)
{
    if (name) snprintf(r->who, sizeof r->who, "%s '%s'", kind, name);
    else snprintf(r->who, sizeof r->who, "%s #%d", kind, index + 1);
}

/* Fails at the first member of obj that is not in allowed (NULL-ended). */
static int check_fields(sj_reader *r, json_t *obj, const char *const *allowed)
{
    const char *key;
    json_t *val;
    json_object_foreach(obj, key, val) {
        int known = 0;
        for (const char *const *a = allowed; *a && !known; a++) known = strcmp(*a, key) == 0;
        if (known) continue;
        char list[256] = "";
        for (const char *const *a = allowed; *a; a++) {
            strncat(list, *a, sizeof list - strlen(list) - 1);
            if (a[1]) strncat(list, ", ", sizeof list - strlen(list) - 1);
        }
        sj_push_key(r, key);
        return sj_fail(r, SJ_AT_KEY, "%s: unknown field '%s' (expected %s)", r->who, key, list);
    }
    (void)val;
    return 0;
}

static int missing(sj_reader *r, const char *key)
{
    return sj_fail(r, SJ_AT_VALUE, "%s: missing field '%s'", r->who, key);
}

/* A number in range; the path is at the value. */
static int number_value(sj_reader *r, json_t *v, const char *field, double *x)
{
    if (!json_is_number(v)) return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be a number", r->who, field);
    *x = json_number_value(v);
    if (!isfinite(*x) || fabs(*x) > BRAUN_SCENE_MAX_ABS)
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' is out of range (%g; the limit is |x| <= %g)",
                       r->who, field, *x, BRAUN_SCENE_MAX_ABS);
    return 0;
}

/* Member key as a number: 0 read, 1 absent and optional, -1 error. */
static int num_field(sj_reader *r, json_t *obj, const char *key, int required, double *x)
{
    json_t *v = json_object_get(obj, key);
    if (!v) return required ? missing(r, key) : 1;
    sj_push_key(r, key);
    int st = number_value(r, v, key, x);
    sj_pop(r);
    return st;
}

/* A number with a domain: sign > 0 asks x > 0, sign = 0 asks x >= 0. */
static int num_field_min(sj_reader *r, json_t *obj, const char *key, int required, int strict,
                         double *x)
{
    int st = num_field(r, obj, key, required, x);
    if (st) return st;
    if (strict ? !(*x > 0) : !(*x >= 0)) {
        sj_push_key(r, key);
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be %s 0 (got %g)", r->who, key,
                       strict ? ">" : ">=", *x);
    }
    return 0;
}

static int vec2_value(sj_reader *r, json_t *v, const char *field, double *xy)
{
    if (!json_is_array(v) || json_array_size(v) != 2 || !json_is_number(json_array_get(v, 0)) ||
        !json_is_number(json_array_get(v, 1)))
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be an array of 2 numbers", r->who, field);
    for (int i = 0; i < 2; i++) {
        sj_push_index(r, i);
        int st = number_value(r, json_array_get(v, (size_t)i), field, &xy[i]);
        sj_pop(r);
        if (st) return st;
    }
    return 0;
}

static int vec2_field(sj_reader *r, json_t *obj, const char *key, int required, double *xy)
{
    json_t *v = json_object_get(obj, key);
    if (!v) return required ? missing(r, key) : 1;
    sj_push_key(r, key);
    int st = vec2_value(r, v, key, xy);
    sj_pop(r);
    return st;
}

static int str_field(sj_reader *r, json_t *obj, const char *key, int required, const char **s)
{
    json_t *v = json_object_get(obj, key);
    if (!v) return required ? missing(r, key) : 1;
    if (!json_is_string(v)) {
        sj_push_key(r, key);
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be a string", r->who, key);
    }
    *s = json_string_value(v);
    return *s ? 0 : -1; /* never NULL for a string; keeps analyzers sure */
}

/* An optional "name": a non-empty string without '.'. */
static int name_field(sj_reader *r, json_t *obj, const char **name)
{
    *name = NULL;
    int st = str_field(r, obj, "name", 0, name);
    if (st < 0) return st;
    if (st == 0 && *name && ((*name)[0] == '\0' || strchr(*name, '.'))) {
        sj_push_key(r, "name");
        return sj_fail(r, SJ_AT_VALUE, "name '%s' must be non-empty and contain no '.'", *name);
    }
    return 0;
}

/* Element i of array `key` as an object; the path is left at the element. */
static int element(sj_reader *r, json_t *arr, int i, const char *kind, json_t **obj)
{
    sj_push_index(r, i);
    *obj = json_array_get(arr, (size_t)i);
    if (!json_is_object(*obj)) return sj_fail(r, SJ_AT_VALUE, "%s #%d must be an object", kind, i + 1);
    return 0;
}

/* Optional top-level array: 0 read (or absent: *arr NULL), -1 error. */
static int array_field(sj_reader *r, json_t *root, const char *key, json_t **arr)
{
    *arr = json_object_get(root, key);
    if (!*arr) return 0;
    if (!json_is_array(*arr)) {
        sj_push_key(r, key);
        return sj_fail(r, SJ_AT_VALUE, "scene: field '%s' must be an array", key);
    }
    return 0;
}

/* ------------------------------------------------------ functions of t */
static int fn_object(sj_reader *r, json_t *v, braun_scene_fn *f);

static int fn_value(sj_reader *r, json_t *v, const char *field, braun_scene_fn *f)
{
    double x = 0;
    memset(f, 0, sizeof *f);
    f->kind = BRAUN_FN_CONSTANT;
    if (json_is_number(v)) {
        if (number_value(r, v, field, &x)) return -1;
        f->a = (braun_real)x;
        return 0;
    }
    if (!json_is_object(v))
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be a number or a function object "
                                       "({\"type\": \"constant\" | \"linear\" | \"sine\" | \"step\", ...})",
                       r->who, field);
    /* Messages about the function's own fields name the field it is. */
    char saved[sizeof r->who];
    memcpy(saved, r->who, sizeof saved);
    snprintf(r->who, sizeof r->who, "%.80s, field '%.60s'", saved, field);
    const int st = fn_object(r, v, f);
    memcpy(r->who, saved, sizeof saved);
    return st;
}

static int fn_object(sj_reader *r, json_t *v, braun_scene_fn *f)
{
    const char *type;
    if (str_field(r, v, "type", 1, &type)) return -1;
    static const char *const k_const[] = {"type", "value", NULL};
    static const char *const k_lin[] = {"type", "value", "rate", NULL};
    static const char *const k_sin[] = {"type", "offset", "amplitude", "omega", "phase", NULL};
    static const char *const k_step[] = {"type", "before", "after", "time", NULL};
    double a = 0, b = 0, c = 0, d = 0;
    int st;
    if (strcmp(type, "constant") == 0) {
        f->kind = BRAUN_FN_CONSTANT;
        st = check_fields(r, v, k_const) || num_field(r, v, "value", 1, &a) < 0;
    } else if (strcmp(type, "linear") == 0) {
        f->kind = BRAUN_FN_LINEAR;
        st = check_fields(r, v, k_lin) || num_field(r, v, "value", 0, &a) < 0 ||
             num_field(r, v, "rate", 1, &b) < 0;
    } else if (strcmp(type, "sine") == 0) {
        f->kind = BRAUN_FN_SINE;
        st = check_fields(r, v, k_sin) || num_field(r, v, "offset", 0, &a) < 0 ||
             num_field(r, v, "amplitude", 1, &b) < 0 || num_field(r, v, "omega", 1, &c) < 0 ||
             num_field(r, v, "phase", 0, &d) < 0;
    } else if (strcmp(type, "step") == 0) {
        f->kind = BRAUN_FN_STEP;
        st = check_fields(r, v, k_step) || num_field(r, v, "before", 1, &a) < 0 ||
             num_field(r, v, "after", 1, &b) < 0 || num_field(r, v, "time", 1, &c) < 0;
    } else {
        sj_push_key(r, "type");
        return sj_fail(r, SJ_AT_VALUE, "%s: unknown function type '%s' (constant, linear, sine, "
                                       "step)", r->who, type);
    }
    if (st) return -1;
    f->a = (braun_real)a;
    f->b = (braun_real)b;
    f->c = (braun_real)c;
    f->d = (braun_real)d;
    return 0;
}

static int fn_field(sj_reader *r, json_t *obj, const char *key, int required, braun_scene_fn *f)
{
    json_t *v = json_object_get(obj, key);
    if (!v) {
        memset(f, 0, sizeof *f);
        return required ? missing(r, key) : 1;
    }
    sj_push_key(r, key);
    int st = fn_value(r, v, key, f);
    sj_pop(r);
    return st;
}

/* ------------------------------------------------------ bodies, points */
static int find_body(const sj_reader *r, const char *name, size_t len)
{
    const braun_scene *s = &r->out->scene;
    for (int k = 0; k < s->nbodies; k++)
        if (strlen(r->out->body_names[k]) == len && strncmp(r->out->body_names[k], name, len) == 0)
            return k;
    return -2;
}

/* Index of a new point. The table is sized for every point the file can
 * make (named ones, one centre per body, two references per element); the
 * guard only keeps a miscount from writing past it. */
static int add_point(sj_reader *r, int body, double x, double y, const char *name)
{
    braun_scene *s = &r->out->scene;
    if (r->npoints >= r->cap_points) return r->cap_points - 1;
    const int i = r->npoints++;
    s->points[i].body = body;
    s->points[i].x = (braun_real)x;
    s->points[i].y = (braun_real)y;
    r->point_names[i] = name;
    s->npoints = r->npoints;
    return i;
}

static int find_point(const sj_reader *r, int body, const char *name)
{
    for (int i = 0; i < r->npoints; i++)
        if (r->out->scene.points[i].body == body && strcmp(r->point_names[i], name) == 0) return i;
    return -1;
}

/* World position of a point at the initial state. */
static void initial_point(const sj_reader *r, int point, double *xy)
{
    const braun_scene *s = &r->out->scene;
    const braun_scene_point *p = &s->points[point];
    if (p->body < 0) {
        xy[0] = p->x;
        xy[1] = p->y;
        return;
    }
    const braun_scene_body *b = &s->bodies[p->body];
    const double c = cos(b->q0[2]), sn = sin(b->q0[2]);
    xy[0] = b->q0[0];
    xy[1] = b->q0[1];
    if (b->kind == BRAUN_BODY_RIGID) {
        xy[0] += c * p->x - sn * p->y;
        xy[1] += sn * p->x + c * p->y;
    }
}

static double initial_distance(const sj_reader *r, int a, int b)
{
    double pa[2], pb[2];
    initial_point(r, a, pa);
    initial_point(r, b, pb);
    return hypot(pb[0] - pa[0], pb[1] - pa[1]);
}

static double initial_angle(const sj_reader *r, int body)
{
    return body >= 0 ? r->out->scene.bodies[body].q0[2] : 0.0;
}

/* A point reference: "body.point", "body" (a rigid body's centre or the
 * particle itself), "ground.point", or [x, y] on the ground. */
static int point_ref(sj_reader *r, json_t *obj, const char *key, int *point)
{
    json_t *v = json_object_get(obj, key);
    if (!v) return missing(r, key);
    sj_push_key(r, key);
    int st = 0;
    if (json_is_array(v)) {
        double xy[2] = {0, 0};
        st = vec2_value(r, v, key, xy);
        if (!st) *point = add_point(r, BRAUN_SCENE_GROUND, xy[0], xy[1], "");
    } else if (json_is_string(v)) {
        const char *ref = json_string_value(v), *dot = strchr(ref, '.');
        const size_t blen = dot ? (size_t)(dot - ref) : strlen(ref);
        const int ground = blen == 6 && strncmp(ref, "ground", 6) == 0;
        const int body = ground ? BRAUN_SCENE_GROUND : find_body(r, ref, blen);
        if (body == -2) {
            st = sj_fail(r, SJ_AT_VALUE, "%s refers to unknown body '%.*s'", r->who, (int)blen, ref);
        } else if (dot) {
            *point = find_point(r, body, dot + 1);
            if (*point < 0 || dot[1] == '\0') {
                char names[200] = "";
                for (int i = 0; i < r->npoints; i++) {
                    if (r->out->scene.points[i].body != body || !r->point_names[i][0]) continue;
                    if (names[0]) strncat(names, ", ", sizeof names - strlen(names) - 1);
                    strncat(names, r->point_names[i], sizeof names - strlen(names) - 1);
                }
                st = sj_fail(r, SJ_AT_VALUE, "%s refers to unknown point '%s' (%.*s has %s%s)",
                             r->who, ref, (int)blen, ref, names[0] ? "points " : "no points",
                             names);
            }
        } else if (ground) {
            st = sj_fail(r, SJ_AT_VALUE, "%s: field '%s': 'ground' needs a point ('ground.NAME' "
                                         "or [x, y])", r->who, key);
        } else {
            /* The centre: one implicit point per body, made on first use. */
            *point = find_point(r, body, "");
            if (*point < 0) *point = add_point(r, body, 0, 0, "");
        }
    } else {
        st = sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be a point: \"body.point\", \"body\" "
                                     "or [x, y] on the ground", r->who, key);
    }
    sj_pop(r);
    return st;
}

/* A body reference: a body's name, or "ground" where allowed. */
static int body_ref(sj_reader *r, json_t *obj, const char *key, int required, int ground_ok,
                    int *body)
{
    const char *name = "";
    int st = str_field(r, obj, key, required, &name);
    if (st) return st;
    sj_push_key(r, key);
    if (strcmp(name, "ground") == 0) {
        *body = BRAUN_SCENE_GROUND;
        if (!ground_ok) st = sj_fail(r, SJ_AT_VALUE, "%s: field '%s' cannot be the ground", r->who, key);
    } else {
        *body = find_body(r, name, strlen(name));
        if (*body == -2) st = sj_fail(r, SJ_AT_VALUE, "%s refers to unknown body '%s'", r->who, name);
        else if (r->out->scene.bodies[*body].kind != BRAUN_BODY_RIGID)
            st = sj_fail(r, SJ_AT_VALUE, "%s: body '%s' in field '%s' must be rigid (it has no "
                                         "angle)", r->who, name, key);
    }
    sj_pop(r);
    return st;
}

/* Named points of a rigid body or of the ground: {"NAME": [x, y], ...}. */
static int read_points(sj_reader *r, json_t *obj, int body)
{
    json_t *pts = json_object_get(obj, "points");
    if (!pts) return 0;
    sj_push_key(r, "points");
    if (!json_is_object(pts)) {
        sj_fail(r, SJ_AT_VALUE, "%s: field 'points' must be an object {\"NAME\": [x, y], ...}", r->who);
        return -1;
    }
    const char *key;
    json_t *val;
    json_object_foreach(pts, key, val) {
        double xy[2] = {0, 0};
        sj_push_key(r, key);
        if (key[0] == '\0' || strchr(key, '.'))
            return sj_fail(r, SJ_AT_KEY, "%s: point name '%s' must be non-empty and contain no "
                                         "'.'", r->who, key);
        char field[160];
        snprintf(field, sizeof field, "points.%s", key);
        if (vec2_value(r, val, field, xy)) return -1;
        add_point(r, body, xy[0], xy[1], key);
        sj_pop(r);
    }
    sj_pop(r);
    return 0;
}

static int read_body(sj_reader *r, json_t *obj, int k)
{
    static const char *const keys[] = {"name",  "type",     "mass",  "inertia", "position",
                                       "angle", "velocity", "omega", "points",  NULL};
    static const char *const keys_particle[] = {"name", "type", "mass", "position", "velocity",
                                                NULL};
    braun_scene_body *b = &r->out->scene.bodies[k];
    const char *name = NULL, *type = "";
    double x = 0, xy[2] = {0, 0};
    set_who(r, "body", NULL, k);
    if (name_field(r, obj, &name)) return -1;
    if (!name) return missing(r, "name");
    set_who(r, "body", name, k);
    if (strcmp(name, "ground") == 0) {
        sj_push_key(r, "name");
        return sj_fail(r, SJ_AT_VALUE, "%s: field 'name': 'ground' is reserved for the fixed frame",
                       r->who);
    }
    const int twin = find_body(r, name, strlen(name));
    if (twin != -2) {
        set_who(r, "body", NULL, k);
        sj_push_key(r, "name");
        return sj_fail(r, SJ_AT_VALUE, "%s: field 'name': '%s' is already the name of body #%d",
                       r->who, name, twin + 1);
    }
    if (str_field(r, obj, "type", 1, &type)) return -1;
    if (strcmp(type, "rigid") == 0) {
        b->kind = BRAUN_BODY_RIGID;
    } else if (strcmp(type, "particle") == 0) {
        b->kind = BRAUN_BODY_PARTICLE;
    } else {
        sj_push_key(r, "type");
        return sj_fail(r, SJ_AT_VALUE, "%s: unknown body type '%s' (rigid, particle)", r->who, type);
    }
    const int rigid = b->kind == BRAUN_BODY_RIGID;
    if (check_fields(r, obj, rigid ? keys : keys_particle)) return -1;
    if (num_field_min(r, obj, "mass", 1, rigid, &x)) return -1;
    b->mass = (braun_real)x;
    if (rigid) {
        if (num_field_min(r, obj, "inertia", 1, 1, &x)) return -1;
        b->inertia = (braun_real)x;
    }
    if (vec2_field(r, obj, "position", 1, xy)) return -1;
    b->q0[0] = (braun_real)xy[0];
    b->q0[1] = (braun_real)xy[1];
    xy[0] = xy[1] = 0;
    if (vec2_field(r, obj, "velocity", 0, xy) < 0) return -1;
    b->v0[0] = (braun_real)xy[0];
    b->v0[1] = (braun_real)xy[1];
    x = 0;
    if (rigid && num_field(r, obj, "angle", 0, &x) < 0) return -1;
    b->q0[2] = (braun_real)x;
    x = 0;
    if (rigid && num_field(r, obj, "omega", 0, &x) < 0) return -1;
    b->v0[2] = (braun_real)x;
    r->out->body_names[k] = name;
    r->out->scene.nbodies = k + 1; /* visible to find_body from now on */
    return rigid ? read_points(r, obj, k) : 0;
}

/* --------------------------------------------------------------- rods */
static int read_rod(sj_reader *r, json_t *obj, int k)
{
    static const char *const keys[] = {"name", "a", "b", "mass", "length", NULL};
    braun_scene_rod *rod = &r->out->scene.rods[k];
    const char *name;
    double x = 0;
    set_who(r, "rod", NULL, k);
    if (name_field(r, obj, &name)) return -1;
    set_who(r, "rod", name, k);
    r->rod_names[k] = name;
    if (check_fields(r, obj, keys) || point_ref(r, obj, "a", &rod->a) ||
        point_ref(r, obj, "b", &rod->b) || num_field_min(r, obj, "mass", 1, 0, &x))
        return -1;
    rod->mass = (braun_real)x;
    int st = num_field_min(r, obj, "length", 0, 1, &x);
    if (st < 0) return -1;
    rod->length = (braun_real)(st == 1 ? initial_distance(r, rod->a, rod->b) : x);
    return 0;
}

/* ------------------------------------------------------------- joints */
static int drive_field(sj_reader *r, json_t *obj, braun_scene_joint *j)
{
    int st = fn_field(r, obj, "drive", 0, &j->drive);
    if (st < 0) return -1;
    j->driven = st == 0;
    if (j->driven && j->drive.kind == BRAUN_FN_STEP) {
        sj_push_key(r, "drive");
        return sj_fail(r, SJ_AT_VALUE, "%s: a drive must be smooth (constant, linear or sine), "
                                       "not a step", r->who);
    }
    return 0;
}

static int axis_field(sj_reader *r, json_t *obj, braun_scene_joint *j)
{
    double xy[2] = {0, 0};
    if (vec2_field(r, obj, "axis", 1, xy)) return -1;
    if (xy[0] == 0 && xy[1] == 0) {
        sj_push_key(r, "axis");
        return sj_fail(r, SJ_AT_VALUE, "%s: field 'axis' must not be the zero vector", r->who);
    }
    j->axis[0] = (braun_real)xy[0];
    j->axis[1] = (braun_real)xy[1];
    return 0;
}

static int read_knife(sj_reader *r, json_t *obj, int json_index)
{
    static const char *const keys[] = {"name", "type", "body", "at", "direction", NULL};
    braun_scene *s = &r->out->scene;
    const int k = s->nknives;
    braun_scene_knife *kn = &s->knives[k];
    double xy[2] = {0, 0};
    int body;
    if (check_fields(r, obj, keys) || body_ref(r, obj, "body", 1, 0, &body)) return -1;
    kn->body = body;
    if (vec2_field(r, obj, "at", 0, xy) < 0) return -1;
    kn->x = (braun_real)xy[0];
    kn->y = (braun_real)xy[1];
    if (vec2_field(r, obj, "direction", 1, xy)) return -1;
    if (xy[0] == 0 && xy[1] == 0) {
        sj_push_key(r, "direction");
        return sj_fail(r, SJ_AT_VALUE, "%s: field 'direction' must not be the zero vector", r->who);
    }
    kn->dir[0] = (braun_real)xy[0];
    kn->dir[1] = (braun_real)xy[1];
    r->knife_json[k] = json_index;
    r->out->knife_names[k] = r->out->joint_names[json_index];
    s->nknives = k + 1;
    return 0;
}

static int read_joint(sj_reader *r, json_t *obj, int json_index)
{
    static const char *const k_rev[] = {"name", "type", "a", "b", NULL};
    static const char *const k_dist[] = {"name", "type", "a", "b", "length", "drive", NULL};
    static const char *const k_slide[] = {"name", "type", "point", "line", "axis", "drive", NULL};
    static const char *const k_prism[] = {"name", "type", "point", "line",
                                          "axis", "angle", "drive", NULL};
    static const char *const k_angle[] = {"name", "type", "a", "b", "angle", "drive", NULL};
    braun_scene *s = &r->out->scene;
    const char *name = NULL, *type = "";
    double x = 0;
    set_who(r, "joint", NULL, json_index);
    if (name_field(r, obj, &name)) return -1;
    set_who(r, "joint", name, json_index);
    r->out->joint_names[json_index] = name;
    if (str_field(r, obj, "type", 1, &type)) return -1;
    if (strcmp(type, "knife") == 0) return read_knife(r, obj, json_index);

    braun_scene_joint *j = &s->joints[s->njoints];
    memset(j, 0, sizeof *j);
    int st;
    if (strcmp(type, "revolute") == 0) {
        j->type = BRAUN_JOINT_REVOLUTE;
        st = check_fields(r, obj, k_rev) || point_ref(r, obj, "a", &j->a) ||
             point_ref(r, obj, "b", &j->b);
    } else if (strcmp(type, "distance") == 0) {
        j->type = BRAUN_JOINT_DISTANCE;
        st = check_fields(r, obj, k_dist) || point_ref(r, obj, "a", &j->a) ||
             point_ref(r, obj, "b", &j->b) || drive_field(r, obj, j);
        if (!st) {
            const int got = num_field_min(r, obj, "length", 0, 1, &x);
            st = got < 0;
            j->value = (braun_real)(got == 1 ? initial_distance(r, j->a, j->b) : x);
            if (!st && got == 0 && j->driven) {
                sj_push_key(r, "length");
                st = sj_fail(r, SJ_AT_KEY, "%s: give 'length' or 'drive', not both", r->who) != 0;
            }
        }
    } else if (strcmp(type, "slider") == 0 || strcmp(type, "prismatic") == 0) {
        const int prism = type[0] == 'p';
        j->type = prism ? BRAUN_JOINT_PRISMATIC : BRAUN_JOINT_SLIDER;
        st = check_fields(r, obj, prism ? k_prism : k_slide) ||
             point_ref(r, obj, "point", &j->a) || point_ref(r, obj, "line", &j->b) ||
             axis_field(r, obj, j) || drive_field(r, obj, j);
        if (!st && prism) {
            const int got = num_field(r, obj, "angle", 0, &x);
            st = got < 0;
            j->value = (braun_real)(got == 1 ? initial_angle(r, s->points[j->a].body) -
                                                   initial_angle(r, s->points[j->b].body)
                                             : x);
        }
    } else if (strcmp(type, "angle") == 0) {
        j->type = BRAUN_JOINT_ANGLE;
        st = check_fields(r, obj, k_angle) || body_ref(r, obj, "a", 1, 1, &j->a) ||
             body_ref(r, obj, "b", 1, 1, &j->b) || drive_field(r, obj, j);
        if (!st) {
            const int got = num_field(r, obj, "angle", 0, &x);
            st = got < 0;
            j->value = (braun_real)(got == 1 ? initial_angle(r, j->b) - initial_angle(r, j->a) : x);
            if (!st && got == 0 && j->driven) {
                sj_push_key(r, "angle");
                st = sj_fail(r, SJ_AT_KEY, "%s: give 'angle' or 'drive', not both", r->who) != 0;
            }
        }
    } else {
        sj_push_key(r, "type");
        return sj_fail(r, SJ_AT_VALUE, "%s: unknown joint type '%s' (revolute, distance, slider, "
                                       "prismatic, angle, knife)", r->who, type);
    }
    if (st) return -1;
    r->out->joint_names[json_index] = name;
    r->joint_json[s->njoints] = json_index;
    s->njoints++;
    return 0;
}

/* ------------------------------------------------------------ effects */
static int read_effect(sj_reader *r, json_t *obj, int k)
{
    static const char *const k_grav[] = {"name", "type", "g", NULL};
    static const char *const k_spring[] = {"name",    "type",        "a", "b", "stiffness",
                                           "damping", "rest_length", NULL};
    static const char *const k_tors[] = {"name",    "type",       "a", "b", "stiffness",
                                         "damping", "rest_angle", NULL};
    static const char *const k_force[] = {"name", "type", "point", "fx", "fy", NULL};
    static const char *const k_torque[] = {"name", "type", "body", "reaction", "torque", NULL};
    static const char *const k_motor[] = {"name",         "type",         "rotor", "stator",
                                          "stall_torque", "no_load_speed", NULL};
    braun_scene_effect *e = &r->out->scene.effects[k];
    const char *name = NULL, *type = "";
    double x = 0;
    memset(e, 0, sizeof *e);
    set_who(r, "effect", NULL, k);
    if (name_field(r, obj, &name)) return -1;
    set_who(r, "effect", name, k);
    r->out->effect_names[k] = name;
    if (str_field(r, obj, "type", 1, &type)) return -1;
    int st, got;
    if (strcmp(type, "gravity") == 0) {
        double xy[2] = {0, 0};
        e->type = BRAUN_EFFECT_GRAVITY;
        st = check_fields(r, obj, k_grav) || vec2_field(r, obj, "g", 1, xy);
        e->g[0] = (braun_real)xy[0];
        e->g[1] = (braun_real)xy[1];
    } else if (strcmp(type, "spring") == 0) {
        e->type = BRAUN_EFFECT_SPRING;
        st = check_fields(r, obj, k_spring) || point_ref(r, obj, "a", &e->a) ||
             point_ref(r, obj, "b", &e->b);
        x = 0;
        st = st || num_field_min(r, obj, "stiffness", 0, 0, &x) < 0;
        e->k = (braun_real)x;
        x = 0;
        st = st || num_field_min(r, obj, "damping", 0, 0, &x) < 0;
        e->c = (braun_real)x;
        if (!st) {
            got = num_field_min(r, obj, "rest_length", 0, 0, &x);
            st = got < 0;
            e->rest = (braun_real)(got == 1 ? initial_distance(r, e->a, e->b) : x);
        }
    } else if (strcmp(type, "torsion") == 0) {
        e->type = BRAUN_EFFECT_TORSION;
        st = check_fields(r, obj, k_tors) || body_ref(r, obj, "a", 1, 1, &e->a) ||
             body_ref(r, obj, "b", 1, 1, &e->b);
        x = 0;
        st = st || num_field_min(r, obj, "stiffness", 0, 0, &x) < 0;
        e->k = (braun_real)x;
        x = 0;
        st = st || num_field_min(r, obj, "damping", 0, 0, &x) < 0;
        e->c = (braun_real)x;
        if (!st) {
            got = num_field(r, obj, "rest_angle", 0, &x);
            st = got < 0;
            e->rest = (braun_real)(got == 1 ? initial_angle(r, e->b) - initial_angle(r, e->a) : x);
        }
    } else if (strcmp(type, "force") == 0) {
        e->type = BRAUN_EFFECT_FORCE;
        st = check_fields(r, obj, k_force) || point_ref(r, obj, "point", &e->a) ||
             fn_field(r, obj, "fx", 0, &e->f[0]) < 0 || fn_field(r, obj, "fy", 0, &e->f[1]) < 0;
    } else if (strcmp(type, "torque") == 0) {
        e->type = BRAUN_EFFECT_TORQUE;
        e->b = BRAUN_SCENE_GROUND;
        st = check_fields(r, obj, k_torque) || body_ref(r, obj, "body", 1, 0, &e->a) ||
             body_ref(r, obj, "reaction", 0, 1, &e->b) < 0 ||
             fn_field(r, obj, "torque", 1, &e->f[0]);
    } else if (strcmp(type, "motor") == 0) {
        e->type = BRAUN_EFFECT_MOTOR;
        e->b = BRAUN_SCENE_GROUND;
        st = check_fields(r, obj, k_motor) || body_ref(r, obj, "rotor", 1, 0, &e->a) ||
             body_ref(r, obj, "stator", 0, 1, &e->b) < 0 ||
             num_field(r, obj, "stall_torque", 1, &x);
        e->tau0 = (braun_real)x;
        if (!st) {
            st = num_field(r, obj, "no_load_speed", 1, &x) != 0;
            e->omega0 = (braun_real)x;
            if (!st && x == 0) {
                sj_push_key(r, "no_load_speed");
                st = sj_fail(r, SJ_AT_VALUE, "%s: field 'no_load_speed' must not be 0", r->who) != 0;
            }
        }
    } else {
        sj_push_key(r, "type");
        return sj_fail(r, SJ_AT_VALUE, "%s: unknown effect type '%s' (gravity, spring, torsion, "
                                       "force, torque, motor)", r->who, type);
    }
    return st ? -1 : 0;
}

/* ------------------------------------------------- corrections, reference */
static int read_corrections(sj_reader *r, json_t *root)
{
    /* Every scene has an energy law: driven joints add the work of their
     * constraint forces through BRAUN_CONSTRAINT_WORK. */
    const unsigned all = BRAUN_CORRECT_ALL;
    json_t *v = json_object_get(root, "corrections");
    r->out->corrections = all;
    if (!v) return 0;
    sj_push_key(r, "corrections");
    if (json_is_string(v) && strcmp(json_string_value(v), "all") == 0) {
        sj_pop(r);
        return 0;
    }
    if (json_is_string(v) && strcmp(json_string_value(v), "none") == 0) {
        r->out->corrections = BRAUN_CORRECT_NONE;
        sj_pop(r);
        return 0;
    }
    if (!json_is_array(v))
        return sj_fail(r, SJ_AT_VALUE, "scene: field 'corrections' must be \"all\", \"none\" or an "
                                       "array of \"position\", \"velocity\", \"energy\"");
    unsigned bits = 0;
    for (size_t i = 0; i < json_array_size(v); i++) {
        json_t *item = json_array_get(v, i);
        const char *s = json_is_string(item) ? json_string_value(item) : "";
        sj_push_index(r, (int)i);
        if (strcmp(s, "position") == 0) bits |= BRAUN_CORRECT_POSITION;
        else if (strcmp(s, "velocity") == 0) bits |= BRAUN_CORRECT_VELOCITY;
        else if (strcmp(s, "energy") == 0) bits |= BRAUN_CORRECT_ENERGY;
        else
            return sj_fail(r, SJ_AT_VALUE, "scene: field 'corrections': unknown correction '%s' "
                                           "(position, velocity, energy)",
                           json_is_string(item) ? s : "(not a string)");
        sj_pop(r);
    }
    r->out->corrections = bits;
    sj_pop(r);
    return 0;
}

/* ------------------------------------------------------------- driver */
/* The JSON path of a scene element, for errors the builder finds. */
static void element_path(sj_reader *r, const braun_scene_error *e)
{
    static const char *const arrays[] = {NULL, "bodies", NULL, "rods", "joints", "joints", "effects"};
    const braun_scene *s = &r->out->scene;
    r->depth = 0;
    int index = e->index;
    const char *kind = "scene", *name = NULL;
    switch (e->element) {
    case BRAUN_SCENE_ELEM_BODY: kind = "body"; name = r->out->body_names[index]; break;
    case BRAUN_SCENE_ELEM_ROD: kind = "rod"; name = r->rod_names[index]; break;
    case BRAUN_SCENE_ELEM_JOINT:
        kind = "joint";
        index = r->joint_json[index];
        name = r->out->joint_names[index];
        break;
    case BRAUN_SCENE_ELEM_KNIFE:
        kind = "joint";
        index = r->knife_json[index];
        name = r->out->joint_names[index];
        break;
    case BRAUN_SCENE_ELEM_EFFECT: kind = "effect"; name = r->out->effect_names[index]; break;
    case BRAUN_SCENE_ELEM_POINT: {
        const int body = s->points[index].body;
        kind = body >= 0 ? "body" : "scene";
        if (body >= 0) {
            name = r->out->body_names[body];
            sj_push_key(r, "bodies");
            sj_push_index(r, body);
        } else {
            sj_push_key(r, "ground");
        }
        set_who(r, kind, name, body);
        return;
    }
    default: break;
    }
    if (e->element < (int)(sizeof arrays / sizeof arrays[0]) && arrays[e->element] && index >= 0) {
        sj_push_key(r, arrays[e->element]);
        sj_push_index(r, index);
    }
    if (e->element == BRAUN_SCENE_ELEM_SCENE) snprintf(r->who, sizeof r->who, "scene");
    else set_who(r, kind, name, index);
}

int sj_read_scene(sj_reader *r, json_t *root)
{
    static const char *const keys[] = {"name",    "description", "bodies",      "ground",
                                       "rods",    "joints",      "effects",     "corrections",
                                       "reference", NULL};
    braun_scene_file *out = r->out;
    braun_scene *s = &out->scene;
    json_t *bodies, *rods, *joints, *effects, *ground;
    snprintf(r->who, sizeof r->who, "scene");
    if (!json_is_object(root)) return sj_fail(r, SJ_AT_VALUE, "a scene must be a JSON object");
    if (check_fields(r, root, keys)) return -1;
    if (str_field(r, root, "name", 1, &out->name)) return -1;
    out->description = "";
    if (str_field(r, root, "description", 0, &out->description) < 0) return -1;
    bodies = json_object_get(root, "bodies");
    if (!bodies) return missing(r, "bodies");
    if (array_field(r, root, "bodies", &bodies) || array_field(r, root, "rods", &rods) ||
        array_field(r, root, "joints", &joints) || array_field(r, root, "effects", &effects))
        return -1;
    if (json_array_size(bodies) == 0) {
        sj_push_key(r, "bodies");
        return sj_fail(r, SJ_AT_VALUE, "scene: field 'bodies' is empty: a scene needs a moving body");
    }
    ground = json_object_get(root, "ground");
    if (ground && !json_is_object(ground)) {
        sj_push_key(r, "ground");
        return sj_fail(r, SJ_AT_VALUE, "scene: field 'ground' must be an object {\"points\": {...}}");
    }

    /* Sizes: every array is allocated once, before any element is read. */
    const int nb = (int)json_array_size(bodies);
    const int nr = rods ? (int)json_array_size(rods) : 0;
    const int nj = joints ? (int)json_array_size(joints) : 0;
    const int ne = effects ? (int)json_array_size(effects) : 0;
    int np = nb + 2 * (nr + nj + ne) + 1;
    for (int k = 0; k < nb; k++) {
        json_t *pts = json_object_get(json_array_get(bodies, (size_t)k), "points");
        if (json_is_object(pts)) np += (int)json_object_size(pts);
    }
    if (ground && json_is_object(json_object_get(ground, "points")))
        np += (int)json_object_size(json_object_get(ground, "points"));
    r->cap_points = np;
    s->bodies = calloc((size_t)nb + 1, sizeof *s->bodies);
    s->points = calloc((size_t)np, sizeof *s->points);
    s->rods = calloc((size_t)nr + 1, sizeof *s->rods);
    s->joints = calloc((size_t)nj + 1, sizeof *s->joints);
    s->knives = calloc((size_t)nj + 1, sizeof *s->knives);
    s->effects = calloc((size_t)ne + 1, sizeof *s->effects);
    r->point_names = calloc((size_t)np, sizeof *r->point_names);
    r->knife_json = calloc((size_t)nj + 1, sizeof *r->knife_json);
    r->joint_json = calloc((size_t)nj + 1, sizeof *r->joint_json);
    r->rod_names = calloc((size_t)nr + 1, sizeof *r->rod_names);
    out->body_names = calloc((size_t)nb + 1, sizeof *out->body_names);
    out->joint_names = calloc((size_t)nj + 1, sizeof *out->joint_names);
    out->knife_names = calloc((size_t)nj + 1, sizeof *out->knife_names);
    out->effect_names = calloc((size_t)ne + 1, sizeof *out->effect_names);
    if (!s->bodies || !s->points || !s->rods || !s->joints || !s->knives || !s->effects ||
        !r->point_names || !r->knife_json || !r->joint_json || !r->rod_names || !out->body_names || !out->joint_names ||
        !out->knife_names || !out->effect_names)
        return sj_fail(r, SJ_AT_VALUE, "out of memory");

    if (ground) {
        static const char *const gkeys[] = {"points", NULL};
        sj_push_key(r, "ground");
        snprintf(r->who, sizeof r->who, "ground");
        if (check_fields(r, ground, gkeys) || read_points(r, ground, BRAUN_SCENE_GROUND)) return -1;
        sj_pop(r);
    }
    sj_push_key(r, "bodies");
    for (int k = 0; k < nb; k++) {
        json_t *obj;
        if (element(r, bodies, k, "body", &obj) || read_body(r, obj, k)) return -1;
        sj_pop(r);
    }
    sj_pop(r);
    sj_push_key(r, "rods");
    for (int k = 0; k < nr; k++) {
        json_t *obj;
        if (element(r, rods, k, "rod", &obj) || read_rod(r, obj, k)) return -1;
        s->nrods = k + 1;
        sj_pop(r);
    }
    sj_pop(r);
    sj_push_key(r, "joints");
    for (int k = 0; k < nj; k++) {
        json_t *obj;
        if (element(r, joints, k, "joint", &obj) || read_joint(r, obj, k)) return -1;
        sj_pop(r);
    }
    sj_pop(r);
    sj_push_key(r, "effects");
    for (int k = 0; k < ne; k++) {
        json_t *obj;
        if (element(r, effects, k, "effect", &obj) || read_effect(r, obj, k)) return -1;
        s->neffects = k + 1;
        sj_pop(r);
    }
    sj_pop(r);
    snprintf(r->who, sizeof r->who, "scene");

    if (read_corrections(r, root)) return -1;

    /* Build: what the builder refuses is reported at its element. */
    braun_scene_error berr;
    int st = braun_scene_build(s, &out->sys, &berr);
    if (st) {
        element_path(r, &berr);
        return sj_fail(r, SJ_AT_VALUE, "%s: %s", r->who, berr.what ? berr.what : braun_status_str(st));
    }

    out->reference = NULL;
    const char *ref = "";
    int got = str_field(r, root, "reference", 0, &ref);
    if (got < 0) return -1;
    if (got == 0) {
        const braun_builtin *b = braun_builtin_find(ref);
        sj_push_key(r, "reference");
        if (!b) return sj_fail(r, SJ_AT_VALUE, "scene: field 'reference': unknown built-in model "
                                               "'%s' (see braun list)", ref);
        if (b->sys.n != s->n)
            return sj_fail(r, SJ_AT_VALUE, "scene: field 'reference': '%s' has %d coordinates, "
                                           "the scene %d", ref, b->sys.n, s->n);
        sj_pop(r);
        out->reference = ref;
    }

    out->q0 = calloc((size_t)s->n, sizeof *out->q0);
    out->v0 = calloc((size_t)s->n, sizeof *out->v0);
    if (!out->q0 || !out->v0) return sj_fail(r, SJ_AT_VALUE, "out of memory");
    braun_scene_initial_state(s, out->q0, out->v0);
    out->sys.user = s;
    return 0;
}
