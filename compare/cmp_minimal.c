/* Minimal-coordinate equations of scenes, written by the harness from the
 * scene's mechanism (cmp_mech.h): the references of scenes that name no
 * built-in model (issue 14: never braun against braun). Nothing of
 * libbraun's method: the links' masses, inertias and joint points, and
 * Lagrange's equation on the minimal coordinates.
 *
 *   open chain   links on a tree of revolute joints (rigid links) and
 *                distance joints (point masses) from the ground, no loop,
 *                gravity only: the absolute angles α (the link's angle, or
 *                the swing angle of a distance joint). Every centre of
 *                mass is r_l = c_l + Σ_k R(α_k) w_lk with constant c_l,
 *                w_lk, so with J_l[:, k] = E R(α_k) w_lk (E: a quarter
 *                turn) the equation is
 *                  (Σ_l m_l J_lᵀJ_l + diag I) α'' = Σ_l m_l J_lᵀ (g + Σ_k R(α_k) w_lk α_k'²)
 *                (double-pendulum, chain-N, the pendulum scene).
 *   parallelogram  K ≥ 2 equal parallel cranks on ground pivots and one
 *                coupler pinned to every crank tip (the coupler
 *                translates): one angle θ of the cranks,
 *                  M θ'' = −dV/dθ,  M = Σ_i (I_i + m_i |d_i|²) + m_c L²
 *                (parallelogram-redundant: redundant rows everywhere, a
 *                bifurcation where the cranks lie on the ground line; the
 *                lift follows the parallelogram branch, as the four-bar's
 *                closed form does).
 * The lift to libbraun's q, v goes through the links' poses and
 * cmp_mech_state; a model is accepted only if its lift of the initial
 * minimal state is the target's q0, v0 to 1e-9. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "cmp_mech.h"

#define MAX_K CMP_MINIMAL_MAX

typedef enum { MIN_CHAIN = 0, MIN_PARALLELOGRAM } min_kind;

struct cmp_minimal {
    min_kind kind;
    char name[96];
    cmp_mech mech;
    int k;                       /* minimal coordinates */
    double y0[2 * MAX_K];
    double g[2];
    /* open chain: per link, its angle coordinate (-1: a point mass), and
     * the terms c_l + Σ_k R(α_k) w_lk of its centre of mass */
    int angle_of[MAX_K];
    double c[MAX_K][2];
    double w[MAX_K][MAX_K][2];
    int uses[MAX_K][MAX_K];
    /* parallelogram: the cranks' pivots and initial centres, the coupler */
    int coupler;
    double th0, L, Meff;
    double *pivot;               /* 2 per link (cranks) */
    double *pose;                /* 6 per link: scratch */
};

static void rot(double a, const double *u, double *out)
{
    const double c = cos(a), s = sin(a);
    out[0] = c * u[0] - s * u[1];
    out[1] = s * u[0] + c * u[1];
}

/* World position of point p of link l at its initial pose. */
static void point_at(const cmp_mech *m, int l, const double *p, double *xy)
{
    const cmp_link *L = &m->links[l];
    const double pose[6] = {L->x, L->y, L->th, 0, 0, 0};
    cmp_mech_point(pose, 0, p, xy);
}

/* ------------------------------------------------------------ open chain */
/* The tree joint of link l: its point on l (pc) and on the parent (pp). */
static void tree_points(const cmp_mech *m, int l, double *pc, double *pp)
{
    const cmp_mjoint *J = &m->joints[m->links[l].joint];
    const int child_is_a = l == J->a;
    memcpy(pc, child_is_a ? J->pa : J->pb, 2 * sizeof(double));
    memcpy(pp, child_is_a ? J->pb : J->pa, 2 * sizeof(double));
}

