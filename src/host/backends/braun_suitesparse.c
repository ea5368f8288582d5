/*
 * SuiteSparse backend of the linear-solver table (braun_linsolver.h), for
 * large mechanisms with a sparsity (braun.h: CSR pattern of A = [A_q; A_vv],
 * block-diagonal M). Weighted formulation as in the core: M = R^T R,
 * C = A R^-1.
 *
 *   M = R^T R     one dense upper Cholesky factor per diagonal block, O(n)
 *                 for bounded block sizes. (CHOLMOD would find the same
 *                 block-diagonal factor after an ordering, a symbolic
 *                 analysis and a supernodal/simplicial dispatch that cost
 *                 more than the 3x3 factorizations themselves, and its R^-1
 *                 solves would need permutations and a dense wrapper per
 *                 call; block-diagonal M needs none of that.)
 *   C = A R^-1    row i of C is row i of A times R_b^-1 on every block b the
 *                 row touches, so C has A's pattern expanded to whole blocks;
 *                 that pattern (and where each A value lands in it) is built
 *                 once in create(). C in CSR (rows x n) is C^T in CSC
 *                 (n x rows): the SPQR input below is a view, not a copy.
 *
 * Three ways to factor C (per slot: slot 0 all m + p rows, slot 1 the first
 * m rows, each with its own state): G = C C^T by Cholesky when C has full
 * rank, the same Cholesky with the dependent rows set aside when C has
 * exactly dependent rows (redundant constraints), SPQR otherwise.
 *
 *  Full rank (the usual case): G = C C^T = A M^-1 A^T, sparse SPD, rows x rows.
 *   Its pattern (two rows are coupled when they touch a common mass block)
 *   and a product map (G_ij = sum over shared blocks b of C_ib . C_jb, as
 *   offsets into C's values) are built in create(), with the CHOLMOD symbolic
 *   analysis. G is stored already permuted to CHOLMOD's fill-reducing order
 *   (upper triangle, analysed again in natural order), because
 *   cholmod_l_factorize would otherwise build a permuted transpose of G at
 *   every call. Every factor_c fills G's values from the map and factors it
 *   (LDL^T; "Numeric factorization" below). Then
 *       C^+ r = C^T G^-1 r,     N z = z - C^T G^-1 C z.
 *   The solves with a simplicial factor (CHOLMOD's choice for chain- and
 *   tree-like mechanisms; LDL^T or LL^T) are done here, in place:
 *   cholmod_l_solve2 reshapes its workspace for a single right-hand side
 *   and so reallocates it at every call. A supernodal factor (dense
 *   couplings, e.g. many rows on one body) goes through cholmod_l_solve2.
 *   With a simplicial factor nothing is allocated per call (after the first
 *   factorization; tested). G squares the condition number of C, so each
 *   solve is checked (componentwise residual of C x = r, resp. C N z = 0,
 *   with the sparse C) and refined by up to two further solves when the
 *   check fails.
 *   Rank decision: C is declared rank deficient when a pivot of G's LDL^T
 *   is at most dbound (next section: the rows may be set aside; else the
 *   QR path), a pivot is negative, or the ratio min/max of the diagonal of L (of
 *   L L^T; sqrt(cholmod_l_rcond) for LL^T and LDL^T factors alike) is below
 *   max(tol, 1e-6). The floor 1e-6 is needed because G squares the
 *   condition number: the Cholesky pivot of a row that depends on earlier
 *   ones comes out at round-off level of G, ~eps·||C||^2, i.e. its L
 *   diagonal at ~sqrt(eps)·||C|| = 1.5e-8·||C||, far above a relative
 *   tolerance such as the default 10·max(rows,n)·eps. The ratio is always
 *   >= 1/cond(C) (min L_jj >= sigma_min(C), max L_jj <= sigma_max(C)), so
 *   well-conditioned C never takes the slower path. It is only a bound:
 *   measured, it exceeds 1/cond(C) by 3x for a row 1e-3 ... 1e-7 from a copy
 *   of another, and by about sqrt(rows) when the near dependence is spread
 *   over many rows (a closed chain near its straight configuration: 3x at 6
 *   links, 13x at 150, 32x at 1000), so G is accepted up to cond(C) ~ 2e7
 *   (cond(G) ~ 5e14). The refinement below still makes those solves as
 *   accurate as a backward-stable method's (1000-link closed chain at cond
 *   2.3e7: 2e-10 of |x|, cond·eps = 5e-9; N z to 1e-8 of |z|). A real
 *   estimate of cond_1(G) from the factor (Hager and Higham, as LAPACK's
 *   xLACN2) is within 1.4x of cond_2(G) in those cases but costs about five
 *   solves with L: factor_c on a 1000-link chain 74 -> 173 us (2.3x), for no
 *   accuracy gained, so the diagonal bound stays. (A row 1e-9 from a copy of
 *   another, cond(C) 1.2e10, never reaches the ratio: its pivot, 1e-18
 *   cmax^2, is below dbound, and the next section refuses to set it aside:
 *   the row is not dependent to round-off.) A rejected G hands over to the
 *   QR path, which then decides the rank with the caller's tol.
 *   After a rejection the next CHOL_SKIP_CALLS factorizations of the slot go
 *   to the QR path directly (an ill-conditioned C would otherwise pay for a
 *   useless Cholesky at every call); then the Cholesky is tried again. Not
 *   after a refusal of the next section's, which the next call usually
 *   passes (the first call of a run, without the rank rule's keep).
 *
 *  Redundant rows on the Cholesky path (rows that depend exactly on others,
 *   as in the redundant ladder, a double parallelogram or a duplicated
 *   joint: a structural deficiency, with the dependent rows' residuals at
 *   round-off). G's LDL^T is computed with its pivots of magnitude at most
 *   dbound = CHOL_DBOUND·max_i G_ii = 1e-13 cmax^2 replaced by +-dbound
 *   (CHOLMOD's Common->dbound). The pivot of a row is its squared distance
 *   from the span of the rows eliminated before it; for a row that depends
 *   on them it comes out at round-off, a few eps·cmax^2, and is replaced.
 *   Those rows (D) are set aside and the others (B) kept: L without D's
 *   rows and columns is the factor of G_BB = C_B C_B^T, as long as the
 *   columns of L at D's pivots are round-off over dbound, i.e. at most
 *   DEP_LMAX = 1 (checked; a row only nearly dependent leaves entries up to
 *   sqrt(pivot)·cmax/dbound there and is refused), and the solves of this
 *   path skip those rows and columns. One symbolic analysis thus serves
 *   full-rank and redundant C, and a redundant C costs a Cholesky per call,
 *   not SPQR's analysis and two QRs (ladder of 1000 cells, 12 000 rows:
 *   about 72 -> 16 ms per RK4 step).
 *   The rank is k = rows - |D| when (a) the rank rule's cap allows k; (b)
 *   the kept rows pass the tests of a full-rank G (positive pivots, ratio
 *   at least lim, the probe), lim with tol_new when the rule's keep is
 *   below k; (c) the rows set aside depend on the kept ones to within thr =
 *   tol·cmax, or max(tol, tol_new)·cmax when keep <= k (direction k + 1 is
 *   then beyond keep). With K = [-W^T; I] (below) the left null vectors of
 *   the exact dependence (K^T K >= I), sigma_(k+1)(C) <= ||C^T K||_2 <=
 *   ||C^T K||_F, and column j of C^T K is row j's distance from the kept
 *   rows' span, at most its distance from those before it. (c) holds when
 *   the sum over D of bounds on those squared distances (dbound, what
 *   earlier set-aside columns took from the pivot, DEP_PIVOT_ERR·eps·cmax^2
 *   = 1e3 eps cmax^2 for rounding) is at most (DEP_MARGIN·thr)^2,
 *   DEP_MARGIN = 0.1: in a run, at a step's later stages (tol_new 1e-3).
 *   Else DEP_PROBES = 2 probes in C-space (dep_probe): for a fixed w of +-1
 *   on D, v = C_D^T w minus its projection on the row space of C_B is
 *   C^T K w, whose mean square estimates ||C^T K||_F^2; accepted when that
 *   is at most (DEP_MARGIN·thr)^2 (a solve's error lies in the row space of
 *   C_B, orthogonal to C^T K w, and can only enlarge it). A randomized
 *   check: a dependence broken along a direction u (in D's coordinates)
 *   with |u·w| < 0.1 for both fixed w is found only once it exceeds thr
 *   ten times over. A factorization that fails (a)-(c) goes to the QR path.
 *   With C = P C_B, P = [I; W] in row order, W = C_D C_B^+ (exactly; the
 *   rows set aside replaced by their projections on the row space of C_B,
 *   the rank-k approximation that the QR path's complete orthogonal
 *   decomposition makes when SPQR keeps the same rows):
 *       C^+ r = C_B^+ P^+ r = C_B^+ (r_B + W^T s),
 *       (I + W W^T) s = t = r_D - W r_B
 *   (min |u - r_B|^2 + |W u - r_D|^2 by the Woodbury identity), t the
 *   inconsistency of the rows set aside: at rounding level for a consistent
 *   r (an acceleration's), then C^+ r = C_B^+ r_B, refined as the full-rank
 *   path refines; else s by conjugate gradients, each product with
 *   I + W W^T two solves with G_BB, preconditioned by diag(I + W W^T)
 *   estimated from one +-1 vector (exact when the dependences share no kept
 *   rows; 1-2 iterations on the ladder); W^T s and C_B^+ W^T s summed from
 *   CG's products and corrected once (corrected semi-normal equations,
 *   Björck, BIT 27 (1987)). CG stops when t is at rounding level of
 *   |r| + |C||x| (REFINE_TOL eps), or below the caller's round-off floor
 *   of r (rhs_floor, braun_linsolver.h: the core's for the position and
 *   velocity corrections, docs/method.md; 0 after every factor_c), where t also
 *   counts as consistent from the start; a CG that has not after CG_MAX = 200
 *   iterations (W huge: the kept rows nearly dependent themselves) moves
 *   the factorization to the QR path, which must find the same rank.
 *   N z = z - C_B^T G_BB^-1 C_B z, refined as on the full-rank path. Cost:
 *   a Cholesky per factor_c, plus two solves at a run's step starts (the
 *   probe); pinv 2 solves for a consistent r, about 7 with CG. Nothing is
 *   allocated per call (tested).
 *   Walks of L shared (every result bit for bit that of one solve each):
 *   the probe of an accepted Cholesky (chol_probe) solves the forward
 *   pass's r_v (handed to factor_c as resid) in the same walk of L, and the
 *   pinv that follows finds that solve done (g_solve compares its right-
 *   hand side bit for bit); the two dependency probes' first solves share a
 *   walk; ldl_numeric records the replaced pivots and the extreme kept ones
 *   for chol_dep and the full-rank test. The 2000-cell ladder (24 000 rows;
 *   its kept rows' pivot ratio 0.008, below CHOL_PROBE_RATIO, so every
 *   factorization is probed): about 30.5 -> 27.3 ms per corrected RK4
 *   step; 24-25 with the corrections' floors and G formed inside
 *   ldl_numeric (interleaved runs, 2026-12-03; docs/performance.md,
 *   Optimisations item 15).
 *
 *  Numeric factorization: the first of each layout of L is CHOLMOD's; a
 *   simplicial LDL^T (columns sorted, diagonal first: checked) is then
 *   factored again here, at once and from then on (ldl_numeric:
 *   left-looking on that pattern, the same pivot replacement; CHOLMOD's
 *   factor only gives the layout, so the first factorization after create
 *   rounds as every later one and a run repeated after braun_set_state is
 *   the first bit for bit), about twice as fast as cholmod_l_factorize's
 *   row-oriented one (ladder, 12 000 rows: 0.73 against 1.42 ms). From
 *   then on it also forms G: the product map is reordered to its walk of
 *   G's lower columns (ldl_build), and each G_ij is summed where it is
 *   scattered, the same sums as the map's in entry order, so G->x is
 *   neither written nor read (a CHOLMOD refactorization of a new layout
 *   fills it through map_e).
 *
 *  Rank deficient otherwise (singular configurations, rows not dependent
 *   to round-off, the rank rule's cap below the rank): SPQR,
 *   rank-revealing sparse QR (Heath's method) of C^T with the absolute
 *   tolerance tol·max_i ||row i of C|| (the largest column norm of C^T: the
 *   first pivot of the core's column-pivoted QR), through SuiteSparseQR_C,
 *   which returns R in upper trapezoidal form with its column permutation E
 *   and Q as Householder vectors (H, HTau, HPinv):
 *       C^T E = Q [R11 R12; 0 0],  R11 k x k upper triangular, k = rank,
 *   so C = E S Q1^T with S = [R11 R12]^T (rows x k, full column rank) and
 *       C^+ r = Q1 S^+ E^T r,      N z = z - Q1 Q1^T z.
 *   With k < rows S^+ is the least-squares solve through a second SPQR
 *   factorization of S (no rank detection; S E2 = Q2 [R2; 0]):
 *       S^+ b = E2 R2^-1 (Q2^T b)[0..k).
 *   Together this is a complete orthogonal decomposition (as LAPACK's
 *   xGELSY and the core's src/core/braun_qrcp.c): C^+ r is the minimum-norm
 *   least-squares solution also for r outside range(C), not only the basic
 *   solution of the k rows SPQR kept. Q, Q2 are applied by the loops below
 *   from the Householder form (H(h) = I - tau_h v_h v_h^T, Q^T = H(nh-1) ...
 *   H(0) P with (P x)[HPinv[i]] = x[i], the convention of SPQR's
 *   spqr_happly / SuiteSparseQR_qmult). SPQR allocates its factors at every
 *   call of this path; Heath's method is reliable for exactly dependent rows
 *   (their remaining column norm is at round-off level) but, unlike column
 *   pivoting, not a guaranteed rank-revealing method for nearly dependent
 *   ones: close to a singular configuration the rank it reports may differ
 *   from the one the core's QRCP (or an SVD) finds with the same tol. With a
 *   clear gap between the kept and the dropped directions they agree
 *   (tested against LAPACK's SVD: exact and scaled copies of rows, a double
 *   parallelogram, a row 1e-9 from another with tol 1e-6 and with the
 *   default tol).
 *
 *  Full rank on the QR path (k = rows: G refused but every row kept, i.e.
 *   cond(C) beyond ~1e6 yet below 1/tol; or the CHOL_SKIP_CALLS after a
 *   rejection): C = E R^T Q1^T, C^+ b = Q1 R^-T E^T b. Householder QR is
 *   backward stable, hence only cond(C)·eps accurate: the computed Q1 spans
 *   the row space of a C perturbed by eps·|C|, turned by ~cond(C)·eps, and
 *   the minimum-norm solution turns with it, mostly into null(C), where a
 *   residual r - C x does not see it. Measured with a row 1e-9 from a copy
 *   of another (cond(C) 1.2e10): C^+ r off by 1.6e-6 of |x| (dgelsd's own
 *   error 2.8e-7), N z by 2e-7. So when min/max |R_jj| < QR_REFINE_RATIO =
 *   1e-3 (the same bound on 1/cond(C) as L's diagonal; above it cond(C) is
 *   at most ~3e4 with the overestimates measured above, and the unrefined
 *   error ~cond(C)·eps at most ~3e-12) the solves are refined on the
 *   augmented system
 *       x - C^T y = 0,  C x = b       (Björck, BIT 7 (1967) and 8 (1968)),
 *   y = E R^-1 R^-T E^T b to start (so that C^T y = x), with the residuals
 *   d = C^T y - x and g = b - C x in doubled precision (compensated sums of
 *   exact products: Dot2 of Ogita, Rump and Oishi, SISC 26 (2005); one sweep
 *   over C) and
 *   the correction from the same factor: w = R^-T E^T (g - C d),
 *   dy = E R^-1 w, dx = d + Q1 w; at most QR_REFINE_MAX = 2 steps, fewer
 *   once the correction is at rounding level of x. null_project refines
 *   x = C^+ (C z) the same way with C z formed exactly inside g, then
 *   returns z - x. The error then behaves as (cond(C)·eps)^2 + eps, x and y
 *   being stored in double: measured 1e-16, 1.6e-13, 1e-9 of |x| at cond(C)
 *   1.2e8, 1.2e10, 1.2e12 (unrefined 6e-9, 1.6e-6, 1.2e-4), N z 6e-17,
 *   3e-14, 2.4e-9 (unrefined 1.3e-9, 2e-7, 1.1e-5). Cost on a 1000-link chain
 *   with one such row (test_bench, "qr-fr"): pinv 37 -> 270 us, null_project
 *   44 -> 320 us, beside 700 us for factor_c (factor_c + pinv + null_project
 *   0.77 -> 1.30 us per link); the Cholesky path and the rank-deficient QR
 *   path are unchanged (74 us per factor_c on that chain without the row).
 *   Rank-deficient factorizations are not refined: the residuals would be
 *   those of C, not of the truncated E S Q1^T whose pseudoinverse is wanted.
 *
 * lsq's residual ||r - C C^+ r|| is computed with the sparse C from the
 * returned x (all paths). Cost per call: O(nnz(C)·block size) to form C,
 * O(products of the map) for G, then the LDL^T or SPQR's factorization and
 * O(nnz(L)) resp. O(nnz(H) + nnz(R) + nnz(R2)) per solve (refined: up to
 * three times that, plus two compensated sweeps over C). The work vectors
 * (10 of rows, 7 of n entries) are allocated in create().
 *
 * tol <= 0 in factor_c selects the core's default, 10·max(rows, n)·eps.
 *
 * Status codes: factor_c returns BRAUN_ERR_ARGUMENT for a bad slot or row
 * count, BRAUN_ERR_NONFINITE for NaN/Inf in C, BRAUN_ERR_BUFFER when CHOLMOD
 * or SPQR runs out of memory (CHOLMOD_OUT_OF_MEMORY, CHOLMOD_TOO_LARGE),
 * BRAUN_ERR_ARGUMENT when they refuse their input (CHOLMOD_INVALID: a bug
 * here), and BRAUN_ERR_NONFINITE for any other failure (e.g. a factor not of
 * the expected triangular form), the closest braun_status to "numerical
 * failure". The void operations (pinv, lsq, null_project) cannot return a
 * status: if their solve fails, or the slot has no valid factorization, they
 * write NaN, which the core's finite checks turn into an error.
 *
 * All arithmetic is in double (SuiteSparse's type); a BRAUN_SINGLE build
 * converts at the interface.
 */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <SuiteSparseQR_C.h>
