/* Prismatic joint: a slider (scene_slider.c) whose two bodies also keep
 * their relative angle, θ_P - θ_L - value = 0 (scene_angle.c): the line
 * row, the angle row, and the drive row when driven. */
#include "scene_internal.h"

enum { F_POINT, F_LINE, F_AXIS, F_ANGLE, F_DRIVE };

/* Scene files: an angle left out is the initial relative angle. */
static void prismatic_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    j->driven = (int)BRAUN_FIELD_GIVEN(given, F_DRIVE);
    if (!BRAUN_FIELD_GIVEN(given, F_ANGLE))
        j->value = braun_scene_initial_angle(s, s->points[j->a].body) -
                   braun_scene_initial_angle(s, s->points[j->b].body);
}

static const char *prismatic_check(const braun_scene *s, const braun_scene_joint *j)
{
    const char *why = braun_scene__slider_check(s, j);
    if (why) return why;
    if (!braun_scene__is_rigid(s, braun_scene__body_of(s, j->a)))
        return "a prismatic joint's sliding body must be rigid";
    return NULL;
}

static int prismatic_rows(const braun_scene_joint *j)
{
    return 2 + (j->driven ? 1 : 0);
}

static int prismatic_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                          const braun_real *q, const braun_real *v, braun_real *phi,
                          braun_real *A, braun_real *b, braun_real *bv)
{
    braun_scene__slider_rows(s, j, 1, t, q, v, phi, A, b, bv);
    return 0;
}

static const braun_scene_field prismatic_fields[] = {
    [F_POINT] = {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a),
                 BRAUN_FIELD_REQUIRED, NULL},
    [F_LINE] = {"line", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED,
                NULL},
    [F_AXIS] = {"axis", BRAUN_FIELD_REAL, 2, offsetof(braun_scene_joint, axis),
                BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO, NULL},
    [F_ANGLE] = {"angle", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_joint, value), 0, NULL},
    [F_DRIVE] = {"drive", BRAUN_FIELD_FN, 0, offsetof(braun_scene_joint, drive), BRAUN_FIELD_SMOOTH,
                 NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_prismatic = {
    "prismatic", "BRAUN_JOINT_PRISMATIC", 0, prismatic_fields, prismatic_defaults,
    prismatic_check, prismatic_rows, NULL, prismatic_eval, 2};
