/* What the spatial joints share: rows built from products of world vectors
 * that are points, point differences or body-fixed directions.
 *
 * Every row here is Φ = x·y (- f(t)) with x, y such vectors. With
 * x'' = J_x v' + cc_x (scene_point.c, the body classes):
 *   A_q  = yᵀJ_x + xᵀJ_y,   b_q = f',
 *   Φ''  = A_q v' + cc_x·y + 2 x'·y' + x·cc_y - f'',
 *   b_qv = -(cc_x·y + 2 x'·y' + x·cc_y) + f''.
 * A revolute's drive row C(t) s - S(t) c (C = cos f, S = sin f, s = w1·r2,
 * c = r1·r2) adds the t-derivatives of C and S (see drive_row).
 *
 * Frames: a spatial joint carries on body1 its axis u1, a reference r1 ⊥ u1
 * and w1 = u1 × r1 (a body-fixed vector too: the cross product of two
 * body-fixed vectors, formed in the body frame), and on body2 u2, r2, w2,
 * the images of u1, r1 at the initial configuration. Then
 *   axes parallel      r1·u2 = 0, w1·u2 = 0
 *   orientation kept   u1·r2 = 0, r1·w2 = 0, w1·u2 = 0
 * whose Jacobians have full rank at the initial relative orientation, and
 * the joint angle is θ = atan2(w1·r2, r1·r2). */
#include "scene_internal.h"

void braun_scene__vec(scene_vec *x, const scene_pt *p1, const scene_pt *p2)
{
    x->p1 = p1;
    x->p2 = p2;
    for (int k = 0; k < 3; k++) {
        x->x[k] = p1->pos[k] - (p2 ? p2->pos[k] : 0);
        x->dx[k] = p1->vel[k] - (p2 ? p2->vel[k] : 0);
        x->cc[k] = p1->cc[k] - (p2 ? p2->cc[k] : 0);
    }
}

void braun_scene__vec_grad(const scene_vec *x, const braun_real *g, braun_real scale,
                           braun_real *row)
{
    const braun_real a[3] = {scale * g[0], scale * g[1], scale * g[2]};
    braun_scene_pt_grad(x->p1, a, row);
    if (x->p2) {
        const braun_real m[3] = {-a[0], -a[1], -a[2]};
        braun_scene_pt_grad(x->p2, m, row);
    }
}

void braun_scene__dot_row(const scene_vec *x, const scene_vec *y, const braun_scene_fn *f,
                          braun_real t, braun_real *phi, braun_real *A, braun_real *b,
                          braun_real *bv)
{
    braun_real fv = 0, df = 0, ddf = 0;
    if (f) braun_scene_fn_eval(f, t, &fv, &df, &ddf);
    if (phi) phi[0] = braun_scene__dot3(x->x, y->x) - fv;
    if (A) {
        braun_scene__vec_grad(x, y->x, 1, A);
        braun_scene__vec_grad(y, x->x, 1, A);
    }
    if (b) b[0] = df;
    if (bv)
        bv[0] = -(braun_scene__dot3(x->cc, y->x) + 2 * braun_scene__dot3(x->dx, y->dx) +
                  braun_scene__dot3(x->x, y->cc)) + ddf;
}

void braun_scene__coincide_rows(const braun_scene *s, int a, int b, const braun_real *q,
                                const braun_real *v, braun_real *phi, braun_real *A,
                                braun_real *b_q, braun_real *bv)
{
    const int n = s->n;
    scene_pt Pa, Pb;
    braun_scene__point(s, a, q, v, &Pa);
    braun_scene__point(s, b, q, v, &Pb);
    for (int k = 0; k < 3; k++) {
        if (phi) phi[k] = Pa.pos[k] - Pb.pos[k];
        if (A) {
            braun_real g[3] = {0, 0, 0};
            braun_real *row = A + braun_scene__at(k, 0, n);
            g[k] = 1;
            braun_scene_pt_grad(&Pa, g, row);
            g[k] = -1;
            braun_scene_pt_grad(&Pb, g, row);
        }
        if (b_q) b_q[k] = 0;
        if (bv) bv[k] = Pb.cc[k] - Pa.cc[k];
    }
}

void braun_scene__frame_bodies(const braun_scene *s, const braun_scene_joint *j, int *body1,
                               int *body2)
{
    /* Joints with a line or plane carry it on point b's body (as the
     * planar slider); the others on point a's. */
    const braun_scene_joint_class *c = j->type;
    const int on_b = c == &braun_scene_joint_prismatic3d || c == &braun_scene_joint_cylindrical ||
                     c == &braun_scene_joint_point_line || c == &braun_scene_joint_point_plane;
    const int a = braun_scene__body_of(s, j->a), b = braun_scene__body_of(s, j->b);
    *body1 = on_b ? b : a;
    *body2 = on_b ? a : b;
}

