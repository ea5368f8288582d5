/* MuJoCo on spatial mechanisms: the MJCF a MuJoCo user writes for a
 * spatial scene (cmp_mech3.h), and the map between MuJoCo's state and
 * libbraun's.
 *
 * A body's frame is libbraun's (origin at the centre of mass, the same
 * orientation), placed in its parent's frame at the initial poses. Tree
 * joints: revolute3d → hinge about the axis at the joint's point,
 * spherical → ball, weld → no joint, a free root → freejoint (its qpos are
 * libbraun's coordinates of the body: centre and quaternion), prismatic3d
 * → slide along the axis; a particle3d (a point mass) held by a spherical
 * joint → welded to that point (its orientation is not a coordinate), a
 * free particle → three slides. Loop-closing joints: spherical →
 * `connect`; revolute3d → two `connect`s, at the
 * joint's point and one unit along its axis (six rows for five: MuJoCo's
 * soft constraints take the redundant row). Springs are spatial tendons
 * with stiffness, damping and springlength; torsion3d on a tree hinge is
 * the hinge's stiffness, damping and springref (θ = ±qpos: libbraun's
 * angle turns b relative to a; the hinge turns its child). Welded or
 * prismatic loops, torsion on a loop-closing joint: refused with a
 * sentence. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_mujoco3.h"

#ifdef CMP_HAVE_MUJOCO
#define put cmp_text_put

int cmp_mujoco3_prepare(const cmp_target *tg, cmp_mech3 *m, char *why, size_t whysize)
{
    if (cmp_mech3_for_target(tg, m, why, whysize)) return -1;
    if (cmp_mech3_tree(m, why, whysize)) {
        cmp_mech3_free(m);
        return -1;
    }
    const char *bad = NULL, *what = "";
    for (int j = 0; j < m->njoints && !bad; j++)
        if (!m->joints[j].tree &&
            (m->joints[j].kind == CMP_J3_WELD || m->joints[j].kind == CMP_J3_PRISMATIC)) {
            bad = m->joints[j].name;
            what = "MuJoCo: a weld or prismatic joint closing a loop (not translated)";
        }
    for (int i = 0; i < m->nforces && !bad; i++)
        if (m->forces[i].kind == CMP_F3_TORSION && !m->joints[m->forces[i].joint].tree) {
            bad = m->joints[m->forces[i].joint].name;
            what = "MuJoCo: a torsion spring on a joint that closes a loop";
        }
    if (bad) {
        snprintf(why, whysize, "%s ('%s')", what, bad);
        cmp_mech3_free(m);
        return -1;
    }
    return 0;
}

/* Pose of body b's frame in body p's frame (p = -1: the world), initial. */
static void relative_pose(const cmp_mech3 *m, int b, int p, double *pos, double *quat)
{
    const cmp_body3 *B = &m->bodies[b];
    if (p < 0) {
        memcpy(pos, B->pos, 3 * sizeof(double));
        memcpy(quat, B->quat, 4 * sizeof(double));
        return;
    }
    const cmp_body3 *P = &m->bodies[p];
    const double d[3] = {B->pos[0] - P->pos[0], B->pos[1] - P->pos[1], B->pos[2] - P->pos[2]};
    const double pc[4] = {P->quat[0], -P->quat[1], -P->quat[2], -P->quat[3]};
    cmp_quat_rotate_inv(P->quat, d, pos);
    cmp_quat_mul(pc, B->quat, quat);
}

typedef cmp_mj_sites sites;
#define put_sites cmp_mujoco_put_sites
#define add_site(S, body, p) cmp_mujoco_add_site(S, body, p, 3)

/* The torsion spring-damper on tree joint j, as hinge attributes. */
static void put_torsion(cmp_text *t, const cmp_mech3 *m, int j, int child)
{
    for (int i = 0; i < m->nforces; i++) {
        const cmp_force3 *F = &m->forces[i];
        if (F->kind != CMP_F3_TORSION || F->joint != j) continue;
        const double sign = child == m->joints[j].b ? 1 : -1;
        put(t, " stiffness=\"%.17g\" damping=\"%.17g\" springref=\"%.17g\"", F->k, F->c,
            sign * F->rest);
    }
}

