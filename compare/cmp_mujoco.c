/* mujoco: MuJoCo 2.2.2 (Debian libmujoco-dev) through its C API, on an MJCF
 * text generated from the target's mechanism (cmp_mech.h), loaded from
 * memory (mj_loadXML with a virtual file).
 *
 * The model is what a MuJoCo user writes: a kinematic tree of hinge and
 * slide joints (the spanning tree of cmp_mech_tree: MuJoCo's coordinates
 * are joint coordinates), loop-closing revolute joints as `connect`
 * equalities, loop-closing distance joints as `tendon` equalities on a
 * spatial tendon, springs as spatial tendons with stiffness and damping,
 * torsion springs and dampers as joint stiffness and damping, a motor as a
 * `general` actuator with an affine bias (τ = τ0 − (τ0/ω0)ω, ctrl = 1).
 * MuJoCo 2.2.2 has no time-dependent equality: a driven angle is a `joint`
 * equality to a clock — a slide joint of a 1e12 kg body moving at 1 m/s,
 * which gravity (along y) does not act on. Contacts are disabled.
 * Equality constraints are soft in MuJoCo: solref (time constant, damping
 * ratio) and solimp are the settings the study sweeps.
 *
 * A run fails (a recorded row) when MuJoCo raises a warning that resets
 * its state (bad qpos, qvel, qacc), when the state is not finite, or when
 * the model does not compile (the compiler's message). */
#include <setjmp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "cmp_mech.h"
#include "cmp_peer.h"
#include "cmp_mujoco3.h"
#include "cmp_text.h"

#ifdef CMP_HAVE_MUJOCO
#include <mujoco/mujoco.h>

/* ------------------------------------------------------------ MJCF text */
typedef cmp_text text;
#define put cmp_text_put

/* Point p of link a's frame in link b's frame, both at their initial poses
 * (a, b = -1: the world). */
static void frame_to_frame(const cmp_mech *m, int a, const double *p, int b, double *out)
{
    double w[2] = {p[0], p[1]};
    if (a >= 0) {
        const cmp_link *L = &m->links[a];
        const double c = cos(L->th), s = sin(L->th);
        w[0] = L->x + c * p[0] - s * p[1];
        w[1] = L->y + s * p[0] + c * p[1];
    }
    if (b < 0) {
        out[0] = w[0];
        out[1] = w[1];
        return;
    }
    const cmp_link *L = &m->links[b];
    const double c = cos(L->th), s = sin(L->th), dx = w[0] - L->x, dy = w[1] - L->y;
    out[0] = c * dx + s * dy;
    out[1] = -s * dx + c * dy;
}

/* A direction of link a's frame in link b's frame. */
static void dir_to_frame(const cmp_mech *m, int a, const double *u, int b, double *out)
{
    const double ta = a >= 0 ? m->links[a].th : 0, tb = b >= 0 ? m->links[b].th : 0;
    const double c = cos(ta - tb), s = sin(ta - tb);
    out[0] = c * u[0] - s * u[1];
    out[1] = s * u[0] + c * u[1];
}

static double angle_of(const cmp_mech *m, int l)
{
    return l >= 0 ? m->links[l].th : 0;
}

/* The tree joint of link l: its point on l and on the parent. */
static void tree_points(const cmp_mech *m, int l, double *pc, double *pp)
{
    const cmp_mjoint *J = &m->joints[m->links[l].joint];
    const int child_is_a = l == J->a;
    memcpy(pc, child_is_a ? J->pa : J->pb, 2 * sizeof(double));
    memcpy(pp, child_is_a ? J->pb : J->pa, 2 * sizeof(double));
}

static const double CLOCK_MASS = 1e12, CLOCK_SPEED = 1.0;

void cmp_mujoco_solparams(text *t, const cmp_spec *sp)
{
    const cmp_peer_opts *o = &sp->peer;
    if (o->timeconst >= 0) {
        const double tc = o->timeconst > 0 ? o->timeconst : 2.0 * sp->h;
        put(t, " solref=\"%.17g %.17g\"", tc, o->dampratio > 0 ? o->dampratio : 1.0);
    }
    if (o->solimp[0] > 0)
        put(t, " solimp=\"%.17g %.17g %.17g 0.5 2\"", o->solimp[0], o->solimp[1], o->solimp[2]);
}

