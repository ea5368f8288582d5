/* simbody on spatial mechanisms (cmp_mech3.h): the model a Simbody user
 * writes for a spatial scene, part of the plugin (cmp_simbody.cpp runs
 * it). Each body's frame is libbraun's (origin at the centre of mass).
 * Tree joints as mobilizers, their frames chosen so that q = 0 (the
 * identity rotation) is the initial configuration:
 *   - a free root: MobilizedBody::Free on the ground (q = quaternion and
 *     position: the body's pose);
 *   - revolute3d: Pin about the joint's axis (the mobilizer frames' common
 *     Z) at the joint's point; spherical: Ball at it; weld: Weld;
 *     prismatic3d: Slider along the axis (the frames' common X);
 *   - a particle3d (a point mass, no inertia): Translation when free,
 *     Weld at the point of a spherical joint (its orientation is no
 *     coordinate).
 * Loop-closing joints are constraints: spherical → Constraint::Ball;
 * revolute3d → Ball and two ConstantAngle rows holding a's axis at 90° to
 * two directions of b normal to b's axis (libbraun's five rows); weld →
 * Constraint::Weld. Forces: UniformGravity, TwoPointLinearSpring and
 * Damper, torsion3d on a tree Pin as MobilityLinearSpring and Damper on
 * its coordinate (libbraun's θ turns b relative to a about the axis; the
 * Pin turns its child: θ = ±q). Torsion on a loop-closing joint is
 * refused with a sentence. */
#include <cmath>
#include <cstdio>
#include <cstring>

#include "cmp_simbody_model.h"

using namespace SimTK;

