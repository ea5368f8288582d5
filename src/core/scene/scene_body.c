/* Rigid bodies (x, y, θ) and particles (x, y): the diagonal blocks of the
 * mass matrix, diag(m, m, I) or diag(m, m), as in the paper's Eq. 21. */
#include "scene_internal.h"

void braun_scene__body_mass(const braun_scene *s, const braun_scene_body *bd, braun_real *M)
{
    const int n = s->n, i = bd->iq;
    M[braun_scene__at(i, i, n)] += bd->mass;
    M[braun_scene__at(i + 1, i + 1, n)] += bd->mass;
    if (bd->kind == BRAUN_BODY_RIGID) M[braun_scene__at(i + 2, i + 2, n)] += bd->inertia;
}

braun_real braun_scene__body_kinetic(const braun_scene_body *bd, const braun_real *v,
                                     braun_real *dEdv)
{
    const int i = bd->iq;
    const braun_real px = bd->mass * v[i], py = bd->mass * v[i + 1];
    braun_real T = px * v[i] + py * v[i + 1];
    if (dEdv) {
        dEdv[i] += px;
        dEdv[i + 1] += py;
    }
    if (bd->kind == BRAUN_BODY_RIGID) {
        const braun_real L = bd->inertia * v[i + 2];
        T += L * v[i + 2];
        if (dEdv) dEdv[i + 2] += L;
    }
    return BRAUN_R(0.5) * T;
}
