/* Uniform rods in natural coordinates (the paper's four-bar, Sec. 4.2):
 * the two end points are particles or ground points. A rod's kinetic
 * energy is exactly (m/6)(|v_a|² + v_a·v_b + |v_b|²) while its length is
 * kept, so it adds m/3 on the diagonal blocks of its ends and m/6 between
 * them; its length is the row |P_b - P_a|² - L² = 0. */
#include "scene_internal.h"

/* Column of x of a rod end, -1 on the ground. */
static int end_col(const braun_scene *s, int point)
{
    const int body = s->points[point].body;
    return body < 0 ? -1 : s->bodies[body].iq;
}

void braun_scene__rod_mass(const braun_scene *s, const braun_scene_rod *r, braun_real *M)
{
    const int n = s->n, ia = end_col(s, r->a), ib = end_col(s, r->b);
    const braun_real d = r->mass / BRAUN_R(3.0), o = r->mass / BRAUN_R(6.0);
    for (int k = 0; k < 2; k++) {
        if (ia >= 0) M[braun_scene__at(ia + k, ia + k, n)] += d;
        if (ib >= 0) M[braun_scene__at(ib + k, ib + k, n)] += d;
        if (ia >= 0 && ib >= 0) {
            M[braun_scene__at(ia + k, ib + k, n)] += o;
            M[braun_scene__at(ib + k, ia + k, n)] += o;
        }
    }
}

braun_real braun_scene__rod_kinetic(const braun_scene *s, const braun_scene_rod *r,
                                    const braun_real *v, braun_real *dEdv)
{
    const int ia = end_col(s, r->a), ib = end_col(s, r->b);
    const braun_real d = r->mass / BRAUN_R(3.0), o = r->mass / BRAUN_R(6.0);
    braun_real T = 0;
    for (int k = 0; k < 2; k++) {
        const braun_real va = ia >= 0 ? v[ia + k] : 0, vb = ib >= 0 ? v[ib + k] : 0;
        /* (M v) at the two ends; T = ½ vᵀ M v. */
        const braun_real pa = d * va + o * vb, pb = o * va + d * vb;
        T += va * pa + vb * pb;
        if (dEdv) {
            if (ia >= 0) dEdv[ia + k] += pa;
            if (ib >= 0) dEdv[ib + k] += pb;
        }
    }
    return BRAUN_R(0.5) * T;
}

/* Quadratic in q, scleronomic: b_q = 0 and b_qv = -2|v_b - v_a|². */
void braun_scene__rod_rows(const braun_scene *s, const braun_scene_rod *r, const braun_real *q,
                           const braun_real *v, braun_real *phi, braun_real *A, braun_real *b,
                           braun_real *bv)
{
    scene_pt Pa, Pb;
    braun_scene__point(s, r->a, q, v, &Pa);
    braun_scene__point(s, r->b, q, v, &Pb);
    const braun_real dx = Pb.pos[0] - Pa.pos[0], dy = Pb.pos[1] - Pa.pos[1];
    if (phi) phi[0] = dx * dx + dy * dy - r->length * r->length;
    if (A) {
        braun_scene__add_grad(&Pb, BRAUN_R(2.0) * dx, BRAUN_R(2.0) * dy, A);
        braun_scene__add_grad(&Pa, BRAUN_R(-2.0) * dx, BRAUN_R(-2.0) * dy, A);
    }
    if (b) b[0] = 0;
    if (bv) {
        const braun_real ux = Pb.vel[0] - Pa.vel[0], uy = Pb.vel[1] - Pa.vel[1];
        bv[0] = BRAUN_R(-2.0) * (ux * ux + uy * uy);
    }
}