namespace {

Vec3 vec(const double *p)
{
    return Vec3(p[0], p[1], p[2]);
}

Rotation rot(const double *quat)
{
    return Rotation(Quaternion(quat[0], quat[1], quat[2], quat[3]));
}

/* Body b's initial orientation (the ground's for b = -1). */
Rotation orientation(const cmp_mech3 *m, int b)
{
    return b < 0 ? Rotation(0.0, ZAxis) : rot(m->bodies[b].quat);
}

/* A tree joint's mobilizer frame M on the child (at the child's point):
 * a Pin's Z along the axis; the body's orientation otherwise. (The
 * identity as a zero turn: GCC 12 warns on Rotation()'s inlined body.) */
Rotation m_frame(const cmp_joint3 *J, const double *axis_child)
{
    if (J->kind == CMP_J3_REVOLUTE) return Rotation(UnitVec3(vec(axis_child)), ZAxis);
    if (J->kind == CMP_J3_PRISMATIC) return Rotation(UnitVec3(vec(axis_child)), XAxis);
    return Rotation(0.0, ZAxis);
}

/* Where M and F sit: the joint's points, or for a slider the child's
 * origin and the parent's point there at the start. */
void m_f_origins(const cmp_mech3 *m, int b, const cmp_joint3 *J, Vec3 &oM, Vec3 &oF)
{
    const cmp_body3 *B = &m->bodies[b];
    const double *pc, *ac, *pp, *ap;
    cmp_joint3_side(J, b, &pc, &ac);
    cmp_joint3_side(J, B->parent, &pp, &ap);
    if (J->kind != CMP_J3_PRISMATIC) {
        oM = vec(pc);
        oF = vec(pp);
        return;
    }
    oM = Vec3(0);
    if (B->parent < 0) {
        oF = vec(B->pos);
        return;
    }
    const cmp_body3 *P = &m->bodies[B->parent];
    oF = ~rot(P->quat) * (vec(B->pos) - vec(P->pos));
}

/* Two unit directions normal to u. */
void normals(const Vec3 &u, Vec3 &n1, Vec3 &n2)
{
    const UnitVec3 uu(u);
    const UnitVec3 p = uu.perp();
    n1 = Vec3(p[0], p[1], p[2]);
    n2 = cross(Vec3(uu[0], uu[1], uu[2]), n1);
}

void add_mobilizer(cmp_sb::Model &M, const cmp_mech3 *m, int b)
{
    const cmp_body3 *B = &m->bodies[b];
    const double *I = B->inertia;
    const Inertia inertia = B->point_mass ? Inertia(0) : Inertia(I[0], I[1], I[2], I[3], I[4], I[5]);
    const Body::Rigid info(MassProperties(B->mass, Vec3(0), inertia));
    MobilizedBody &parent = M.body(B->parent);
    if (B->joint < 0) {
        if (B->point_mass) M.mob[(size_t)b] = MobilizedBody::Translation(parent, info);
        else M.mob[(size_t)b] = MobilizedBody::Free(parent, Transform(), info, Transform());
        return;
    }
    const cmp_joint3 *J = &m->joints[B->joint];
    const double *pc, *ac;
    cmp_joint3_side(J, b, &pc, &ac);
    /* M on the child at its point; F on the parent at its point, with M's
     * initial orientation (R_PF = R_Pᵀ R_C R_CM): X_FM = identity at q = 0. */
    const Rotation R_CM = m_frame(J, ac);
    const Rotation R_PF = ~orientation(m, B->parent) * orientation(m, b) * R_CM;
    Vec3 oM, oF;
    m_f_origins(m, b, J, oM, oF);
    const Transform X_BM(R_CM, oM), X_PF(R_PF, oF);
    if (J->kind == CMP_J3_REVOLUTE) M.mob[(size_t)b] = MobilizedBody::Pin(parent, X_PF, info, X_BM);
    else if (J->kind == CMP_J3_PRISMATIC) M.mob[(size_t)b] = MobilizedBody::Slider(parent, X_PF, info, X_BM);
    else if (J->kind == CMP_J3_SPHERICAL && !B->point_mass)
        M.mob[(size_t)b] = MobilizedBody::Ball(parent, X_PF, info, X_BM);
    else M.mob[(size_t)b] = MobilizedBody::Weld(parent, X_PF, info, X_BM);
}

/* q, u of body b's mobilizer from the initial poses. */
void set_initial(cmp_sb::Model &M, const cmp_mech3 *m, int b, State &s)
{
    const cmp_body3 *B = &m->bodies[b];
    const MobilizedBody &mb = M.mob[(size_t)b];
    if (B->joint < 0 && B->point_mass) {
        mb.setQToFitTranslation(s, vec(B->pos));
        mb.setUToFitLinearVelocity(s, vec(B->vel));
        return;
    }
    if (B->joint < 0) {
        mb.setQToFitTransform(s, Transform(rot(B->quat), vec(B->pos)));
        mb.setUToFitVelocity(s, SpatialVec(vec(B->omega), vec(B->vel)));
        return;
    }
    const cmp_joint3 *J = &m->joints[B->joint];
    if (J->kind == CMP_J3_WELD || B->point_mass) return;
    mb.setQToFitTransform(s, Transform());
    /* ω (or a slider's velocity) of M in F, in F (= the child's M frame at
     * q = 0). */
    const double *pc, *ac;
    cmp_joint3_side(J, b, &pc, &ac);
    const Rotation R_F = orientation(m, b) * m_frame(J, ac);
    if (J->kind == CMP_J3_PRISMATIC) {
        double vp[3];
        cmp_sb::H->mech3_velocity0(m, B->parent, B->pos, vp);
        mb.setUToFitLinearVelocity(s, ~R_F * (vec(B->vel) - vec(vp)));
        return;
    }
    const Vec3 wp = B->parent >= 0 ? vec(m->bodies[B->parent].omega) : Vec3(0);
    mb.setUToFitAngularVelocity(s, ~R_F * (vec(B->omega) - wp));
}

} // namespace

