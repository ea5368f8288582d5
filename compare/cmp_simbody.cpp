/* simbody: Simbody 3.7 (Debian libsimbody-dev) through its C++ API, on a
 * multibody model built from the target's mechanism (cmp_mech.h). Simbody
 * has no C API, so this one file is C++; it never links into libbraun.a,
 * nor into the harness: it is the plugin $(BUILD)/lib/cmp_simbody.so that
 * compare/cmp_simbody_host.c loads (cmp_simbody_plugin.h says why) and it
 * calls the harness only through the host's table H. docs/compare.md,
 * "Simbody", has the measurements.
 *
 * The model is what a Simbody user writes for a planar mechanism: the
 * spanning tree of cmp_mech_tree as mobilizers (Simbody's coordinates are
 * joint coordinates), all of them about or along the world's Z, so that
 * the motion stays in the x-y plane:
 *   - a free rigid root: MobilizedBody::Planar (q = θ, x, y); a free point
 *     mass: MobilizedBody::Translation (its z coordinate is never forced);
 *   - a revolute tree joint: Pin at the joint's point (q = θ_child −
 *     θ_parent); a point mass pinned to its parent has no freedom of its
 *     own: Weld;
 *   - a slider tree joint: Slider along the line (q = the point's abscissa
 *     on it); a rigid child turns about its point as well: Slider to a
 *     massless frame (Body::Massless), then Pin;
 *   - a distance tree joint: Pin at the parent's point swinging the child
 *     at the joint's length; a rigid child turns about its own point too:
 *     Pin to a massless arm, then Pin at the arm's end.
 * Loop-closing joints are constraints: revolute → two Constraint::
 * PointInPlane rows (the planar x and y of the pin; the variant "ball" uses
 * Constraint::Ball, whose third row is identically zero in the plane),
 * distance → Constraint::Rod, slider → Constraint::PointInPlane with the
 * line's normal, knife edge → Constraint::NoSlip1D (the blade's point on the
 * body, sideways direction, body against ground). An angle joint on a
 * revolute tree joint (fixed or driven linearly in time: what cmp_mech_tree
 * accepts) is a prescribed Motion::Custom of the Pin's angle. Forces:
 * Force::UniformGravity, Force::TwoPointLinearSpring and TwoPointLinear-
 * Damper, torsion on a tree hinge as MobilityLinearSpring and Mobility-
 * LinearDamper, the motor law τ = τ0(1 − (ω_a − ω_b)/ω0) as a Force::Custom.
 *
 * A run sets the mobilizers' q, u from the links' initial poses (so the
 * Simbody state maps back to the target's q0, v0: tests/compare/
 * test_simbody.c), lets Integrator::initialize() realize it (it projects:
 * how far it moved is in the outcome's detail when it is not negligible),
 * and steps to each grid time t_j = j·dt_out with stepTo. Interpolated
 * reports are off by default (Simbody interpolates report states with a
 * cubic Hermite polynomial, which at loose accuracy is worse than the
 * integrator: its best chance is to step to each report time); the
 * variant words (any order) change the defaults:
 *   "interp"      setAllowInterpolation(true)  (Simbody's default)
 *   "every-step"  setProjectEveryStep(true)
 *   "inf-norm"    setUseInfinityNorm(true)
 *   "ball"        loop-closing revolute joints as Constraint::Ball
 * Accuracy: spec.rtol (0: Simbody's 1e-3); constraint tolerance:
 * spec.peer.ctol (0: Simbody's default, accuracy/10). The fixed step
 * CMP_SB_RKM_FIXED is Runge–Kutta–Merson with setFixedStepSize(spec.h);
 * it reports at its steps (every cmp_every(dt_out, h)-th, as MuJoCo's and
 * braun's fixed steps): stepTo a grid time that is not a multiple of h
 * shortens the step that lands on it (h = 0.02 on the 0.05 s grid took
 * steps of 0.02, 0.02, 0.01: 1200 steps over 20 s, not 1000).
 *
 * A run fails (a recorded row, the trajectory kept up to the last good
 * sample) on any Simbody exception (an integrator step failure arrives as
 * Integrator::StepFailed: its message is kept), a non-finite state, a
 * termination reason other than reaching the final time, or more than
 * SB_MAX_STEPS steps in one output interval (SB_TOO_MUCH_WORK). */
#include "cmp_simbody_model.h"
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <Simbody.h>

using namespace SimTK;

namespace cmp_sb {
const cmp_sb_host *H;
}

