/* Slider (point on a line); the prismatic joint (scene_prismatic.c) adds a
 * fixed relative angle. The line passes through point A (on body L or the
 * ground) with unit direction u = R(θ_L) u_L and normal n = R(θ_L) n_L,
 * n_L = u_L turned by +90°. With e = P - A:
 *   Φ = n·e                                            (1 row)
 *   A_q = nᵀ(J_P - J_A) + (Jn·e) at θ_L                 (Jn = ∂n/∂θ_L)
 *   Φ'' = A_q v' + n·(cc_P - cc_A) + 2ω_L (Jn)·e' - ω_L² n·e
 * so b_qv = -n·(cc_P - cc_A) - 2ω_L (Jn)·e' + ω_L² n·e (the paper's row 5
 * of Eq. 22 is the ground case). A driven slider adds u·e - f(t) = 0 with
 * the same algebra and b_q = f', b_qv += f''. A prismatic joint adds
 * θ_P - θ_L - value = 0 (scene_angle.c). */
#include "scene_internal.h"

/* One row g·e - f(t) with g = R(θ_L) g_L a body-fixed direction of L. */
static void line_row(const braun_scene *s, int body_l, const scene_pt *P, const scene_pt *Pa,
                     const braun_real *gl, const braun_scene_fn *f, braun_real t,
                     const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
                     braun_real *b, braun_real *bv)
{
    braun_real th, w;
    const int col = braun_scene__angle(s, body_l, q, v, &th, &w);
    braun_real c, sn;
    braun_sincos(th, &sn, &c);
    /* Ground lines keep g exact (no rotation by 0). */
    const braun_real gx = col >= 0 ? c * gl[0] - sn * gl[1] : gl[0];
    const braun_real gy = col >= 0 ? sn * gl[0] + c * gl[1] : gl[1];
    const braun_real jx = -gy, jy = gx; /* ∂g/∂θ_L */
    const braun_real ex = P->pos[0] - Pa->pos[0], ey = P->pos[1] - Pa->pos[1];
    braun_real x = 0, dx = 0, ddx = 0;
    if (f) braun_scene_fn_eval(f, t, &x, &dx, &ddx);
    if (phi) phi[0] = gx * ex + gy * ey - x;
    if (A) {
        braun_scene__add_grad(P, gx, gy, A);
        braun_scene__add_grad(Pa, -gx, -gy, A);
        if (col >= 0) A[col] += jx * ex + jy * ey;
    }
    if (b) b[0] = dx;
    if (bv) {
        const braun_real cx = P->cc[0] - Pa->cc[0], cy = P->cc[1] - Pa->cc[1];
        braun_real r = -(gx * cx + gy * cy) + ddx;
        if (col >= 0) {
            const braun_real dex = P->vel[0] - Pa->vel[0], dey = P->vel[1] - Pa->vel[1];
            r += -BRAUN_R(2.0) * w * (jx * dex + jy * dey) + w * w * (gx * ex + gy * ey);
        }
        bv[0] = r;
    }
}

void braun_scene__slider_rows(const braun_scene *s, const braun_scene_joint *j, int lock,
                              braun_real t, const braun_real *q, const braun_real *v,
                              braun_real *phi, braun_real *A, braun_real *b, braun_real *bv)
{
    const int n = s->n;
    const int body_l = s->points[j->b].body;
    scene_pt P, Pa;
    braun_scene__point(s, j->a, q, v, &P);
    braun_scene__point(s, j->b, q, v, &Pa);
    const braun_real norm = braun_sqrt(j->axis[0] * j->axis[0] + j->axis[1] * j->axis[1]);
    const braun_real u[2] = {j->axis[0] / norm, j->axis[1] / norm};
    const braun_real nl[2] = {-u[1], u[0]};
    int r = 0;
#define ROW(k) (phi ? phi + (k) : NULL), (A ? A + braun_scene__at(k, 0, n) : NULL), \
               (b ? b + (k) : NULL), (bv ? bv + (k) : NULL)
    line_row(s, body_l, &P, &Pa, nl, NULL, t, q, v, ROW(r));
    r++;
    if (lock) {
        const braun_scene_fn fixed = {BRAUN_FN_CONSTANT, j->value, 0, 0, 0};
        braun_scene__angle_rows(s, body_l, s->points[j->a].body, &fixed, t, q, v, ROW(r));
        r++;
    }
    if (j->driven) line_row(s, body_l, &P, &Pa, u, &j->drive, t, q, v, ROW(r));
#undef ROW
}

const char *braun_scene__slider_check(const braun_scene *s, const braun_scene_joint *j)
{
    const char *same = braun_scene__same_body_points(s, j->a, j->b, 0);
    if (same) return same;
    if (j->axis[0] == 0 && j->axis[1] == 0) return "slider axis is the zero vector";
    if (braun_scene__body_of(s, j->a) < 0) return "the sliding point is on the ground";
    const int bl = braun_scene__body_of(s, j->b);
    if (bl >= 0 && !braun_scene__is_rigid(s, bl))
        return "the line of a slider must be on a rigid body or the ground";
    return NULL;
}

enum { F_POINT, F_LINE, F_AXIS, F_DRIVE };

static void slider_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    (void)s;
    j->driven = (int)BRAUN_FIELD_GIVEN(given, F_DRIVE);
}

static int slider_rows(const braun_scene_joint *j)
{
    return 1 + (j->driven ? 1 : 0);
}

static int slider_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                       const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
                       braun_real *b, braun_real *bv)
{
    braun_scene__slider_rows(s, j, 0, t, q, v, phi, A, b, bv);
    return 0;
}

static const braun_scene_field slider_fields[] = {
    [F_POINT] = {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a),
                 BRAUN_FIELD_REQUIRED, NULL},
    [F_LINE] = {"line", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b), BRAUN_FIELD_REQUIRED,
                NULL},
    [F_AXIS] = {"axis", BRAUN_FIELD_REAL, 2, offsetof(braun_scene_joint, axis),
                BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO, NULL},
    [F_DRIVE] = {"drive", BRAUN_FIELD_FN, 0, offsetof(braun_scene_joint, drive), BRAUN_FIELD_SMOOTH,
                 NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_slider = {
    "slider", "BRAUN_JOINT_SLIDER", 0, slider_fields, slider_defaults, braun_scene__slider_check,
    slider_rows, NULL, slider_eval, 2};