static void body_open(text *t, const cmp_mech *m, int l, int depth)
{
    const cmp_link *L = &m->links[l];
    const int p = L->parent;
    double c[2], centre[2] = {0, 0};
    frame_to_frame(m, l, centre, p, c);
    const double rel = L->th - angle_of(m, p);
    /* A point mass gets a negligible inertia (MuJoCo needs one > 0). */
    const double I = L->point_mass || !(L->inertia > 0) ? 1e-12 * (L->mass > 0 ? L->mass : 1)
                                                        : L->inertia;
    put(t, "%*s<body name=\"L%d\" pos=\"%.17g %.17g 0\" quat=\"%.17g 0 0 %.17g\">\n", 2 * depth, "",
        l, c[0], c[1], cos(0.5 * rel), sin(0.5 * rel));
    put(t, "%*s<inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
        2 * depth + 2, "", L->mass > 0 ? L->mass : 1e-12, I, I, I);
    const int in = 2 * depth + 2;
    if (L->joint < 0) {
        /* Free planar root: world x, y in the body's frame, then its angle. */
        const double ux[2] = {1, 0}, uy[2] = {0, 1};
        double ax[2], ay[2];
        dir_to_frame(m, -1, ux, l, ax);
        dir_to_frame(m, -1, uy, l, ay);
        put(t, "%*s<joint name=\"J%dx\" type=\"slide\" pos=\"0 0 0\" axis=\"%.17g %.17g 0\"/>\n", in,
            "", l, ax[0], ax[1]);
        put(t, "%*s<joint name=\"J%dy\" type=\"slide\" pos=\"0 0 0\" axis=\"%.17g %.17g 0\"/>\n", in,
            "", l, ay[0], ay[1]);
        if (!L->point_mass)
            put(t, "%*s<joint name=\"J%d\" type=\"hinge\" pos=\"0 0 0\" axis=\"0 0 1\"/>\n", in, "",
                l);
        return;
    }
    const cmp_mjoint *J = &m->joints[L->joint];
    double pc[2], pp[2];
    tree_points(m, l, pc, pp);
    if (J->kind == CMP_MJ_REVOLUTE) {
        put(t, "%*s<joint name=\"J%d\" type=\"hinge\" pos=\"%.17g %.17g 0\" axis=\"0 0 1\"", in,
            "", l, pc[0], pc[1]);
        /* A rotational spring-damper on this hinge: k (q - springref), c q'. */
        for (int i = 0; i < m->nforces; i++) {
            const cmp_mforce *F = &m->forces[i];
            int child, sign;
            if (F->kind != CMP_MF_TORSION || cmp_mech_hinge(m, F->a, F->b, &child, &sign) < 0 ||
                child != l)
                continue;
            const double rel0 = angle_of(m, F->b) - angle_of(m, F->a);
            put(t, " stiffness=\"%.17g\" damping=\"%.17g\" springref=\"%.17g\"", F->k, F->c,
                sign * (F->rest - rel0));
        }
        put(t, "/>\n");
    } else if (J->kind == CMP_MJ_SLIDER) {
        double u[2];
        dir_to_frame(m, J->b, J->axis, l, u);
        put(t, "%*s<joint name=\"J%ds\" type=\"slide\" pos=\"%.17g %.17g 0\" axis=\"%.17g %.17g 0\"/>\n",
            in, "", l, J->pa[0], J->pa[1], u[0], u[1]);
        if (!L->point_mass)
            put(t, "%*s<joint name=\"J%d\" type=\"hinge\" pos=\"%.17g %.17g 0\" axis=\"0 0 1\"/>\n",
                in, "", l, J->pa[0], J->pa[1]);
    } else {
        /* Distance: swing about the parent's point, then turn about its own. */
        double at[2];
        frame_to_frame(m, p, pp, l, at);
        put(t, "%*s<joint name=\"J%da\" type=\"hinge\" pos=\"%.17g %.17g 0\" axis=\"0 0 1\"/>\n", in,
            "", l, at[0], at[1]);
        if (!L->point_mass)
            put(t, "%*s<joint name=\"J%d\" type=\"hinge\" pos=\"%.17g %.17g 0\" axis=\"0 0 1\"/>\n",
                in, "", l, pc[0], pc[1]);
    }
}

/* The model's opening: <mujoco>, the compiler and the options (step,
 * integrator, gravity g, solver settings; contacts off). */