static int chain_build(cmp_minimal *mm, char *why, size_t whysize)
{
    cmp_mech *m = &mm->mech;
    if (cmp_mech_tree(m, 0, "an open chain", why, whysize)) return -1;
    for (int j = 0; j < m->njoints; j++)
        if (!m->joints[j].tree) {
            snprintf(why, whysize, "joint '%s' is not on the tree", m->joints[j].name);
            return -1;
        }
    if (m->nlinks < 1 || m->nlinks > MAX_K) {
        snprintf(why, whysize, "%d links: an open chain of 1 to %d links only", m->nlinks, MAX_K);
        return -1;
    }
    for (int i = 0; i < m->nforces; i++)
        if (m->forces[i].kind != CMP_MF_GRAVITY) {
            snprintf(why, whysize, "forces other than gravity");
            return -1;
        }
    int order[MAX_K];
    cmp_mech_order(m, order);
    mm->k = m->nlinks;
    for (int oi = 0; oi < m->nlinks; oi++) {
        const int l = order[oi];
        const cmp_link *L = &m->links[l];
        if (L->joint < 0) {
            snprintf(why, whysize, "link '%s' is free (no joint to the chain)", L->name);
            return -1;
        }
        const cmp_mjoint *J = &m->joints[L->joint];
        double pc[2], pp[2];
        tree_points(m, l, pc, pp);
        /* The anchor: the parent's point, as terms of the parent's angles. */
        const int p = L->parent;
        if (p < 0) {
            mm->c[l][0] = pp[0];
            mm->c[l][1] = pp[1];
        } else {
            mm->c[l][0] = mm->c[p][0];
            mm->c[l][1] = mm->c[p][1];
            for (int k = 0; k < mm->k; k++) {
                mm->uses[l][k] = mm->uses[p][k];
                memcpy(mm->w[l][k], mm->w[p][k], 2 * sizeof(double));
            }
            if (!m->links[p].point_mass) {
                /* + R(θ_p) pp, θ_p = α_p: absorbed in the parent's own term. */
                mm->uses[l][p] = 1;
                mm->w[l][p][0] += pp[0];
                mm->w[l][p][1] += pp[1];
            }
        }
        double anchor[2] = {mm->c[l][0], mm->c[l][1]};
        for (int k = 0; k < mm->k; k++)
            if (mm->uses[l][k]) {
                double r[2];
                rot(mm->y0[k], mm->w[l][k], r);
                anchor[0] += r[0];
                anchor[1] += r[1];
            }
        if (J->kind == CMP_MJ_REVOLUTE && !L->point_mass) {
            /* r_l = anchor − R(θ_l) pc. */
            mm->angle_of[l] = l;
            mm->y0[l] = L->th;
            mm->y0[mm->k + l] = L->w;
            mm->uses[l][l] = 1;
            mm->w[l][l][0] = -pc[0];
            mm->w[l][l][1] = -pc[1];
        } else if (J->kind == CMP_MJ_DISTANCE && L->point_mass) {
            /* r_l = anchor + R(φ) (ℓ, 0), φ the swing angle. */
            const double dx = L->x - anchor[0], dy = L->y - anchor[1], d2 = dx * dx + dy * dy;
            double va[2] = {0, 0};
            for (int k = 0; k < mm->k; k++)
                if (mm->uses[l][k]) {
                    double r[2];
                    rot(mm->y0[k], mm->w[l][k], r);
                    va[0] += -r[1] * mm->y0[mm->k + k];
                    va[1] += r[0] * mm->y0[mm->k + k];
                }
            mm->angle_of[l] = -1;
            mm->y0[l] = atan2(dy, dx);
            mm->y0[mm->k + l] = (dx * (L->vy - va[1]) - dy * (L->vx - va[0])) / d2;
            mm->uses[l][l] = 1;
            mm->w[l][l][0] = sqrt(d2);
            mm->w[l][l][1] = 0;
        } else {
            snprintf(why, whysize, "link '%s': a %s joint to a %s", L->name,
                     J->kind == CMP_MJ_REVOLUTE ? "revolute" : "non-revolute",
                     L->point_mass ? "point mass" : "rigid link");
            return -1;
        }
    }
    snprintf(mm->name, sizeof mm->name, "open chain of %d links: Lagrange's equation on %d angles",
             mm->k, mm->k);
    return 0;
}

/* Centre of mass position and velocity of link l, and J_l (2 x k). */
static void chain_link(const cmp_minimal *mm, int l, const double *y, double *r, double *v,
                       double J[2][MAX_K])
{
    const int k = mm->k;
    r[0] = mm->c[l][0];
    r[1] = mm->c[l][1];
    v[0] = v[1] = 0;
    for (int j = 0; j < k; j++) {
        J[0][j] = J[1][j] = 0;
        if (!mm->uses[l][j]) continue;
        double u[2];
        rot(y[j], mm->w[l][j], u);
        r[0] += u[0];
        r[1] += u[1];
        J[0][j] = -u[1];
        J[1][j] = u[0];
        v[0] += J[0][j] * y[k + j];
        v[1] += J[1][j] * y[k + j];
    }
}

