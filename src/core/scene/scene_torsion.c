/* Rotational spring and damper between two bodies (or a body and the
 * ground) on the relative angle Δ = θ_b - θ_a:
 *   torque on b  τ = -(k (Δ - rest) + c Δ'),  on a -τ
 *   potential    V = ½ k (Δ - rest)²,  input power Ė = -c Δ'². */
#include "scene_internal.h"

static int relative(const braun_scene *s, const braun_scene_effect *e, const braun_real *q,
                    const braun_real *v, braun_real *d, braun_real *dd, int *ca, int *cb)
{
    braun_real ta, tb, wa, wb;
    *ca = braun_scene__angle(s, e->a, q, v, &ta, &wa);
    *cb = braun_scene__angle(s, e->b, q, v, &tb, &wb);
    *d = tb - ta;
    *dd = wb - wa;
    return 0;
}

static int torsion_forces(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                          const braun_real *q, const braun_real *v, braun_real *Q)
{
    braun_real d, dd;
    int ca, cb;
    (void)t;
    relative(s, e, q, v, &d, &dd, &ca, &cb);
    const braun_real tau = -(e->k * (d - e->rest) + e->c * dd);
    if (cb >= 0) Q[cb] += tau;
    if (ca >= 0) Q[ca] -= tau;
    return 0;
}

static int torsion_potential(const braun_scene *s, const braun_scene_effect *e,
                             const braun_real *q, braun_real *V, braun_real *dVdq)
{
    braun_real d, dd;
    int ca, cb;
    relative(s, e, q, NULL, &d, &dd, &ca, &cb);
    const braun_real x = d - e->rest;
    if (dVdq) {
        if (cb >= 0) dVdq[cb] += e->k * x;
        if (ca >= 0) dVdq[ca] -= e->k * x;
    }
    *V = BRAUN_R(0.5) * e->k * x * x;
    return 0;
}

static int torsion_power(const braun_scene *s, const braun_scene_effect *e, braun_real t,
                         const braun_real *q, const braun_real *v, braun_real *P)
{
    braun_real d, dd;
    int ca, cb;
    (void)t;
    relative(s, e, q, v, &d, &dd, &ca, &cb);
    *P = -e->c * dd * dd;
    return 0;
}

/* Only a damper puts energy in or out. */
static int torsion_inputs(const braun_scene_effect *e)
{
    return e->c != 0;
}

static const char *torsion_check(const braun_scene *s, const braun_scene_effect *e)
{
    if ((e->a >= 0 && !braun_scene__is_rigid(s, e->a)) ||
        (e->b >= 0 && !braun_scene__is_rigid(s, e->b)))
        return "rotational spring needs rigid bodies (or ground)";
    const char *same = braun_scene__same_body(e->a, e->b, 2);
    if (same) return same;
    if (e->k < 0 || e->c < 0) return "stiffness and damping must be >= 0";
    return NULL;
}

enum { F_A, F_B, F_STIFFNESS, F_DAMPING, F_REST };

/* Scene files: a rest angle left out is the initial relative angle. */
static void torsion_defaults(const braun_scene *s, braun_scene_effect *e, unsigned given)
{
    if (!BRAUN_FIELD_GIVEN(given, F_REST))
        e->rest = braun_scene_initial_angle(s, e->b) - braun_scene_initial_angle(s, e->a);
}

#define BODY_FLAGS (BRAUN_FIELD_REQUIRED | BRAUN_FIELD_GROUND | BRAUN_FIELD_ANGLE)
static const braun_scene_field torsion_fields[] = {
    [F_A] = {"a", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, a), BODY_FLAGS, NULL},
    [F_B] = {"b", BRAUN_FIELD_BODY, 0, offsetof(braun_scene_effect, b), BODY_FLAGS, NULL},
    [F_STIFFNESS] = {"stiffness", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, k),
                     BRAUN_FIELD_NONNEG, NULL},
    [F_DAMPING] = {"damping", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, c),
                   BRAUN_FIELD_NONNEG, NULL},
    [F_REST] = {"rest_angle", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_effect, rest), 0, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_effect_class braun_scene_effect_torsion = {
    "torsion", "BRAUN_EFFECT_TORSION", torsion_fields, torsion_defaults, torsion_check,
    torsion_forces, torsion_potential, torsion_power, torsion_inputs, 2};