void cmp_mujoco_header(text *t, const cmp_spec *sp, const char *name, const double *g)
{
    static const char *const integ[] = {"Euler", "RK4", "implicit"};
    static const char *const solver[] = {"Newton", "CG", "PGS"};
    const int ii = sp->integrator - CMP_MJ_EULER;
    put(t, "<mujoco model=\"%s\">\n", name);
    put(t, "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n");
    put(t, "  <option timestep=\"%.17g\" integrator=\"%s\" gravity=\"%.17g %.17g %.17g\" "
            "solver=\"%s\" tolerance=\"%.17g\" iterations=\"%d\" jacobian=\"dense\">\n",
        sp->h, integ[ii >= 0 && ii < 3 ? ii : 1], g[0], g[1], g[2],
        solver[sp->peer.solver >= 0 && sp->peer.solver < 3 ? sp->peer.solver : 0],
        sp->peer.tolerance > 0 ? sp->peer.tolerance : 1e-8,
        sp->peer.iterations > 0 ? sp->peer.iterations : 100);
    put(t, "    <flag contact=\"disable\"/>\n  </option>\n");
}

/* Joint (hinge) name of the revolute tree joint of link l. */
static void hinge_name(int l, char *buf, size_t size)
{
    snprintf(buf, size, "J%d", l);
}

/* Sites (cmp_mujoco3.h): collected first, each written inside its body. */
int cmp_mujoco_add_site(cmp_mj_sites *S, int body, const double *p, int dim)
{
    if (S->n == CMP_MJ_MAX_SITES) return -1;
    S->body[S->n] = body;
    for (int k = 0; k < 3; k++) S->p[S->n][k] = k < dim ? p[k] : 0;
    return S->n++;
}

void cmp_mujoco_put_sites(text *t, const cmp_mj_sites *S, int body, int indent)
{
    for (int i = 0; i < S->n; i++)
        if (S->body[i] == body)
            put(t, "%*s<site name=\"S%d\" pos=\"%.17g %.17g %.17g\"/>\n", indent, "", i, S->p[i][0],
                S->p[i][1], S->p[i][2]);
}
typedef cmp_mj_sites sites;
#define put_sites cmp_mujoco_put_sites
#define add_site(S, link, p) cmp_mujoco_add_site(S, link, p, 2)

static void write_body(text *t, const cmp_mech *m, const sites *S, int l, int depth)
{
    body_open(t, m, l, depth);
    put_sites(t, S, l, 2 * depth + 2);
    for (int c = 0; c < m->nlinks; c++)
        if (m->links[c].parent == l) write_body(t, m, S, c, depth + 1);
    put(t, "%*s</body>\n", 2 * depth, "");
}