/* Solve the k x k SPD system A x = b in place (Cholesky). 0 or -1. */
static int spd_solve(int k, double A[MAX_K][MAX_K], double *b)
{
    for (int j = 0; j < k; j++) {
        double d = A[j][j];
        for (int p = 0; p < j; p++) d -= A[j][p] * A[j][p];
        if (!(d > 0)) return -1;
        A[j][j] = sqrt(d);
        for (int i = j + 1; i < k; i++) {
            double s = A[i][j];
            for (int p = 0; p < j; p++) s -= A[i][p] * A[j][p];
            A[i][j] = s / A[j][j];
        }
    }
    for (int i = 0; i < k; i++) {
        double s = b[i];
        for (int p = 0; p < i; p++) s -= A[i][p] * b[p];
        b[i] = s / A[i][i];
    }
    for (int i = k - 1; i >= 0; i--) {
        double s = b[i];
        for (int p = i + 1; p < k; p++) s -= A[p][i] * b[p];
        b[i] = s / A[i][i];
    }
    return 0;
}

static int chain_rhs(const cmp_minimal *mm, const double *y, double *dy)
{
    const int k = mm->k;
    double M[MAX_K][MAX_K], f[MAX_K];
    memset(M, 0, sizeof M);
    memset(f, 0, sizeof f);
    for (int l = 0; l < mm->mech.nlinks; l++) {
        const cmp_link *L = &mm->mech.links[l];
        double r[2], v[2], J[2][MAX_K], acc[2] = {mm->g[0], mm->g[1]};
        chain_link(mm, l, y, r, v, J);
        /* g + Σ_k R(α_k) w_lk α_k'² (the velocity-product terms, moved right). */
        for (int j = 0; j < k; j++)
            if (mm->uses[l][j]) {
                double u[2];
                rot(y[j], mm->w[l][j], u);
                acc[0] += u[0] * y[k + j] * y[k + j];
                acc[1] += u[1] * y[k + j] * y[k + j];
            }
        for (int a = 0; a < k; a++) {
            f[a] += L->mass * (J[0][a] * acc[0] + J[1][a] * acc[1]);
            for (int b = 0; b < k; b++) M[a][b] += L->mass * (J[0][a] * J[0][b] + J[1][a] * J[1][b]);
        }
        if (mm->angle_of[l] >= 0) M[mm->angle_of[l]][mm->angle_of[l]] += L->inertia;
    }
    if (spd_solve(k, M, f)) return -1;
    for (int j = 0; j < k; j++) {
        dy[j] = y[k + j];
        dy[k + j] = f[j];
    }
    return 0;
}

static void chain_pose(const cmp_minimal *mm, const double *y, double *pose)
{
    for (int l = 0; l < mm->mech.nlinks; l++) {
        double r[2], v[2], J[2][MAX_K];
        chain_link(mm, l, y, r, v, J);
        double *s = pose + 6 * l;
        s[0] = r[0];
        s[1] = r[1];
        s[3] = v[0];
        s[4] = v[1];
        const int a = mm->angle_of[l];
        s[2] = a >= 0 ? y[a] : 0;
        s[5] = a >= 0 ? y[mm->k + a] : 0;
    }
}