static void write_body(cmp_text *t, const cmp_mech3 *m, const sites *S, int b, int depth)
{
    const cmp_body3 *B = &m->bodies[b];
    double pos[3], quat[4];
    relative_pose(m, b, B->parent, pos, quat);
    const int in = 2 * depth + 2;
    put(t, "%*s<body name=\"L%d\" pos=\"%.17g %.17g %.17g\" quat=\"%.17g %.17g %.17g %.17g\">\n",
        2 * depth, "", b, pos[0], pos[1], pos[2], quat[0], quat[1], quat[2], quat[3]);
    if (B->point_mass) {
        /* MuJoCo needs an inertia: a negligible one (no joint turns it). */
        const double I = 1e-12 * B->mass;
        put(t, "%*s<inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n", in, "",
            B->mass, I, I, I);
    } else {
        put(t, "%*s<inertial pos=\"0 0 0\" mass=\"%.17g\" fullinertia=\"%.17g %.17g %.17g %.17g %.17g %.17g\"/>\n",
            in, "", B->mass, B->inertia[0], B->inertia[1], B->inertia[2], B->inertia[3],
            B->inertia[4], B->inertia[5]);
    }
    if (B->joint < 0 && B->point_mass) {
        static const char *const xyz[3] = {"1 0 0", "0 1 0", "0 0 1"};
        for (int k = 0; k < 3; k++)
            put(t, "%*s<joint name=\"J%d%c\" type=\"slide\" axis=\"%s\"/>\n", in, "", b, 'x' + k,
                xyz[k]);
    } else if (B->joint < 0) {
        put(t, "%*s<freejoint name=\"J%d\"/>\n", in, "", b);
    } else {
        const cmp_joint3 *J = &m->joints[B->joint];
        const double *p, *axis;
        cmp_joint3_side(J, b, &p, &axis);
        if (J->kind == CMP_J3_REVOLUTE) {
            put(t, "%*s<joint name=\"J%d\" type=\"hinge\" pos=\"%.17g %.17g %.17g\" axis=\"%.17g %.17g %.17g\"",
                in, "", b, p[0], p[1], p[2], axis[0], axis[1], axis[2]);
            put_torsion(t, m, B->joint, b);
            put(t, "/>\n");
        } else if (J->kind == CMP_J3_PRISMATIC) {
            put(t, "%*s<joint name=\"J%d\" type=\"slide\" axis=\"%.17g %.17g %.17g\"/>\n", in, "", b,
                axis[0], axis[1], axis[2]);
        } else if (J->kind == CMP_J3_SPHERICAL && !B->point_mass) {
            put(t, "%*s<joint name=\"J%d\" type=\"ball\" pos=\"%.17g %.17g %.17g\"/>\n", in, "", b,
                p[0], p[1], p[2]);
        } /* weld, a particle on a spherical joint: no joint */
    }
    put_sites(t, S, b, in);
    for (int c = 0; c < m->nbodies; c++)
        if (m->bodies[c].parent == b) write_body(t, m, S, c, depth + 1);
    put(t, "%*s</body>\n", 2 * depth, "");
}

/* One connect equality: point p (body b1's frame) held where it is now on
 * body b2 (or the world). */
static void put_connect(cmp_text *t, const cmp_spec *sp, int j, int k, int b1, int b2, const double *p)
{
    put(t, "    <connect name=\"E%d_%d\" body1=\"L%d\"", j, k, b1);
    if (b2 >= 0) put(t, " body2=\"L%d\"", b2);
    put(t, " anchor=\"%.17g %.17g %.17g\"", p[0], p[1], p[2]);
    cmp_mujoco_solparams(t, sp);
    put(t, "/>\n");
}

int cmp_mujoco3_mjcf(const cmp_mech3 *m, const cmp_spec *sp, const char *name, char **xml,
                     char *why, size_t whysize)
{
    cmp_text t = {NULL, 0, 0, 0};
    sites *S = calloc(1, sizeof *S);
    if (!S) {
        snprintf(why, whysize, "out of memory");
        return -1;
    }
    double g[3] = {0, 0, 0};
    int tend_a[128], tend_b[128], ntend = 0;
    for (int i = 0; i < m->nforces; i++) {
        const cmp_force3 *F = &m->forces[i];
        if (F->kind == CMP_F3_GRAVITY) memcpy(g, F->g, sizeof g);
        if (F->kind != CMP_F3_SPRING || ntend == 128) continue;
        tend_a[ntend] = add_site(S, F->a, F->pa);
        tend_b[ntend++] = add_site(S, F->b, F->pb);
    }
    cmp_mujoco_header(&t, sp, name, g);
    put(&t, "  <worldbody>\n");
    put_sites(&t, S, -1, 4);
    for (int b = 0; b < m->nbodies; b++)
        if (m->bodies[b].parent < 0) write_body(&t, m, S, b, 2);
    put(&t, "  </worldbody>\n");
    if (ntend) {
        put(&t, "  <tendon>\n");
        for (int k = 0, f = 0; k < ntend; k++, f++) {
            while (m->forces[f].kind != CMP_F3_SPRING) f++;
            const cmp_force3 *F = &m->forces[f];
            put(&t, "    <spatial name=\"T%d\" stiffness=\"%.17g\" damping=\"%.17g\" springlength=\"%.17g\">\n"
                    "      <site site=\"S%d\"/>\n      <site site=\"S%d\"/>\n    </spatial>\n",
                k, F->k, F->c, F->rest, tend_a[k], tend_b[k]);
        }
        put(&t, "  </tendon>\n");
    }
    put(&t, "  <equality>\n");
    int neq = 0;
    for (int j = 0; j < m->njoints; j++) {
        const cmp_joint3 *J = &m->joints[j];
        if (J->tree) continue;
        const int b1 = J->a >= 0 ? J->a : J->b, b2 = J->a >= 0 ? J->b : J->a;
        const double *p, *axis;
        cmp_joint3_side(J, b1, &p, &axis);
        put_connect(&t, sp, j, 0, b1, b2, p);
        if (J->kind == CMP_J3_REVOLUTE) {
            const double p2[3] = {p[0] + axis[0], p[1] + axis[1], p[2] + axis[2]};
            put_connect(&t, sp, j, 1, b1, b2, p2);
        }
        neq++;
    }
    if (!neq) put(&t, "    <!-- none -->\n");
    put(&t, "  </equality>\n</mujoco>\n");
    free(S);
    if (t.failed) {
        free(t.s);
        snprintf(why, whysize, "out of memory");
        return -1;
    }
    *xml = t.s;
    return 0;
}