int cmp_mujoco_mjcf(const cmp_mech *m, const cmp_spec *sp, const char *name, char **xml,
                    int *has_clock, char *why, size_t whysize)
{
    text t = {NULL, 0, 0, 0};
    sites S;
    S.n = 0;
    double g[2] = {0, 0};
    for (int i = 0; i < m->nforces; i++)
        if (m->forces[i].kind == CMP_MF_GRAVITY) {
            g[0] = m->forces[i].g[0];
            g[1] = m->forces[i].g[1];
        }
    /* Sites of the tendons: loop-closing distances and springs. */
    int tend_a[256], tend_b[256], ntend = 0;
    for (int j = 0; j < m->njoints; j++) {
        const cmp_mjoint *J = &m->joints[j];
        if (J->tree || J->kind != CMP_MJ_DISTANCE || ntend == 256) continue;
        tend_a[ntend] = add_site(&S, J->a, J->pa);
        tend_b[ntend++] = add_site(&S, J->b, J->pb);
    }
    const int ndist = ntend;
    for (int i = 0; i < m->nforces; i++) {
        const cmp_mforce *F = &m->forces[i];
        if (F->kind != CMP_MF_SPRING || ntend == 256) continue;
        tend_a[ntend] = add_site(&S, F->a, F->pa);
        tend_b[ntend++] = add_site(&S, F->b, F->pb);
    }
    const double g3[3] = {g[0], g[1], 0};
    cmp_mujoco_header(&t, sp, name, g3);
    put(&t, "  <worldbody>\n");
    put_sites(&t, &S, -1, 4);
    for (int l = 0; l < m->nlinks; l++)
        if (m->links[l].parent < 0) write_body(&t, m, &S, l, 2);
    /* The clock of driven angles. */
    int clock = 0;
    for (int j = 0; j < m->njoints; j++)
        clock |= m->joints[j].kind == CMP_MJ_ANGLE && m->joints[j].driven &&
                 m->joints[j].drive.kind == BRAUN_FN_LINEAR;
    if (clock)
        put(&t, "    <body name=\"clock\" pos=\"0 0 -10\">\n      <inertial pos=\"0 0 0\" "
                "mass=\"%.17g\" diaginertia=\"1 1 1\"/>\n      <joint name=\"clock\" "
                "type=\"slide\" axis=\"1 0 0\"/>\n    </body>\n",
            CLOCK_MASS);
    put(&t, "  </worldbody>\n");
    /* Tendons, and joint springs and dampers. */
    if (ntend) {
        put(&t, "  <tendon>\n");
        for (int k = 0; k < ntend; k++) {
            put(&t, "    <spatial name=\"T%d\"", k);
            if (k >= ndist) {
                int f = -1, c = -1;
                for (int i = 0; i < m->nforces; i++)
                    if (m->forces[i].kind == CMP_MF_SPRING && ++c == k - ndist) f = i;
                const cmp_mforce *F = &m->forces[f];
                put(&t, " stiffness=\"%.17g\" damping=\"%.17g\" springlength=\"%.17g\"", F->k, F->c,
                    F->rest);
            }
            put(&t, ">\n      <site site=\"S%d\"/>\n      <site site=\"S%d\"/>\n    </spatial>\n",
                tend_a[k], tend_b[k]);
        }
        put(&t, "  </tendon>\n");
    }
    /* Equalities: loop closures and angles. */
    put(&t, "  <equality>\n");
    int neq = 0;
    for (int j = 0; j < m->njoints; j++) {
        const cmp_mjoint *J = &m->joints[j];
        if (J->tree) continue;
        if (J->kind == CMP_MJ_REVOLUTE) {
            /* anchor: a point of body1 (a link; the world as body2). */
            const int b1 = J->a >= 0 ? J->a : J->b, b2 = J->a >= 0 ? J->b : J->a;
            const double *p1 = J->a >= 0 ? J->pa : J->pb;
            put(&t, "    <connect name=\"E%d\" body1=\"L%d\"", j, b1);
            if (b2 >= 0) put(&t, " body2=\"L%d\"", b2);
            put(&t, " anchor=\"%.17g %.17g 0\"", p1[0], p1[1]);
            cmp_mujoco_solparams(&t, sp);
            put(&t, "/>\n");
            neq++;
        } else if (J->kind == CMP_MJ_DISTANCE) {
            int k = 0;
            for (int i = 0; i < j; i++) k += !m->joints[i].tree && m->joints[i].kind == CMP_MJ_DISTANCE;
            put(&t, "    <tendon name=\"E%d\" tendon1=\"T%d\" polycoef=\"0 0 0 0 0\"", j, k);
            cmp_mujoco_solparams(&t, sp);
            put(&t, "/>\n");
            neq++;
        } else if (J->kind == CMP_MJ_ANGLE) {
            int child, sign;
            char hn[16];
            if (cmp_mech_hinge(m, J->a, J->b, &child, &sign) < 0) continue;
            hinge_name(child, hn, sizeof hn);
            put(&t, "    <joint name=\"E%d\" joint1=\"%s\"", j, hn);
            if (J->driven && J->drive.kind == BRAUN_FN_LINEAR)
                put(&t, " joint2=\"clock\" polycoef=\"0 %.17g 0 0 0\"",
                    sign * (double)J->drive.b / CLOCK_SPEED);
            else
                put(&t, " polycoef=\"0 0 0 0 0\"");
            cmp_mujoco_solparams(&t, sp);
            put(&t, "/>\n");
            neq++;
        } else {
            snprintf(why, whysize, "MuJoCo 2.2.2 cannot close a loop with joint '%s'", J->name);
            free(t.s);
            return -1;
        }
    }
    if (!neq) put(&t, "    <!-- none -->\n");
    put(&t, "  </equality>\n");
    /* Torsion springs, dampers, motors and constant torques on tree hinges. */
    int nact = 0;
    for (int i = 0; i < m->nforces; i++) {
        const cmp_mforce *F = &m->forces[i];
        if (F->kind != CMP_MF_MOTOR && F->kind != CMP_MF_TORQUE) continue;
        int child, sign;
        char hn[16];
        if (cmp_mech_hinge(m, F->a, F->b, &child, &sign) < 0) {
            snprintf(why, whysize, "MuJoCo: a motor is not on a revolute joint of the tree");
            free(t.s);
            return -1;
        }
        hinge_name(child, hn, sizeof hn);
        if (!nact++) put(&t, "  <actuator>\n");
        /* τ on the rotor a: on the hinge coordinate (child − parent) with
         * sign −(θ_b − θ_a)'s: the hinge turns the rotor when the child is a
         * (δW = τ δθ_a − τ δθ_b = −sign·τ δq). A constant torque: the same
         * gain, no bias (ctrl = 1). */
        if (F->kind == CMP_MF_TORQUE)
            put(&t, "    <general joint=\"%s\" ctrllimited=\"false\" gainprm=\"%.17g\"/>\n", hn,
                -sign * (double)F->f.a);
        else
            put(&t, "    <general joint=\"%s\" ctrllimited=\"false\" gainprm=\"%.17g\" biastype=\"affine\" "
                    "biasprm=\"0 0 %.17g\"/>\n",
                hn, -sign * F->tau0, -F->tau0 / F->omega0);
    }
    if (nact) put(&t, "  </actuator>\n");
    put(&t, "</mujoco>\n");
    if (t.failed) {
        free(t.s);
        snprintf(why, whysize, "out of memory");
        return -1;
    }
    *xml = t.s;
    *has_clock = clock;
    return 0;
}