/* ------------------------------------------------------------ parallelogram */
static int parallelogram_build(cmp_minimal *mm, char *why, size_t whysize)
{
    cmp_mech *m = &mm->mech;
    const int nl = m->nlinks;
    /* Cranks: links with a revolute joint to the ground; the coupler: the
     * one link without. */
    int ncrank = 0;
    mm->coupler = -1;
    mm->pivot = calloc((size_t)nl * 2, sizeof(double));
    if (!mm->pivot) {
        snprintf(why, whysize, "out of memory");
        return -1;
    }
    int *pin = calloc((size_t)nl, sizeof(int));
    double *tip = calloc((size_t)nl * 2, sizeof(double));
    if (!pin || !tip) {
        free(pin);
        free(tip);
        snprintf(why, whysize, "out of memory");
        return -1;
    }
    for (int l = 0; l < nl; l++) pin[l] = -1;
    int bad = 0;
    for (int j = 0; j < m->njoints && !bad; j++) {
        const cmp_mjoint *J = &m->joints[j];
        if (J->kind != CMP_MJ_REVOLUTE) bad = 1;
        else if (J->a < 0 || J->b < 0) {
            const int l = J->a < 0 ? J->b : J->a;
            const double *g = J->a < 0 ? J->pa : J->pb;
            mm->pivot[2 * l] = g[0];
            mm->pivot[2 * l + 1] = g[1];
            pin[l] = pin[l] == -1 ? -2 : -3; /* -2: one pivot */
        }
    }
    for (int l = 0; l < nl; l++) {
        if (pin[l] == -2) ncrank++;
        else if (pin[l] == -1 && mm->coupler < 0) mm->coupler = l;
        else bad = 1;
    }
    const int cp = mm->coupler;
    if (!bad && (cp < 0 || ncrank < 2 || m->njoints != 2 * ncrank)) bad = 1;
    /* Each crank pinned to the coupler at its tip: the vector pivot -> tip
     * the same for every crank (the coupler then translates). */
    double v0[2] = {0, 0};
    int first = 1;
    for (int j = 0; j < m->njoints && !bad; j++) {
        const cmp_mjoint *J = &m->joints[j];
        if (J->a < 0 || J->b < 0) continue;
        const int crank = J->a == cp ? J->b : J->a;
        if ((J->a != cp && J->b != cp) || crank == cp) {
            bad = 1;
            break;
        }
        double P[2];
        point_at(m, crank, J->a == crank ? J->pa : J->pb, P);
        const double d[2] = {P[0] - mm->pivot[2 * crank], P[1] - mm->pivot[2 * crank + 1]};
        if (first) {
            v0[0] = d[0];
            v0[1] = d[1];
            first = 0;
        } else if (hypot(d[0] - v0[0], d[1] - v0[1]) > 1e-12 * (1 + hypot(v0[0], v0[1]))) {
            bad = 1;
        }
    }
    free(pin);
    free(tip);
    for (int i = 0; i < m->nforces && !bad; i++)
        if (m->forces[i].kind != CMP_MF_GRAVITY) bad = 1;
    if (bad) {
        snprintf(why, whysize, "not a parallelogram of equal cranks and one coupler under gravity");
        return -1;
    }
    mm->L = hypot(v0[0], v0[1]);
    mm->th0 = atan2(v0[1], v0[0]);
    mm->Meff = m->links[cp].mass * mm->L * mm->L;
    for (int l = 0; l < nl; l++) {
        if (l == cp) continue;
        const cmp_link *L = &m->links[l];
        const double dx = L->x - mm->pivot[2 * l], dy = L->y - mm->pivot[2 * l + 1];
        mm->Meff += L->inertia + L->mass * (dx * dx + dy * dy);
    }
    /* θ' from the first crank's angular velocity (a rigid crank). */
    int c0 = cp == 0 ? 1 : 0;
    mm->k = 1;
    mm->y0[0] = mm->th0;
    mm->y0[1] = m->links[c0].w;
    snprintf(mm->name, sizeof mm->name,
             "parallelogram of %d cranks: M θ'' = −dV/dθ on the cranks' angle", ncrank);
    return 0;
}

static void parallelogram_pose(const cmp_minimal *mm, const double *y, double *pose)
{
    const cmp_mech *m = &mm->mech;
    const double dth = y[0] - mm->th0, w = y[1];
    for (int l = 0; l < m->nlinks; l++) {
        const cmp_link *L = &m->links[l];
        double *s = pose + 6 * l;
        if (l == mm->coupler) {
            /* Translates with the crank tips: Δ = L (e(θ) − e(θ0)). */
            s[0] = L->x + mm->L * (cos(y[0]) - cos(mm->th0));
            s[1] = L->y + mm->L * (sin(y[0]) - sin(mm->th0));
            s[2] = L->th;
            s[3] = -mm->L * sin(y[0]) * w;
            s[4] = mm->L * cos(y[0]) * w;
            s[5] = 0;
            continue;
        }
        const double d0[2] = {L->x - mm->pivot[2 * l], L->y - mm->pivot[2 * l + 1]};
        double d[2];
        rot(dth, d0, d);
        s[0] = mm->pivot[2 * l] + d[0];
        s[1] = mm->pivot[2 * l + 1] + d[1];
        s[2] = L->th + dth;
        s[3] = -d[1] * w;
        s[4] = d[0] * w;
        s[5] = w;
    }
}