#include <cholmod.h>

#include "braun_backends.h"
#include "braun_math.h"

typedef SuiteSparse_long sslong;

/* L-diagonal ratio below which G = C C^T counts as singular (see above). */
#define CHOL_RATIO_MIN 1e-6
/* After a rejected Cholesky, factorizations that go straight to SPQR. */
#define CHOL_SKIP_CALLS 8
/* A solve through G is accepted when |r - C x|_i <= REFINE_TOL·eps·max_i
 * (|r| + |C||x|)_i; else up to REFINE_MAX refinement steps. */
#define REFINE_TOL 64.0
#define REFINE_MAX 2
/* The full-rank QR path refines its solves (qr_refine, up to QR_REFINE_MAX
 * steps) when the ratio min/max |R_jj| is below QR_REFINE_RATIO. */
#define QR_REFINE_MAX 2
#define QR_REFINE_RATIO 1e-3
/* An accepted Cholesky whose L-diagonal ratio is below CHOL_PROBE_RATIO is
 * probed with one solve (chol_probe, see above). */
#define CHOL_PROBE_RATIO 1e-2
/* A column of SPQR's R whose |R_jj| is at most QR_CHECK_RATIO·cmax gets
 * the dependency test (qr_decide); at most QR_DROP_PASSES re-factorizations
 * drop the columns it (or the rank rule) rejects. */
#define QR_CHECK_RATIO 1e-3
#define QR_DROP_PASSES 8
#define QR_DROP_GROW 4.0
/* Redundant rows on the Cholesky path (see above): a pivot of G's LDL^T at
 * most CHOL_DBOUND·max_i G_ii marks a row that depends on earlier ones and
 * is replaced; the rows so set aside need their columns of L at most
 * DEP_LMAX, and their distance from the kept rows (pivot bound with
 * DEP_PIVOT_ERR·eps·cmax^2 for rounding, else DEP_PROBES probes from
 * DEP_SEED) at most DEP_MARGIN times the rank threshold; the
 * least-squares part is conjugate gradients on I + W W^T, at most CG_MAX
 * iterations. */
#define CHOL_DBOUND 1e-13
#define DEP_PROBES 2
#define DEP_MARGIN 0.1
#define DEP_SEED 0x9e3779b97f4a7c15ULL
#define DEP_LMAX 1.0
#define DEP_PIVOT_ERR 1e3
#define CG_MAX 200

enum { PATH_NONE = 0, PATH_ZERO, PATH_CHOL, PATH_QR };

/* A Householder QR from SuiteSparseQR_C: A E = Q [R; 0]. */
typedef struct ss_qr {
    cholmod_sparse *R, *H;
    cholmod_dense *HTau;
    sslong *E, *HPinv; /* NULL: identity */
    sslong ncol, nrow; /* of the factored matrix (sizes of E, HPinv) */
} ss_qr;

typedef struct ss_slot {
    int rows;        /* rows of C in this slot (0: slot unused) */
    int qr_refine;   /* full-rank QR path: refine the solves (see above) */
    double *Cx;      /* values of C, pattern cp/ci of the state */
    double cmax;     /* largest row 2-norm of C */
    int path, rank, skip_chol;
    int map_by_col;  /* gptr/gmap reordered to ldl_numeric's walk of G's
                      * lower columns (entry t: position map_e[t] in G->x,
                      * kept apart from gl_e, which ldl_build frees), which
                      * then forms each G_ij where it scatters it: G->x is
                      * neither written nor read (ldl_build) */
    /* The rank rule of the next factorizations (ss_rank_rule): keep, cap,
     * tol_new as braun_linsolver.h; keep = cap = rows: the plain tol. */
    int rule_keep, rule_cap;
    double rule_tol_new;
    double tol;      /* the relative tolerance of the last factor_c */
    /* Cholesky path with redundant rows: ndep rows set aside, dep[a] (in
     * L's order) and dep_row[i] (in row order) 1 for them, dlist their row
     * indices (increasing); cg_iters the iterations of the last pinv. */
    int ndep, dep_rejected, pdiag_ok, wtw_ok;
    double rhs_floor; /* the caller's round-off floor of t (ss_rhs_floor) */
    double *wtw;     /* rows: W^T w for the first probe vector w */
    double *pdiag;   /* rows: the Jacobi preconditioner of CG (rows D) */
    unsigned char *dep, *dep_row;
    int *dlist;
    long cg_iters;
    /* full-rank path */
    cholmod_sparse *G; /* upper triangle of P C C^T P^T, fixed pattern */
    uint32_t *gptr;  /* G entry e: products gmap[3·gptr[e] .. 3·gptr[e+1]) */
    int *map_e;      /* with map_by_col: entry t's position in G->x */
    uint32_t *gmap;  /* (offset of row i's block in Cx, of row j's, length);
                      * 32 bits: half the memory the fill of G streams */
    sslong *perm, *iperm; /* G is stored as P G P^T: new index c is row perm[c] */
    sslong *lperm;   /* the order of L's rows (perm composed with L->Perm) */
    double *bp;      /* rows: a right-hand side in that order */
    /* The forward pass's right-hand side r_v, handed to factor_c (rc_src,
     * during factor_c only), solved with G beside the probe of an accepted
     * Cholesky in one walk of L (rc as ss_lsq converts it, yc, yc_ok): the
     * pinv that follows finds its first solve done (g_solve compares the
     * right-hand side bit for bit). */
    const braun_real *rc_src;
    double *rc, *yc, *bp2;
    int yc_ok;
    int own_solve;   /* L is simplicial with its diagonal first: solved here */
    int own_fact;    /* ldl_numeric factors L (see below) */
    /* L's pattern in 32 bits for the solves and ldl_numeric (own_solve):
     * column j is li[lbeg[j] .. lend[j]), the positions of L->x; half the
     * index bytes CHOLMOD's 64-bit arrays would stream. */
    int *li, *lbeg, *lend;
    const void *own_i; /* L->i and L->nzmax when own_solve was last checked */
    size_t own_nzmax;
    /* The numeric LDL^T done here on L's pattern (ldl_numeric), once
     * CHOLMOD has factored this layout: the rows of L below the diagonal
     * (row i: columns lr_k[lr_p[i] .. lr_p[i+1]), the position of row i
     * in each), the lower triangle of G by columns (rows gl_i, positions
     * gl_e in G->x), a dense work vector. */
    int *lr_p, *lr_k, *lr_q, *gl_p, *gl_i, *gl_e;
    /* What ldl_numeric saw of the pivots (piv_ok): the columns whose
     * pivots it replaced (piv_hit, increasing) and the smallest and largest
     * of the others, so that neither chol_dep nor the full-rank test walks
     * L's diagonal again. */
    int piv_ok, piv_lbig; /* piv_lbig: a replaced pivot's column has an entry > DEP_LMAX */
    int *piv_hit;
    double piv_min, piv_max;
    double *lw;
    cholmod_factor *L;
    cholmod_dense *X, *Y, *E; /* cholmod_l_solve2 workspaces */
    /* rank-deficient path */
    ss_qr qr;        /* C^T E = Q [R11 R12; 0] */
    ss_qr qr2;       /* S E2 = Q2 [R2; 0], S = [R11 R12]^T, when rank < rows */
} ss_slot;

typedef struct ss_state {
    int n, m, p, rows;
    int nblocks;
    int *bsize, *bstart; /* block sizes, first coordinate of each block */
    size_t *boff;        /* offset of block b in Rb (and in M's values) */
    double *Rb;          /* upper Cholesky factors, block after block, row-major */
    int r_diag;          /* every R_b diagonal (planar bodies, particles):
                          * form_c scales, its zero terms skipped */
    const int *arow;     /* A pattern (the model's arrays) */
    sslong *cp, *ci;     /* C pattern: CSR rows x n = CSC of C^T */
    sslong *a2c;         /* A value k lands at Cx[a2c[k]] */
    sslong *sptr;        /* row i's block segments: sptr[i] .. sptr[i+1] */
    int *sblk;           /* block of a segment */
    sslong *spos;        /* first position of a segment in Cx */
    int *scol, *slen;    /* first column and length of a segment: the
                          * products with C walk segments, not ci (a
                          * segment's columns are consecutive), and read a
                          * third of the indices ci would stream */
    double *wr, *wr2, *wr3, *wr4, *wr5, *wr6, *wr7, *wr8, *wr9, *wr10; /* rows each */
    double *wn, *wn2, *wn3, *wn4, *wn5, *wn6, *wn7; /* n each */
    cholmod_common cc;
    int cc_started;
    ss_slot s[2];
} ss_state;

/* ------------------------------------------------------------------ */
/* Small helpers                                                       */
/* ------------------------------------------------------------------ */
static int cc_fail(const cholmod_common *cc)
{
    if (cc->status == CHOLMOD_OUT_OF_MEMORY || cc->status == CHOLMOD_TOO_LARGE)
        return BRAUN_ERR_BUFFER;
    if (cc->status == CHOLMOD_INVALID) return BRAUN_ERR_ARGUMENT;
    return BRAUN_ERR_NONFINITE;
}

static void fill_nan(int len, braun_real *x)
{
    for (int i = 0; i < len; i++) x[i] = (braun_real)NAN;
}

/* BLAS (linked under CHOLMOD and SPQR anyway): the scaled 2-norm. */
double dnrm2_(const int *n, const double *x, const int *incx);

static double nrm2(int len, const double *x)
{
    const int one = 1;
    return dnrm2_(&len, x, &one);
}

static void qr_free(ss_qr *q, cholmod_common *cc)
{
    if (q->R) cholmod_l_free_sparse(&q->R, cc);
    if (q->H) cholmod_l_free_sparse(&q->H, cc);
    if (q->HTau) cholmod_l_free_dense(&q->HTau, cc);
    if (q->E) cholmod_l_free((size_t)q->ncol, sizeof(sslong), q->E, cc);
    if (q->HPinv) cholmod_l_free((size_t)q->nrow, sizeof(sslong), q->HPinv, cc);
    memset(q, 0, sizeof *q);
}

/* Factor A (nrow x ncol) by SuiteSparseQR_C with absolute tolerance tol
 * (< 0: no rank detection) into q; econ as SuiteSparseQR_C. Returns the rank
 * or a braun status (< 0). */
static sslong qr_factor(ss_qr *q, cholmod_sparse *A, double tol, sslong econ,
                        cholmod_common *cc)
{
    qr_free(q, cc);
    q->nrow = (sslong)A->nrow;
    q->ncol = (sslong)A->ncol;
    sslong rank = SuiteSparseQR_C(SPQR_ORDERING_DEFAULT, tol, econ, 0, A, NULL, NULL,
                                  NULL, NULL, &q->R, &q->E, &q->H, &q->HPinv, &q->HTau, cc);
    if (rank < 0 || !q->R || !q->H || !q->HTau) {
        int st = cc->status < CHOLMOD_OK ? cc_fail(cc) : BRAUN_ERR_NONFINITE;
        qr_free(q, cc);
        return st;
    }
    /* R must be upper trapezoidal: rank rows, column j < rank ending on its
     * nonzero diagonal (SPQR moves the dead columns of a "squeezed" R to the
     * end and adjusts E accordingly). */
    const sslong *Rp = q->R->p, *Ri = q->R->i;
    const double *Rx = q->R->x;
    if ((sslong)q->R->nrow < rank || (sslong)q->R->ncol != q->ncol) {
        qr_free(q, cc);
        return BRAUN_ERR_NONFINITE;
    }
    for (sslong j = 0; j < rank; j++) {
        sslong last = Rp[j + 1] - 1;
        if (last < Rp[j] || Ri[last] != j || Rx[last] == 0) {
            qr_free(q, cc);
            return BRAUN_ERR_NONFINITE;
        }
    }
    return rank;
}

/* x := H(nh-1) ... H(0) x (forward) or H(0) ... H(nh-1) x (backward). */
static void happly(const ss_qr *q, int forward, double *x)
{
    const cholmod_sparse *H = q->H;
    const sslong *Hp = H->p, *Hi = H->i;
    const double *Hx = H->x, *tau = q->HTau->x;
    const sslong nh = (sslong)H->ncol;
    for (sslong k = 0; k < nh; k++) {
        sslong h = forward ? k : nh - 1 - k;
        if (tau[h] == 0) continue;
        double s = 0;
        for (sslong p = Hp[h]; p < Hp[h + 1]; p++) s += Hx[p] * x[Hi[p]];
        s *= tau[h];
        for (sslong p = Hp[h]; p < Hp[h + 1]; p++) x[Hi[p]] -= s * Hx[p];
    }
}

/* t := Q^T b (nrow entries; t and b distinct). */
static void q_t(const ss_qr *q, const double *b, double *t)
{
    for (sslong i = 0; i < q->nrow; i++) t[q->HPinv ? q->HPinv[i] : i] = b[i];
    happly(q, 1, t);
}

/* y := Q t (t is overwritten; y and t distinct). */
static void q_apply(const ss_qr *q, double *t, double *y)
{
    happly(q, 0, t);
    for (sslong i = 0; i < q->nrow; i++) y[i] = t[q->HPinv ? q->HPinv[i] : i];
}