/* ------------------------------------------------------------ the run */
/* MuJoCo's error and warning handlers: an error returns to the run that
 * caused it (mju_error would exit the process), a warning is recorded. */
static jmp_buf *mj_jump;
static char mj_message[160];

static void on_mj_error(const char *msg)
{
    snprintf(mj_message, sizeof mj_message, "%s", msg);
    if (mj_jump) longjmp(*mj_jump, 1);
    /* Outside a run: nothing to return to; the message stays. */
}

static void on_mj_warning(const char *msg)
{
    snprintf(mj_message, sizeof mj_message, "%s", msg);
}

/* The peer's closable loop joints: connect (revolute), tendon (distance). */
static const unsigned MJ_CLOSABLE = CMP_MJ_BIT(CMP_MJ_REVOLUTE) | CMP_MJ_BIT(CMP_MJ_DISTANCE);

static int prepare(const cmp_target *tg, cmp_mech *m, char *why, size_t whysize)
{
    if (cmp_mech_for_target(tg, m, why, whysize)) return -1;
    if (cmp_mech_tree(m, MJ_CLOSABLE, "MuJoCo 2.2.2", why, whysize)) {
        cmp_mech_free(m);
        return -1;
    }
    for (int i = 0; i < m->nforces; i++) {
        const cmp_mforce *F = &m->forces[i];
        int child, sign;
        if ((F->kind == CMP_MF_TORSION || F->kind == CMP_MF_MOTOR || F->kind == CMP_MF_TORQUE) &&
            cmp_mech_hinge(m, F->a, F->b, &child, &sign) < 0) {
            snprintf(why, whysize,
                     "MuJoCo: a torsion spring, motor or torque not on a hinge of the tree");
            cmp_mech_free(m);
            return -1;
        }
    }
    return 0;
}

int cmp_mujoco_supports(const cmp_target *tg, char *why, size_t whysize)
{
    if (cmp_target_is_spatial(tg)) {
        cmp_mech3 m3;
        if (cmp_mujoco3_prepare(tg, &m3, why, whysize)) return 0;
        cmp_mech3_free(&m3);
        return 1;
    }
    cmp_mech m;
    if (prepare(tg, &m, why, whysize)) return 0;
    cmp_mech_free(&m);
    return 1;
}

const char *cmp_mujoco_version(void)
{
    return mj_versionString();
}

/* A compiled model of the target and its bookkeeping. */
typedef struct mj_run {
    int spatial;      /* 1: mech3 (cmp_mujoco3.c), 0: mech */
    cmp_mech mech;
    cmp_mech3 mech3;
    mjModel *model;
    mjData *data;
    int *body;        /* per link: MuJoCo body id */
} mj_run;

static void mj_run_free(mj_run *r)
{
    if (r->data) mj_deleteData(r->data);
    if (r->model) mj_deleteModel(r->model);
    free(r->body);
    cmp_mech_free(&r->mech);
    cmp_mech3_free(&r->mech3);
    memset(r, 0, sizeof *r);
}

static int dof_of(const mjModel *mm, const char *joint)
{
    const int id = mj_name2id(mm, mjOBJ_JOINT, joint);
    return id < 0 ? -1 : mm->jnt_dofadr[id];
}

/* Velocity of link l's material point at world position P (initial). */
static void point_velocity(const cmp_mech *m, int l, const double *P, double *v)
{
    if (l < 0) {
        v[0] = v[1] = 0;
        return;
    }
    const cmp_link *L = &m->links[l];
    v[0] = L->vx - L->w * (P[1] - L->y);
    v[1] = L->vy + L->w * (P[0] - L->x);
}