void braun_scene__frames(const braun_scene *s, const braun_scene_joint *j, int body1, int body2,
                         const braun_real *q, const braun_real *v, scene_frames *F)
{
    braun_real w[3];
    braun_scene_dir_eval(s, body1, j->axis, q, v, &F->u1);
    braun_scene_dir_eval(s, body1, j->ref_a, q, v, &F->r1);
    braun_scene__cross3(j->axis, j->ref_a, w);
    braun_scene_dir_eval(s, body1, w, q, v, &F->w1);
    braun_scene_dir_eval(s, body2, j->axis_b, q, v, &F->u2);
    braun_scene_dir_eval(s, body2, j->ref_b, q, v, &F->r2);
    braun_scene__cross3(j->axis_b, j->ref_b, w);
    braun_scene_dir_eval(s, body2, w, q, v, &F->w2);
}

/* Row r of A (stride n), or NULL. */
#define ROW(A, r, n) ((A) ? (A) + braun_scene__at(r, 0, n) : NULL)
#define AT(x, r) ((x) ? (x) + (r) : NULL)

static void pair_row(const scene_pt *a, const scene_pt *b, braun_real *phi, braun_real *A,
                     braun_real *bq, braun_real *bv)
{
    scene_vec x, y;
    braun_scene__vec(&x, a, NULL);
    braun_scene__vec(&y, b, NULL);
    braun_scene__dot_row(&x, &y, NULL, 0, phi, A, bq, bv);
}

void braun_scene__parallel_rows(const scene_frames *F, braun_real *phi, braun_real *A, int n,
                                braun_real *b, braun_real *bv)
{
    pair_row(&F->r1, &F->u2, AT(phi, 0), ROW(A, 0, n), AT(b, 0), AT(bv, 0));
    pair_row(&F->w1, &F->u2, AT(phi, 1), ROW(A, 1, n), AT(b, 1), AT(bv, 1));
}

void braun_scene__orient_rows(const scene_frames *F, braun_real *phi, braun_real *A, int n,
                              braun_real *b, braun_real *bv)
{
    pair_row(&F->u1, &F->r2, AT(phi, 0), ROW(A, 0, n), AT(b, 0), AT(bv, 0));
    pair_row(&F->r1, &F->w2, AT(phi, 1), ROW(A, 1, n), AT(b, 1), AT(bv, 1));
    pair_row(&F->w1, &F->u2, AT(phi, 2), ROW(A, 2, n), AT(b, 2), AT(bv, 2));
}

/* Φ = C s - S c with s = w1·r2, c = r1·r2, C = cos f(t), S = sin f(t):
 *   A   = C ∇s - S ∇c,   b_q = -Φ_t = f' (S s + C c),
 *   Φ'' = A v' + C s_cc - S c_cc + 2C' s' + C'' s - 2S' c' - S'' c
 * with s_cc, c_cc the velocity products of the dot rows, C' = -S f',
 * C'' = -C f'² - S f'', S' = C f', S'' = -S f'² + C f''. */
void braun_scene__drive_row(const scene_frames *F, const braun_scene_fn *f, braun_real t,
                            braun_real *phi, braun_real *A, braun_real *b, braun_real *bv)
{
    scene_vec w1, r1, r2;
    braun_real th, df, ddf;
    braun_scene__vec(&w1, &F->w1, NULL);
    braun_scene__vec(&r1, &F->r1, NULL);
    braun_scene__vec(&r2, &F->r2, NULL);
    braun_scene_fn_eval(f, t, &th, &df, &ddf);
    braun_real C, S;
    braun_sincos(th, &S, &C);
    const braun_real sv = braun_scene__dot3(w1.x, r2.x), cv = braun_scene__dot3(r1.x, r2.x);
    if (phi) phi[0] = C * sv - S * cv;
    if (A) {
        braun_scene__vec_grad(&w1, r2.x, C, A);
        braun_scene__vec_grad(&r2, w1.x, C, A);
        braun_scene__vec_grad(&r1, r2.x, -S, A);
        braun_scene__vec_grad(&r2, r1.x, -S, A);
    }
    if (b) b[0] = df * (S * sv + C * cv);
    if (bv) {
        const braun_real ds = braun_scene__dot3(w1.dx, r2.x) + braun_scene__dot3(w1.x, r2.dx);
        const braun_real dc = braun_scene__dot3(r1.dx, r2.x) + braun_scene__dot3(r1.x, r2.dx);
        const braun_real scc = braun_scene__dot3(w1.cc, r2.x) + 2 * braun_scene__dot3(w1.dx, r2.dx) +
                               braun_scene__dot3(w1.x, r2.cc);
        const braun_real ccc = braun_scene__dot3(r1.cc, r2.x) + 2 * braun_scene__dot3(r1.dx, r2.dx) +
                               braun_scene__dot3(r1.x, r2.cc);
        const braun_real dC = -S * df, ddC = -C * df * df - S * ddf;
        const braun_real dS = C * df, ddS = -S * df * df + C * ddf;
        bv[0] = -(C * scc - S * ccc + 2 * dC * ds + ddC * sv - 2 * dS * dc - ddS * cv);
    }
}

