/* The scene file reader: from a jansson tree to the element arrays of a
 * braun_scene (docs/scene-format.md). Every check names the element and
 * the field and, through the reader's path, the file position. It knows no
 * element type: bodies, joints and effects are read through the field
 * descriptors of their classes (braun_scene.h), looked up by name among
 * the built-in classes and the program's own (braun_scene_load_ex). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_models.h"
#include "braun_c_locale.h"
#include "scene_json_internal.h"

/* Points an element makes for itself (a knife edge's contact point) are
 * named with a leading '.', which no name in a file can have: references
 * never find them, and messages do not list them. */
#define OWN_POINT "."

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

/* A number in range; the path is at the value. A nonzero number below the
 * smallest normal braun_real underflows: jansson reads "1e-400" as 0 and
 * "1e-310" as a subnormal that keeps a few bits, arithmetic on which is
 * slow too. Both are refused, with the least nonzero magnitude the field
 * accepts: least, BRAUN_SCENE_MIN_NORMAL or, for a parameter with a
 * domain, BRAUN_SCENE_MIN_SCALE (scale_value). */
/* x in the fewest digits that read back as x: "%g" wrote 1000000000001
 * as 1e+12, the limit it breaks. */
static const char *shortest(double x, char *buf, size_t size)
{
    for (int digits = 6; digits <= 17; digits++) {
        braun__c_snprintf(buf, size, "%.*g", digits, x);
        if (braun__c_strtod(buf, NULL) == x) break;
    }
    return buf;
}

static int number_in(sj_reader *r, json_t *v, const char *field, double least, double *x)
{
    if (!json_is_number(v)) return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be a number", r->who, field);
    *x = json_number_value(v);
    if (!isfinite(*x) || fabs(*x) > BRAUN_SCENE_MAX_ABS) {
        char value[32];
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' is out of range (%s; the limit is |x| <= %g)",
                       r->who, field, shortest(*x, value, sizeof value), BRAUN_SCENE_MAX_ABS);
    }
    const sj_underflow *u = sj_underflow_of(r, v);
    if (u || (*x != 0 && fabs(*x) < BRAUN_SCENE_MIN_NORMAL)) {
        char written[48], read[64];
        if (u) snprintf(written, sizeof written, "%.*s", u->len > 40 ? 40 : (int)u->len, u->text);
        else braun__c_snprintf(written, sizeof written, "%.3g", *x);
        if (*x == 0) snprintf(read, sizeof read, "0");
        else braun__c_snprintf(read, sizeof read, "the subnormal %.6g (a few bits at most)", *x);
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' underflows: %s%s is below the smallest "
                                       "normal number %g and would read as %s; the least nonzero "
                                       "magnitude it accepts is %g (%s)",
                       r->who, field, written, u && u->len > 40 ? "..." : "",
                       BRAUN_SCENE_MIN_NORMAL, read, least,
                       least > BRAUN_SCENE_MIN_NORMAL ? "BRAUN_SCENE_MIN_SCALE, for a field with a "
                                                        "domain"
                                                      : "BRAUN_SCENE_MIN_NORMAL");
    }
    return 0;
}

static int number_value(sj_reader *r, json_t *v, const char *field, double *x)
{
    return number_in(r, v, field, BRAUN_SCENE_MIN_NORMAL, x);
}

/* A parameter with a domain (a mass, a length, an axis, a stiffness, a
 * speed: a POSITIVE, NONNEG or NONZERO field), when not 0: at least
 * BRAUN_SCENE_MIN_SCALE in magnitude (a vector: in length), so that its
 * square, which the kinematics forms, is a normal number. */
static int scale_value(sj_reader *r, const char *field, const double *x, int count, int derived)
{
    double len = 0;
    for (int i = 0; i < count; i++) len = hypot(len, x[i]);
    if (len == 0 || len >= BRAUN_SCENE_MIN_SCALE) return 0;
    return sj_fail(r, SJ_AT_VALUE, "%s: field '%s'%s is too small (%s%g; the limit is %g, whose "
                                   "square is still a normal number)",
                   r->who, field, derived ? " (left out: taken from the initial state)" : "",
                   count > 1 ? "length " : "", len, BRAUN_SCENE_MIN_SCALE);
}

/* A value derived from the initial state for a field left out (a
 * distance's length, a spring's rest length) is in the range of a given
 * one: two points 1.2e12 apart made a length the scene builder refused as
 * "rod length must be a finite number > 0" or "joint parameters are not
 * finite numbers in range", naming neither the length nor the limit. */
static int derived_in_range(sj_reader *r, const char *field, const double *x, int count,
                            const char *instead)
{
    for (int i = 0; i < count; i++) {
        if (isfinite(x[i]) && fabs(x[i]) <= BRAUN_SCENE_MAX_ABS) continue;
        char value[32], entry[16] = "", used[80] = "";
        if (count > 1) snprintf(entry, sizeof entry, "[%d]", i);
        if (instead) snprintf(used, sizeof used, ", though '%.40s' is used", instead);
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s'%s (left out: taken from the initial state%s) "
                                       "is %s, beyond the limit |x| <= %g of a scene's numbers",
                       r->who, field, entry, used, shortest(x[i], value, sizeof value),
                       BRAUN_SCENE_MAX_ABS);
    }
    return 0;
}

