/* The braun_system callbacks of a built scene: each loops over the
 * elements that contribute to it, and only those, through their classes.
 * M is assembled from the body classes' blocks and the rods (called once
 * when the scene sets BRAUN_MASS_CONSTANT, at every evaluation when a body
 * class's block depends on q); Q from the effects and the bodies'
 * velocity-product forces; the rows from rods, joints (holonomic ones into
 * Φ_q, nonholonomic ones into Φ_v) and the bodies' own rows;
 * the energy law (Eq. 18) from the kinetic energy of bodies and rods and
 * the effects' potentials; the input power from the effects that put
 * energy in or take it out. */
#include "scene_internal.h"

#define AT BRAUN_SCENE__AT
#define ROW BRAUN_SCENE__ROW

int braun_scene__mass(braun_real t, const braun_real *q, braun_real *M, void *user)
{
    const braun_scene *s = user;
    const int n = s->n;
    (void)t;
    for (size_t i = 0; i < braun_scene__at(n, 0, n); i++) M[i] = 0;
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        braun_real *blk = M + braun_scene__at(bd->iq, bd->iq, n);
        if (bd->kind->mass_at) bd->kind->mass_at(bd, q + bd->iq, blk, n);
        else bd->kind->mass(bd, blk, n);
    }
    for (int k = 0; k < s->nrods; k++) braun_scene__rod_mass(s, &s->rods[k], M);
    return 0;
}

int braun_scene__forces(braun_real t, const braun_real *q, const braun_real *v, braun_real *Q,
                        void *user)
{
    const braun_scene *s = user;
    /* Planar absolute and natural coordinates have a constant M: no
     * Coriolis or centrifugal terms. A body whose block depends on q adds
     * its velocity-product forces. */
    for (int i = 0; i < s->n; i++) Q[i] = 0;
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        if (bd->kind->inertial) bd->kind->inertial(bd, q + bd->iq, v + bd->iq, Q + bd->iq);
    }
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        if (!e->type->forces) continue;
        const int st = e->type->forces(s, e, t, q, v, Q);
        if (st) return st;
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
        if (j->type->nonholonomic) continue;
        const int st = j->type->eval(s, j, t, q, v, AT(phi, j->row), ROW(A, j->row, n),
                                     AT(b, j->row), AT(bv, j->row));
        if (st) return st;
    }
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        const int rows = bd->kind->rows;
        if (rows == 0) continue;
        bd->kind->constraint(bd, q + bd->iq, v ? v + bd->iq : NULL, AT(phi, bd->row),
                             A ? A + braun_scene__at(bd->row, bd->iq, n) : NULL, n,
                             v ? AT(bv, bd->row) : NULL);
        if (b)
            for (int r = 0; r < rows; r++) b[bd->row + r] = 0; /* scleronomic */
    }
    return 0;
}

int braun_scene__nonholonomic(braun_real t, const braun_real *q, const braun_real *v,
                              braun_real *phi, braun_real *A, braun_real *bv, void *user)
{
    const braun_scene *s = user;
    const int n = s->n;
    if (A)
        for (size_t i = 0; i < braun_scene__at(s->p, 0, n); i++) A[i] = 0;
    for (int k = 0; k < s->njoints; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (!j->type->nonholonomic) continue;
        const int st = j->type->eval(s, j, t, q, v, AT(phi, j->row), ROW(A, j->row, n), NULL,
                                     AT(bv, j->row));
        if (st) return st;
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
    for (int k = 0; k < s->nbodies; k++) {
        const braun_scene_body *bd = &s->bodies[k];
        braun_real *dv = dE_dv ? dE_dv + bd->iq : NULL;
        if (bd->kind->kinetic_at)
            T += bd->kind->kinetic_at(bd, q + bd->iq, v + bd->iq, dE_dq ? dE_dq + bd->iq : NULL, dv);
        else
            T += bd->kind->kinetic(bd, v + bd->iq, dv);
    }
    for (int k = 0; k < s->nrods; k++) T += braun_scene__rod_kinetic(s, &s->rods[k], v, dE_dv);
    for (int k = 0; k < s->neffects; k++) {
        const braun_scene_effect *e = &s->effects[k];
        braun_real Vk = 0; /* forces, torques, motors: input power, no potential */
        if (e->type->potential) {
            const int st = e->type->potential(s, e, q, &Vk, dE_dq);
            if (st) return st;
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
        const braun_scene_effect_class *c = e->type;
        braun_real Pk = 0; /* gravity and springs are in E */
        if (c->power && (!c->inputs || c->inputs(e))) {
            const int st = c->power(s, e, t, q, v, &Pk);
            if (st) return st;
        }
        P += Pk;
    }
    *Edot = P;
    return 0;
}