namespace {

using cmp_sb::H;
using cmp_sb::Model;

/* Loop-closing joints Simbody can express (angle joints are handled on the
 * tree hinge, as cmp_mech_tree requires). */
const unsigned SB_CLOSABLE = CMP_MJ_BIT(CMP_MJ_REVOLUTE) | CMP_MJ_BIT(CMP_MJ_DISTANCE) |
                             CMP_MJ_BIT(CMP_MJ_SLIDER) | CMP_MJ_BIT(CMP_MJ_KNIFE);

/* Steps one output interval may take (IDA's limit in the harness too);
 * beyond, the run fails as SB_TOO_MUCH_WORK: near a singular configuration
 * an error-controlled step can shrink to where its error estimate rounds
 * to zero and grind on without end. */
const int SB_MAX_STEPS = 5000;

/* The variant's words. */
struct sb_options {
    bool interp = false, every_step = false, inf_norm = false, ball = false;
};

sb_options parse_variant(const char *variant)
{
    sb_options o;
    o.interp = std::strstr(variant, "interp") != nullptr;
    o.every_step = std::strstr(variant, "every-step") != nullptr;
    o.inf_norm = std::strstr(variant, "inf-norm") != nullptr;
    o.ball = std::strstr(variant, "ball") != nullptr;
    return o;
}

/* ------------------------------------------------------------ geometry */
/* Pose of link l (-1: ground) at the initial state. */
void link_pose(const cmp_mech *m, int l, double *x, double *y, double *th)
{
    if (l < 0) {
        *x = *y = *th = 0;
        return;
    }
    *x = m->links[l].x;
    *y = m->links[l].y;
    *th = m->links[l].th;
}

/* World position of point p of link l at the initial state. */
void world_point(const cmp_mech *m, int l, const double *p, double *P)
{
    double x, y, th;
    link_pose(m, l, &x, &y, &th);
    const double c = std::cos(th), s = std::sin(th);
    P[0] = x + c * p[0] - s * p[1];
    P[1] = y + s * p[0] + c * p[1];
}

/* Velocity of link l's material point at world position P (initial). */
void world_velocity(const cmp_mech *m, int l, const double *P, double *v)
{
    if (l < 0) {
        v[0] = v[1] = 0;
        return;
    }
    const cmp_link *L = &m->links[l];
    v[0] = L->vx - L->w * (P[1] - L->y);
    v[1] = L->vy + L->w * (P[0] - L->x);
}

double link_omega(const cmp_mech *m, int l)
{
    return l < 0 ? 0 : m->links[l].w;
}

/* The tree joint of link l: its point on l and on the parent. */
void tree_points(const cmp_mech *m, int l, double *pc, double *pp)
{
    const cmp_mjoint *J = &m->joints[m->links[l].joint];
    const int child_is_a = l == J->a;
    std::memcpy(pc, child_is_a ? J->pa : J->pb, 2 * sizeof(double));
    std::memcpy(pp, child_is_a ? J->pb : J->pa, 2 * sizeof(double));
}

Vec3 v3(const double *p)
{
    return Vec3(p[0], p[1], 0);
}

Transform frame(double angle, const double *p)
{
    return Transform(Rotation(angle, ZAxis), v3(p));
}

/* ------------------------------------------------------------ elements */
/* A prescribed angle of a Pin: q(t) = sign·f(t) (angle joint θ_b − θ_a =
 * f(t); sign: the hinge's coordinate is child − parent). */
class DriveImpl : public Motion::Custom::Implementation {
public:
    DriveImpl(const braun_scene_fn &f, int sign) : f_(f), sign_(sign) {}
    Implementation *clone() const override { return new DriveImpl(*this); }
    Motion::Level getLevel(const State &) const override { return Motion::Position; }
    void calcPrescribedPosition(const State &s, int nq, Real *q) const override
    {
        eval(s.getTime(), 0, nq, q);
    }
    void calcPrescribedPositionDot(const State &s, int nq, Real *qd) const override
    {
        eval(s.getTime(), 1, nq, qd);
    }
    void calcPrescribedPositionDotDot(const State &s, int nq, Real *qdd) const override
    {
        eval(s.getTime(), 2, nq, qdd);
    }

private:
    void eval(Real t, int order, int nq, Real *out) const
    {
        braun_real v[3] = {0, 0, 0};
        H->fn_eval(&f_, (braun_real)t, &v[0], &v[1], &v[2]);
        for (int i = 0; i < nq; i++) out[i] = sign_ * (double)v[order];
    }
    braun_scene_fn f_;
    int sign_;
};

/* The motor law of libbraun's motor effect: τ = τ0 (1 − (ω_a − ω_b)/ω0) on
 * the rotor a, −τ on the stator b (either may be the ground). */
class MotorImpl : public Force::Custom::Implementation {
public:
    MotorImpl(const MobilizedBody &a, const MobilizedBody &b, double tau0, double omega0)
        : a_(a), b_(b), tau0_(tau0), omega0_(omega0)
    {
    }
    void calcForce(const State &s, Vector_<SpatialVec> &bodyForces, Vector_<Vec3> &,
                   Vector &) const override
    {
        const Real wa = a_.getBodyAngularVelocity(s)[2], wb = b_.getBodyAngularVelocity(s)[2];
        const Real tau = tau0_ * (1 - (wa - wb) / omega0_);
        bodyForces[a_.getMobilizedBodyIndex()][0][2] += tau;
        bodyForces[b_.getMobilizedBodyIndex()][0][2] -= tau;
    }
    Real calcPotentialEnergy(const State &) const override { return 0; }

private:
    MobilizedBody a_, b_;
    double tau0_, omega0_;
};

/* An applied torque of time (scene effect "torque"): τ(t) on a, −τ on b. */
class TorqueImpl : public Force::Custom::Implementation {
public:
    TorqueImpl(const MobilizedBody &a, const MobilizedBody &b, const braun_scene_fn &f)
        : a_(a), b_(b), f_(f)
    {
    }
    void calcForce(const State &s, Vector_<SpatialVec> &bodyForces, Vector_<Vec3> &,
                   Vector &) const override
    {
        braun_real tau = 0;
        H->fn_eval(&f_, (braun_real)s.getTime(), &tau, nullptr, nullptr);
        bodyForces[a_.getMobilizedBodyIndex()][0][2] += (double)tau;
        bodyForces[b_.getMobilizedBodyIndex()][0][2] -= (double)tau;
    }
    Real calcPotentialEnergy(const State &) const override { return 0; }

private:
    MobilizedBody a_, b_;
    braun_scene_fn f_;
};

/* ------------------------------------------------------------ the model */
/* The mechanism's tree, and what Simbody cannot take. 0, or -1 with why. */
int prepare(cmp_mech *m, char *why, size_t whysize)
{
    if (H->mech_tree(m, SB_CLOSABLE, "Simbody 3.7", why, whysize)) return -1;
    for (int i = 0; i < m->nforces; i++) {
        const cmp_mforce *F = &m->forces[i];
        int child, sign;
        if (F->kind == CMP_MF_TORSION && H->mech_hinge(m, F->a, F->b, &child, &sign) < 0) {
            std::snprintf(why, whysize,
                          "Simbody: a torsion spring-damper not on a revolute joint of the tree "
                          "(MobilityLinearSpring needs the hinge's coordinate)");
            return -1;
        }
        if (F->kind == CMP_MF_MOTOR && !(F->omega0 != 0)) {
            std::snprintf(why, whysize, "Simbody: a motor with no-load speed 0");
            return -1;
        }
    }
    for (int j = 0; j < m->njoints; j++) {
        const cmp_mjoint *J = &m->joints[j];
        if (J->kind == CMP_MJ_KNIFE && J->a < 0) {
            std::snprintf(why, whysize, "Simbody: knife edge '%s' is on the ground", J->name);
            return -1;
        }
    }
    return 0;
}

MassProperties mass_of(const cmp_link *L)
{
    /* A point mass: no rotational inertia (its mobilizers never rotate it
     * alone); a planar link: Izz as given, the same about x and y so that
     * the inertia is physically valid (they never act in the plane). */
    const double I = L->point_mass || !(L->inertia > 0) ? 0 : L->inertia;
    return MassProperties(L->mass, Vec3(0), Inertia(I));
}


/* What a tree joint's mobilizers need from the initial state: a slider's
 * direction α (in the parent's frame), its coordinate and rate; a
 * distance's direction φ (world) from the parent's point to the child's and
 * its angular rate. */
struct tree_geom {
    double alpha = 0, qs = 0, us = 0;
    double phi = 0, arm = 0;
};

tree_geom geometry(const cmp_mech *m, int l)
{
    tree_geom g;
    const cmp_link *L = &m->links[l];
    if (L->joint < 0) return g;
    const cmp_mjoint *J = &m->joints[L->joint];
    const int p = L->parent;
    double pc[2], pp[2], P0[2], Pc[2], v0[2], vc[2], xp, yp, thp;
    tree_points(m, l, pc, pp);
    link_pose(m, p, &xp, &yp, &thp);
    world_point(m, p, pp, P0);
    world_point(m, l, pc, Pc);
    world_velocity(m, p, P0, v0);
    world_velocity(m, l, Pc, vc);
    const double dx = Pc[0] - P0[0], dy = Pc[1] - P0[1];
    if (J->kind == CMP_MJ_SLIDER) {
        /* q = (P_a − O_F)·e; its rate (Ṗ_a − Ȯ_F)·e, the term (P_a − O_F)·ė
         * vanishing on the line. */
        g.alpha = std::atan2(J->axis[1], J->axis[0]);
        const double e[2] = {std::cos(thp + g.alpha), std::sin(thp + g.alpha)};
        g.qs = dx * e[0] + dy * e[1];
        g.us = (vc[0] - v0[0]) * e[0] + (vc[1] - v0[1]) * e[1];
    } else if (J->kind == CMP_MJ_DISTANCE) {
        g.phi = std::atan2(dy, dx);
        g.arm = (dx * (vc[1] - v0[1]) - dy * (vc[0] - v0[0])) / (dx * dx + dy * dy);
    }
    return g;
}

/* The mobilizer(s) of link l, its parent's already built. */
void add_mobilizer(Model &M, int l)
{
    const cmp_mech *m = M.mech;
    const cmp_link *L = &m->links[l];
    const Body::Rigid info(mass_of(L));
    MobilizedBody &parent = M.body(L->parent);
    if (L->joint < 0) {
        /* A free root: world x, y (and θ) as its coordinates. */
        if (L->point_mass) M.mob[(size_t)l] = MobilizedBody::Translation(parent, info);
        else M.mob[(size_t)l] = MobilizedBody::Planar(parent, info);
        return;
    }
    const cmp_mjoint *J = &m->joints[L->joint];
    const tree_geom g = geometry(m, l);
    double pc[2], pp[2];
    tree_points(m, l, pc, pp);
    if (J->kind == CMP_MJ_REVOLUTE) {
        if (L->point_mass) M.mob[(size_t)l] = MobilizedBody::Weld(parent, frame(0, pp), info, frame(0, pc));
        else M.mob[(size_t)l] = MobilizedBody::Pin(parent, frame(0, pp), info, frame(0, pc));
    } else if (J->kind == CMP_MJ_SLIDER) {
        /* F at the line's point of the parent, its x along the line. */
        if (L->point_mass) {
            M.mob[(size_t)l] = MobilizedBody::Slider(parent, frame(g.alpha, pp), info, frame(0, pc));
        } else {
            MobilizedBody::Slider S(parent, frame(g.alpha, pp), Body::Massless(), Transform());
            M.mid[(size_t)l] = S;
            M.mob[(size_t)l] = MobilizedBody::Pin(S, Transform(), info, frame(0, pc));
        }
    } else {
        /* Distance: the pivot at the parent's point; the child's point at
         * the joint's length from it. */
        if (L->point_mass) {
            /* B's frame at the mass (point pc), M at the pivot. */
            const double c = std::cos(g.phi - L->th), s = std::sin(g.phi - L->th);
            const double piv[2] = {pc[0] - J->length * c, pc[1] - J->length * s};
            M.mob[(size_t)l] = MobilizedBody::Pin(parent, frame(0, pp), info, frame(0, piv));
        } else {
            const double end[2] = {J->length, 0};
            MobilizedBody::Pin S(parent, frame(0, pp), Body::Massless(), Transform());
            M.mid[(size_t)l] = S;
            M.mob[(size_t)l] = MobilizedBody::Pin(S, frame(0, end), info, frame(0, pc));
        }
    }
}

/* q, u of link l's mobilizer(s) in s from the links' initial poses:
 * analytic, so that the state maps back to q0, v0 to rounding. */
void set_initial(Model &M, int l, State &s)
{
    const cmp_mech *m = M.mech;
    const cmp_link *L = &m->links[l];
    const MobilizedBody &b = M.mob[(size_t)l];
    if (L->joint < 0) {
        const double q[3] = {L->point_mass ? L->x : L->th, L->point_mass ? L->y : L->x,
                             L->point_mass ? 0 : L->y};
        const double u[3] = {L->point_mass ? L->vx : L->w, L->point_mass ? L->vy : L->vx,
                             L->point_mass ? 0 : L->vy};
        for (int i = 0; i < 3; i++) {
            b.setOneQ(s, i, q[i]);
            b.setOneU(s, i, u[i]);
        }
        return;
    }
    const cmp_mjoint *J = &m->joints[L->joint];
    const tree_geom g = geometry(m, l);
    double xp, yp, thp;
    link_pose(m, L->parent, &xp, &yp, &thp);
    const double wp = link_omega(m, L->parent);
    if (J->kind == CMP_MJ_REVOLUTE) {
        if (L->point_mass) return; /* Weld */
        b.setOneQ(s, 0, L->th - thp);
        b.setOneU(s, 0, L->w - wp);
    } else if (J->kind == CMP_MJ_SLIDER) {
        const MobilizedBody &S = L->point_mass ? b : M.mid[(size_t)l];
        S.setOneQ(s, 0, g.qs);
        S.setOneU(s, 0, g.us);
        if (!L->point_mass) {
            b.setOneQ(s, 0, L->th - thp - g.alpha);
            b.setOneU(s, 0, L->w - wp);
        }
    } else if (L->point_mass) {
        b.setOneQ(s, 0, L->th - thp);
        b.setOneU(s, 0, g.arm - wp);
    } else {
        const MobilizedBody &S = M.mid[(size_t)l];
        S.setOneQ(s, 0, g.phi - thp);
        S.setOneU(s, 0, g.arm - wp);
        b.setOneQ(s, 0, L->th - g.phi);
        b.setOneU(s, 0, L->w - g.arm);
    }
}

/* The loop-closing joints and angle joints. */
void add_constraints(Model &M, const sb_options &o)
{
    cmp_mech *m = M.mech;
    for (int j = 0; j < m->njoints; j++) {
        const cmp_mjoint *J = &m->joints[j];
        if (J->tree) continue;
        if (J->kind == CMP_MJ_REVOLUTE) {
            if (o.ball) {
                Constraint::Ball(M.body(J->a), v3(J->pa), M.body(J->b), v3(J->pb));
            } else {
                /* The planar rows: P_b − O_a along a's x and y is p_a. */
                Constraint::PointInPlane(M.body(J->a), UnitVec3(XAxis), J->pa[0], M.body(J->b),
                                         v3(J->pb));
                Constraint::PointInPlane(M.body(J->a), UnitVec3(YAxis), J->pa[1], M.body(J->b),
                                         v3(J->pb));
            }
        } else if (J->kind == CMP_MJ_DISTANCE) {
            Constraint::Rod(M.body(J->a), v3(J->pa), M.body(J->b), v3(J->pb), J->length);
        } else if (J->kind == CMP_MJ_SLIDER) {
            /* P_a on the line through p_b along b's axis: n·P_a = n·p_b. */
            const double n[2] = {-J->axis[1], J->axis[0]};
            Constraint::PointInPlane(M.body(J->b), UnitVec3(v3(n)),
                                     n[0] * J->pb[0] + n[1] * J->pb[1], M.body(J->a), v3(J->pa));
        } else if (J->kind == CMP_MJ_KNIFE) {
            /* The blade's point has no velocity along the blade's normal
             * relative to the ground. */
            const double n[2] = {-J->axis[1], J->axis[0]};
            Constraint::NoSlip1D(M.body(J->a), v3(J->pa), UnitVec3(v3(n)), M.body(J->a),
                                 M.matter.updGround());
        } else if (J->kind == CMP_MJ_ANGLE) {
            int child, sign;
            if (H->mech_hinge(m, J->a, J->b, &child, &sign) < 0) continue; /* refused in prepare */
            braun_scene_fn f = J->drive;
            if (!J->driven) {
                std::memset(&f, 0, sizeof f);
                f.kind = BRAUN_FN_CONSTANT;
                f.a = (braun_real)J->value;
            }
            Motion::Custom(M.mob[(size_t)child], new DriveImpl(f, sign));
        }
    }
}

void add_forces(Model &M)
{
    cmp_mech *m = M.mech;
    for (int i = 0; i < m->nforces; i++) {
        const cmp_mforce *F = &m->forces[i];
        if (F->kind == CMP_MF_GRAVITY) {
            Force::UniformGravity(M.forces, M.matter, Vec3(F->g[0], F->g[1], 0));
        } else if (F->kind == CMP_MF_SPRING) {
            if (F->k != 0)
                Force::TwoPointLinearSpring(M.forces, M.body(F->a), v3(F->pa), M.body(F->b),
                                            v3(F->pb), F->k, F->rest);
            if (F->c != 0)
                Force::TwoPointLinearDamper(M.forces, M.body(F->a), v3(F->pa), M.body(F->b),
                                            v3(F->pb), F->c);
        } else if (F->kind == CMP_MF_TORSION) {
            /* On the hinge's coordinate q = sign·(θ_b − θ_a): the generalized
             * force −k(q − sign·rest) − c q'. */
            int child, sign;
            if (H->mech_hinge(m, F->a, F->b, &child, &sign) < 0) continue; /* refused in prepare */
            if (F->k != 0)
                Force::MobilityLinearSpring(M.forces, M.mob[(size_t)child], MobilizerQIndex(0),
                                            F->k, sign * F->rest);
            if (F->c != 0)
                Force::MobilityLinearDamper(M.forces, M.mob[(size_t)child], MobilizerUIndex(0),
                                            F->c);
        } else if (F->kind == CMP_MF_MOTOR) {
            Force::Custom(M.forces, new MotorImpl(M.body(F->a), M.body(F->b), F->tau0, F->omega0));
        } else if (F->kind == CMP_MF_TORQUE) {
            Force::Custom(M.forces, new TorqueImpl(M.body(F->a), M.body(F->b), F->f));
        }
    }
}

/* The whole model of a target and its initial state (realized through
 * Velocity). Returns nullptr with why when Simbody cannot express it;
 * throws on Simbody's own errors. */
std::unique_ptr<Model> make_model(cmp_mech *m, const sb_options &o, char *why, size_t whysize)
{
    if (m->spatial) {
        if (cmp_sb::spatial_prepare(m->spatial, why, whysize)) return nullptr;
        std::unique_ptr<Model> M(new Model(m));
        cmp_sb::spatial_build(*M, o.ball);
        return M;
    }
    if (prepare(m, why, whysize)) return nullptr;
    std::unique_ptr<Model> M(new Model(m));
    const int nl = m->nlinks;
    M->mob.assign((size_t)nl, MobilizedBody());
    M->mid.assign((size_t)nl, MobilizedBody());
    std::vector<int> order((size_t)nl + 1);
    H->mech_order(m, order.data());
    for (int k = 0; k < nl; k++) add_mobilizer(*M, order[(size_t)k]);
    add_constraints(*M, o);
    add_forces(*M);
    M->state = M->system.realizeTopology();
    for (int l = 0; l < nl; l++) set_initial(*M, l, M->state);
    M->system.realize(M->state, Stage::Velocity);
    return M;
}

/* Link l's angle from the mobilizers' coordinates down the tree: the same
 * angle as its rotation matrix gives, but continuous (no 2π ambiguity
 * between samples, however fast a link turns). */
double link_angle(const Model &M, const State &s, int l)
{
    const cmp_mech *m = M.mech;
    const cmp_link *L = &m->links[l];
    if (L->joint < 0) return L->point_mass ? 0 : M.mob[(size_t)l].getOneQ(s, 0);
    const double thp = L->parent < 0 ? 0 : link_angle(M, s, L->parent);
    const cmp_mjoint *J = &m->joints[L->joint];
    const MobilizedBody &b = M.mob[(size_t)l];
    if (J->kind == CMP_MJ_REVOLUTE) return L->point_mass ? thp : thp + b.getOneQ(s, 0);
    if (J->kind == CMP_MJ_SLIDER) {
        const double alpha = std::atan2(J->axis[1], J->axis[0]);
        return thp + alpha + (L->point_mass ? 0 : b.getOneQ(s, 0));
    }
    if (L->point_mass) return thp + b.getOneQ(s, 0);
    return thp + M.mid[(size_t)l].getOneQ(s, 0) + b.getOneQ(s, 0);
}

/* Link poses (x, y, θ, vx, vy, ω of each centre of mass) from a state
 * realized through Velocity (planar mechanisms). */
void poses_of(const Model &M, const State &s, double *pose)
{
    for (int l = 0; l < M.mech->nlinks; l++) {
        const MobilizedBody &b = M.mob[(size_t)l];
        const Transform &X = b.getBodyTransform(s);
        const Vec3 &v = b.getBodyOriginVelocity(s);
        double *p = pose + 6 * l;
        p[0] = X.p()[0];
        p[1] = X.p()[1];
        p[2] = link_angle(M, s, l);
        p[3] = v[0];
        p[4] = v[1];
        p[5] = b.getBodyAngularVelocity(s)[2];
    }
}

/* The poses sample() needs as scratch: 6 per link, 13 per spatial body. */
size_t pose_size(const cmp_mech *m)
{
    return (m->spatial ? 13 * (size_t)m->spatial->nbodies : 6 * (size_t)m->nlinks) + 1;
}

/* libbraun's q, v from a state realized through Velocity; pose: scratch of
 * pose_size(M.mech). */
void sample(const Model &M, const State &s, double *pose, double *q, double *v)
{
    if (M.mech->spatial) {
        cmp_sb::spatial_sample(M, s, pose, q, v);
        return;
    }
    poses_of(M, s, pose);
    H->mech_state(M.mech, pose, q, v);
}

std::unique_ptr<Integrator> make_integrator(const Model &M, const cmp_spec *sp,
                                            const sb_options &o, char *why, size_t whysize)
{
    std::unique_ptr<Integrator> in;
    switch (sp->integrator) {
    case CMP_SB_RKM:
    case CMP_SB_RKM_FIXED: in.reset(new RungeKuttaMersonIntegrator(M.system)); break;
    case CMP_SB_RKF: in.reset(new RungeKuttaFeldbergIntegrator(M.system)); break;
    case CMP_SB_RK3: in.reset(new RungeKutta3Integrator(M.system)); break;
    case CMP_SB_CPODES: in.reset(new CPodesIntegrator(M.system, CPodes::BDF, CPodes::Newton)); break;
    default:
        std::snprintf(why, whysize, "integrator %d is not one of Simbody's", sp->integrator);
        return nullptr;
    }
    if (sp->integrator == CMP_SB_RKM_FIXED) {
        if (!(sp->h > 0)) {
            std::snprintf(why, whysize, "a fixed step needs h > 0");
            return nullptr;
        }
        in->setFixedStepSize(sp->h);
    }
    if (sp->rtol > 0) in->setAccuracy(sp->rtol);
    if (sp->peer.ctol > 0) in->setConstraintTolerance(sp->peer.ctol);
    in->setInternalStepLimit(SB_MAX_STEPS);
    in->setAllowInterpolation(o.interp);
    in->setProjectEveryStep(o.every_step);
    in->setUseInfinityNorm(o.inf_norm);
    return in;
}

/* Erase from s every piece that starts with `from` and ends with `to`
 * (inclusive); to == nullptr: just `from`. */
void erase_all(std::string &s, const char *from, const char *to)
{
    for (size_t k; (k = s.find(from)) != std::string::npos;) {
        size_t e = k + std::strlen(from);
        if (to) {
            e = s.find(to, k + std::strlen(from));
            if (e == std::string::npos) return;
            e += std::strlen(to);
        }
        s.erase(k, e - k);
    }
}

/* A Simbody exception's message on one line, short enough for a row's
 * detail: without "SimTK Exception thrown at FILE:LINE:", "Error detected
 * by Simbody method", "(Required condition ... was not met.)", and with
 * "Integrator step failed at time T apparently because:" as "step failed:"
 * (the row says when). */
std::string one_line(const char *what)
{
    std::string s(what ? what : "");
    erase_all(s, "SimTK Exception thrown at ", ":\n");
    erase_all(s, "Error detected by Simbody method ", nullptr);
    erase_all(s, "(Required condition", "was not met.)");
    for (size_t k; (k = s.find("Integrator step failed at time")) != std::string::npos;) {
        const size_t e = s.find("because:", k);
        if (e == std::string::npos) break;
        s.replace(k, e + 8 - k, "step failed:");
    }
    std::string out;
    bool space = false;
    for (char c : s) {
        const bool ws = c == '\n' || c == '\r' || c == '\t' || c == ' ';
        if (ws) {
            space = !out.empty();
            continue;
        }
        if (space) out += ' ';
        space = false;
        out += c;
    }
    return out;
}

bool finite_state(const State &s)
{
    const Vector &y = s.getY();
    for (int i = 0; i < y.size(); i++)
        if (!std::isfinite(y[i])) return false;
    return true;
}

void fill_counts(const Integrator &in, cmp_counts *k)
{
    k->steps = in.getNumStepsTaken();
    k->rejected = in.getNumStepsAttempted() - in.getNumStepsTaken();
    k->rhs_evals = in.getNumRealizations();
    k->err_fails = in.getNumErrorTestFailures();
    k->conv_fails = in.getNumConvergenceTestFailures();
    k->lin_solves = in.getNumIterations();
    k->iterations = in.getNumProjections();
}

void fail(cmp_outcome *out, const char *status, double t, const char *msg)
{
    out->status = -1;
    std::snprintf(out->status_name, sizeof out->status_name, "%s", status);
    std::snprintf(out->detail, sizeof out->detail, "at t = %.9g (%s)", t, msg);
    out->t_reached = t;
}

/* Largest change of q, u between two states (how far initialize() moved
 * the state it was given). */
double moved(const State &a, const State &b)
{
    double d = 0;
    for (int i = 0; i < a.getNQ(); i++) d = std::max(d, std::fabs(a.getQ()[i] - b.getQ()[i]));
    for (int i = 0; i < a.getNU(); i++) d = std::max(d, std::fabs(a.getU()[i] - b.getU()[i]));
    return d;
}


/* ------------------------------------------------------------ the run */
void run(cmp_mech *m, int n, const cmp_spec *sp, cmp_traj *tr, cmp_outcome *out)
{
    std::memset(out, 0, sizeof *out);
    const sb_options o = parse_variant(sp->variant);
    char why[160] = "";
    std::unique_ptr<Model> M;
    std::unique_ptr<Integrator> in;
    try {
        M = make_model(m, o, why, sizeof why);
        if (M) in = make_integrator(*M, sp, o, why, sizeof why);
    } catch (const std::exception &e) {
        fail(out, "SB_MODEL_ERROR", 0, one_line(e.what()).c_str());
        return;
    }
    if (!M || !in) {
        fail(out, "UNSUPPORTED", 0, why);
        return;
    }
    std::vector<double> pose(pose_size(m)), q((size_t)n + 1), v((size_t)n + 1);
    /* The report interval: the output grid's, or for the fixed step a
     * whole number of steps (every step if dt_out is not a multiple of h). */
    double dt = sp->dt_out;
    if (sp->integrator == CMP_SB_RKM_FIXED && sp->h > 0) {
        const double r = sp->dt_out / sp->h;
        const long k = (long)std::floor(r + 0.5);
        dt = sp->h * (double)(k >= 1 && std::fabs(r - (double)k) <= 1e-9 * r ? k : 1);
    }
    const long nout = std::max(1L, (long)std::floor(sp->T / dt + 0.5));
    double cpu = 0, t_good = 0;
    const char *status = nullptr;
    std::string msg;
    try {
        double c0 = H->cpu_seconds();
        in->initialize(M->state);
        cpu += H->cpu_seconds() - c0;
        const double dq = moved(M->state, in->getState());
        if (dq > 1e-12)
            std::snprintf(out->detail, sizeof out->detail,
                          "initialize() projected the initial state by %.3g", dq);
        if (m->spatial) cmp_sb::spatial_seed(m->spatial, q.data());
        sample(*M, in->getState(), pose.data(), q.data(), v.data());
        if (H->traj_push(tr, 0, q.data(), v.data())) throw std::bad_alloc();
        for (long j = 1; j <= nout; j++) {
            const double tj = j == nout ? sp->T : (double)j * dt;
            c0 = H->cpu_seconds();
            /* The first call after initialize() returns at once (start of
             * a continuous interval): step until the report time. */
            Integrator::SuccessfulStepStatus st = Integrator::ReachedReportTime;
            while (in->getTime() < tj && !in->isSimulationOver() &&
                   st != Integrator::ReachedStepLimit)
                st = in->stepTo(tj);
            cpu += H->cpu_seconds() - c0;
            if (st == Integrator::ReachedStepLimit) {
                status = "SB_TOO_MUCH_WORK";
                char b[96];
                std::snprintf(b, sizeof b, "%d steps without reaching t = %.9g", SB_MAX_STEPS, tj);
                msg = b;
                break;
            }
            const State &s = in->getState();
            if (in->isSimulationOver() &&
                in->getTerminationReason() != Integrator::ReachedFinalTime) {
                status = "SB_TERMINATED";
                msg = Integrator::getTerminationReasonString(in->getTerminationReason());
                break;
            }
            if (!finite_state(s)) {
                status = "DIVERGED";
                msg = "the state is not finite";
                break;
            }
            t_good = s.getTime();
            sample(*M, s, pose.data(), q.data(), v.data());
            if (H->traj_push(tr, t_good, q.data(), v.data())) throw std::bad_alloc();
        }
    } catch (const std::bad_alloc &) {
        status = "OUT_OF_MEMORY";
        msg = "out of memory";
    } catch (const std::exception &e) {
        msg = one_line(e.what());
        status = msg.find("step failed") != std::string::npos ? "SB_STEP_FAILED"
                 : tr->count == 0                             ? "SB_INIT_FAILED"
                                                              : "SB_EXCEPTION";
    }
    out->cpu_self = cpu > 0 ? cpu : 1e-9;
    fill_counts(*in, &out->counts);
    if (status) {
        /* After a failed step the integrator is back at its last good state. */
        double t = t_good;
        try {
            if (finite_state(in->getAdvancedState()))
                t = std::max(t_good, (double)in->getAdvancedTime());
        } catch (...) {
        }
        fail(out, status, t, msg.c_str());
        return;
    }
    out->t_reached = sp->T;
    std::snprintf(out->status_name, sizeof out->status_name, "OK");
}

int supports(cmp_mech *m, char *why, size_t whysize)
{
    if (m->spatial) return cmp_sb::spatial_prepare(m->spatial, why, whysize) == 0;
    return prepare(m, why, whysize) == 0;
}

const char *version_string(void)
{
    static char version[32];
    if (!version[0]) {
        int major = 0, minor = 0, build = 0;
        SimTK_version_simbody(&major, &minor, &build);
        std::snprintf(version, sizeof version, "%d.%d", major, minor);
    }
    return version;
}

int initial_state(cmp_mech *m, const cmp_spec *sp, double *q, double *v, double *moved_by,
                  char *why, size_t whysize)
{
    try {
        const sb_options o = parse_variant(sp ? sp->variant : "");
        std::unique_ptr<Model> M = make_model(m, o, why, whysize);
        if (!M) return -1;
        std::vector<double> pose(pose_size(m));
        if (m->spatial) cmp_sb::spatial_seed(m->spatial, q);
        sample(*M, M->state, pose.data(), q, v);
        if (moved_by) {
            *moved_by = NAN;
            if (sp) {
                std::unique_ptr<Integrator> in = make_integrator(*M, sp, o, why, whysize);
                if (!in) return -1;
                in->initialize(M->state);
                *moved_by = moved(M->state, in->getState());
            }
        }
        return 0;
    } catch (const std::exception &e) {
        std::snprintf(why, whysize, "%s", one_line(e.what()).c_str());
        return -1;
    }
}

double step_cost(cmp_mech *m, const cmp_spec *sp, long steps, char *why, size_t whysize)
{
    try {
        if (!(sp->h > 0) || steps < 1) {
            std::snprintf(why, whysize, "a step cost needs h > 0 and steps >= 1");
            return NAN;
        }
        const sb_options o = parse_variant(sp->variant);
        std::unique_ptr<Model> M = make_model(m, o, why, whysize);
        if (!M) return NAN;
        cmp_spec fixed = *sp;
        if (fixed.integrator == CMP_SB_RKM) fixed.integrator = CMP_SB_RKM_FIXED;
        std::unique_ptr<Integrator> in = make_integrator(*M, &fixed, o, why, whysize);
        if (!in) return NAN;
        in->setFixedStepSize(sp->h);
        in->setAllowInterpolation(false);
        in->initialize(M->state);
        const double c0 = H->cpu_seconds();
        for (long k = 1; k <= steps; k++) {
            const double t = (double)k * sp->h;
            while (in->getTime() < t) in->stepTo(t);
        }
        return (H->cpu_seconds() - c0) / (double)steps;
    } catch (const std::exception &e) {
        std::snprintf(why, whysize, "%s", one_line(e.what()).c_str());
        return NAN;
    }
}

const cmp_sb_plugin table = {
    CMP_SB_PLUGIN_VERSION, version_string, supports, run, initial_state, step_cost,
};

} // namespace

extern "C" __attribute__((visibility("default"))) const cmp_sb_plugin *
cmp_simbody_plugin_v2(const cmp_sb_host *host)
{
    if (!host || host->version != CMP_SB_PLUGIN_VERSION) return nullptr;
    cmp_sb::H = host;
    return &table;
}