/* Member key as a number (least: as number_in): 0 read, 1 absent and
 * optional, -1 error. */
static int num_field_in(sj_reader *r, json_t *obj, const char *key, int required, double least,
                        double *x)
{
    json_t *v = json_object_get(obj, key);
    if (!v) return required ? missing(r, key) : 1;
    sj_push_key(r, key);
    int st = number_in(r, v, key, least, x);
    sj_pop(r);
    return st;
}

static int num_field(sj_reader *r, json_t *obj, const char *key, int required, double *x)
{
    return num_field_in(r, obj, key, required, BRAUN_SCENE_MIN_NORMAL, x);
}

/* A number with a domain: sign > 0 asks x > 0, sign = 0 asks x >= 0. */
static int num_field_min(sj_reader *r, json_t *obj, const char *key, int required, int strict,
                         double *x)
{
    int st = num_field_in(r, obj, key, required, BRAUN_SCENE_MIN_SCALE, x);
    if (st) return st;
    if (strict ? !(*x > 0) : !(*x >= 0)) {
        sj_push_key(r, key);
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be %s 0 (got %g)", r->who, key,
                       strict ? ">" : ">=", *x);
    }
    sj_push_key(r, key);
    st = scale_value(r, key, x, 1, 0);
    sj_pop(r);
    return st;
}

/* An array of count numbers in range; the path is at the value. */
static int vec_value(sj_reader *r, json_t *v, const char *field, int count, double *x)
{
    int ok = json_is_array(v) && json_array_size(v) == (size_t)count;
    for (int i = 0; ok && i < count; i++) ok = json_is_number(json_array_get(v, (size_t)i));
    if (!ok)
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be an array of %d numbers", r->who,
                       field, count);
    for (int i = 0; i < count; i++) {
        sj_push_index(r, i);
        int st = number_value(r, json_array_get(v, (size_t)i), field, &x[i]);
        sj_pop(r);
        if (st) return st;
    }
    return 0;
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
    const char *type = NULL; /* set by str_field on success; -O3 -flto cannot tell */
    if (str_field(r, v, "type", 1, &type)) return -1;
    static const char *const k_const[] = {"type", "value", NULL};
    static const char *const k_lin[] = {"type", "value", "rate", NULL};
    static const char *const k_sin[] = {"type", "offset", "amplitude", "omega", "phase", NULL};
    static const char *const k_step[] = {"type", "before", "after", "time", NULL};
    double a = 0, b = 0, c = 0, d = 0;
    int st;
    if (strcmp(type, "constant") == 0) {
        f->kind = BRAUN_FN_CONSTANT;
        /* value, offset and phase are 0 when left out, in every type (the
         * constant's value was required, the linear's not); the other
         * fields are the function's shape and required. */
        st = check_fields(r, v, k_const) || num_field(r, v, "value", 0, &a) < 0;
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

/* ------------------------------------------------------ bodies, points */
static int find_body(const sj_reader *r, const char *name, size_t len)
{
    return sj_find_body(r, name, len);
}

/* Index of a new point. The table is sized for every point the file can
 * make (named ones, one centre per body, one per member of an element);
 * the guard only keeps a miscount from writing past it. */
static int add_point(sj_reader *r, int body, const double *xyz, const char *name)
{
    braun_scene *s = &r->out->scene;
    if (r->npoints >= r->cap_points) return r->cap_points - 1;
    const int i = r->npoints++;
    s->points[i].body = body;
    s->points[i].x = (braun_real)xyz[0];
    s->points[i].y = (braun_real)xyz[1];
    s->points[i].z = (braun_real)xyz[2];
    r->point_names[i] = name;
    s->npoints = r->npoints;
    return i;
}

static int find_point(const sj_reader *r, int body, const char *name)
{
    return sj_find_point(r, body, name);
}

/* A point reference: "body.point", "body" (a rigid body's centre or the
 * particle itself), "ground.point", or [x, y] ([x, y, z] in a spatial
 * scene) on the ground. */
static int point_ref(sj_reader *r, json_t *obj, const char *key, int *point)
{
    json_t *v = json_object_get(obj, key);
    if (!v) return missing(r, key);
    sj_push_key(r, key);
    int st = 0;
    if (json_is_array(v)) {
        double xyz[3] = {0, 0, 0};
        st = vec_value(r, v, key, r->dim, xyz);
        if (!st) *point = add_point(r, BRAUN_SCENE_GROUND, xyz, "");
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
                    const char *pn = r->point_names[i];
                    if (r->out->scene.points[i].body != body || !pn[0] || pn[0] == OWN_POINT[0])
                        continue;
                    if (names[0]) strncat(names, ", ", sizeof names - strlen(names) - 1);
                    strncat(names, pn, sizeof names - strlen(names) - 1);
                }
                st = sj_fail(r, SJ_AT_VALUE, "%s refers to unknown point '%s' (%.*s has %s%s)",
                             r->who, ref, (int)blen, ref, names[0] ? "points " : "no points",
                             names);
            }
        } else if (ground) {
            st = sj_fail(r, SJ_AT_VALUE, "%s: field '%s': 'ground' needs a point ('ground.NAME' "
                                         "or %s)", r->who, key, r->dim == 3 ? "[x, y, z]" : "[x, y]");
        } else {
            /* The centre: one implicit point per body, made on first use. */
            static const double origin[3] = {0, 0, 0};
            *point = find_point(r, body, "");
            if (*point < 0) {
                *point = add_point(r, body, origin, "");
                sj_set_centre(r, body, *point);
            }
        }
    } else {
        st = sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be a point: \"body.point\", \"body\" "
                                     "or %s on the ground", r->who, key,
                     r->dim == 3 ? "[x, y, z]" : "[x, y]");
    }
    sj_pop(r);
    return st;
}