void braun_scene__joint_angle(const braun_scene *s, const braun_scene_joint *j,
                              const braun_real *q, const braun_real *v, braun_real *theta,
                              braun_real *rate, braun_real scale, braun_real *grad)
{
    int b1, b2;
    braun_real w[3];
    scene_pt R1, W1, R2;
    scene_vec r1, w1, r2;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    braun_scene__cross3(j->axis, j->ref_a, w);
    braun_scene_dir_eval(s, b1, j->ref_a, q, v, &R1);
    braun_scene_dir_eval(s, b1, w, q, v, &W1);
    braun_scene_dir_eval(s, b2, j->ref_b, q, v, &R2);
    braun_scene__vec(&r1, &R1, NULL);
    braun_scene__vec(&w1, &W1, NULL);
    braun_scene__vec(&r2, &R2, NULL);
    const braun_real sv = braun_scene__dot3(w1.x, r2.x), cv = braun_scene__dot3(r1.x, r2.x);
    const braun_real rr = sv * sv + cv * cv;
    *theta = braun_scene__atan2(sv, cv);
    /* θ' = (c s' - s c')/(s² + c²); ∂θ/∂q likewise. */
    if (rate) {
        const braun_real ds = braun_scene__dot3(w1.dx, r2.x) + braun_scene__dot3(w1.x, r2.dx);
        const braun_real dc = braun_scene__dot3(r1.dx, r2.x) + braun_scene__dot3(r1.x, r2.dx);
        *rate = rr > 0 ? (cv * ds - sv * dc) / rr : 0;
    }
    if (grad && rr > 0) {
        const braun_real a = scale * cv / rr, c = -scale * sv / rr;
        braun_scene__vec_grad(&w1, r2.x, a, grad);
        braun_scene__vec_grad(&r2, w1.x, a, grad);
        braun_scene__vec_grad(&r1, r2.x, c, grad);
        braun_scene__vec_grad(&r2, r1.x, c, grad);
    }
}

/* ----------------------------------------------------------- defaults */
void braun_scene__initial_dir(const braun_scene *s, int body, const braun_real *d,
                              braun_real *out)
{
    if (body < 0) {
        for (int k = 0; k < 3; k++) out[k] = d[k];
        return;
    }
    const braun_scene_body *bd = &s->bodies[body];
    braun_real q[BRAUN_SCENE_MAX_DOF];
    const braun_real *q0 = bd->q0;
    scene_pt D;
    if (bd->kind->initial) {
        braun_real v[BRAUN_SCENE_MAX_DOF];
        bd->kind->initial(bd, q, v);
        q0 = q;
    }
    D.body = bd;
    D.col = -1;
    D.direction = 1;
    for (int k = 0; k < 3; k++) D.vel[k] = D.cc[k] = 0;
    bd->kind->direction(bd, d, q0, NULL, &D);
    for (int k = 0; k < 3; k++) out[k] = D.pos[k];
}

void braun_scene__initial_dir_inverse(const braun_scene *s, int body, const braun_real *x,
                                      braun_real *out)
{
    for (int i = 0; i < 3; i++) {
        braun_real e[3] = {0, 0, 0}, col[3];
        e[i] = 1;
        braun_scene__initial_dir(s, body, e, col);
        out[i] = braun_scene__dot3(col, x);
    }
}

/* A unit vector ⊥ the unit vector u: the world axis least along u, with
 * its u part removed. */
static void perpendicular(const braun_real *u, braun_real *r)
{
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (braun_fabs(u[i]) < braun_fabs(u[k])) k = i;
    for (int i = 0; i < 3; i++) r[i] = (i == k) - u[k] * u[i];
    braun_scene__normalize3(r);
}

/* The unit vector x minus its part along the unit vector u, normalised;
 * 0 when x lies within 1e-6 of ±u (no direction left but round-off: the
 * check then refuses the frame). */
static void orthogonalize(braun_real *x, const braun_real *u)
{
    const braun_real d = braun_scene__dot3(x, u);
    for (int i = 0; i < 3; i++) x[i] -= d * u[i];
    if (braun_scene__normalize3(x) < BRAUN_R(1e-6))
        for (int i = 0; i < 3; i++) x[i] = 0;
}