namespace cmp_sb {

int spatial_prepare(cmp_mech3 *m, char *why, size_t whysize)
{
    if (H->mech3_tree(m, why, whysize)) return -1;
    for (int j = 0; j < m->njoints; j++)
        if (!m->joints[j].tree && m->joints[j].kind == CMP_J3_PRISMATIC) {
            std::snprintf(why, whysize, "Simbody: prismatic joint '%s' closes a loop (not translated)",
                          m->joints[j].name);
            return -1;
        }
    for (int i = 0; i < m->nforces; i++)
        if (m->forces[i].kind == CMP_F3_TORSION && !m->joints[m->forces[i].joint].tree) {
            std::snprintf(why, whysize,
                          "Simbody: a torsion spring-damper on joint '%s', which closes a loop "
                          "(MobilityLinearSpring needs a mobilizer's coordinate)",
                          m->joints[m->forces[i].joint].name);
            return -1;
        }
    return 0;
}

void spatial_build(Model &M, bool ball_only)
{
    const cmp_mech3 *m = M.mech->spatial;
    const int nb = m->nbodies;
    M.mob.assign((size_t)nb, MobilizedBody());
    M.mid.assign((size_t)nb, MobilizedBody());
    std::vector<int> order((size_t)nb + 1);
    H->mech3_order(m, order.data());
    for (int k = 0; k < nb; k++) add_mobilizer(M, m, order[(size_t)k]);
    for (int j = 0; j < m->njoints; j++) {
        const cmp_joint3 *J = &m->joints[j];
        if (J->tree) continue;
        if (J->kind == CMP_J3_WELD) {
            /* Frames at the joint's points with the bodies' initial relative
             * orientation. */
            const Rotation R_ab = ~orientation(m, J->a) * orientation(m, J->b);
            Constraint::Weld(M.body(J->a), Transform(R_ab, vec(J->pa)), M.body(J->b),
                             Transform(vec(J->pb)));
            continue;
        }
        Constraint::Ball(M.body(J->a), vec(J->pa), M.body(J->b), vec(J->pb));
        if (J->kind == CMP_J3_REVOLUTE && !ball_only) {
            Vec3 n1, n2;
            normals(vec(J->axis_b), n1, n2);
            Constraint::ConstantAngle(M.body(J->a), UnitVec3(vec(J->axis)), M.body(J->b), UnitVec3(n1));
            Constraint::ConstantAngle(M.body(J->a), UnitVec3(vec(J->axis)), M.body(J->b), UnitVec3(n2));
        }
    }
    for (int i = 0; i < m->nforces; i++) {
        const cmp_force3 *F = &m->forces[i];
        if (F->kind == CMP_F3_GRAVITY) {
            Force::UniformGravity(M.forces, M.matter, vec(F->g));
        } else if (F->kind == CMP_F3_SPRING) {
            if (F->k != 0)
                Force::TwoPointLinearSpring(M.forces, M.body(F->a), vec(F->pa), M.body(F->b),
                                            vec(F->pb), F->k, F->rest);
            if (F->c != 0)
                Force::TwoPointLinearDamper(M.forces, M.body(F->a), vec(F->pa), M.body(F->b),
                                            vec(F->pb), F->c);
        } else if (F->kind == CMP_F3_TORSION) {
            const cmp_joint3 *J = &m->joints[F->joint];
            /* the Pin's child: the body whose tree joint this is */
            const int child = J->b >= 0 && m->bodies[J->b].joint == F->joint ? J->b : J->a;
            const double sign = child == J->b ? 1 : -1;
            if (F->k != 0)
                Force::MobilityLinearSpring(M.forces, M.mob[(size_t)child], MobilizerQIndex(0), F->k,
                                            sign * F->rest);
            if (F->c != 0)
                Force::MobilityLinearDamper(M.forces, M.mob[(size_t)child], MobilizerUIndex(0), F->c);
        }
    }
    M.state = M.system.realizeTopology();
    for (int b = 0; b < nb; b++) set_initial(M, m, b, M.state);
    M.system.realize(M.state, Stage::Velocity);
}

void spatial_seed(const cmp_mech3 *m, double *q)
{
    for (int b = 0; b < m->nbodies; b++)
        if (!m->bodies[b].point_mass)
            for (int k = 0; k < 4; k++) q[m->bodies[b].iq + 3 + k] = m->bodies[b].quat[k];
}

void spatial_sample(const Model &M, const State &s, double *pose, double *q, double *v)
{
    const cmp_mech3 *m = M.mech->spatial;
    for (int b = 0; b < m->nbodies; b++) {
        const MobilizedBody &mb = M.mob[(size_t)b];
        const Transform &X = mb.getBodyTransform(s);
        const Vec4 quat = X.R().convertRotationToQuaternion().asVec4();
        const Vec3 &vo = mb.getBodyOriginVelocity(s), &w = mb.getBodyAngularVelocity(s);
        double *p = pose + 13 * b;
        for (int k = 0; k < 3; k++) {
            p[k] = X.p()[k];
            p[7 + k] = vo[k];
            p[10 + k] = w[k];
        }
        for (int k = 0; k < 4; k++) p[3 + k] = quat[k];
    }
    H->mech3_state(m, pose, q, v);
}

} // namespace cmp_sb