/* A body reference: a body's name, or "ground" where allowed; a body with
 * an angle (rigid) where asked. */
static int body_ref(sj_reader *r, json_t *obj, const char *key, int ground_ok, int angle,
                    int *body)
{
    const char *name = "";
    int st = str_field(r, obj, key, 1, &name);
    if (st) return st;
    sj_push_key(r, key);
    if (strcmp(name, "ground") == 0) {
        *body = BRAUN_SCENE_GROUND;
        if (!ground_ok) st = sj_fail(r, SJ_AT_VALUE, "%s: field '%s' cannot be the ground", r->who, key);
    } else {
        *body = find_body(r, name, strlen(name));
        if (*body == -2) st = sj_fail(r, SJ_AT_VALUE, "%s refers to unknown body '%s'", r->who, name);
        else if (angle && r->out->scene.bodies[*body].kind->angle < 0)
            /* A rigid3d body has no single angle either: the element is
             * planar, and its spatial counterpart is what was meant. */
            st = r->out->scene.bodies[*body].kind == BRAUN_BODY_RIGID3D
                     ? sj_fail(r, SJ_AT_VALUE,
                               "%s: body '%s' in field '%s' is a rigid3d body, and this element is "
                               "planar (it acts on a planar body's angle): use its spatial "
                               "counterpart where there is one (torque3d, body_torque, torsion3d, motor3d, "
                               "revolute3d; a knife edge has none: docs/scene-format.md)",
                               r->who, name, key)
                     : sj_fail(r, SJ_AT_VALUE, "%s: body '%s' in field '%s' must be rigid (a "
                                               "particle has no angle)", r->who, name, key);
    }
    sj_pop(r);
    return st;
}

/* Named points of a body or of the ground: {"NAME": [x, y], ...} (count
 * coordinates each: 2 planar, 3 spatial). */
static int read_points(sj_reader *r, json_t *obj, int body, int count)
{
    json_t *pts = json_object_get(obj, "points");
    if (!pts) return 0;
    sj_push_key(r, "points");
    if (!json_is_object(pts)) {
        sj_fail(r, SJ_AT_VALUE, "%s: field 'points' must be an object {\"NAME\": %s, ...}", r->who,
                count == 3 ? "[x, y, z]" : "[x, y]");
        return -1;
    }
    const char *key;
    json_t *val;
    const int first = r->npoints;
    json_object_foreach(pts, key, val) {
        double xyz[3] = {0, 0, 0};
        sj_push_key(r, key);
        if (count != 2 && count != 3)
            return sj_fail(r, SJ_AT_KEY, "%s: points of %d coordinates", r->who, count);
        if (key[0] == '\0' || strchr(key, '.'))
            return sj_fail(r, SJ_AT_KEY, "%s: point name '%s' must be non-empty and contain no "
                                         "'.'", r->who, key);
        char field[160];
        snprintf(field, sizeof field, "points.%s", key);
        if (vec_value(r, val, field, count, xyz)) return -1;
        add_point(r, body, xyz, key);
        sj_pop(r);
    }
    sj_index_points(r, body, first);
    sj_pop(r);
    return 0;
}

/* ------------------------------------------------------------ classes */
/* fn: the class named type among the built-in list and the program's
 * extra one (each NULL-terminated, extra may be NULL); NULL, with the
 * names of both in names, when there is none. */
#define CLASS_FINDER(fn, T)                                                                 \
    static const T *fn(const T *const *builtin, const T *const *extra, const char *type,   \
                       char *names, size_t size)                                           \
    {                                                                                      \
        const T *const *lists[2] = {builtin, extra};                                       \
        names[0] = '\0';                                                                   \
        for (int l = 0; l < 2; l++)                                                        \
            for (const T *const *c = lists[l]; c && *c; c++)                               \
                if (strcmp((*c)->name, type) == 0) return *c;                              \
        for (int l = 0; l < 2; l++)                                                        \
            for (const T *const *c = lists[l]; c && *c; c++) {                             \
                if (names[0]) strncat(names, ", ", size - strlen(names) - 1);              \
                strncat(names, (*c)->name, size - strlen(names) - 1);                      \
            }                                                                              \
        return NULL;                                                                       \
    }