static int parallelogram_rhs(const cmp_minimal *mm, const double *y, double *dy)
{
    /* dV/dθ = −Σ m g·(∂r/∂θ): cranks ∂r/∂θ = E d, the coupler L E e(θ). */
    const cmp_mech *m = &mm->mech;
    const double dth = y[0] - mm->th0;
    double dV = 0;
    for (int l = 0; l < m->nlinks; l++) {
        const cmp_link *L = &m->links[l];
        double dr[2];
        if (l == mm->coupler) {
            dr[0] = -mm->L * sin(y[0]);
            dr[1] = mm->L * cos(y[0]);
        } else {
            const double d0[2] = {L->x - mm->pivot[2 * l], L->y - mm->pivot[2 * l + 1]};
            double d[2];
            rot(dth, d0, d);
            dr[0] = -d[1];
            dr[1] = d[0];
        }
        dV -= L->mass * (mm->g[0] * dr[0] + mm->g[1] * dr[1]);
    }
    dy[0] = y[1];
    dy[1] = -dV / mm->Meff;
    return 0;
}

/* ------------------------------------------------------------ interface */
void cmp_minimal_free(cmp_minimal *mm)
{
    if (!mm) return;
    cmp_mech_free(&mm->mech);
    free(mm->pivot);
    free(mm->pose);
    free(mm);
}

int cmp_minimal_dim(const cmp_minimal *mm)
{
    return 2 * mm->k;
}

const double *cmp_minimal_y0(const cmp_minimal *mm)
{
    return mm->y0;
}

const char *cmp_minimal_name(const cmp_minimal *mm)
{
    return mm->name;
}

int cmp_minimal_rhs(const cmp_minimal *mm, double t, const double *y, double *dy)
{
    (void)t;
    const int st = mm->kind == MIN_CHAIN ? chain_rhs(mm, y, dy) : parallelogram_rhs(mm, y, dy);
    for (int i = 0; i < 2 * mm->k && !st; i++)
        if (!isfinite(dy[i])) return -1;
    return st;
}

void cmp_minimal_state(cmp_minimal *mm, const double *y, double *q, double *v)
{
    if (mm->kind == MIN_CHAIN) chain_pose(mm, y, mm->pose);
    else parallelogram_pose(mm, y, mm->pose);
    cmp_mech_state(&mm->mech, mm->pose, q, v);
}

cmp_minimal *cmp_minimal_new(const cmp_target *tg, char *why, size_t whysize)
{
    cmp_minimal *mm = calloc(1, sizeof *mm);
    if (!mm) {
        snprintf(why, whysize, "out of memory");
        return NULL;
    }
    char w1[256] = "", w2[256] = "";
    if (cmp_mech_for_target(tg, &mm->mech, why, whysize)) {
        cmp_minimal_free(mm);
        return NULL;
    }
    for (int i = 0; i < mm->mech.nforces; i++)
        if (mm->mech.forces[i].kind == CMP_MF_GRAVITY) {
            mm->g[0] = mm->mech.forces[i].g[0];
            mm->g[1] = mm->mech.forces[i].g[1];
        }
    const int n = tg->sys.n;
    mm->pose = calloc(6 * (size_t)mm->mech.nlinks + 2 * (size_t)n, sizeof(double));
    int ok = mm->pose != NULL;
    if (ok) {
        mm->kind = MIN_CHAIN;
        ok = chain_build(mm, w1, sizeof w1) == 0;
    }
    if (mm->pose && !ok) {
        /* The chain's tree is not the parallelogram's: start over. */
        cmp_mech_free(&mm->mech);
        memset(mm->uses, 0, sizeof mm->uses);
        memset(mm->w, 0, sizeof mm->w);
        mm->kind = MIN_PARALLELOGRAM;
        ok = cmp_mech_for_target(tg, &mm->mech, w2, sizeof w2) == 0 &&
             parallelogram_build(mm, w2, sizeof w2) == 0;
    }
    if (!ok) {
        snprintf(why, whysize, "no minimal equation: not an open chain (%s), not a "
                 "parallelogram (%s)", w1, w2);
        cmp_minimal_free(mm);
        return NULL;
    }
    /* The lift of the initial minimal state must be the target's state. */
    double *q = mm->pose + 6 * mm->mech.nlinks, *v = q + n;
    cmp_minimal_state(mm, mm->y0, q, v);
    double dq = 0, dv = 0;
    for (int i = 0; i < n; i++) {
        dq = fmax(dq, fabs(q[i] - tg->q0[i]));
        dv = fmax(dv, fabs(v[i] - tg->v0[i]));
    }
    if (!(dq <= 1e-9 && dv <= 1e-9)) {
        snprintf(why, whysize, "%s: its initial state misses the scene's by %.3g in q, %.3g in v",
                 mm->name, dq, dv);
        cmp_minimal_free(mm);
        return NULL;
    }
    return mm;
}