void cmp_mujoco3_qvel(const cmp_mech3 *m, const mjModel *mm, mjData *d)
{
    char nm[24];
    for (int b = 0; b < m->nbodies; b++) {
        const cmp_body3 *B = &m->bodies[b];
        if (B->point_mass && B->joint < 0) {
            for (int k = 0; k < 3; k++) {
                snprintf(nm, sizeof nm, "J%d%c", b, 'x' + k);
                const int id = mj_name2id(mm, mjOBJ_JOINT, nm);
                if (id >= 0) d->qvel[mm->jnt_dofadr[id]] = B->vel[k];
            }
            continue;
        }
        snprintf(nm, sizeof nm, "J%d", b);
        const int id = mj_name2id(mm, mjOBJ_JOINT, nm);
        if (id < 0) continue; /* welded */
        const int k = mm->jnt_dofadr[id];
        const double *wp = B->parent >= 0 ? m->bodies[B->parent].omega : NULL;
        double rel[3], local[3];
        for (int i = 0; i < 3; i++) rel[i] = B->omega[i] - (wp ? wp[i] : 0);
        cmp_quat_rotate_inv(B->quat, rel, local);
        if (B->joint < 0) {
            /* freejoint: world velocity of the origin, local angular velocity. */
            for (int i = 0; i < 3; i++) {
                d->qvel[k + i] = B->vel[i];
                d->qvel[k + 3 + i] = local[i];
            }
        } else if (m->joints[B->joint].kind == CMP_J3_REVOLUTE) {
            const double *p, *axis;
            cmp_joint3_side(&m->joints[B->joint], b, &p, &axis);
            d->qvel[k] = local[0] * axis[0] + local[1] * axis[1] + local[2] * axis[2];
        } else if (m->joints[B->joint].kind == CMP_J3_PRISMATIC) {
            /* The child's origin against the parent's point there, along
             * the axis (world). */
            const double *p, *axis;
            cmp_joint3_side(&m->joints[B->joint], b, &p, &axis);
            double vp[3], u[3];
            cmp_mech3_velocity0(m, B->parent, B->pos, vp);
            cmp_quat_rotate(B->quat, axis, u);
            d->qvel[k] = (B->vel[0] - vp[0]) * u[0] + (B->vel[1] - vp[1]) * u[1] +
                         (B->vel[2] - vp[2]) * u[2];
        } else {
            for (int i = 0; i < 3; i++) d->qvel[k + i] = local[i];
        }
    }
}

void cmp_mujoco3_pose(const cmp_mech3 *m, const mjModel *mm, mjData *d, const int *body,
                      double *pose)
{
    mj_kinematics(mm, d);
    mj_comPos(mm, d);
    mj_comVel(mm, d);
    for (int b = 0; b < m->nbodies; b++) {
        const int id = body[b];
        double res[6];
        mj_objectVelocity(mm, d, mjOBJ_BODY, id, res, 0);
        double *s = pose + 13 * b;
        for (int k = 0; k < 3; k++) {
            s[k] = d->xpos[3 * id + k];
            s[7 + k] = res[3 + k];
            s[10 + k] = res[k];
        }
        for (int k = 0; k < 4; k++) s[3 + k] = d->xquat[4 * id + k];
    }
}
#endif