CLASS_FINDER(find_body_class, braun_scene_body_class)
CLASS_FINDER(find_joint_class, braun_scene_joint_class)
CLASS_FINDER(find_effect_class, braun_scene_effect_class)

/* An unknown "type": the message names the known ones ("unknown joint
 * type 'welded' (revolute, distance, ...)"). */
static int unknown_type(sj_reader *r, const char *kind, const char *type, const char *names)
{
    sj_push_key(r, "type");
    return sj_fail(r, SJ_AT_VALUE, "%s: unknown %s type '%s' (%s)", r->who, kind, type, names);
}

/* "name", "type" and the keys of a class's fields: the members an object
 * of that class may have. */
static int check_class_fields(sj_reader *r, json_t *obj, const braun_scene_field *fields,
                              int named)
{
    const char *keys[40];
    int k = 0;
    if (named) keys[k++] = "name";
    keys[k++] = "type";
    for (const braun_scene_field *f = fields; f && f->key && k < 39; f++) keys[k++] = f->key;
    keys[k] = NULL;
    return check_fields(r, obj, keys);
}

/* A number or an array of numbers into count braun_reals, with the
 * descriptor's domain; the path is at the value. */
static int real_value(sj_reader *r, json_t *v, const braun_scene_field *f, braun_real *out)
{
    /* A vector of the scene's dimension: 2 entries in a planar scene. */
    const int count = (f->flags & BRAUN_FIELD_DIMVEC) && r->dim == 2 ? 2
                      : f->count > 0                                 ? f->count
                                                                     : 1;
    double x[8] = {0};
    if (count > 8) return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' has too many entries", r->who, f->key);
    /* A vector's domain is on its length (scale_value), not its entries. */
    const double least = (f->flags & (BRAUN_FIELD_POSITIVE | BRAUN_FIELD_NONNEG | BRAUN_FIELD_NONZERO))
                             ? BRAUN_SCENE_MIN_SCALE
                             : BRAUN_SCENE_MIN_NORMAL;
    if (count == 1 ? number_in(r, v, f->key, least, x) : vec_value(r, v, f->key, count, x)) return -1;
    int zero = 1;
    for (int i = 0; i < count; i++) {
        if ((f->flags & BRAUN_FIELD_POSITIVE) && !(x[i] > 0))
            return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be > 0 (got %g)", r->who, f->key, x[i]);
        if ((f->flags & BRAUN_FIELD_NONNEG) && !(x[i] >= 0))
            return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must be >= 0 (got %g)", r->who, f->key,
                           x[i]);
        zero = zero && x[i] == 0;
    }
    if ((f->flags & BRAUN_FIELD_NONZERO) && zero)
        return sj_fail(r, SJ_AT_VALUE, "%s: field '%s' must not be %s", r->who, f->key,
                       count == 1 ? "0" : "the zero vector");
    if ((f->flags & (BRAUN_FIELD_POSITIVE | BRAUN_FIELD_NONNEG | BRAUN_FIELD_NONZERO)) &&
        scale_value(r, f->key, x, count, 0))
        return -1;
    if ((f->flags & BRAUN_FIELD_UNIT) && count > 1) {
        double len = 0;
        for (int i = 0; i < count; i++) len = hypot(len, x[i]);
        for (int i = 0; i < count; i++) x[i] /= len; /* not 0: NONZERO goes with it */
    }
    for (int i = 0; i < count; i++) out[i] = (braun_real)x[i];
    return 0;
}

/* A joint by its name (effects on a joint's axis). */
static int joint_ref(sj_reader *r, json_t *obj, const braun_scene_field *f, int *joint)
{
    const char *name = "";
    int st = str_field(r, obj, f->key, 1, &name);
    if (st) return st;
    sj_push_key(r, f->key);
    *joint = sj_find_joint(r, name);
    if (*joint == -2) return sj_fail(r, SJ_AT_VALUE, "out of memory");
    if (*joint < 0)
        return sj_fail(r, SJ_AT_VALUE, "%s refers to unknown joint '%s' (a joint is named by its "
                                       "\"name\")", r->who, name);
    sj_pop(r);
    return 0;
}

