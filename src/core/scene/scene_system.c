/* The braun_system callbacks of a built scene: each loops over the
 * elements that contribute to it, and only those. M is assembled from
 * bodies and rods (called once: the scene sets BRAUN_MASS_CONSTANT);
 * Q from the effects; the rows from rods, joints and knife edges; the
 * energy law (Eq. 18) from kinetic energy, gravity and springs; the input
 * power from dampers, forces, torques and motors. */
#include "scene_internal.h"

int braun_scene__mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const braun_scene *s = user;
    const int n = s->n;
    (void)t;
    (void)q;
    for (size_t i = 0; i < braun_scene__at(n, 0, n); i++) M[i] = 0;
    for (int k = 0; k < s->nbodies; k++) braun_scene__body_mass(s, &s->bodies[k], M);
    for (int k = 0; k < s->nrods; k++) braun_scene__rod_mass(s, &s->rods[k], M);
    return 0;
}

int braun_scene__forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                        void *user)
{
    const braun_scene *s = user;
    /* Absolute and natural coordinates with a constant M: no Coriolis or
     * centrifugal terms, Q is the applied forces alone. */
    for (int i = 0; i < s->n; i++) Q[i] = 0;
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        switch (e->type) {
        case BRAUN_EFFECT_GRAVITY: braun_scene__gravity_forces(s, e, q, Q); break;
        case BRAUN_EFFECT_SPRING:
            if (braun_scene__spring_forces(s, e, q, v, Q)) return 1;
            break;
        case BRAUN_EFFECT_TORSION: braun_scene__torsion_forces(s, e, q, v, Q); break;
        case BRAUN_EFFECT_FORCE: braun_scene__force_forces(s, e, t, q, Q); break;
        case BRAUN_EFFECT_TORQUE: braun_scene__torque_forces(s, e, t, Q); break;
        case BRAUN_EFFECT_MOTOR: braun_scene__motor_forces(s, e, q, v, Q); break;
        default: return -1;
        }
    }
    return 0;
}

/* Pointer to row r of an output, or NULL when the output is not wanted. */
#define AT(x, r) ((x) ? (x) + (r) : NULL)
#define ROW(A, r, n) ((A) ? (A) + braun_scene__at(r, 0, n) : NULL)

int braun_scene__joint_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                            const braun_real *q, const braun_real *v, braun_real *phi,
                            braun_real *A, braun_real *b, braun_real *bv)
{
    switch (j->type) {
    case BRAUN_JOINT_REVOLUTE: braun_scene__revolute_rows(s, j, q, v, phi, A, b, bv); break;
    case BRAUN_JOINT_DISTANCE: braun_scene__distance_rows(s, j, t, q, v, phi, A, b, bv); break;
    case BRAUN_JOINT_SLIDER:
    case BRAUN_JOINT_PRISMATIC: braun_scene__slider_rows(s, j, t, q, v, phi, A, b, bv); break;
    case BRAUN_JOINT_ANGLE: {
        const braun_scene_fn fixed = {BRAUN_FN_CONSTANT, j->value, 0, 0, 0};
        braun_scene__angle_rows(s, j->a, j->b, j->driven ? &j->drive : &fixed, t, q, v, phi, A,
                                b, bv);
        break;
    }
    default: return -1;
    }
    return 0;
}

int braun_scene__holonomic(braun_real t, const braun_real *q, const braun_real *v,
                           braun_real *phi, braun_real *A, braun_real *b, braun_real *bv,
                           void *user)
{
    const braun_scene *s = user;
    const int n = s->n;
    if (A)
        for (size_t i = 0; i < braun_scene__at(s->m, 0, n); i++) A[i] = 0;
    for (int k = 0; k < s->nrods; k++) {
        const braun_scene_rod *r = &s->rods[k];
        braun_scene__rod_rows(s, r, q, v, AT(phi, r->row), ROW(A, r->row, n), AT(b, r->row),
                              AT(bv, r->row));
    }
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (braun_scene__joint_eval(s, j, t, q, v, AT(phi, j->row), ROW(A, j->row, n),
                                    AT(b, j->row), AT(bv, j->row)))
            return -1;
    }
    return 0;
}

int braun_scene__nonholonomic(braun_real t, const braun_real *q, const braun_real *v,
                              braun_real *phi, braun_real *A, braun_real *bv, void *user)
{
    const braun_scene *s = user;
    const int n = s->n;
    (void)t;
    if (A)
        for (size_t i = 0; i < braun_scene__at(s->p, 0, n); i++) A[i] = 0;
    for (int k = 0; k < s->nknives; k++) {
        const braun_scene_knife *kn = &s->knives[k];
        braun_scene__knife_rows(s, kn, q, v, AT(phi, kn->row), ROW(A, kn->row, n),
                                AT(bv, kn->row));
    }
    return 0;
}

int braun_scene__energy(braun_real t, const braun_real *q, const braun_real *v, braun_real *E,
                        braun_real *dE_dq, braun_real *dE_dv, braun_real *dE_dt, void *user)
{
    const braun_scene *s = user;
    braun_real T = 0, V = 0;
    (void)t;
    if (dE_dq)
        for (int i = 0; i < s->n; i++) dE_dq[i] = 0;
    if (dE_dv)
        for (int i = 0; i < s->n; i++) dE_dv[i] = 0;
    for (int k = 0; k < s->nbodies; k++) T += braun_scene__body_kinetic(&s->bodies[k], v, dE_dv);
    for (int k = 0; k < s->nrods; k++) T += braun_scene__rod_kinetic(s, &s->rods[k], v, dE_dv);
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        braun_real Vk = 0;
        switch (e->type) {
        case BRAUN_EFFECT_GRAVITY: Vk = braun_scene__gravity_potential(s, e, q, dE_dq); break;
        case BRAUN_EFFECT_SPRING:
            if (braun_scene__spring_potential(s, e, q, &Vk, dE_dq)) return 1;
            break;
        case BRAUN_EFFECT_TORSION: Vk = braun_scene__torsion_potential(s, e, q, dE_dq); break;
        default: break; /* forces, torques, motors: input power, no potential */
        }
        V += Vk;
    }
    if (E) *E = T + V;
    if (dE_dt) *dE_dt = 0; /* no potential depends on t */
    return 0;
}

int braun_scene__power(braun_real t, const braun_real *q, const braun_real *v,
                       braun_real *Edot, void *user)
{
    const braun_scene *s = user;
    braun_real P = 0;
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        braun_real Pk = 0;
        switch (e->type) {
        case BRAUN_EFFECT_SPRING:
            if (e->c != 0 && braun_scene__spring_power(s, e, q, v, &Pk)) return 1;
            break;
        case BRAUN_EFFECT_TORSION:
            if (e->c != 0) Pk = braun_scene__torsion_power(s, e, q, v);
            break;
        case BRAUN_EFFECT_FORCE: Pk = braun_scene__force_power(s, e, t, q, v); break;
        case BRAUN_EFFECT_TORQUE: Pk = braun_scene__torque_power(s, e, t, q, v); break;
        case BRAUN_EFFECT_MOTOR: Pk = braun_scene__motor_power(s, e, q, v); break;
        default: break; /* gravity and springs are in E */
        }
        P += Pk;
    }
    *Edot = P;
    return 0;
}