void braun_scene__frame_defaults(const braun_scene *s, braun_scene_joint *j, int body1,
                                 int body2, int axis_b_given)
{
    braun_real w[3];
    if (braun_scene__normalize3(j->axis) == 0) return; /* the check refuses it */
    perpendicular(j->axis, j->ref_a);
    if (!braun_scene__has_frame(s, body1) || !braun_scene__has_frame(s, body2)) return;
    if (axis_b_given) {
        braun_scene__normalize3(j->axis_b);
    } else {
        braun_scene__initial_dir(s, body1, j->axis, w);
        braun_scene__initial_dir_inverse(s, body2, w, j->axis_b);
        braun_scene__normalize3(j->axis_b);
    }
    braun_scene__initial_dir(s, body1, j->ref_a, w);
    braun_scene__initial_dir_inverse(s, body2, w, j->ref_b);
    orthogonalize(j->ref_b, j->axis_b);
}


const char *braun_scene__frame_check(const braun_scene *s, const braun_scene_joint *j,
                                     int body1, int body2, int need_b)
{
    const char *same = braun_scene__same_body_points(s, j->a, j->b, 0);
    if (same) return same;
    if (!braun_scene__has_frame(s, body1) || !braun_scene__has_frame(s, body2))
        return "a body of the joint has no orientation (a particle): its axes need rigid3d "
               "bodies or the ground";
    if (!braun_scene__is_unit3(j->axis) || !braun_scene__is_unit3(j->ref_a))
        return "the joint's axis and reference direction must be unit vectors (scene files and "
               "braun_scene_defaults() normalise them)";
    if (braun_fabs(braun_scene__dot3(j->axis, j->ref_a)) > BRAUN_SCENE__UNIT_TOL)
        return "the joint's reference direction must be perpendicular to its axis";
    if (need_b) {
        /* braun_scene__frame_defaults leaves ref_b 0 when the reference
         * direction, as it lies initially, is along the given axis_b. */
        if (braun_scene__is_unit3(j->axis_b) && braun_scene__dot3(j->ref_b, j->ref_b) == 0)
            return "the joint's axis_b is perpendicular to its axis as the bodies lie initially: "
                   "ref_b cannot be taken from the initial state (start the bodies with the "
                   "axes nearly parallel)";
        if (!braun_scene__is_unit3(j->axis_b) || !braun_scene__is_unit3(j->ref_b))
            return "the joint's axis_b and ref_b must be unit vectors (scene files and "
                   "braun_scene_defaults() fill them from the initial state)";
        if (braun_fabs(braun_scene__dot3(j->axis_b, j->ref_b)) > BRAUN_SCENE__UNIT_TOL)
            return "the joint's ref_b must be perpendicular to its axis_b";
    }
    return NULL;
}

/* ------------------------------------------------------------- line rows */
/* P (point a) on the line through A (point b) along u1 on body1:
 * r1·e = 0, w1·e = 0 with e = P - A; with parallel, first the two rows of
 * the axes kept parallel (cylindrical). Frame 2 is evaluated only then, so
 * P's body may be a particle for point_line. */
void braun_scene__line_rows(const braun_scene *s, const braun_scene_joint *j, int parallel,
                            const braun_real *q, const braun_real *v, braun_real *phi,
                            braun_real *A, braun_real *b, braun_real *bv)
{
    const int n = s->n;
    int b1, b2, r = 0;
    braun_real wb[3];
    scene_pt P, Pa, R1, W1;
    scene_vec e, r1, w1;
    braun_scene__frame_bodies(s, j, &b1, &b2);
    if (parallel) {
        scene_frames F;
        braun_scene__frames(s, j, b1, b2, q, v, &F);
        braun_scene__parallel_rows(&F, phi, A, n, b, bv);
        r = 2;
    }
    braun_scene__cross3(j->axis, j->ref_a, wb);
    braun_scene_dir_eval(s, b1, j->ref_a, q, v, &R1);
    braun_scene_dir_eval(s, b1, wb, q, v, &W1);
    braun_scene__point(s, j->a, q, v, &P);
    braun_scene__point(s, j->b, q, v, &Pa);
    braun_scene__vec(&e, &P, &Pa);
    braun_scene__vec(&r1, &R1, NULL);
    braun_scene__vec(&w1, &W1, NULL);
    braun_scene__dot_row(&r1, &e, NULL, 0, AT(phi, r), ROW(A, r, n), AT(b, r), AT(bv, r));
    braun_scene__dot_row(&w1, &e, NULL, 0, AT(phi, r + 1), ROW(A, r + 1, n), AT(b, r + 1),
                         AT(bv, r + 1));
}