/* One field, present in obj, into the element at elem. */
static int read_field(sj_reader *r, json_t *obj, json_t *v, const braun_scene_field *f,
                      void *elem, int body)
{
    char *at = (char *)elem + f->offset;
    int *ref = (int *)(void *)at;
    const int count = f->count > 0 ? f->count : 1;
    int st;
    switch (f->kind) {
    case BRAUN_FIELD_POINT: return point_ref(r, obj, f->key, ref);
    case BRAUN_FIELD_BODY:
        return body_ref(r, obj, f->key, (f->flags & BRAUN_FIELD_GROUND) != 0,
                        (f->flags & BRAUN_FIELD_ANGLE) != 0, ref);
    case BRAUN_FIELD_BODY_POINT: {
        /* The element's own point, at the body's origin until an OFFSET
         * field moves it. */
        static const double origin[3] = {0, 0, 0};
        int b;
        if (body_ref(r, obj, f->key, 0, (f->flags & BRAUN_FIELD_ANGLE) != 0, &b)) return -1;
        *ref = add_point(r, b, origin, OWN_POINT);
        return 0;
    }
    case BRAUN_FIELD_OFFSET: {
        double x[3] = {0, 0, 0};
        sj_push_key(r, f->key);
        st = count != 2 ? sj_fail(r, SJ_AT_VALUE, "%s: field '%s': points have 2 coordinates",
                                  r->who, f->key)
                        : vec_value(r, v, f->key, count, x);
        sj_pop(r);
        if (st) return -1;
        if (*ref >= 0 && *ref < r->npoints) {
            braun_scene_point *pt = &r->out->scene.points[*ref];
            pt->x = (braun_real)x[0];
            pt->y = (braun_real)x[1];
        }
        return 0;
    }
    case BRAUN_FIELD_REAL:
        sj_push_key(r, f->key);
        st = real_value(r, v, f, (braun_real *)(void *)at);
        sj_pop(r);
        return st;
    case BRAUN_FIELD_FN: {
        braun_scene_fn *fn = (braun_scene_fn *)(void *)at;
        sj_push_key(r, f->key);
        st = fn_value(r, v, f->key, fn);
        if (!st && (f->flags & BRAUN_FIELD_SMOOTH) && fn->kind == BRAUN_FN_STEP)
            st = sj_fail(r, SJ_AT_VALUE, "%s: a %s must be smooth (constant, linear or sine), "
                                         "not a step", r->who, f->key);
        sj_pop(r);
        return st;
    }
    case BRAUN_FIELD_POINTS: return read_points(r, obj, body, count);
    case BRAUN_FIELD_JOINT: return joint_ref(r, obj, f, ref);
    default:
        sj_push_key(r, f->key);
        return sj_fail(r, SJ_AT_KEY, "%s: field '%s' has a kind the reader does not know (%d)",
                       r->who, f->key, f->kind);
    }
}

/* Every field of a class's table, in table order, then the exclusions;
 * given: a bit per field present. body: the element's index, for a body's
 * named points. */
static int read_fields(sj_reader *r, json_t *obj, const braun_scene_field *fields, void *elem,
                       int body, unsigned *given)
{
    *given = 0;
    int i = 0;
    for (const braun_scene_field *f = fields; f && f->key; f++, i++) {
        json_t *v = json_object_get(obj, f->key);
        if (!v) {
            if (f->flags & BRAUN_FIELD_REQUIRED) return missing(r, f->key);
            /* Optional references left out: a body is the ground, a point
             * none (the builder refuses it unless the class allows). */
            if (f->kind == BRAUN_FIELD_BODY) *(int *)(void *)((char *)elem + f->offset) = BRAUN_SCENE_GROUND;
            if (f->kind == BRAUN_FIELD_POINT || f->kind == BRAUN_FIELD_BODY_POINT ||
                f->kind == BRAUN_FIELD_JOINT)
                *(int *)(void *)((char *)elem + f->offset) = -1;
            continue;
        }
        if (i < 32) *given |= 1u << i;
        if (read_field(r, obj, v, f, elem, body)) return -1;
    }
    i = 0;
    for (const braun_scene_field *f = fields; f && f->key; f++, i++) {
        if (!f->excludes || i >= 32 || !BRAUN_FIELD_GIVEN(*given, i)) continue;
        if (!json_object_get(obj, f->excludes)) continue;
        sj_push_key(r, f->key);
        return sj_fail(r, SJ_AT_KEY, "%s: give '%s' or '%s', not both", r->who, f->key, f->excludes);
    }
    return 0;
}

/* Values a class's defaults hook derived from the initial state for fields
 * left out (a distance's length, a spring's rest length) meet the limits
 * of given ones. A field whose alternative is given (a length beside a
 * drive) is unused and only held to the range of a scene's numbers, which
 * the scene builder checks too (with no word of the field). */
static int derived_values(sj_reader *r, json_t *obj, const braun_scene_field *fields,
                          const void *elem, unsigned given)
{
    int i = 0;
    for (const braun_scene_field *f = fields; f && f->key; f++, i++) {
        if (f->kind != BRAUN_FIELD_REAL || i >= 32 || BRAUN_FIELD_GIVEN(given, i)) continue;
        if (!(f->flags & (BRAUN_FIELD_POSITIVE | BRAUN_FIELD_NONNEG | BRAUN_FIELD_NONZERO)))
            continue;
        const int unused = f->excludes && json_object_get(obj, f->excludes);
        const braun_real *v = (const braun_real *)(const void *)((const char *)elem + f->offset);
        const int count = f->count > 0 && f->count <= 8 ? f->count : 1;
        double x[8];
        for (int k = 0; k < count; k++) x[k] = (double)v[k];
        if (derived_in_range(r, f->key, x, count, unused ? f->excludes : NULL)) return -1;
        if (!unused && scale_value(r, f->key, x, count, 1)) return -1;
    }
    return 0;
}