/* qvel of the tree's joints from the links' initial velocities. */
static void initial_qvel(const mj_run *r, int has_clock)
{
    const cmp_mech *m = &r->mech;
    const mjModel *mm = r->model;
    double *qvel = r->data->qvel;
    char nm[24];
    int k;
    for (int l = 0; l < m->nlinks; l++) {
        const cmp_link *L = &m->links[l];
        const double wp = L->parent >= 0 ? m->links[L->parent].w : 0;
        snprintf(nm, sizeof nm, "J%d", l);
        const int hinge = dof_of(mm, nm);
        if (L->joint < 0) {
            snprintf(nm, sizeof nm, "J%dx", l);
            if ((k = dof_of(mm, nm)) >= 0) qvel[k] = L->vx;
            snprintf(nm, sizeof nm, "J%dy", l);
            if ((k = dof_of(mm, nm)) >= 0) qvel[k] = L->vy;
            if (hinge >= 0) qvel[hinge] = L->w;
            continue;
        }
        const cmp_mjoint *J = &m->joints[L->joint];
        double pc[2], pp[2], Pc[2], Pp[2], vc[2], vp[2];
        tree_points(m, l, pc, pp);
        frame_to_frame(m, l, pc, -1, Pc);
        frame_to_frame(m, L->parent, pp, -1, Pp);
        if (J->kind == CMP_MJ_REVOLUTE) {
            if (hinge >= 0) qvel[hinge] = L->w - wp;
        } else if (J->kind == CMP_MJ_SLIDER) {
            double u[2];
            dir_to_frame(m, J->b, J->axis, -1, u);
            point_velocity(m, l, Pc, vc);
            point_velocity(m, L->parent, Pc, vp);
            snprintf(nm, sizeof nm, "J%ds", l);
            if ((k = dof_of(mm, nm)) >= 0) qvel[k] = u[0] * (vc[0] - vp[0]) + u[1] * (vc[1] - vp[1]);
            if (hinge >= 0) qvel[hinge] = L->w - wp;
        } else {
            point_velocity(m, l, Pc, vc);
            point_velocity(m, L->parent, Pp, vp);
            const double dx = Pc[0] - Pp[0], dy = Pc[1] - Pp[1];
            const double arm = (dx * (vc[1] - vp[1]) - dy * (vc[0] - vp[0])) / (dx * dx + dy * dy);
            snprintf(nm, sizeof nm, "J%da", l);
            if ((k = dof_of(mm, nm)) >= 0) qvel[k] = arm - wp;
            if (hinge >= 0) qvel[hinge] = L->w - arm;
        }
    }
    if (has_clock && (k = dof_of(mm, "clock")) >= 0) qvel[k] = CLOCK_SPEED;
}

static int mj_build(const cmp_target *tg, const cmp_spec *sp, mj_run *r, char *why, size_t whysize)
{
    memset(r, 0, sizeof *r);
    r->spatial = cmp_target_is_spatial(tg);
    char *xml = NULL;
    int has_clock = 0;
    if (r->spatial) {
        if (cmp_mujoco3_prepare(tg, &r->mech3, why, whysize)) return -1;
        if (cmp_mujoco3_mjcf(&r->mech3, sp, tg->name, &xml, why, whysize)) {
            mj_run_free(r);
            return -1;
        }
    } else {
        if (prepare(tg, &r->mech, why, whysize)) return -1;
        if (cmp_mujoco_mjcf(&r->mech, sp, tg->name, &xml, &has_clock, why, whysize)) {
            mj_run_free(r);
            return -1;
        }
    }
    const int nbodies = r->spatial ? r->mech3.nbodies : r->mech.nlinks;
    /* MuJoCo 2.2.2's mjVFS holds 2000 file names of 1000 bytes: 2 MB, on
     * the heap (valgrind took it on the stack for a stack overflow). */
    mjVFS *vfs = malloc(sizeof *vfs);
    const int len = (int)strlen(xml);
    int rc = -1;
    if (!vfs) {
        snprintf(why, whysize, "out of memory");
    } else {
        mj_defaultVFS(vfs);
        if (mj_makeEmptyFileVFS(vfs, "scene.xml", len) == 0) {
            memcpy(vfs->filedata[mj_findFileVFS(vfs, "scene.xml")], xml, (size_t)len);
            char err[512] = "";
            r->model = mj_loadXML("scene.xml", vfs, err, sizeof err);
            if (!r->model) snprintf(why, whysize, "MJCF: %s", err);
            else rc = 0;
        } else {
            snprintf(why, whysize, "MuJoCo's virtual file system is full");
        }
        mj_deleteVFS(vfs);
        free(vfs);
    }
    free(xml);
    if (rc == 0) {
        r->data = mj_makeData(r->model);
        r->body = malloc(((size_t)nbodies + 1) * sizeof(int));
        if (!r->data || !r->body) rc = -1;
    }
    for (int l = 0; rc == 0 && l < nbodies; l++) {
        char nm[16];
        snprintf(nm, sizeof nm, "L%d", l);
        r->body[l] = mj_name2id(r->model, mjOBJ_BODY, nm);
        if (r->body[l] < 0) rc = -1;
    }
    if (rc) {
        if (!why[0]) snprintf(why, whysize, "out of memory");
        mj_run_free(r);
        return -1;
    }
    if (r->spatial) cmp_mujoco3_qvel(&r->mech3, r->model, r->data);
    else initial_qvel(r, has_clock);
    for (int i = 0; i < r->model->nu; i++) r->data->ctrl[i] = 1;
    return 0;
}