/* w := R(0:k,0:k)^-T b (forward substitution by columns of the CSC R). */
static void r_solve_t(const cholmod_sparse *R, sslong k, const double *b, double *w)
{
    const sslong *Rp = R->p, *Ri = R->i;
    const double *Rx = R->x;
    for (sslong j = 0; j < k; j++) {
        double s = b[j];
        sslong last = Rp[j + 1] - 1; /* the diagonal */
        for (sslong p = Rp[j]; p < last; p++) s -= Rx[p] * w[Ri[p]];
        w[j] = s / Rx[last];
    }
}

/* y[0..k) := R(0:k,0:k)^-1 y[0..k) (back substitution, in place). */
static void r_solve(const cholmod_sparse *R, sslong k, double *y)
{
    const sslong *Rp = R->p, *Ri = R->i;
    const double *Rx = R->x;
    for (sslong j = k - 1; j >= 0; j--) {
        sslong last = Rp[j + 1] - 1;
        double u = y[j] / Rx[last];
        y[j] = u;
        for (sslong p = Rp[j]; p < last; p++) y[Ri[p]] -= Rx[p] * u;
    }
}

/* ------------------------------------------------------------------ */
/* C = A R^-1 and products with it                                     */
/* ------------------------------------------------------------------ */
/* y := C x (rows); if bound: bound := max_i (|r_i| + (|C||x|)_i) with r = y0
 * when y0 is given (y := y0 - C x then). */
static void c_mul(const ss_state *s, const ss_slot *f, const double *x, const double *y0,
                  double *y, double *bound)
{
    const sslong *sptr = s->sptr;
    const int *scol = s->scol, *slen = s->slen;
    const double *c = f->Cx; /* segments lie one after another in Cx */
    double bmax = 0;
    for (int i = 0; i < f->rows; i++) {
        double acc = 0, abs_acc = 0;
        for (sslong g = sptr[i]; g < sptr[i + 1]; g++) {
            const double *xb = x + scol[g];
            const int len = slen[g];
            if (len == 3) { /* planar bodies; the same sums in the same order */
                const double t0 = c[0] * xb[0], t1 = c[1] * xb[1], t2 = c[2] * xb[2];
                acc += t0;
                abs_acc += fabs(t0);
                acc += t1;
                abs_acc += fabs(t1);
                acc += t2;
                abs_acc += fabs(t2);
            } else {
                for (int k = 0; k < len; k++) {
                    const double t = c[k] * xb[k];
                    acc += t;
                    abs_acc += fabs(t);
                }
            }
            c += len;
        }
        if (y0) {
            abs_acc += fabs(y0[i]);
            acc = y0[i] - acc;
        }
        y[i] = acc;
        if (abs_acc > bmax) bmax = abs_acc;
    }
    if (bound) *bound = bmax;
}

/* x += C^T y (n). */
static void ct_mul_add(const ss_state *s, const ss_slot *f, const double *y, double *x)
{
    const sslong *sptr = s->sptr;
    const int *scol = s->scol, *slen = s->slen;
    for (int i = 0; i < f->rows; i++) {
        const double yi = y[i];
        if (yi == 0) continue;
        const double *c = f->Cx + s->cp[i];
        for (sslong g = sptr[i]; g < sptr[i + 1]; g++) {
            double *xb = x + scol[g];
            const int len = slen[g];
            for (int k = 0; k < len; k++) xb[k] += c[k] * yi;
            c += len;
        }
    }
}

static double inf_norm(int len, const double *x)
{
    double a = 0;
    for (int i = 0; i < len; i++)
        if (!(fabs(x[i]) <= a)) {
            a = fabs(x[i]);
            if (a != a) break; /* NaN wins */
        }
    return a;
}

/* Error-free transformations: a + b = *s + *e (Knuth's TwoSum) and
 * a·b = *p + *e (TwoProduct) exactly, barring overflow and underflow, in
 * IEEE double with FLT_EVAL_METHOD 0 (SSE2, every 64-bit target). The
 * product's error is fma(a, b, -p) where the target has a fused
 * multiply-add (the compiler may contract only there); elsewhere, where a
 * call to fma() would be a slow software emulation, Dekker's product of
 * Veltkamp halves. */
static void two_sum(double a, double b, double *s, double *e)
{
    const double t = a + b, z = t - a;
    *s = t;
    *e = (a - (t - z)) + (b - z);
}

static void two_prod(double a, double b, double *p, double *e)
{
    const double t = a * b;
    *p = t;
#ifdef FP_FAST_FMA
    *e = fma(a, b, -t);
#else
    const double split = 134217729.0; /* 2^27 + 1 */
    const double ca = split * a, ah = ca - (ca - a), al = a - ah;
    const double cb = split * b, bh = cb - (cb - b), bl = b - bh;
    *e = ((ah * bh - t) + ah * bl + al * bh) + al * bl;
#endif
}

/* The residuals of the augmented system x - C^T y = 0, C x = b, in one
 * sweep over C: g := b - C x with b = r (z NULL) or b = C z (r NULL), and
 * d := C^T y - x, each entry as accurate as if computed in twice the
 * working precision and then rounded (Ogita, Rump and Oishi's Dot2:
 * compensated sums of exact products). e: n entries of workspace. */
static void aug_resid(const ss_state *s, const ss_slot *f, const double *x, const double *y,
                      const double *r, const double *z, double *g, double *d, double *e)
{
    const int n = s->n;
    for (int j = 0; j < n; j++) d[j] = -x[j], e[j] = 0;
    for (int i = 0; i < f->rows; i++) {
        const double yi = y[i];
        double sum = r ? r[i] : 0, err = 0, p, pe, se;
        for (sslong q = s->cp[i]; q < s->cp[i + 1]; q++) {
            const double c = f->Cx[q];
            const sslong j = s->ci[q];
            two_prod(c, x[j], &p, &pe);
            two_sum(sum, -p, &sum, &se);
            err += se - pe;
            if (z) {
                two_prod(c, z[j], &p, &pe);
                two_sum(sum, p, &sum, &se);
                err += se + pe;
            }
            two_prod(c, yi, &p, &pe);
            two_sum(d[j], p, &d[j], &se);
            e[j] += se + pe;
        }
        g[i] = sum + err;
    }
    for (int j = 0; j < n; j++) d[j] += e[j];
}