/* ------------------------------------------------------------- bodies */
static int read_body(sj_reader *r, json_t *obj, int k)
{
    braun_scene_body *b = &r->out->scene.bodies[k];
    const char *name = NULL;
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
    const char *type = "";
    char names[512];
    if (str_field(r, obj, "type", 1, &type)) return -1;
    const braun_scene_body_class *c =
        find_body_class(braun_scene_body_classes, r->extra.bodies, type, names, sizeof names);
    if (!c) return unknown_type(r, "body", type, names);
    b->kind = c;
    if (check_class_fields(r, obj, c->fields, 1)) return -1;
    r->out->body_names[k] = name;
    r->out->scene.nbodies = k + 1; /* visible to find_body from now on */
    unsigned given;
    if (read_fields(r, obj, c->fields, b, k, &given)) return -1;
    if (c->defaults) c->defaults(b, given);
    return 0;
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
    rod->length = st == 1 ? braun_scene_initial_distance(&r->out->scene, rod->a, rod->b)
                          : (braun_real)x;
    if (st == 1) {
        x = (double)rod->length;
        return derived_in_range(r, "length", &x, 1, NULL) || scale_value(r, "length", &x, 1, 1) ? -1 : 0;
    }
    return 0;
}

/* ------------------------------------------------------------- joints */
static int read_joint(sj_reader *r, json_t *obj, int k)
{
    braun_scene *s = &r->out->scene;
    braun_scene_joint *j = &s->joints[k];
    const char *name = NULL;
    memset(j, 0, sizeof *j);
    set_who(r, "joint", NULL, k);
    if (name_field(r, obj, &name)) return -1;
    set_who(r, "joint", name, k);
    r->out->joint_names[k] = name;
    const char *type = "";
    char names[512];
    if (str_field(r, obj, "type", 1, &type)) return -1;
    const braun_scene_joint_class *c =
        find_joint_class(braun_scene_joint_classes, r->extra.joints, type, names, sizeof names);
    if (!c) return unknown_type(r, "joint", type, names);
    j->type = c;
    unsigned given;
    if (check_class_fields(r, obj, c->fields, 1) || read_fields(r, obj, c->fields, j, k, &given))
        return -1;
    if (c->defaults) c->defaults(s, j, given);
    if (derived_values(r, obj, c->fields, j, given)) return -1;
    s->njoints = k + 1;
    return 0;
}

/* ------------------------------------------------------------ effects */
static int read_effect(sj_reader *r, json_t *obj, int k)
{
    braun_scene *s = &r->out->scene;
    braun_scene_effect *e = &s->effects[k];
    const char *name = NULL;
    memset(e, 0, sizeof *e);
    set_who(r, "effect", NULL, k);
    if (name_field(r, obj, &name)) return -1;
    set_who(r, "effect", name, k);
    r->out->effect_names[k] = name;
    const char *type = "";
    char names[512];
    if (str_field(r, obj, "type", 1, &type)) return -1;
    const braun_scene_effect_class *c =
        find_effect_class(braun_scene_effect_classes, r->extra.effects, type, names, sizeof names);
    if (!c) return unknown_type(r, "effect", type, names);
    e->type = c;
    unsigned given;
    if (check_class_fields(r, obj, c->fields, 1) || read_fields(r, obj, c->fields, e, k, &given))
        return -1;
    if (c->defaults) c->defaults(s, e, given);
    if (derived_values(r, obj, c->fields, e, given)) return -1;
    s->neffects = k + 1;
    return 0;
}