/* q, v of libbraun from MuJoCo's qpos, qvel (in a scratch mjData). */
static void to_state(mj_run *r, mjData *d, double *pose, double *q, double *v)
{
    const mjModel *mm = r->model;
    mj_kinematics(mm, d);
    mj_comPos(mm, d);
    mj_comVel(mm, d);
    for (int l = 0; l < r->mech.nlinks; l++) {
        const int id = r->body[l];
        double res[6];
        mj_objectVelocity(mm, d, mjOBJ_BODY, id, res, 0);
        double *s = pose + 6 * l;
        s[0] = d->xpos[3 * id];
        s[1] = d->xpos[3 * id + 1];
        s[2] = cmp_mech_unwrap(s[2], atan2(d->xmat[9 * id + 3], d->xmat[9 * id]));
        s[3] = res[3];
        s[4] = res[4];
        s[5] = res[2];
    }
    cmp_mech_state(&r->mech, pose, q, v);
}

static int bad_state(const mjModel *mm, const mjData *d, char *what, size_t size)
{
    static const int kinds[] = {mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC};
    static const char *const names[] = {"MJ_WARN_BADQPOS", "MJ_WARN_BADQVEL", "MJ_WARN_BADQACC"};
    for (int k = 0; k < 3; k++)
        if (d->warning[kinds[k]].number > 0) {
            snprintf(what, size, "%s", names[k]);
            return 1;
        }
    for (int i = 0; i < mm->nq; i++)
        if (!isfinite(d->qpos[i])) {
            snprintf(what, size, "DIVERGED");
            return 1;
        }
    return 0;
}