/* Cx := A R^-1 for the slot's rows; f->cmax. Returns 0, or -1 on NaN/Inf. */
static int form_c(ss_state *s, ss_slot *f, const braun_real *A)
{
    double *Cx = f->Cx;
    const sslong nnz = s->cp[f->rows];
    const int nA = s->arow[f->rows];
    double allfin = 0, cmax = 0;
    memset(Cx, 0, (size_t)nnz * sizeof *Cx);
    for (int k = 0; k < nA; k++) Cx[s->a2c[k]] = (double)A[k];
    for (int i = 0; i < f->rows; i++) {
        for (sslong g = s->sptr[i]; g < s->sptr[i + 1]; g++) {
            /* c R_b = a on this block: forward substitution over columns. */
            const int b = s->sblk[g], bs = s->bsize[b];
            const double *Rb = s->Rb + s->boff[b];
            double *c = Cx + s->spos[g];
            if (s->r_diag) { /* t - c_k·0 = t: the same quotients */
                for (int j = 0; j < bs; j++) c[j] /= Rb[j * bs + j];
                continue;
            }
            for (int j = 0; j < bs; j++) {
                double t = c[j];
                for (int k = 0; k < j; k++) t -= c[k] * Rb[k * bs + j];
                c[j] = t / Rb[j * bs + j];
            }
        }
        double sq = 0;
        for (sslong p = s->cp[i]; p < s->cp[i + 1]; p++) {
            allfin += Cx[p] * 0;
            sq += Cx[p] * Cx[p];
        }
        if (sq > cmax) cmax = sq;
    }
    f->cmax = sqrt(cmax);
    if (allfin != 0 || !(f->cmax <= DBL_MAX)) {
        /* NaN/Inf in C (or overflow of its norm): refuse. */
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------------ */
/* create / destroy                                                    */
/* ------------------------------------------------------------------ */
static void slot_free(ss_slot *f, cholmod_common *cc)
{
    qr_free(&f->qr, cc);
    qr_free(&f->qr2, cc);
    if (f->L) cholmod_l_free_factor(&f->L, cc);
    if (f->G) cholmod_l_free_sparse(&f->G, cc);
    if (f->X) cholmod_l_free_dense(&f->X, cc);
    if (f->Y) cholmod_l_free_dense(&f->Y, cc);
    if (f->E) cholmod_l_free_dense(&f->E, cc);
    free(f->Cx);
    free(f->gptr);
    free(f->gmap);
    free(f->map_e);
    free(f->perm);
    free(f->iperm);
    free(f->lperm);
    free(f->bp);
    free(f->rc);
    free(f->yc);
    free(f->bp2);
    free(f->li);
    free(f->lbeg);
    free(f->lend);
    free(f->piv_hit);
    free(f->lr_p);
    free(f->lr_k);
    free(f->lr_q);
    free(f->gl_p);
    free(f->gl_i);
    free(f->gl_e);
    free(f->lw);
    free(f->dep);
    free(f->pdiag);
    free(f->wtw);
    free(f->dep_row);
    free(f->dlist);
    memset(f, 0, sizeof *f);
}

static void ss_destroy(void *state)
{
    ss_state *s = state;
    if (!s) return;
    if (s->cc_started) {
        slot_free(&s->s[0], &s->cc);
        slot_free(&s->s[1], &s->cc);
        cholmod_l_finish(&s->cc);
    }
    free(s->bsize);
    free(s->bstart);
    free(s->boff);
    free(s->Rb);
    free(s->cp);
    free(s->ci);
    free(s->a2c);
    free(s->sptr);
    free(s->sblk);
    free(s->spos);
    free(s->scol);
    free(s->slen);
    free(s->wr);
    free(s->wr2);
    free(s->wr3);
    free(s->wr4);
    free(s->wr5);
    free(s->wr6);
    free(s->wr7);
    free(s->wr8);
    free(s->wr9);
    free(s->wr10);
    free(s->wn);
    free(s->wn2);
    free(s->wn3);
    free(s->wn4);
    free(s->wn5);
    free(s->wn6);
    free(s->wn7);
    free(s);
}

static void *xcalloc(size_t count, size_t size)
{
    return calloc(count ? count : 1, size);
}

static int cmp_long(const void *a, const void *b)
{
    sslong x = *(const sslong *)a, y = *(const sslong *)b;
    return (x > y) - (x < y);
}

/* Block -> (row, position of its segment in Cx) lists for the first `rows`
 * rows, rows increasing. */
typedef struct blist {
    sslong *ptr, *row, *pos;
} blist;

static void blist_free(blist *b)
{
    free(b->ptr);
    free(b->row);
    free(b->pos);
}

static int blist_build(const ss_state *s, int rows, blist *b)
{
    const int nb = s->nblocks;
    const sslong nseg = s->sptr[rows];
    b->ptr = xcalloc((size_t)nb + 1, sizeof *b->ptr);
    b->row = xcalloc((size_t)nseg, sizeof *b->row);
    b->pos = xcalloc((size_t)nseg, sizeof *b->pos);
    if (!b->ptr || !b->row || !b->pos) return BRAUN_ERR_BUFFER;
    for (sslong g = 0; g < nseg; g++) b->ptr[s->sblk[g] + 1]++;
    for (int k = 0; k < nb; k++) b->ptr[k + 1] += b->ptr[k];
    for (int i = 0; i < rows; i++)
        for (sslong g = s->sptr[i]; g < s->sptr[i + 1]; g++) {
            sslong k = b->ptr[s->sblk[g]]++;
            b->row[k] = i;
            b->pos[k] = s->spos[g];
        }
    for (int k = nb; k > 0; k--) b->ptr[k] = b->ptr[k - 1];
    b->ptr[0] = 0;
    return BRAUN_OK;
}

/* One triangle of G = C C^T (rows x rows) as a CHOLMOD matrix, in the row
 * order perm (new index c is row perm[c]; iperm its inverse; NULL: the
 * identity): upper (stype 1: new indices a <= c in column c) or lower.
 * Two rows are coupled when they touch a common block. With map: the
 * product lists of every entry, G_ij = sum over shared blocks b of
 * C_ib . C_jb, as (offset of row i's segment, of row j's, length). */
static cholmod_sparse *g_pattern(ss_state *s, int rows, const blist *bl, const sslong *perm,
                                 const sslong *iperm, int upper, uint32_t **gptr,
                                 uint32_t **gmap, int *status)
{
    cholmod_common *cc = &s->cc;
    cholmod_sparse *G = NULL;
    sslong *mark = xcalloc((size_t)rows, sizeof *mark), *loc = xcalloc((size_t)rows, sizeof *loc),
           *cnt = xcalloc((size_t)rows, sizeof *cnt), *list = xcalloc((size_t)rows, sizeof *list);
    *status = BRAUN_ERR_BUFFER;
    if (!mark || !loc || !cnt || !list) goto out;
#define NEW(i) (iperm ? iperm[i] : (i))
#define KEEP(ni, c) (upper ? (ni) <= (c) : (ni) >= (c))

    /* Pass 1: entries and products. */
    sslong nnzG = 0, nprod = 0;
    for (int i = 0; i < rows; i++) mark[i] = -1;
    for (sslong c = 0; c < rows; c++) {
        const sslong j = perm ? perm[c] : c;
        for (sslong g = s->sptr[j]; g < s->sptr[j + 1]; g++) {
            const int b = s->sblk[g];
            for (sslong k = bl->ptr[b]; k < bl->ptr[b + 1]; k++) {
                sslong i = bl->row[k];
                if (!KEEP(NEW(i), c)) continue;
                nprod++;
                if (mark[i] != c) {
                    mark[i] = c;
                    nnzG++;
                }
            }
        }
    }
    G = cholmod_l_allocate_sparse((size_t)rows, (size_t)rows, (size_t)nnzG, 1, 1, upper ? 1 : -1,
                                  CHOLMOD_REAL, cc);
    if (!G) {
        *status = cc_fail(cc);
        goto out;
    }
    if (gmap && (nprod > (sslong)UINT32_MAX || s->cp[rows] > (sslong)UINT32_MAX)) {
        /* beyond 32-bit offsets (nnz(C) or the products of G over 4e9) */
        cholmod_l_free_sparse(&G, cc);
        *status = BRAUN_ERR_SIZE;
        goto out;
    }
    if (gmap) {
        *gptr = xcalloc((size_t)nnzG + 1, sizeof **gptr);
        *gmap = xcalloc(3 * (size_t)nprod, sizeof **gmap);
        if (!*gptr || !*gmap) {
            cholmod_l_free_sparse(&G, cc);
            goto out;
        }
    }
    sslong *Gp = G->p, *Gi = G->i;

    /* Pass 2: sorted (new) row indices of each column, then the products. */
    sslong e0 = 0, q = 0;
    for (int i = 0; i < rows; i++) mark[i] = -1;
    for (sslong c = 0; c < rows; c++) {
        const sslong j = perm ? perm[c] : c;
        sslong len = 0;
        Gp[c] = e0;
        for (sslong g = s->sptr[j]; g < s->sptr[j + 1]; g++) {
            const int b = s->sblk[g];
            for (sslong k = bl->ptr[b]; k < bl->ptr[b + 1]; k++) {
                sslong ni = NEW(bl->row[k]);
                if (!KEEP(ni, c) || mark[ni] == c) continue;
                mark[ni] = c;
                list[len++] = ni;
            }
        }
        qsort(list, (size_t)len, sizeof *list, cmp_long);
        for (sslong t = 0; t < len; t++) {
            Gi[e0 + t] = list[t];
            loc[list[t]] = t;
            cnt[t] = 0;
        }
        if (gmap) {
            for (sslong g = s->sptr[j]; g < s->sptr[j + 1]; g++) {
                const int b = s->sblk[g];
                for (sslong k = bl->ptr[b]; k < bl->ptr[b + 1]; k++) {
                    sslong ni = NEW(bl->row[k]);
                    if (KEEP(ni, c)) cnt[loc[ni]]++;
                }
            }
            for (sslong t = 0; t < len; t++) {
                (*gptr)[e0 + t] = (uint32_t)q;
                q += cnt[t];
                cnt[t] = (*gptr)[e0 + t]; /* fill cursor */
            }
            for (sslong g = s->sptr[j]; g < s->sptr[j + 1]; g++) {
                const int b = s->sblk[g];
                for (sslong k = bl->ptr[b]; k < bl->ptr[b + 1]; k++) {
                    sslong ni = NEW(bl->row[k]);
                    if (!KEEP(ni, c)) continue;
                    sslong at = cnt[loc[ni]]++;
                    (*gmap)[3 * at] = (uint32_t)bl->pos[k];     /* the other row's block b */
                    (*gmap)[3 * at + 1] = (uint32_t)s->spos[g]; /* row j's block b */
                    (*gmap)[3 * at + 2] = (uint32_t)s->bsize[b];
                }
            }
        }
        e0 += len;
    }
#undef NEW
#undef KEEP
    Gp[rows] = e0;
    if (gmap) (*gptr)[nnzG] = (uint32_t)q;
    memset(G->x, 0, (size_t)nnzG * sizeof(double));
    *status = BRAUN_OK;
out:
    free(mark);
    free(loc);
    free(cnt);
    free(list);
    return G;
}

/* The full-rank path's structures for the first `rows` rows. CHOLMOD picks
 * the fill-reducing order P on G's pattern; G is then stored permuted
 * (P G P^T, upper triangle) and analysed again in its natural order, so that
 * cholmod_l_factorize factors it in place: with any other ordering or a
 * lower triangle it builds a permuted transpose of G at every call. */
static int slot_build(ss_state *s, ss_slot *f, int rows)
{
    cholmod_common *cc = &s->cc;
    blist bl = {NULL, NULL, NULL};
    cholmod_sparse *G0 = NULL;
    cholmod_factor *L0 = NULL;
    int st;

    f->rows = rows;
    f->rule_keep = f->rule_cap = rows;
    f->rule_tol_new = 0;
    f->Cx = xcalloc((size_t)s->cp[rows], sizeof *f->Cx);
    f->perm = xcalloc((size_t)rows, sizeof *f->perm);
    f->iperm = xcalloc((size_t)rows, sizeof *f->iperm);
    f->lperm = xcalloc((size_t)rows, sizeof *f->lperm);
    f->bp = xcalloc((size_t)rows, sizeof *f->bp);
    f->rc = xcalloc((size_t)rows, sizeof *f->rc);
    f->yc = xcalloc((size_t)rows, sizeof *f->yc);
    f->bp2 = xcalloc((size_t)rows, sizeof *f->bp2);
    f->dep = xcalloc((size_t)rows, sizeof *f->dep);
    f->pdiag = xcalloc((size_t)rows, sizeof *f->pdiag);
    f->wtw = xcalloc((size_t)rows, sizeof *f->wtw);
    f->dep_row = xcalloc((size_t)rows, sizeof *f->dep_row);
    f->dlist = xcalloc((size_t)rows, sizeof *f->dlist);
    f->piv_hit = xcalloc((size_t)rows, sizeof *f->piv_hit);
    if (!f->Cx || !f->perm || !f->iperm || !f->lperm || !f->bp || !f->rc || !f->yc || !f->bp2 ||
        !f->dep || !f->dep_row ||
        !f->dlist || !f->pdiag || !f->wtw || !f->piv_hit)
        return BRAUN_ERR_BUFFER;
    if ((st = blist_build(s, rows, &bl)) != BRAUN_OK) goto out;

    /* The ordering, from the pattern alone. */
    G0 = g_pattern(s, rows, &bl, NULL, NULL, 0, NULL, NULL, &st);
    if (!G0) goto out;
    L0 = cholmod_l_analyze(G0, cc);
    if (!L0) {
        st = cc_fail(cc);
        goto out;
    }
    const sslong *P = L0->Perm;
    for (sslong c = 0; c < rows; c++) {
        f->perm[c] = P ? P[c] : c;
        f->iperm[f->perm[c]] = c;
    }

    /* P G P^T, upper triangle, with the product map; natural order. */
    f->G = g_pattern(s, rows, &bl, f->perm, f->iperm, 1, &f->gptr, &f->gmap, &st);
    if (!f->G) goto out;
    {
        const int nmethods = cc->nmethods, ordering = cc->method[0].ordering,
                  postorder = cc->postorder;
        cc->nmethods = 1;
        cc->method[0].ordering = CHOLMOD_NATURAL;
        cc->postorder = 0;
        f->L = cholmod_l_analyze(f->G, cc);
        cc->nmethods = nmethods;
        cc->method[0].ordering = ordering;
        cc->postorder = postorder;
    }
    if (!f->L) {
        st = cc_fail(cc);
        goto out;
    }
    /* Natural order: L->Perm is the identity, but compose it anyway. */
    for (sslong a = 0; a < rows; a++) {
        const sslong *LP = f->L->Perm;
        f->lperm[a] = f->perm[LP ? LP[a] : a];
    }
    st = BRAUN_OK;
out:
    if (L0) cholmod_l_free_factor(&L0, cc);
    if (G0) cholmod_l_free_sparse(&G0, cc);
    blist_free(&bl);
    return st;
}

static int ss_create(void **state, const braun_model *model)
{
    if (!state) return BRAUN_ERR_ARGUMENT;
    *state = NULL;
    if (!model) return BRAUN_ERR_ARGUMENT;
    const braun_system *sys = &model->sys;
    const braun_sparsity *sp = sys->sparsity;
    if (!sp) return BRAUN_ERR_ARGUMENT;
    const int n = sys->n, m = sys->m, p = sys->p;
    if (n <= 0 || m < 0 || p < 0 || n > BRAUN_MAX_SPARSE || m > BRAUN_MAX_SPARSE ||
        p > BRAUN_MAX_SPARSE)
        return BRAUN_ERR_SIZE;
    const int rows = m + p;
    if (!sp->row_ptr || (rows > 0 && !sp->col) || !sp->block || sp->nblocks <= 0)
        return BRAUN_ERR_ARGUMENT;
    /* Blocks must tile the diagonal. */
    long sum = 0;
    for (int b = 0; b < sp->nblocks; b++) {
        if (sp->block[b] <= 0) return BRAUN_ERR_SIZE;
        sum += sp->block[b];
        if (sum > n) return BRAUN_ERR_SIZE;
    }
    if (sum != n) return BRAUN_ERR_SIZE;
    /* Pattern: row pointers from 0, nondecreasing; columns in range and
     * increasing within a row. */
    if (sp->row_ptr[0] != 0) return BRAUN_ERR_ARGUMENT;
    for (int i = 0; i < rows; i++) {
        if (sp->row_ptr[i + 1] < sp->row_ptr[i]) return BRAUN_ERR_ARGUMENT;
        for (int k = sp->row_ptr[i]; k < sp->row_ptr[i + 1]; k++)
            if (sp->col[k] < 0 || sp->col[k] >= n ||
                (k > sp->row_ptr[i] && sp->col[k] <= sp->col[k - 1]))
                return BRAUN_ERR_ARGUMENT;
    }

    ss_state *s = calloc(1, sizeof *s);
    if (!s) return BRAUN_ERR_BUFFER;
    int st = BRAUN_ERR_BUFFER;
    int *blk_of = NULL;
    s->n = n;
    s->m = m;
    s->p = p;
    s->rows = rows;
    s->nblocks = sp->nblocks;
    s->arow = sp->row_ptr;

    const int nb = sp->nblocks;
    s->bsize = xcalloc((size_t)nb, sizeof *s->bsize);
    s->bstart = xcalloc((size_t)nb, sizeof *s->bstart);
    s->boff = xcalloc((size_t)nb + 1, sizeof *s->boff);
    blk_of = xcalloc((size_t)n, sizeof *blk_of);
    if (!s->bsize || !s->bstart || !s->boff || !blk_of) goto fail;
    for (int b = 0, c0 = 0; b < nb; b++) {
        s->bsize[b] = sp->block[b];
        s->bstart[b] = c0;
        s->boff[b + 1] = s->boff[b] + (size_t)sp->block[b] * (size_t)sp->block[b];
        for (int j = 0; j < sp->block[b]; j++) blk_of[c0 + j] = b;
        c0 += sp->block[b];
    }
    s->Rb = xcalloc(s->boff[nb], sizeof *s->Rb);
    if (!s->Rb) goto fail;

    /* C pattern: each row's blocks (increasing, as its columns are) expanded
     * to whole blocks. */
    sslong nseg = 0, nnzC = 0;
    for (int i = 0; i < rows; i++) {
        int last = -1;
        for (int k = sp->row_ptr[i]; k < sp->row_ptr[i + 1]; k++) {
            int b = blk_of[sp->col[k]];
            if (b != last) {
                nseg++;
                nnzC += s->bsize[b];
                last = b;
            }
        }
    }
    s->cp = xcalloc((size_t)rows + 1, sizeof *s->cp);
    s->ci = xcalloc((size_t)nnzC, sizeof *s->ci);
    s->a2c = xcalloc((size_t)sp->row_ptr[rows], sizeof *s->a2c);
    s->sptr = xcalloc((size_t)rows + 1, sizeof *s->sptr);
    s->sblk = xcalloc((size_t)nseg, sizeof *s->sblk);
    s->spos = xcalloc((size_t)nseg, sizeof *s->spos);
    s->scol = xcalloc((size_t)nseg, sizeof *s->scol);
    s->slen = xcalloc((size_t)nseg, sizeof *s->slen);
    if (!s->cp || !s->ci || !s->a2c || !s->sptr || !s->sblk || !s->spos || !s->scol || !s->slen)
        goto fail;
    {
        sslong g = 0, pos = 0;
        for (int i = 0; i < rows; i++) {
            s->cp[i] = pos;
            s->sptr[i] = g;
            int last = -1;
            for (int k = sp->row_ptr[i]; k < sp->row_ptr[i + 1]; k++) {
                int b = blk_of[sp->col[k]];
                if (b != last) {
                    s->sblk[g] = b;
                    s->spos[g] = pos;
                    s->scol[g] = s->bstart[b];
                    s->slen[g] = s->bsize[b];
                    for (int j = 0; j < s->bsize[b]; j++) s->ci[pos + j] = s->bstart[b] + j;
                    pos += s->bsize[b];
                    g++;
                    last = b;
                }
                s->a2c[k] = s->spos[g - 1] + (sp->col[k] - s->bstart[b]);
            }
        }
        s->cp[rows] = pos;
        s->sptr[rows] = g;
    }

    s->wr = xcalloc((size_t)rows, sizeof *s->wr);
    s->wr2 = xcalloc((size_t)rows, sizeof *s->wr2);
    s->wr3 = xcalloc((size_t)rows, sizeof *s->wr3);
    s->wn = xcalloc((size_t)n, sizeof *s->wn);
    s->wn2 = xcalloc((size_t)n, sizeof *s->wn2);
    s->wn3 = xcalloc((size_t)n, sizeof *s->wn3);
    s->wr4 = xcalloc((size_t)rows, sizeof *s->wr4);
    s->wr5 = xcalloc((size_t)rows, sizeof *s->wr5);
    s->wr6 = xcalloc((size_t)rows, sizeof *s->wr6);
    s->wr7 = xcalloc((size_t)rows, sizeof *s->wr7);
    s->wr8 = xcalloc((size_t)rows, sizeof *s->wr8);
    s->wr9 = xcalloc((size_t)rows, sizeof *s->wr9);
    s->wr10 = xcalloc((size_t)rows, sizeof *s->wr10);
    s->wn4 = xcalloc((size_t)n, sizeof *s->wn4);
    s->wn5 = xcalloc((size_t)n, sizeof *s->wn5);
    s->wn6 = xcalloc((size_t)n, sizeof *s->wn6);
    s->wn7 = xcalloc((size_t)n, sizeof *s->wn7);
    if (!s->wr || !s->wr2 || !s->wr3 || !s->wr4 || !s->wr5 || !s->wr6 || !s->wr7 || !s->wr8 ||
        !s->wr9 || !s->wr10 || !s->wn || !s->wn2 || !s->wn3 || !s->wn4 || !s->wn5 || !s->wn6 ||
        !s->wn7)
        goto fail;

    if (!cholmod_l_start(&s->cc)) goto fail;
    s->cc_started = 1;
    s->cc.print = 0; /* no messages on stdout: statuses are returned */
    /* Simplicial factors of exactly their column counts (no room to grow
     * for updates, which this backend never makes): less memory for the
     * solves to stream. */
    s->cc.grow2 = 0;

    if (rows > 0 && (st = slot_build(s, &s->s[0], rows)) != BRAUN_OK) goto fail;
    if (m > 0 && p > 0 && (st = slot_build(s, &s->s[1], m)) != BRAUN_OK) goto fail;
    free(blk_of);
    *state = s;
    return BRAUN_OK;
fail:
    free(blk_of);
    ss_destroy(s);
    return st;
}

/* ------------------------------------------------------------------ */
/* M = R^T R, blockwise                                                */
/* ------------------------------------------------------------------ */
static int ss_factor_mass(void *state, const braun_real *M, braun_real sym_tol, int *bad_i,
                          int *bad_j, braun_real *bad_value)
{
    ss_state *s = state;
    /* Symmetry first, for all blocks (as braun_chol_factor: a non-symmetric
     * M is a modelling bug, reported before any pivot; each pair against
     * its own diagonal entries). */
    for (int b = 0; b < s->nblocks; b++) {
        const int bs = s->bsize[b];
        const braun_real *Mb = M + s->boff[b];
        for (int i = 0; i < bs; i++)
            for (int j = i + 1; j < bs; j++) {
                double asym = fabs((double)Mb[i * bs + j] - (double)Mb[j * bs + i]);
                if (asym * asym > (double)sym_tol * (double)sym_tol *
                                      fabs((double)Mb[i * bs + i] * (double)Mb[j * bs + j])) {
                    if (bad_i) *bad_i = s->bstart[b] + i;
                    if (bad_j) *bad_j = s->bstart[b] + j;
                    if (bad_value) *bad_value = (braun_real)asym;
                    return BRAUN_ERR_MASS_NOT_SYMMETRIC;
                }
            }
    }
    const double n_eps = (double)s->n * (double)BRAUN_EPS;
    for (int b = 0; b < s->nblocks; b++) {
        const int bs = s->bsize[b];
        const braun_real *Mb = M + s->boff[b];
        double *R = s->Rb + s->boff[b];
        for (int i = 0; i < bs; i++) {
            double d = (double)Mb[i * bs + i];
            for (int k = 0; k < i; k++) d -= R[k * bs + i] * R[k * bs + i];
            /* Pivot at round-off level of its own diagonal entry: singular
             * to working precision (also catches NaN); braun_chol_factor's
             * rule n·ε·|M_ii|, which no change of a coordinate's unit
             * changes. */
            if (!(d > n_eps * fabs((double)Mb[i * bs + i]))) {
                if (bad_i) *bad_i = s->bstart[b] + i;
                if (bad_j) *bad_j = s->bstart[b] + i;
                if (bad_value) *bad_value = (braun_real)d;
                return BRAUN_ERR_MASS_NOT_SPD;
            }
            double rii = sqrt(d);
            R[i * bs + i] = rii;
            for (int j = i + 1; j < bs; j++) {
                double t = (double)Mb[i * bs + j];
                for (int k = 0; k < i; k++) t -= R[k * bs + i] * R[k * bs + j];
                R[i * bs + j] = t / rii;
            }
            for (int j = 0; j < i; j++) R[i * bs + j] = 0;
        }
    }
    s->r_diag = 1;
    for (int b = 0; b < s->nblocks && s->r_diag; b++) {
        const int bs = s->bsize[b];
        const double *R = s->Rb + s->boff[b];
        for (int i = 0; i < bs; i++)
            for (int j = i + 1; j < bs; j++)
                if (R[i * bs + j] != 0) s->r_diag = 0;
    }
    return BRAUN_OK;
}

static void ss_solve_rt(void *state, const braun_real *b, braun_real *x)
{
    const ss_state *s = state;
    for (int blk = 0; blk < s->nblocks; blk++) {
        const int bs = s->bsize[blk], c0 = s->bstart[blk];
        const double *R = s->Rb + s->boff[blk];
        for (int i = 0; i < bs; i++) {
            double t = (double)b[c0 + i];
            for (int k = 0; k < i; k++) t -= R[k * bs + i] * (double)x[c0 + k];
            x[c0 + i] = (braun_real)(t / R[i * bs + i]);
        }
    }
}

static void ss_solve_r(void *state, const braun_real *b, braun_real *x)
{
    const ss_state *s = state;
    for (int blk = 0; blk < s->nblocks; blk++) {
        const int bs = s->bsize[blk], c0 = s->bstart[blk];
        const double *R = s->Rb + s->boff[blk];
        for (int i = bs - 1; i >= 0; i--) {
            double t = (double)b[c0 + i];
            for (int k = i + 1; k < bs; k++) t -= R[i * bs + k] * (double)x[c0 + k];
            x[c0 + i] = (braun_real)(t / R[i * bs + i]);
        }
    }
}

static void ss_mul_r(void *state, const braun_real *x, braun_real *y)
{
    const ss_state *s = state;
    for (int blk = 0; blk < s->nblocks; blk++) {
        const int bs = s->bsize[blk], c0 = s->bstart[blk];
        const double *R = s->Rb + s->boff[blk];
        for (int i = 0; i < bs; i++) {
            double t = 0;
            for (int k = i; k < bs; k++) t += R[i * bs + k] * (double)x[c0 + k];
            y[c0 + i] = (braun_real)t;
        }
    }
}

/* ------------------------------------------------------------------ */
/* factor_c                                                            */
/* ------------------------------------------------------------------ */
static int g_solve(ss_state *s, ss_slot *f, const double *b, double *out);
static void g_solve2(ss_slot *f, const double *b1, const double *b2, double *out1, double *out2);

/* The probe of an accepted Cholesky (see above): y = G^-1 x for a fixed
 * pseudo-random x in [-1, 1)^rows gives sqrt(|x|/|y|) >= sigma_min(C) (up to
 * the rounding of the solve), so sqrt(|x|/|y|) < lim·cmax <= lim·sigma_max
 * proves cond(C) > 1/lim whatever the L diagonal says. 1: accepted, 0: G
 * rejected, < 0: error. */
static int chol_probe(ss_state *s, ss_slot *f, double lim)
{
    const int rows = f->rows;
    double *x = s->wr3, *y = s->wr2;
    unsigned long long u = 0x2545f4914f6cdd1dULL;
    for (int i = 0; i < rows; i++) {
        u = u * 6364136223846793005ULL + 1442695040888963407ULL;
        x[i] = f->dep_row[i] ? 0 : (double)(u >> 11) * 0x1p-52 - 1.0; /* kept rows only */
    }
    if (f->rc_src && f->own_solve) {
        for (int i = 0; i < rows; i++) f->rc[i] = (double)f->rc_src[i]; /* as ss_lsq */
        g_solve2(f, x, f->rc, y, f->yc); /* and r_v's, for the pinv */
        f->yc_ok = 1;
    } else if (g_solve(s, f, x, y)) {
        return cc_fail(&s->cc);
    }
    const double nx = nrm2(rows, x), ny = nrm2(rows, y);
    if (!(ny <= DBL_MAX)) return 0; /* overflow: singular to working precision */
    return ny > 0 && sqrt(nx / ny) >= lim * f->cmax ? 1 : 0;
}

/* A dependency probe's start: the next fixed w of +-1 on the rows set
 * aside (u: the generator's state), v = C_D^T w and y = C_B v, for the
 * solve y := G_BB^-1 y. */
static void probe_start(ss_state *s, ss_slot *f, unsigned long long *u, double *w, double *v,
                        double *y)
{
    memset(w, 0, (size_t)f->rows * sizeof *w);
    for (int k = 0; k < f->ndep; k++) {
        *u = *u * 6364136223846793005ULL + 1442695040888963407ULL;
        w[f->dlist[k]] = (*u >> 63) ? 1.0 : -1.0;
    }
    memset(v, 0, (size_t)s->n * sizeof *v);
    ct_mul_add(s, f, w, v); /* v = C_D^T w */
    c_mul(s, f, v, NULL, y, NULL);
    for (int k = 0; k < f->ndep; k++) y[f->dlist[k]] = 0; /* C_B v */
}

/* The dependency probe of the rows set aside (see above): for DEP_PROBES
 * fixed vectors w of +-1 on them, v = C_D^T w less its projection on the
 * row space of the kept rows, C_B^T G_BB^-1 C_B v, is C^T k for the left
 * null vector k = [-W^T w; w] of the rows' exact dependence; its mean
 * square estimates ||C^T K||_F^2 >= sigma_(k+1)^2. The error of a solve
 * with G_BB lies in that row space, orthogonal to the exact difference, so
 * it can only enlarge the estimate: it is refined (as null_project
 * refines) only when it fails. Accepted (1) when it is at most
 * (DEP_MARGIN·thr)^2; 0: rejected, < 0: error. */
static int dep_probe(ss_state *s, ss_slot *f, double thr)
{
    const int rows = f->rows, n = s->n;
    double *w = s->wr4, *y = s->wr5, *v = s->wn4;
    const double lim = DEP_MARGIN * thr, lim2 = lim * lim;
    unsigned long long u = DEP_SEED;
    double sum = 0;
    /* With two probes, both first solves in one walk of L (g_solve2, the
     * same results as one solve each): probe 1 starts from v1, y1. */
    const int pair = DEP_PROBES == 2 && f->own_solve;
    double *y1 = s->wr6, *v1 = s->wn5;
    if (pair) {
        probe_start(s, f, &u, w, v, y);
        probe_start(s, f, &u, w, v1, y1);
        g_solve2(f, y, y1, y, y1);
    }
    for (int probe = 0; probe < DEP_PROBES; probe++) {
        if (pair && probe == 1) {
            v = v1;
            y = y1;
        } else if (!pair) {
            probe_start(s, f, &u, w, v, y);
            if (g_solve(s, f, y, y)) return cc_fail(&s->cc);
        }
        double nv2 = 0;
        for (int it = 0; it <= REFINE_MAX; it++) {
            if (it > 0) {
                c_mul(s, f, v, NULL, y, NULL);
                for (int k = 0; k < f->ndep; k++) y[f->dlist[k]] = 0; /* C_B v */
                if (g_solve(s, f, y, y)) return cc_fail(&s->cc);
            }
            if (probe == 0 && it == 0) { /* W^T w */
                memcpy(f->wtw, y, (size_t)rows * sizeof *y);
                f->wtw_ok = 1;
            }
            for (int i = 0; i < rows; i++) y[i] = -y[i];
            ct_mul_add(s, f, y, v);
            const double nv = nrm2(n, v);
            if (!(nv <= DBL_MAX)) return 0;
            nv2 = nv * nv;
            if ((sum + nv2) / DEP_PROBES <= lim2) break;
        }
        sum += nv2;
        if (sum / DEP_PROBES > lim2) break;
    }
    return sum / DEP_PROBES <= lim2 ? 1 : 0;
}

/* No rows set aside. */
static void dep_clear(ss_slot *f)
{
    for (int k = 0; k < f->ndep; k++) f->dep_row[f->dlist[k]] = 0;
    memset(f->dep, 0, (size_t)f->rows * sizeof *f->dep);
    f->ndep = 0;
}

/* ldl_numeric's record of the pivots (piv_hit, piv_min, piv_max,
 * piv_lbig, acc), read from a factor CHOLMOD computed: the number of
 * pivots replaced, or -1 for a negative pivot beyond round-off. */
static int piv_scan(ss_slot *f, double dbound, double *acc)
{
    const cholmod_factor *L = f->L;
    const sslong *Lp = L->p, *Li = L->i, *Lnz = L->nz;
    const double *Lx = L->x;
    double dmin = DBL_MAX, dmax = 0;
    int nd = 0;
    f->piv_lbig = 0;
    for (int a = 0; a < f->rows; a++) {
        const double d = Lx[Lp[a]];
        if (fabs(d) <= dbound) {
            if (nd == 0) memset(acc, 0, (size_t)f->rows * sizeof *acc);
            f->piv_hit[nd++] = a;
            for (sslong q = Lp[a] + 1; q < Lp[a] + Lnz[a]; q++) {
                const double l = Lx[q];
                if (!(fabs(l) <= DEP_LMAX)) f->piv_lbig = 1;
                acc[Li[q]] += l * l * dbound;
            }
        } else if (!(d > 0)) {
            return -1; /* a negative pivot beyond round-off: not this path */
        } else {
            if (d < dmin) dmin = d;
            if (d > dmax) dmax = d;
        }
    }
    f->piv_min = dmin;
    f->piv_max = dmax;
    return nd;
}

/* An LDL^T of G whose pivots at most dbound CHOLMOD replaced: those rows
 * (D) are set aside, and the rank is k = rows - |D| when (see above) the
 * rank rule's cap allows k, the kept rows' pivots pass the tests of a
 * full-rank G (positive, ratio at least lim, the probe), and the rows set
 * aside pass the dependency probe at the threshold of direction k + 1. 1:
 * accepted, 0: rejected, < 0: error. */
static int chol_dep(ss_state *s, ss_slot *f, double tol, double dbound, int hits)
{
    const int rows = f->rows;
    /* The record of the pivots: ldl_numeric's, or read from CHOLMOD's L. */
    int nd = f->piv_ok ? hits : piv_scan(f, dbound, s->wr6);
    for (int k = 0; k < nd; k++) {
        const int a = f->piv_hit[k];
        f->dep[a] = 1;
        f->dep_row[f->lperm[a]] = 1;
    }
    const double dmin = f->piv_min, dmax = f->piv_max;
    /* The columns of L at the replaced pivots: entries at most DEP_LMAX
     * (so that G_BB = L_BB D_BB L_BB^T up to dbound·DEP_LMAX^2 per entry),
     * and the bound on the squared distance of each row set aside from the
     * kept rows before it: dbound, plus what the columns of earlier rows
     * set aside took from its pivot (acc), plus DEP_PIVOT_ERR·eps·cmax^2. */
    if (nd > 0 && f->piv_lbig) nd = -1;
    double pbound = 0;
    for (int k = 0; k < nd; k++)
        pbound += dbound + s->wr6[f->piv_hit[k]] + DEP_PIVOT_ERR * DBL_EPSILON * f->cmax * f->cmax;
    if (nd > 0) {
        int k = 0;
        for (int i = 0; i < rows; i++)
            if (f->dep_row[i]) f->dlist[k++] = i;
    }
    f->ndep = nd > 0 ? nd : 0;
    f->wtw_ok = 0;
    const int rank = rows - f->ndep;
    int st = 0;
    if (nd > 0 && rank > 0 && rank <= f->rule_cap) {
        /* The kept rows: as a full-rank G, with tol_new when the rule's
         * keep is below their number. */
        double lim = tol > CHOL_RATIO_MIN ? tol : CHOL_RATIO_MIN;
        if (f->rule_keep < rank && f->rule_tol_new > lim) lim = f->rule_tol_new;
        const double ratio = sqrt(dmin / dmax);
        st = ratio >= lim;
        if (st == 1 && ratio < CHOL_PROBE_RATIO) st = chol_probe(s, f, lim);
        /* The rows set aside: direction k + 1 counts past tol, and past
         * tol_new too beyond the rule's keep; the pivots' bound decides
         * when it is far enough below, else the probe. */
        if (st == 1) {
            double thr = tol;
            if (f->rule_keep <= rank && f->rule_tol_new > thr) thr = f->rule_tol_new;
            const double lim2 = DEP_MARGIN * thr * f->cmax;
            if (!(pbound <= lim2 * lim2)) st = dep_probe(s, f, thr * f->cmax);
        }
    }
    if (st != 1) {
        /* (dlist may not be set: clear everything) */
        for (int a = 0; a < rows; a++) f->dep[a] = f->dep_row[a] = 0;
        f->ndep = 0;
    }
    return st;
}

/* One entry of G = C C^T from its products in the map. */
static inline double g_entry(const double *Cx, const uint32_t *gmap, uint32_t t0, uint32_t t1)
{
    double g = 0;
    for (uint32_t t = t0; t < t1; t++) {
        const uint32_t *m = gmap + 3 * (size_t)t;
        const double *ci = Cx + m[0], *cj = Cx + m[1];
        if (m[2] == 3) { /* planar bodies */
            g += ci[0] * cj[0] + ci[1] * cj[1] + ci[2] * cj[2];
        } else {
            for (uint32_t k = 0; k < m[2]; k++) g += ci[k] * cj[k];
        }
    }
    return g;
}

/* L's pattern in 32 bits (li, lbeg, lend). 1: built, 0: positions beyond
 * int (the solves then go through CHOLMOD), < 0: out of memory. */
static int l32_build(ss_slot *f)
{
    const cholmod_factor *L = f->L;
    const sslong n = (sslong)L->n, *Lp = L->p, *Li = L->i, *Lnz = L->nz;
    free(f->li), free(f->lbeg), free(f->lend);
    f->li = f->lbeg = f->lend = NULL;
    sslong top = 0;
    for (sslong j = 0; j < n; j++)
        if (Lp[j] + Lnz[j] > top) top = Lp[j] + Lnz[j];
    if (n > INT_MAX || top > INT_MAX) return 0;
    f->li = xcalloc((size_t)(top > 0 ? top : 1), sizeof *f->li);
    f->lbeg = xcalloc((size_t)n, sizeof *f->lbeg);
    f->lend = xcalloc((size_t)n, sizeof *f->lend);
    if (!f->li || !f->lbeg || !f->lend) return BRAUN_ERR_BUFFER;
    for (sslong j = 0; j < n; j++) {
        f->lbeg[j] = (int)Lp[j];
        f->lend[j] = (int)(Lp[j] + Lnz[j]);
        for (sslong q = Lp[j]; q < Lp[j] + Lnz[j]; q++) f->li[q] = (int)Li[q];
    }
    return 1;
}

/* The structures of ldl_numeric for the simplicial LDL^T that CHOLMOD
 * just computed (columns sorted, diagonal first: checked). 1: built, 0:
 * this factor is not of that form, < 0: out of memory. */
static int ldl_build(ss_slot *f)
{
    const cholmod_factor *L = f->L;
    const sslong n = (sslong)L->n, *Lp = L->p, *Li = L->i, *Lnz = L->nz;
    const cholmod_sparse *G = f->G;
    const sslong *Gp = G->p, *Gi = G->i;
    free(f->lr_p), free(f->lr_k), free(f->lr_q), free(f->gl_p), free(f->gl_i), free(f->gl_e);
    free(f->lw);
    f->lr_p = f->lr_k = f->lr_q = f->gl_p = f->gl_i = f->gl_e = NULL;
    f->lw = NULL;
    for (sslong k = 0; k < n; k++)
        for (sslong q = Lp[k] + 1; q < Lp[k] + Lnz[k]; q++)
            if (Li[q] <= Li[q - 1]) return 0;
    const sslong nl = Lp[n] - n, ng = Gp[n];
    f->lr_p = xcalloc((size_t)n + 1, sizeof *f->lr_p);
    f->lr_k = xcalloc((size_t)(nl > 0 ? nl : 1), sizeof *f->lr_k);
    f->lr_q = xcalloc((size_t)(nl > 0 ? nl : 1), sizeof *f->lr_q);
    f->gl_p = xcalloc((size_t)n + 1, sizeof *f->gl_p);
    f->gl_i = xcalloc((size_t)ng, sizeof *f->gl_i);
    f->gl_e = xcalloc((size_t)ng, sizeof *f->gl_e);
    f->lw = xcalloc((size_t)n, sizeof *f->lw);
    if (!f->lr_p || !f->lr_k || !f->lr_q || !f->gl_p || !f->gl_i || !f->gl_e || !f->lw)
        return BRAUN_ERR_BUFFER;
    /* rows of L, by counting */
    for (sslong k = 0; k < n; k++)
        for (sslong q = Lp[k] + 1; q < Lp[k] + Lnz[k]; q++) f->lr_p[Li[q] + 1]++;
    for (sslong i = 0; i < n; i++) f->lr_p[i + 1] += f->lr_p[i];
    int *next = f->gl_p; /* as a cursor first */
    for (sslong i = 0; i < n; i++) next[i] = f->lr_p[i];
    for (sslong k = 0; k < n; k++)
        for (sslong q = Lp[k] + 1; q < Lp[k] + Lnz[k]; q++) {
            const int at = next[Li[q]]++;
            f->lr_k[at] = (int)k;
            f->lr_q[at] = (int)q;
        }
    /* lower G: upper entry (a, c), a <= c, is entry (c, a) of column a */
    memset(f->gl_p, 0, ((size_t)n + 1) * sizeof *f->gl_p);
    for (sslong c = 0; c < n; c++)
        for (sslong e = Gp[c]; e < Gp[c + 1]; e++) f->gl_p[Gi[e] + 1]++;
    for (sslong a = 0; a < n; a++) f->gl_p[a + 1] += f->gl_p[a];
    int *cur = xcalloc((size_t)n, sizeof *cur);
    if (!cur) return BRAUN_ERR_BUFFER;
    for (sslong a = 0; a < n; a++) cur[a] = f->gl_p[a];
    for (sslong c = 0; c < n; c++)
        for (sslong e = Gp[c]; e < Gp[c + 1]; e++) {
            const int at = cur[Gi[e]]++;
            f->gl_i[at] = (int)c;
            f->gl_e[at] = (int)e;
        }
    free(cur);
    if (!f->map_by_col) {
        /* The product map in the order of that walk (entry t of the lower
         * columns is G entry gl_e[t]): ldl_numeric reads it front to back. */
        uint32_t *np = xcalloc((size_t)ng + 1, sizeof *np);
        uint32_t *nm = xcalloc(3 * (size_t)f->gptr[ng] + 1, sizeof *nm);
        int *me = xcalloc((size_t)ng + 1, sizeof *me);
        if (!np || !nm || !me) {
            free(np), free(nm), free(me);
            return BRAUN_ERR_BUFFER;
        }
        uint32_t q = 0;
        for (sslong t = 0; t < ng; t++) {
            const sslong e = f->gl_e[t];
            me[t] = (int)e;
            for (uint32_t u = f->gptr[e]; u < f->gptr[e + 1]; u++, q++)
                for (int k = 0; k < 3; k++) nm[3 * (size_t)q + k] = f->gmap[3 * (size_t)u + k];
            np[t + 1] = q;
        }
        free(f->gptr), free(f->gmap);
        f->gptr = np;
        f->gmap = nm;
        f->map_e = me;
        f->map_by_col = 1;
    }
    return 1;
}

/* L D L^T = G numerically on the pattern CHOLMOD found (left-looking:
 * column j gathers G's column j, takes the updates of the columns k of
 * row j, then divides by its pivot), pivots of magnitude at most dbound
 * replaced by +-dbound as CHOLMOD's Common->dbound does; about twice as
 * fast as cholmod_l_factorize's row-oriented LDL^T on the ladder (measured
 * 0.73 against 1.42 ms at 12 000 rows). Returns the pivots replaced, or -1
 * for NaN; *neg: the pivots below -dbound (G is positive semidefinite:
 * such a factorization is refused). */
static long ldl_numeric(ss_slot *f, double dbound, long *neg, double *acc)
{
    cholmod_factor *L = f->L;
    const int n = (int)L->n, *Lb = f->lbeg, *Le = f->lend, *Li = f->li;
    double *Lx = L->x, *x = f->lw;
    const double *Gx = f->G->x;
    const int *lr_p = f->lr_p, *lr_k = f->lr_k, *lr_q = f->lr_q;
    long hits = 0;
    double dmin = DBL_MAX, dmax = 0;
    *neg = 0;
    f->piv_ok = 0;
    f->piv_lbig = 0;
    const uint32_t *gptr = f->gptr, *gmap = f->gmap;
    for (int j = 0; j < n; j++) {
        if (f->map_by_col) {
            for (int t = f->gl_p[j]; t < f->gl_p[j + 1]; t++)
                x[f->gl_i[t]] = g_entry(f->Cx, gmap, gptr[t], gptr[t + 1]);
        } else {
            for (int t = f->gl_p[j]; t < f->gl_p[j + 1]; t++) x[f->gl_i[t]] = Gx[f->gl_e[t]];
        }
        for (int t = lr_p[j]; t < lr_p[j + 1]; t++) {
            const int k = lr_k[t], qj = lr_q[t], qend = Le[k];
            const double lkj = Lx[qj] * Lx[Lb[k]]; /* L_jk D_k */
            for (int q = qj; q < qend; q++) x[Li[q]] -= Lx[q] * lkj;
        }
        double d = x[j];
        if (d != d) return -1;
        if (!(fabs(d) > dbound)) {
            d = d < 0 ? -dbound : dbound;
            f->piv_hit[hits++] = j;
        } else if (d < 0) {
            ++*neg;
        } else {
            if (d < dmin) dmin = d;
            if (d > dmax) dmax = d;
        }
        Lx[Lb[j]] = d;
        x[j] = 0;
        for (int q = Lb[j] + 1; q < Le[j]; q++) {
            Lx[q] = x[Li[q]] / d;
            x[Li[q]] = 0;
        }
        if (hits > 0 && f->piv_hit[hits - 1] == j) {
            /* chol_dep's checks of a replaced pivot's column, while it is
             * at hand: entries at most DEP_LMAX, and what they take from
             * the later pivots (acc, in chol_dep's order). */
            if (hits == 1) memset(acc, 0, (size_t)n * sizeof *acc);
            for (int q = Lb[j] + 1; q < Le[j]; q++) {
                const double l = Lx[q];
                if (!(fabs(l) <= DEP_LMAX)) f->piv_lbig = 1;
                acc[Li[q]] += l * l * dbound;
            }
        }
    }
    f->piv_min = dmin;
    f->piv_max = dmax;
    f->piv_ok = 1;
    return hits;
}

/* G = C C^T from the product map, then its LDL^T (ldl_numeric's; at the
 * first factorization of a layout of L CHOLMOD's first, which ldl_numeric
 * then repeats when it can factor that layout) with the pivots of
 * dependent rows replaced (simplicial factors only). 1: accepted (full
 * rank, or rank rows - ndep with the rows set aside), 0: rank deficient or
 * ill-conditioned otherwise, < 0: error. */
static int chol_try(ss_state *s, ss_slot *f, double tol)
{
    cholmod_common *cc = &s->cc;
    double *Gx = f->G->x;
    const sslong nnzG = (sslong)f->G->nzmax;
    const double *Cx = f->Cx;
    const uint32_t *gptr = f->gptr, *gmap = f->gmap;
    const cholmod_factor *L = f->L;
    int own = f->own_fact && L->i == f->own_i && L->nzmax == f->own_nzmax;
    if (!f->map_by_col) {
        for (sslong e = 0; e < nnzG; e++) Gx[e] = g_entry(Cx, gmap, gptr[e], gptr[e + 1]);
    } else if (!own) { /* (ldl_numeric forms them itself) */
        for (sslong t = 0; t < nnzG; t++) Gx[f->map_e[t]] = g_entry(Cx, gmap, gptr[t], gptr[t + 1]);
    }
    dep_clear(f);
    /* max_i G_ii = cmax^2 */
    const double dbound = CHOL_DBOUND * f->cmax * f->cmax;
    long hits = 0;
    if (!own) {
        f->piv_ok = 0;
        cc->dbound = f->L->is_super ? 0 : dbound;
        cc->ndbounds_hit = 0;
        int ok = cholmod_l_factorize(f->G, f->L, cc);
        cc->dbound = 0;
        if (cc->status == CHOLMOD_NOT_POSDEF) return 0;
        if (!ok || cc->status < CHOLMOD_OK) return cc_fail(cc);
        hits = cc->ndbounds_hit > 0;
        /* Solve with a simplicial L here (cholmod_l_solve2 reallocates its
         * workspace at every call for one right-hand side); CHOLMOD keeps
         * the diagonal first in each column: checked once for each layout
         * of L, as are the structures of ldl_numeric, which factors it
         * from then on (LDL^T only). */
        f->own_solve = !L->is_super && L->xtype == CHOLMOD_REAL &&
                       L->dtype == CHOLMOD_DOUBLE && L->p && L->i && L->nz && L->x;
        if (f->own_solve && (L->i != f->own_i || L->nzmax != f->own_nzmax)) {
            const sslong *Lp = L->p, *Li = L->i, *Lnz = L->nz;
            for (sslong j = 0; j < (sslong)L->n && f->own_solve; j++)
                f->own_solve = Lnz[j] > 0 && Li[Lp[j]] == j;
            if (f->own_solve) {
                const int b = l32_build(f);
                if (b < 0) return b;
                f->own_solve = b;
            }
            f->own_fact = 0;
            if (f->own_solve && !L->is_ll) {
                const int b = ldl_build(f);
                if (b < 0) return b;
                f->own_fact = b;
            }
            f->own_i = f->own_solve ? L->i : NULL;
            f->own_nzmax = L->nzmax;
        }
        /* A layout that ldl_numeric factors from now on is factored by it
         * already now, from the same G (the reordered map forms each G_ij
         * with the same sums): CHOLMOD's factorization only gave the
         * pattern, so the first factorization of a run after
         * braun_data_init rounds as every later one does, and a run
         * repeated after braun_set_state reproduces the first bit for bit. */
        own = f->own_fact && L->i == f->own_i && L->nzmax == f->own_nzmax;
    }
    if (own) {
        long neg;
        hits = ldl_numeric(f, dbound, &neg, s->wr6);
        if (hits < 0) return BRAUN_ERR_NONFINITE;
        if (neg > 0) return 0;
    }
    if (hits > 0) {
        /* Pivots replaced: only an LDL^T solved here can set their rows
         * aside. */
        if (!f->own_solve || L->is_ll) return 0;
        const int st = chol_dep(s, f, tol, dbound, (int)hits);
        if (st == 0) f->dep_rejected = 1;
        return st;
    }
    if (f->rule_cap < f->rows) return 0;
    /* (cholmod_l_rcond of an LDL^T: min/max |D|, all positive here) */
    double rc = f->piv_ok ? f->piv_min / f->piv_max : cholmod_l_rcond(f->L, cc);
    if (rc < 0) return cc_fail(cc);
    /* The rank rule: a previous rank below rows (keep) asks for tol_new
     * too before every row counts again. */
    double lim = tol > CHOL_RATIO_MIN ? tol : CHOL_RATIO_MIN;
    if (f->rule_keep < f->rows && f->rule_tol_new > lim) lim = f->rule_tol_new;
    const double ratio = sqrt(rc);
    if (!(ratio >= lim)) return 0;
    if (ratio < CHOL_PROBE_RATIO) return chol_probe(s, f, lim);
    return 1;
}

/* The rank decision on the k live columns of SPQR's R (see above). For a
 * live column j, sig_j = 1/|R(0:j,0:j)^-1 e_j| = |R_jj| / sqrt(1 + |a|^2),
 * a = R(0:j-1,0:j-1)^-1 R(0:j-1,j), is an upper bound of the smallest
 * singular value of the rows of C that columns 0..j stand for, hence of C
 * (interlacing): sig_j <= tau = tol·cmax proves a dependence at the
 * caller's tolerance, however far above tau Heath's round-off left R_jj.
 * It is computed (one back substitution over columns 0..j) for the columns
 * with |R_jj| <= max(QR_CHECK_RATIO·cmax, tau_new), else sig_j = |R_jj|.
 * The rank is that of the independent columns (sig_j > tau), under the
 * rank rule at most max(keep, #{sig_j > tau_new}) of them, tau_new =
 * max(tol_new, tol)·cmax, and at most cap. When that is below k, the
 * first column (in R's order) that fails the test must go: returns 1 with
 * *tol2 just above its |R_jj| (SPQR's test is |R_jj| <= tol), and the
 * caller factors again. Only the first: once column j1 is a direction of
 * round-off, every later sig_j inherits 1/|R_j1j1| through a, so later
 * columns with ordinary pivots would fail too (the redundant ladder near
 * its singular configuration: a dependent column with |R_jj| = 1e-11 and
 * sig 3e-16, then two independent ones with |R_jj| 6e-4 and sig 7e-16).
 * The earlier columns are sound: the columns of R(0:j1-1,0:j1-1)^-1 are
 * those solutions, so its smallest singular value is at least
 * tau/sqrt(j1). Returns 0 when the rank stands. */
static int qr_decide(ss_state *s, ss_slot *f, sslong k, double tau, double *tol2)
{
    const cholmod_sparse *R = f->qr.R;
    const sslong *Rp = R->p;
    const double *Rx = R->x;
    double *w = s->wr5;
    const double tol_new = f->rule_tol_new * f->cmax;
    const double tau_new = tol_new > tau ? tol_new : tau;
    const double gate = QR_CHECK_RATIO * f->cmax > tau_new ? QR_CHECK_RATIO * f->cmax : tau_new;
    sslong ndep = 0, nstrong = 0, first_dep = -1, first_weak = -1, weakest = -1;
    double sig_min = DBL_MAX;
    for (sslong j = 0; j < k; j++) {
        const double d = fabs(Rx[Rp[j + 1] - 1]);
        double sj = d;
        if (d <= gate) {
            for (sslong i = 0; i < j; i++) w[i] = 0;
            w[j] = 1;
            r_solve(R, j + 1, w);
            const double nw = nrm2((int)(j + 1), w);
            sj = nw <= DBL_MAX ? 1.0 / nw : 0; /* Inf/NaN: singular */
            if (!(sj <= d)) sj = d;
        }
        if (sj <= tau) {
            ndep++;
            if (first_dep < 0) first_dep = j;
        } else if (sj > tau_new) {
            nstrong++;
        } else if (first_weak < 0) {
            first_weak = j;
        }
        if (sj < sig_min) sig_min = sj, weakest = j;
    }
    sslong target = k - ndep;
    if (f->rule_keep < target) {
        const sslong t = nstrong > f->rule_keep ? nstrong : f->rule_keep;
        if (t < target) target = t;
    }
    if (f->rule_cap < target) target = f->rule_cap > 0 ? f->rule_cap : 0;
    if (target >= k) return 0;
    /* A dependent column first, then one the rule excludes, then (the cap
     * alone) the weakest. */
    const sslong j1 = first_dep >= 0 ? first_dep : (first_weak >= 0 ? first_weak : weakest);
    const double d1 = fabs(Rx[Rp[j1 + 1] - 1]);
    *tol2 = (d1 > tau ? d1 : tau) * (1 + 1e-9);
    return 1;
}

/* SPQR of C^T and, when rank < rows, of S = [R11 R12]^T. Rank or < 0. */
static int qr_try(ss_state *s, ss_slot *f, double tol)
{
    cholmod_common *cc = &s->cc;
    cholmod_sparse Ct;
    memset(&Ct, 0, sizeof Ct);
    Ct.nrow = (size_t)s->n;
    Ct.ncol = (size_t)f->rows;
    Ct.nzmax = (size_t)s->cp[f->rows];
    Ct.p = s->cp;
    Ct.i = s->ci;
    Ct.x = f->Cx;
    Ct.stype = 0;
    Ct.itype = CHOLMOD_LONG;
    Ct.xtype = CHOLMOD_REAL;
    Ct.dtype = CHOLMOD_DOUBLE;
    Ct.sorted = 1;
    Ct.packed = 1;
    qr_free(&f->qr2, cc);
    const double tau = tol * f->cmax;
    sslong k = qr_factor(&f->qr, &Ct, tau, 0, cc);
    if (k < 0) return (int)k;
    /* The dependency test and the rank rule: re-factor with a larger
     * tolerance while they drop live columns. */
    double last = tau;
    int stalled = 0;
    for (int pass = 0; pass < QR_DROP_PASSES && k > 0; pass++) {
        double tol2 = 0;
        if (!qr_decide(s, f, k, tau, &tol2)) break;
        /* After a pass that dropped nothing (a later dependent column came
         * out live in place of the dropped one, its pivot round-off just
         * above the new tolerance), the tolerance grows faster. */
        if (stalled && tol2 < QR_DROP_GROW * last) tol2 = QR_DROP_GROW * last;
        if (tol2 <= last) tol2 = last * (1 + 1e-9);
        sslong k2 = qr_factor(&f->qr, &Ct, tol2, 0, cc);
        if (k2 < 0) return (int)k2;
        stalled = k2 >= k;
        k = k2;
        last = tol2;
    }
    f->qr_refine = 0;
    if (k == f->rows) {
        /* min/max |R_jj| >= 1/cond(C), as the Cholesky's L-diagonal ratio */
        const sslong *Rp = f->qr.R->p;
        const double *Rx = f->qr.R->x;
        double dmin = DBL_MAX, dmax = 0;
        for (sslong j = 0; j < k; j++) {
            const double d = fabs(Rx[Rp[j + 1] - 1]);
            if (d < dmin) dmin = d;
            if (d > dmax) dmax = d;
        }
        f->qr_refine = !(dmin >= QR_REFINE_RATIO * dmax);
    }
    if (k > 0 && k < f->rows) {
        cholmod_sparse *S = cholmod_l_transpose(f->qr.R, 1, cc); /* rows x k (R has k rows) */
        if (!S) return cc_fail(cc);
        if ((sslong)S->ncol != k) {
            cholmod_l_free_sparse(&S, cc);
            return BRAUN_ERR_NONFINITE;
        }
        sslong k2 = qr_factor(&f->qr2, S, SPQR_NO_TOL, k, cc);
        cholmod_l_free_sparse(&S, cc);
        if (k2 < 0) return (int)k2;
        if (k2 != k) return BRAUN_ERR_NONFINITE; /* S has full column rank */
    }
    return (int)k;
}

static int ss_factor_c(void *state, int slot, int rows, const braun_real *A, braun_real tol,
                       const braun_real *atil, braun_real *resid)
{
    ss_state *s = state;
    if (!s || slot < 0 || slot > 1) return BRAUN_ERR_ARGUMENT;
    ss_slot *f = &s->s[slot];
    const int expect = slot == 0 ? s->rows : (s->m > 0 && s->p > 0 ? s->m : -1);
    if (rows != expect || (rows > 0 && !A)) return BRAUN_ERR_ARGUMENT;
    f->path = PATH_NONE;
    f->rank = 0;
    f->pdiag_ok = 0;
    f->rc_src = NULL;
    f->yc_ok = 0;
    f->rhs_floor = 0;
    if (rows == 0) {
        f->path = PATH_ZERO;
        return 0;
    }
    if (form_c(s, f, A) != 0) return BRAUN_ERR_NONFINITE;
    if (atil && resid) {
        double *x = s->wn, *y = s->wr;
        for (int j = 0; j < s->n; j++) x[j] = (double)atil[j];
        c_mul(s, f, x, NULL, y, NULL);
        for (int i = 0; i < rows; i++) resid[i] = (braun_real)((double)resid[i] - y[i]);
    }
    if (f->cmax == 0) {
        f->path = PATH_ZERO;
        return 0;
    }
    double t = (double)tol;
    if (!(t > 0)) t = 10.0 * (double)(rows > s->n ? rows : s->n) * DBL_EPSILON;
    f->tol = t;

    if (f->rule_cap < rows) {
        /* The rank rule caps the rank below rows: no Cholesky. */
    } else if (f->skip_chol > 0) {
        f->skip_chol--;
    } else {
        f->dep_rejected = 0;
        f->rc_src = atil ? resid : NULL; /* r_v, which the pinv to follow takes */
        int st = chol_try(s, f, t);
        f->rc_src = NULL;
        if (st != 1) f->yc_ok = 0;
        if (st < 0) return st;
        if (st == 1) {
            f->path = PATH_CHOL;
            f->rank = rows - f->ndep;
            return f->rank;
        }
        f->skip_chol = f->dep_rejected ? 0 : CHOL_SKIP_CALLS;
    }
    int k = qr_try(s, f, t);
    if (k < 0) return k;
    f->path = k == 0 ? PATH_ZERO : PATH_QR;
    f->rank = k;
    return k;
}

/* ------------------------------------------------------------------ */
/* Solves                                                              */
/* ------------------------------------------------------------------ */
/* x := (L L^T)^-1 x or (L D L^T)^-1 x with a simplicial CHOLMOD factor
 * (columns Lp[j] .. Lp[j] + Lnz[j], the diagonal first). With dep: the rows
 * and columns j with dep[j] set are left out, i.e. x := G_BB^-1 x on the
 * others and 0 on them (the columns of L at those pivots are round-off
 * over dbound, and G_BB = L_BB D_BB L_BB^T; see above). */
static void l_solve(const ss_slot *f, const unsigned char *dep, double *x)
{
    const cholmod_factor *L = f->L;
    const int n = (int)L->n, *Lb = f->lbeg, *Le = f->lend, *Li = f->li;
    const double *Lx = L->x;
    if (L->is_ll) {
        for (int j = 0; j < n; j++) {
            if (dep && dep[j]) {
                x[j] = 0;
                continue;
            }
            const int p = Lb[j], pend = Le[j];
            const double xj = x[j] /= Lx[p];
            for (int q = p + 1; q < pend; q++) x[Li[q]] -= Lx[q] * xj;
        }
        for (int j = n - 1; j >= 0; j--) {
            if (dep && dep[j]) continue;
            const int p = Lb[j], pend = Le[j];
            double t = x[j];
            for (int q = p + 1; q < pend; q++) t -= Lx[q] * x[Li[q]];
            x[j] = t / Lx[p];
        }
    } else {
        for (int j = 0; j < n; j++) {
            if (dep && dep[j]) {
                x[j] = 0;
                continue;
            }
            const int p = Lb[j], pend = Le[j];
            const double xj = x[j];
            for (int q = p + 1; q < pend; q++) x[Li[q]] -= Lx[q] * xj;
            x[j] = xj / Lx[p]; /* D */
        }
        for (int j = n - 1; j >= 0; j--) {
            if (dep && dep[j]) continue;
            const int p = Lb[j], pend = Le[j];
            double t = x[j];
            for (int q = p + 1; q < pend; q++) t -= Lx[q] * x[Li[q]];
            x[j] = t;
        }
    }
}

/* out := G^-1 b (rows; out may be b). 0 or -1. */
static int g_solve(ss_state *s, ss_slot *f, const double *b, double *out)
{
    const int rows = f->rows;
    double *bp = f->bp;
    if (f->yc_ok && memcmp(b, f->rc, (size_t)rows * sizeof *b) == 0) {
        f->yc_ok = 0; /* solved with the probe (chol_probe) */
        memmove(out, f->yc, (size_t)rows * sizeof *out);
        return 0;
    }
    if (f->own_solve) {
        for (int a = 0; a < rows; a++) bp[a] = b[f->lperm[a]];
        l_solve(f, f->ndep ? f->dep : NULL, bp);
        for (int a = 0; a < rows; a++) out[f->lperm[a]] = bp[a];
        return 0;
    }
    if (f->ndep) return -1; /* set-aside rows are solved here only */
    for (int c = 0; c < rows; c++) bp[c] = b[f->perm[c]];
    cholmod_dense B;
    memset(&B, 0, sizeof B);
    B.nrow = (size_t)rows;
    B.ncol = 1;
    B.nzmax = (size_t)rows;
    B.d = (size_t)rows;
    B.x = bp;
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_l_solve2(CHOLMOD_A, f->L, &B, NULL, &f->X, NULL, &f->Y, &f->E, &s->cc))
        return -1;
    const double *X = f->X->x;
    for (int c = 0; c < rows; c++) out[f->perm[c]] = X[c];
    return 0;
}

/* l_solve for two right-hand sides in one walk of L: each the same
 * operations in the same order as l_solve's. */
static void l_solve2(const ss_slot *f, const unsigned char *dep, double *x, double *z)
{
    const cholmod_factor *L = f->L;
    const int n = (int)L->n, *Lb = f->lbeg, *Le = f->lend, *Li = f->li;
    const double *Lx = L->x;
    const int ll = L->is_ll;
    for (int j = 0; j < n; j++) {
        if (dep && dep[j]) {
            x[j] = z[j] = 0;
            continue;
        }
        const int p = Lb[j], pend = Le[j];
        const double xj = ll ? (x[j] /= Lx[p]) : x[j], zj = ll ? (z[j] /= Lx[p]) : z[j];
        for (int q = p + 1; q < pend; q++) {
            const double l = Lx[q];
            x[Li[q]] -= l * xj;
            z[Li[q]] -= l * zj;
        }
        if (!ll) {
            x[j] = xj / Lx[p]; /* D */
            z[j] = zj / Lx[p];
        }
    }
    for (int j = n - 1; j >= 0; j--) {
        if (dep && dep[j]) continue;
        const int p = Lb[j], pend = Le[j];
        double t = x[j], w = z[j];
        for (int q = p + 1; q < pend; q++) {
            const double l = Lx[q];
            t -= l * x[Li[q]];
            w -= l * z[Li[q]];
        }
        x[j] = ll ? t / Lx[p] : t;
        z[j] = ll ? w / Lx[p] : w;
    }
}

/* out1 := G^-1 b1, out2 := G^-1 b2 with the simplicial factor solved here
 * (own_solve), bit for bit g_solve's results. */
static void g_solve2(ss_slot *f, const double *b1, const double *b2, double *out1, double *out2)
{
    const int rows = f->rows;
    double *bp = f->bp, *bp2 = f->bp2;
    for (int a = 0; a < rows; a++) {
        bp[a] = b1[f->lperm[a]];
        bp2[a] = b2[f->lperm[a]];
    }
    l_solve2(f, f->ndep ? f->dep : NULL, bp, bp2);
    for (int a = 0; a < rows; a++) {
        out1[f->lperm[a]] = bp[a];
        out2[f->lperm[a]] = bp2[a];
    }
}

/* With a full-rank QR factor (rank = rows: C = E R^T Q1^T exactly, up to
 * rounding): dx := Q1 w and, when dy is given, dy := E R^-1 w, for
 * w = R^-T E^T b; so dx = C^T dy = C^+ b. dy may be b. */
static void qr_full_solve(ss_state *s, const ss_slot *f, const double *b, double *dx, double *dy)
{
    const ss_qr *q = &f->qr;
    const int n = s->n, k = f->rows;
    double *bt = s->wr, *w = s->wr2, *t = s->wn3;
    for (int j = 0; j < k; j++) bt[j] = b[q->E ? q->E[j] : j]; /* E^T b */
    r_solve_t(q->R, k, bt, w);
    if (dy) {
        memcpy(bt, w, (size_t)k * sizeof *bt);
        r_solve(q->R, k, bt);
        for (int j = 0; j < k; j++) dy[q->E ? q->E[j] : j] = bt[j];
    }
    memcpy(t, w, (size_t)k * sizeof *t);
    for (int j = k; j < n; j++) t[j] = 0;
    q_apply(q, t, dx);
}

/* Refinement of x = C^+ b on the full-rank QR path, b = r (z NULL) or
 * b = C z (r NULL), as the augmented system x - C^T y = 0, C x = b
 * (Björck): residuals d = C^T y - x and g = b - C x in doubled precision
 * (aug_resid), correction dy = G^-1 (g - C d) = E R^-1 w,
 * dx = d + C^T dy = d + Q1 w with w = R^-T E^T (g - C d). x and y (rows,
 * with x = C^T y on entry up to rounding) are updated in place. Stops when
 * the correction is at rounding level of x. */
static void qr_refine(ss_state *s, const ss_slot *f, const double *r, const double *z, double *x,
                      double *y)
{
    const int n = s->n, rows = f->rows;
    double *g = s->wr5, *d = s->wn4, *dx = s->wn5;
    for (int it = 0; it < QR_REFINE_MAX; it++) {
        aug_resid(s, f, x, y, r, z, g, d, dx); /* g = b - C x, d = C^T y - x */
        c_mul(s, f, d, g, g, NULL);            /* g := g - C d */
        qr_full_solve(s, f, g, dx, g); /* dx := Q1 w, g := dy */
        for (int j = 0; j < n; j++) dx[j] += d[j];
        /* A non-finite correction (overflow in the residuals of a huge x)
         * leaves the last iterate. */
        const double dmax = inf_norm(n, dx);
        if (!(dmax <= DBL_MAX)) break;
        for (int i = 0; i < rows; i++) y[i] += g[i];
        for (int j = 0; j < n; j++) x[j] += dx[j];
        if (dmax <= REFINE_TOL * DBL_EPSILON * inf_norm(n, x)) break;
    }
}

/* The redundant-rows Cholesky path (see above): C = P C_B with P = [I; W]
 * in row order, W = C_D C_B^+. */

/* z := W^T p = G_BB^-1 C_B C_D^T p for p zero on the kept rows (z zero on
 * the rows set aside): the least-squares solution of C_B^T z = C_D^T p by
 * its normal equations, computed (init) or given, with up to `refine`
 * corrections from the residual C_D^T p - C_B^T z (corrected semi-normal
 * equations, Björck, BIT 27 (1987)). 0 or -1. */
static int wt_solve(ss_state *s, ss_slot *f, const double *p, double *z, int init, int refine)
{
    const int n = s->n, rows = f->rows;
    double *v = s->wn3, *rho = s->wn4, *g = s->wr;
    memset(v, 0, (size_t)n * sizeof *v);
    ct_mul_add(s, f, p, v); /* C_D^T p */
    double bound;
    c_mul(s, f, v, NULL, g, &bound);
    if (init && g_solve(s, f, g, z)) return -1;
    for (int it = 0; it < refine; it++) {
        for (int j = 0; j < n; j++) rho[j] = -v[j];
        ct_mul_add(s, f, z, rho); /* C_B^T z - C_D^T p */
        c_mul(s, f, rho, NULL, g, NULL);
        for (int k = 0; k < f->ndep; k++) g[f->dlist[k]] = 0;
        if (inf_norm(rows, g) <= REFINE_TOL * DBL_EPSILON * bound) break;
        if (g_solve(s, f, g, g)) return -1;
        for (int i = 0; i < rows; i++) z[i] -= g[i];
    }
    return 0;
}

/* x := C_B^+ u (u zero on the rows set aside) = C_B^T G_BB^-1 u, computed
 * (init) or given, with up to `refine` corrections from u - C_B x as the
 * Cholesky path refines. 0 or -1. */
static int cbp_solve(ss_state *s, ss_slot *f, const double *u, double *x, int init, int refine)
{
    const int n = s->n, rows = f->rows;
    double *y = s->wr, *res = s->wr2;
    if (init) {
        memset(x, 0, (size_t)n * sizeof *x);
        if (g_solve(s, f, u, y)) return -1;
        ct_mul_add(s, f, y, x);
    }
    for (int it = 0; it < refine; it++) {
        double bound;
        c_mul(s, f, x, u, res, &bound);
        for (int k = 0; k < f->ndep; k++) res[f->dlist[k]] = 0;
        if (inf_norm(rows, res) <= REFINE_TOL * DBL_EPSILON * bound) break;
        if (g_solve(s, f, res, y)) return -1;
        ct_mul_add(s, f, y, x);
    }
    return 0;
}

/* ap := (I + W W^T) p on the rows set aside (its other entries are not
 * written), leaving z = W^T p (s->wr8) and xx = C_B^+ z (s->wn6), both
 * unrefined. 0 or -1. */
static int ww_apply(ss_state *s, ss_slot *f, const double *p, double *ap)
{
    double *z = s->wr8, *xx = s->wn6;
    if (wt_solve(s, f, p, z, 1, 0) || cbp_solve(s, f, z, xx, 1, 0)) return -1;
    for (int k = 0; k < f->ndep; k++) { /* rows D: p + W W^T p */
        const int i = f->dlist[k];
        double acc = 0;
        for (sslong q = s->cp[i]; q < s->cp[i + 1]; q++) acc += f->Cx[q] * xx[s->ci[q]];
        ap[i] = p[i] + acc;
    }
    return 0;
}

static double dot_dep(const ss_slot *f, const double *a, const double *b)
{
    double sum = 0;
    for (int k = 0; k < f->ndep; k++) sum += a[f->dlist[k]] * b[f->dlist[k]];
    return sum;
}

/* x := C^+ r = C_B^+ (r_B + W^T s) with (I + W W^T) s = t = r_D - W r_B,
 * t the inconsistency of the rows set aside (see above): x = C_B^+ r_B
 * first (refined on the kept rows as the Cholesky path refines), s by
 * conjugate gradients with a Jacobi preconditioner when t is above
 * round-off; CG's products also give W^T s and C_B^+ W^T s as sums, each
 * then refined. 0, -1 (a solve failed), or 1: CG did not converge in
 * CG_MAX iterations (x not written in full). */
static int pinv_basis(ss_state *s, ss_slot *f, const double *r, double *x, int lsq)
{
    const int n = s->n, rows = f->rows;
    double *res = s->wr2, *t = s->wr4, *sv = s->wr5, *pv = s->wr6, *ap = s->wr7,
           *zr = s->wr9, *za = s->wr10, *xa = s->wn7;
    double bound = 0;
    if (lsq && !f->pdiag_ok && f->wtw_ok && f->own_solve) {
        /* lsq's right-hand side (the position error) is inconsistent on
         * the rows set aside at round-off (every call on the ladders): CG
         * follows, and its preconditioner needs G^-1 W^T w. Both solves in
         * one walk of L, that one kept for g_solve to find; otherwise
         * cbp_solve's first solve exactly. */
        double *y = s->wr;
        memcpy(f->rc, f->wtw, (size_t)rows * sizeof *f->rc);
        g_solve2(f, r, f->rc, y, f->yc);
        f->yc_ok = 1;
        memset(x, 0, (size_t)n * sizeof *x);
        ct_mul_add(s, f, y, x);
    } else if (cbp_solve(s, f, r, x, 1, 0)) {
        return -1;
    }
    for (int it = 0;; it++) {
        c_mul(s, f, x, r, res, &bound); /* r - C x */
        for (int i = 0; i < rows; i++) t[i] = 0;
        for (int k = 0; k < f->ndep; k++) {
            const int i = f->dlist[k];
            t[i] = res[i];
            res[i] = 0;
        }
        if (it == REFINE_MAX || inf_norm(rows, res) <= REFINE_TOL * DBL_EPSILON * bound) break;
        double *y = s->wr;
        if (g_solve(s, f, res, y)) return -1;
        ct_mul_add(s, f, y, x);
    }
    /* t at rounding level of |r| + |C||x|, or below the caller's floor
     * (the rounding of the computation that produced r): consistent. */
    const double stop = REFINE_TOL * DBL_EPSILON * bound > f->rhs_floor
                            ? REFINE_TOL * DBL_EPSILON * bound
                            : f->rhs_floor;
    f->cg_iters = 0;
    if (inf_norm(rows, t) <= stop) return 0; /* consistent */
    /* The Jacobi preconditioner, once per factorization: the diagonal of
     * I + W W^T estimated as w .* (I + W W^T) w for the first vector w of
     * the dependency probe, whose W^T w it kept (exact where the
     * dependences of the rows set aside share no kept rows; at least 1 as
     * the true diagonal). */
    if (!f->pdiag_ok) {
        double *xx = s->wn6;
        unsigned long long u = DEP_SEED;
        if (!f->wtw_ok) {
            for (int i = 0; i < rows; i++) pv[i] = 0;
            for (int k = 0; k < f->ndep; k++) {
                u = u * 6364136223846793005ULL + 1442695040888963407ULL;
                pv[f->dlist[k]] = (u >> 63) ? 1.0 : -1.0;
            }
            if (wt_solve(s, f, pv, f->wtw, 1, 0)) return -1;
            f->wtw_ok = 1;
            u = DEP_SEED;
        }
        if (cbp_solve(s, f, f->wtw, xx, 1, 0)) return -1;
        for (int k = 0; k < f->ndep; k++) {
            const int i = f->dlist[k];
            u = u * 6364136223846793005ULL + 1442695040888963407ULL;
            double acc = 0;
            for (sslong q = s->cp[i]; q < s->cp[i + 1]; q++) acc += f->Cx[q] * xx[s->ci[q]];
            const double dj = 1 + ((u >> 63) ? acc : -acc);
            f->pdiag[i] = dj > 1 ? dj : 1;
        }
        f->pdiag_ok = 1;
    }
    /* PCG: s = 0, residual t, preconditioned residual zr, direction pv;
     * za = W^T s, xa = C_B^+ W^T s. */
    for (int i = 0; i < rows; i++) sv[i] = pv[i] = zr[i] = za[i] = 0;
    memset(xa, 0, (size_t)n * sizeof *xa);
    for (int k = 0; k < f->ndep; k++) {
        const int i = f->dlist[k];
        zr[i] = t[i] / f->pdiag[i];
        pv[i] = zr[i];
    }
    double rz = dot_dep(f, t, zr);
    int converged = 0;
    for (int it = 0; it < CG_MAX && !converged; it++) {
        if (ww_apply(s, f, pv, ap)) return -1;
        const double pap = dot_dep(f, pv, ap);
        if (!(pap > 0)) break;
        const double alpha = rz / pap;
        const double *z = s->wr8, *xx = s->wn6;
        for (int k = 0; k < f->ndep; k++) {
            const int i = f->dlist[k];
            sv[i] += alpha * pv[i];
            t[i] -= alpha * ap[i];
        }
        for (int i = 0; i < rows; i++) za[i] += alpha * z[i];
        for (int j = 0; j < n; j++) xa[j] += alpha * xx[j];
        f->cg_iters++;
        if (inf_norm(rows, t) <= stop) {
            converged = 1;
            break;
        }
        double rz2 = 0;
        for (int k = 0; k < f->ndep; k++) {
            const int i = f->dlist[k];
            zr[i] = t[i] / f->pdiag[i];
            rz2 += t[i] * zr[i];
        }
        const double beta = rz2 / rz;
        rz = rz2;
        for (int k = 0; k < f->ndep; k++) {
            const int i = f->dlist[k];
            pv[i] = zr[i] + beta * pv[i];
        }
    }
    if (!converged) return 1;
    /* x += C_B^+ W^T s, both factors refined */
    if (wt_solve(s, f, sv, za, 0, REFINE_MAX) || cbp_solve(s, f, za, xa, 0, REFINE_MAX)) return -1;
    for (int j = 0; j < n; j++) x[j] += xa[j];
    return 0;
}

/* Move a factorization of the redundant-rows Cholesky path to the QR
 * path (pinv_basis could not solve its least-squares part); 0, or -1 when
 * SPQR fails or finds another rank (the slot then has no factorization). */
static int qr_switch(ss_state *s, ss_slot *f)
{
    dep_clear(f);
    const int k = qr_try(s, f, f->tol);
    if (k != f->rank) {
        f->path = PATH_NONE;
        return -1;
    }
    f->path = PATH_QR;
    f->skip_chol = CHOL_SKIP_CALLS;
    return 0;
}

/* x := C^+ r (doubles; x has n entries, r rows). 0 or -1. */
static int pinv_d(ss_state *s, ss_slot *f, const double *r, double *x, int lsq)
{
    const int n = s->n, rows = f->rows;
    memset(x, 0, (size_t)n * sizeof *x);
    if (f->path == PATH_ZERO) return 0;
    if (f->path == PATH_CHOL && f->ndep) {
        const int st = pinv_basis(s, f, r, x, lsq);
        if (st <= 0) return st;
        /* CG did not converge (W large: the kept rows nearly dependent
         * among themselves): this factorization moves to the QR path,
         * which must find the same rank. */
        if (qr_switch(s, f)) return -1;
        memset(x, 0, (size_t)n * sizeof *x);
    }
    if (f->path == PATH_CHOL) {
        double *y = s->wr, *res = s->wr2;
        if (g_solve(s, f, r, y)) return -1;
        ct_mul_add(s, f, y, x);
        for (int it = 0; it < REFINE_MAX; it++) {
            double bound;
            c_mul(s, f, x, r, res, &bound); /* res = r - C x */
            if (inf_norm(rows, res) <= REFINE_TOL * DBL_EPSILON * bound) break;
            if (g_solve(s, f, res, y)) return -1;
            ct_mul_add(s, f, y, x);
        }
        return 0;
    }
    if (f->path != PATH_QR) return -1;
    if (f->rank == rows) {
        double *y = s->wr4;
        qr_full_solve(s, f, r, x, f->qr_refine ? y : NULL); /* S = R11^T */
        if (f->qr_refine) qr_refine(s, f, r, NULL, x, y);
        return 0;
    }
    const ss_qr *q = &f->qr;
    const sslong k = f->rank;
    double *b = s->wr, *w = s->wr2, *t = s->wn3;
    for (int j = 0; j < rows; j++) b[j] = r[q->E ? q->E[j] : j]; /* E^T r */
    {
        /* S^+ b = E2 R2^-1 (Q2^T b)[0..k) */
        const ss_qr *q2 = &f->qr2;
        double *u = w; /* rows entries */
        q_t(q2, b, u);
        r_solve(q2->R, k, u);
        for (sslong j = 0; j < k; j++) b[q2->E ? q2->E[j] : j] = u[j];
        memcpy(w, b, (size_t)k * sizeof *w);
    }
    for (sslong j = 0; j < k; j++) t[j] = w[j];
    for (int j = (int)k; j < n; j++) t[j] = 0;
    q_apply(q, t, x); /* x = Q1 w */
    return 0;
}

static void ss_lsq(void *state, int slot, const braun_real *r, braun_real *x,
                   braun_real *resid_norm)
{

    ss_state *s = state;
    const int n = s->n;
    ss_slot *f = slot == 0 || slot == 1 ? &s->s[slot] : NULL;
    if (!f || f->path == PATH_NONE) {
        fill_nan(n, x);
        if (resid_norm) *resid_norm = (braun_real)NAN;
        return;
    }
    const int rows = f->rows;
    double *rd = s->wr3, *xd = s->wn2;
    for (int i = 0; i < rows; i++) rd[i] = (double)r[i];
    if (pinv_d(s, f, rd, xd, resid_norm != NULL)) {
        fill_nan(n, x);
        if (resid_norm) *resid_norm = (braun_real)NAN;
        return;
    }
    for (int j = 0; j < n; j++) x[j] = (braun_real)xd[j];
    if (resid_norm) {
        double *res = s->wr2;
        c_mul(s, f, xd, rd, res, NULL); /* r - C x */
        *resid_norm = (braun_real)nrm2(rows, res);
    }
}

static void ss_pinv(void *state, int slot, const braun_real *r, braun_real *x)
{
    ss_lsq(state, slot, r, x, NULL);
}

/* The round-off floor of the slot's next pinv/lsq right-hand sides
 * (braun_linsolver.h): pinv_basis takes their inconsistency t as consistent,
 * and stops CG, at max(REFINE_TOL·eps·(|r| + |C||x|), floor). */
static void ss_rhs_floor(void *state, int slot, braun_real floor)
{
    ss_state *s = state;
    if (!s || slot < 0 || slot > 1) return;
    const double fl = (double)floor;
    s->s[slot].rhs_floor = fl > 0 && fl <= DBL_MAX ? fl : 0;
}

static void ss_null_project(void *state, int slot, braun_real *z)
{

    ss_state *s = state;
    if (slot < 0 || slot > 1) {
        fill_nan(s->n, z);
        return;
    }
    ss_slot *f = &s->s[slot];
    const int n = s->n, rows = f->rows;
    if (f->path == PATH_ZERO) return;
    double *zd = s->wn, *t = s->wn3;
    for (int j = 0; j < n; j++) zd[j] = (double)z[j];
    if (f->path == PATH_CHOL) {
        double *u = s->wr, *y = s->wr2;
        /* z := z - C^T G^-1 C z, repeated while C z is above round-off of
         * |C||z| for the z given (N is a projector: a repeat only removes
         * solve error). */
        double bound0 = 0;
        for (int it = 0; it <= REFINE_MAX; it++) {
            double bound;
            c_mul(s, f, zd, NULL, u, &bound);
            for (int k = 0; k < f->ndep; k++) u[f->dlist[k]] = 0; /* C_B z */
            if (it == 0) bound0 = bound;
            else if (inf_norm(rows, u) <= REFINE_TOL * DBL_EPSILON * bound0) break;
            if (g_solve(s, f, u, y)) {
                fill_nan(n, z);
                return;
            }
            for (int i = 0; i < rows; i++) y[i] = -y[i];
            ct_mul_add(s, f, y, zd);
        }
    } else if (f->path == PATH_QR && f->rank == rows && f->qr_refine) {
        /* z := z - x, x = C^+ C z = Q1 w, w = (Q^T z)(0..k), refined with
         * y = E R^-1 w (C^T y = x). */
        const ss_qr *q = &f->qr;
        double *x = s->wn2, *y = s->wr4, *bt = s->wr;
        q_t(q, zd, t);
        memcpy(bt, t, (size_t)rows * sizeof *bt);
        r_solve(q->R, rows, bt);
        for (int j = 0; j < rows; j++) y[q->E ? q->E[j] : j] = bt[j];
        for (int j = rows; j < n; j++) t[j] = 0;
        q_apply(q, t, x);
        qr_refine(s, f, NULL, zd, x, y);
        for (int j = 0; j < n; j++) zd[j] -= x[j];
    } else if (f->path == PATH_QR) {
        /* z := Q [0; (Q^T z)(k..n)] */
        q_t(&f->qr, zd, t);
        for (int j = 0; j < f->rank; j++) t[j] = 0;
        q_apply(&f->qr, t, zd);
    } else {
        fill_nan(n, z);
        return;
    }
    for (int j = 0; j < n; j++) z[j] = (braun_real)zd[j];
}

/* The rank rule of the slot's next factorizations (braun_linsolver.h):
 * kept until changed, as the built-in kernels do. */
static void ss_rank_rule(void *state, int slot, int keep, int cap, braun_real tol_new)
{
    ss_state *s = state;
    if (!s || slot < 0 || slot > 1) return;
    ss_slot *f = &s->s[slot];
    f->rule_keep = keep < 0 ? 0 : keep;
    f->rule_cap = cap < 0 ? 0 : cap;
    f->rule_tol_new = (double)tol_new > 0 ? (double)tol_new : 0;
}

/* ------------------------------------------------------------------ */
static const braun_linsolver ss_table = {
    "suitesparse",
    BRAUN_LS_NEEDS_SPARSITY,
    ss_create,
    ss_destroy,
    ss_factor_mass,
    ss_solve_rt,
    ss_solve_r,
    ss_mul_r,
    ss_factor_c,
    ss_pinv,
    ss_lsq,
    ss_null_project,
    NULL, /* state_bytes: created, not in the data block */
    NULL, /* bind */
    NULL, /* mass_buffer: the core keeps M */
    ss_rank_rule,
    NULL, /* soft_find: no soft-direction filter (docs/method.md) */
    NULL, /* soft_project */
    ss_rhs_floor,
    NULL, /* stage_order: the rows set aside follow its fixed row order anyway */
};

const braun_linsolver *braun_linsolver_suitesparse(void) { return &ss_table; }