/* ------------------------------------------------- corrections, reference */
static int read_corrections(sj_reader *r, json_t *root)
{
    /* Every scene has an energy law: driven joints add the work of their
     * constraint forces, which the core adds to Ė (a scene without drives
     * is declared scleronomic). */
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

/* ------------------------------------------------------------- report */
/* The body whose CSV name (its "name", or "body[i]" without one) is a
 * reported point's, or -1. */
static int report_clash(const braun_scene_file *out, const char *key)
{
    for (int b = 0; b < out->scene.nbodies; b++) {
        char own[32];
        const char *bn = out->body_names ? out->body_names[b] : NULL;
        if (!bn) {
            snprintf(own, sizeof own, "body[%d]", b);
            bn = own;
        }
        if (strcmp(bn, key) == 0) return b;
    }
    return -1;
}

/* "report": {"NAME": point, ...}: named points for the trajectory CSV. */
static int read_report(sj_reader *r, json_t *report)
{
    braun_scene_file *out = r->out;
    const size_t n = json_object_size(report);
    out->report_names = calloc(n + 1, sizeof *out->report_names);
    out->report_points = calloc(n + 1, sizeof *out->report_points);
    if (!out->report_names || !out->report_points) return sj_fail(r, SJ_AT_VALUE, "out of memory");
    const char *key;
    json_t *val;
    sj_push_key(r, "report");
    json_object_foreach(report, key, val) {
        snprintf(r->who, sizeof r->who, "reported point '%.120s'", key);
        if (key[0] == '\0' || strchr(key, '.')) {
            sj_push_key(r, key);
            return sj_fail(r, SJ_AT_KEY, "%s: a reported point's name must be non-empty and "
                                         "contain no '.'", r->who);
        }
        int point = -1;
        if (point_ref(r, report, key, &point)) return -1;
        /* NAME.x, NAME.y would repeat a body's columns of the CSV (body.x,
         * body.y; "body[3]" names an unnamed body there), and --plot
         * NAME.x could mean either: refused, but for the body itself
         * ({"P1": "P1"}, the IFToMM scenes), whose columns agree. */
        const int clash = report_clash(out, key);
        const braun_scene_point *pt = &out->scene.points[point];
        if (clash >= 0 && !(pt->body == clash && pt->x == 0 && pt->y == 0 && pt->z == 0)) {
            sj_push_key(r, key);
            if (r->dim == 3) /* a spatial body's columns are NAME.q[k]: no clash there */
                return sj_fail(r, SJ_AT_KEY, "%s: body %d is named '%.120s' too: --points and "
                                             "--plot %.120s.x would mean either; give the point a "
                                             "name no body has", r->who, clash, key, key);
            return sj_fail(r, SJ_AT_KEY, "%s: body %d is named '%.120s' too: the trajectory CSV's "
                                         "columns %.120s.x, %.120s.y would name both; give the "
                                         "point a name no body has", r->who, clash, key, key, key);
        }
        out->report_names[out->nreports] = key;
        out->report_points[out->nreports++] = point;
    }
    (void)val;
    sj_pop(r);
    return 0;
}

/* ------------------------------------------------------------- driver */
/* The scene is spatial when its bodies are (their classes' dim), known
 * before the ground points, which are read first. An unknown type or a
 * type of the other dimension is reported when that body is read. */
static int scene_dimension(sj_reader *r, json_t *bodies)
{
    r->dim = 2;
    for (size_t k = 0; k < json_array_size(bodies); k++) {
        json_t *t = json_object_get(json_array_get(bodies, k), "type");
        if (!json_is_string(t)) continue;
        char names[512];
        const braun_scene_body_class *c = find_body_class(
            braun_scene_body_classes, r->extra.bodies, json_string_value(t), names, sizeof names);
        if (c) {
            r->dim = c->dim == 3 ? 3 : 2;
            return 0;
        }
    }
    return 0;
}

/* The JSON path of a scene element, for errors the builder finds. */
static void element_path(sj_reader *r, const braun_scene_error *e)
{
    static const char *const arrays[] = {NULL, "bodies", NULL, "rods", "joints", "effects"};
    const braun_scene *s = &r->out->scene;
    r->depth = 0;
    int index = e->index;
    const char *kind = "scene", *name = NULL;
    switch (e->element) {
    case BRAUN_SCENE_ELEM_BODY: kind = "body"; name = r->out->body_names[index]; break;
    case BRAUN_SCENE_ELEM_ROD: kind = "rod"; name = r->rod_names[index]; break;
    case BRAUN_SCENE_ELEM_JOINT: kind = "joint"; name = r->out->joint_names[index]; break;
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
                                       "reference", "report",    NULL};
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
    json_t *report = json_object_get(root, "report");
    if (report && !json_is_object(report)) {
        sj_push_key(r, "report");
        return sj_fail(r, SJ_AT_VALUE, "scene: field 'report' must be an object {\"NAME\": point, "
                                       "...}");
    }
    if (scene_dimension(r, bodies)) return -1;
    ground = json_object_get(root, "ground");
    if (ground && !json_is_object(ground)) {
        sj_push_key(r, "ground");
        return sj_fail(r, SJ_AT_VALUE, "scene: field 'ground' must be an object {\"points\": {...}}");
    }

    /* Sizes: every array is allocated once, before any element is read.
     * Points: a centre per body, its named points, and at most one per
     * member of a rod, joint or effect. */
    const int nb = (int)json_array_size(bodies);
    const int nr = rods ? (int)json_array_size(rods) : 0;
    const int nj = joints ? (int)json_array_size(joints) : 0;
    const int ne = effects ? (int)json_array_size(effects) : 0;
    int np = nb + 2 * nr + 1;
    for (int k = 0; k < nb; k++) {
        json_t *pts = json_object_get(json_array_get(bodies, (size_t)k), "points");
        if (json_is_object(pts)) np += (int)json_object_size(pts);
    }
    for (int k = 0; k < nj + ne; k++) {
        json_t *obj = json_array_get(k < nj ? joints : effects, (size_t)(k < nj ? k : k - nj));
        if (json_is_object(obj)) np += (int)json_object_size(obj);
    }
    if (ground && json_is_object(json_object_get(ground, "points")))
        np += (int)json_object_size(json_object_get(ground, "points"));
    if (report) np += (int)json_object_size(report);
    r->cap_points = np;
    s->bodies = calloc((size_t)nb + 1, sizeof *s->bodies);
    s->points = calloc((size_t)np, sizeof *s->points);
    s->rods = calloc((size_t)nr + 1, sizeof *s->rods);
    s->joints = calloc((size_t)nj + 1, sizeof *s->joints);
    s->effects = calloc((size_t)ne + 1, sizeof *s->effects);
    r->point_names = calloc((size_t)np, sizeof *r->point_names);
    r->point_sorted = calloc((size_t)np, sizeof *r->point_sorted);
    r->rod_names = calloc((size_t)nr + 1, sizeof *r->rod_names);
    out->body_names = calloc((size_t)nb + 1, sizeof *out->body_names);
    out->joint_names = calloc((size_t)nj + 1, sizeof *out->joint_names);
    out->effect_names = calloc((size_t)ne + 1, sizeof *out->effect_names);
    if (!s->bodies || !s->points || !s->rods || !s->joints || !s->effects || !r->point_names ||
        !r->point_sorted || sj_index_bodies(r, bodies) ||
        !r->rod_names || !out->body_names || !out->joint_names || !out->effect_names)
        return sj_fail(r, SJ_AT_VALUE, "out of memory");

    if (ground) {
        static const char *const gkeys[] = {"points", NULL};
        sj_push_key(r, "ground");
        snprintf(r->who, sizeof r->who, "ground");
        if (check_fields(r, ground, gkeys) || read_points(r, ground, BRAUN_SCENE_GROUND, r->dim))
            return -1;
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
    {
        int later = 0, first = 0;
        const int dup = sj_duplicate_joint(r, &later, &first);
        if (dup == -2) return sj_fail(r, SJ_AT_VALUE, "out of memory");
        if (dup) {
            sj_push_index(r, later);
            sj_push_key(r, "name");
            set_who(r, "joint", NULL, later);
            return sj_fail(r, SJ_AT_VALUE, "%s: field 'name': '%s' is already the name of joint #%d "
                           "(effects refer to a joint by its name, and messages name it)", r->who,
                           r->out->joint_names[later], first + 1);
        }
    }
    sj_pop(r);
    sj_push_key(r, "effects");
    for (int k = 0; k < ne; k++) {
        json_t *obj;
        if (element(r, effects, k, "effect", &obj) || read_effect(r, obj, k)) return -1;
        sj_pop(r);
    }
    sj_pop(r);
    snprintf(r->who, sizeof r->who, "scene");
    if (report && read_report(r, report)) return -1;

    if (read_corrections(r, root)) return -1;

    /* Build: what the builder refuses is reported at its element. */
    braun_scene_error berr;
    /* Storage of the coordinates' natural sizes (braun_scene.q_scale): the
     * accuracy guard judges each coordinate in its own unit. */
    {
        size_t n = 0;
        for (int k = 0; k < s->nbodies; k++)
            if (s->bodies[k].kind && s->bodies[k].kind->dof > 0) n += (size_t)s->bodies[k].kind->dof;
        s->q_scale = calloc(n + 1, sizeof *s->q_scale);
        if (!s->q_scale) return sj_fail(r, SJ_AT_VALUE, "out of memory");
    }
    int st = braun_scene_build(s, &out->sys, &berr);
    if (st) {
        element_path(r, &berr);
        return sj_fail(r, SJ_AT_VALUE, "%s: %s", r->who, berr.what ? berr.what : braun_status_str(st));
    }

    out->reference = NULL;
    const char *ref = "";
    const braun_builtin *ref_model = NULL;
    int got = str_field(r, root, "reference", 0, &ref);
    if (got < 0) return -1;
    if (got == 0) {
        const braun_builtin *b = braun_builtin_find(ref);
        sj_push_key(r, "reference");
        if (!b) {
            /* The models with a reference solution, by name (braun list
             * also lists andrews, whose reference is not this kind). */
            char names[160] = "";
            for (int k = 0; braun_builtin_at(k); k++) {
                if (k) strncat(names, ", ", sizeof names - strlen(names) - 1);
                strncat(names, braun_builtin_at(k)->name, sizeof names - strlen(names) - 1);
            }
            return sj_fail(r, SJ_AT_VALUE, "scene: field 'reference': '%.60s' is not a built-in "
                                           "model with a reference (one of %s)", ref, names);
        }
        if (b->sys.n != s->n)
            return sj_fail(r, SJ_AT_VALUE, "scene: field 'reference': '%s' has %d coordinates, "
                                           "the scene %d", ref, b->sys.n, s->n);
        sj_pop(r);
        out->reference = ref;
        ref_model = b;
    }

    out->q0 = calloc((size_t)s->n, sizeof *out->q0);
    out->v0 = calloc((size_t)s->n, sizeof *out->v0);
    if (!out->q0 || !out->v0) return sj_fail(r, SJ_AT_VALUE, "out of memory");
    braun_scene_initial_state(s, out->q0, out->v0);
    out->sys.user = s;
    /* What the reader accepted must also compute: M factors, and every
     * element evaluates at the initial state. */
    if (sj_check_mass(r) || sj_check_initial(r)) return -1;
    if (ref_model && sj_check_reference(r, ref_model)) return -1;
    return 0;
}