void cmp_run_mujoco(const cmp_target *tg, const cmp_spec *sp, cmp_traj *tr, cmp_outcome *out)
{
    memset(out, 0, sizeof *out);
    cmp_traj_clear(tr);
    mj_run r;
    char why[160] = "";
    mju_user_error = on_mj_error;
    mju_user_warning = on_mj_warning;
    if (mj_build(tg, sp, &r, why, sizeof why)) {
        snprintf(out->status_name, sizeof out->status_name, "%s",
                 strncmp(why, "MJCF", 4) ? "UNSUPPORTED" : "MJCF_ERROR");
        snprintf(out->detail, sizeof out->detail, "at t = 0 (%s)", why);
        out->status = -1;
        return;
    }
    const mjModel *mm = r.model;
    mjData *d = r.data;
    const int nq = mm->nq, nv = mm->nv, n = tg->sys.n;
    const long steps = (long)floor(sp->T / sp->h + 0.5), every = cmp_every(sp->dt_out, sp->h);
    /* Raw samples (qpos, qvel) during the run; converted afterwards. */
    const long cap = steps / every + 2;
    double *raw = malloc((size_t)cap * (size_t)(nq + nv + 1) * sizeof(double));
    if (!raw) {
        snprintf(out->status_name, sizeof out->status_name, "OUT_OF_MEMORY");
        out->status = -1;
        mj_run_free(&r);
        return;
    }
    long ns = 0;
    const int evals = sp->integrator == CMP_MJ_RK4 ? 4 : 1;
    jmp_buf jump;
    volatile long k = 0;
    volatile int failed = 0;
    mj_jump = &jump;
    mj_message[0] = '\0';
    const double c0 = cmp_cpu_seconds();
    if (setjmp(jump) == 0) {
        double *row = raw;
        row[0] = 0;
        memcpy(row + 1, d->qpos, (size_t)nq * sizeof(double));
        memcpy(row + 1 + nq, d->qvel, (size_t)nv * sizeof(double));
        ns = 1;
        for (k = 1; k <= steps; k++) {
            mj_step(mm, d);
            out->counts.iterations += d->solver_iter;
            if (bad_state(mm, d, out->status_name, sizeof out->status_name)) {
                failed = 1;
                break;
            }
            if (k % every == 0 || k == steps) {
                row = raw + (size_t)ns * (size_t)(nq + nv + 1);
                row[0] = k == steps ? sp->T : (double)k * sp->h;
                memcpy(row + 1, d->qpos, (size_t)nq * sizeof(double));
                memcpy(row + 1 + nq, d->qvel, (size_t)nv * sizeof(double));
                ns++;
            }
        }
    } else {
        failed = 2;
        snprintf(out->status_name, sizeof out->status_name, "MJ_ERROR");
    }
    mj_jump = NULL;
    out->cpu_self = cmp_cpu_seconds() - c0;
    const long done = failed ? k - 1 : steps;
    out->counts.steps = done > 0 ? done : 0;
    out->counts.rhs_evals = (long)evals * out->counts.steps;
    out->t_reached = failed ? (double)done * sp->h : sp->T;
    if (failed) {
        out->status = -1;
        snprintf(out->detail, sizeof out->detail, "at t = %.9g (%s)", (double)k * sp->h,
                 mj_message[0] ? mj_message : "MuJoCo reset its state");
    } else {
        snprintf(out->status_name, sizeof out->status_name, "OK");
    }
    /* Samples to q, v. */
    mjData *d2 = mj_makeData(mm);
    const size_t npose = r.spatial ? 13 * (size_t)r.mech3.nbodies : 6 * (size_t)r.mech.nlinks;
    double *pose = malloc((npose + 2 * (size_t)n) * sizeof(double));
    if (d2 && pose) {
        double *q = pose + npose, *v = q + n;
        for (int l = 0; l < r.mech.nlinks; l++) pose[6 * l + 2] = r.mech.links[l].th;
        /* Spatial: each quaternion takes the sign of the previous sample's. */
        memcpy(q, tg->q0, (size_t)n * sizeof(double));
        for (long j = 0; j < ns; j++) {
            const double *row = raw + (size_t)j * (size_t)(nq + nv + 1);
            memcpy(d2->qpos, row + 1, (size_t)nq * sizeof(double));
            memcpy(d2->qvel, row + 1 + nq, (size_t)nv * sizeof(double));
            if (r.spatial) {
                cmp_mujoco3_pose(&r.mech3, mm, d2, r.body, pose);
                cmp_mech3_state(&r.mech3, pose, q, v);
            } else {
                to_state(&r, d2, pose, q, v);
            }
            if (cmp_traj_push(tr, row[0], q, v)) break;
        }
    }
    free(pose);
    if (d2) mj_deleteData(d2);
    free(raw);
    mj_run_free(&r);
}

double cmp_mujoco_step_cost(const cmp_target *tg, const cmp_spec *sp, long steps, char *why,
                            size_t whysize)
{
    mj_run r;
    mju_user_error = on_mj_error;
    mju_user_warning = on_mj_warning;
    if (mj_build(tg, sp, &r, why, whysize)) return NAN;
    const double c0 = cmp_cpu_seconds();
    for (long k = 0; k < steps; k++) mj_step(r.model, r.data);
    const double c = cmp_cpu_seconds() - c0;
    mj_run_free(&r);
    return c / (double)steps;
}

#else /* no MuJoCo: the method exists, its runs say why they did not run */
void cmp_run_mujoco(const cmp_target *tg, const cmp_spec *sp, cmp_traj *tr, cmp_outcome *out)
{
    (void)tg;
    (void)sp;
    memset(out, 0, sizeof *out);
    cmp_traj_clear(tr);
    snprintf(out->status_name, sizeof out->status_name, "NOT_BUILT");
    snprintf(out->detail, sizeof out->detail, "at t = 0 (built without libmujoco-dev)");
    out->status = -1;
}

int cmp_mujoco_supports(const cmp_target *tg, char *why, size_t whysize)
{
    (void)tg;
    snprintf(why, whysize, "built without MuJoCo");
    return 0;
}

const char *cmp_mujoco_version(void)
{
    return NULL;
}

double cmp_mujoco_step_cost(const cmp_target *tg, const cmp_spec *sp, long steps, char *why,
                            size_t whysize)
{
    (void)tg;
    (void)sp;
    (void)steps;
    snprintf(why, whysize, "built without MuJoCo");
    return NAN;
}
#endif
