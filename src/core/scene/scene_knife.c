/* Knife edge / sleigh (nonholonomic, Sec. 2.2): the contact point P of a
 * rigid body cannot move across the blade. With the unit normal
 * n = R(θ) n_L (n_L = blade direction turned by +90°):
 *   Φ_v  = n·P' = n·(r' + jt ω)                       (1 row, linear in v)
 *   A_vv = [n_x, n_y, n·jt]
 *   b_vv = -(∂Φ_v/∂q) v = -ω (Jn·P' - ω n·Rp) = -ω Jn·P' - n·cc
 * using ∂n/∂θ = Jn (n turned by +90°), ∂jt/∂θ = -Rp and cc = -Rp ω². */
#include "scene_internal.h"

void braun_scene__knife_rows(const braun_scene *s, const braun_scene_knife *k,
                             const braun_real *q, const braun_real *v, braun_real *phi,
                             braun_real *A, braun_real *bv)
{
    const braun_scene_body *bd = &s->bodies[k->body];
    const int ix = bd->iq;
    const braun_real th = q[ix + 2], w = v[ix + 2];
    const braun_real c = braun_cos(th), sn = braun_sin(th);
    const braun_real norm = braun_sqrt(k->dir[0] * k->dir[0] + k->dir[1] * k->dir[1]);
    const braun_real nlx = -k->dir[1] / norm, nly = k->dir[0] / norm;
    const braun_real nx = c * nlx - sn * nly, ny = sn * nlx + c * nly;
    /* Contact point relative to the centre of mass, world frame: R p. */
    const braun_real rx = c * k->x - sn * k->y, ry = sn * k->x + c * k->y;
    const braun_real jtx = -ry, jty = rx;
    const braun_real vx = v[ix] + jtx * w, vy = v[ix + 1] + jty * w;
    if (phi) phi[0] = nx * vx + ny * vy;
    if (A) {
        A[ix] += nx;
        A[ix + 1] += ny;
        A[ix + 2] += nx * jtx + ny * jty;
    }
    if (bv) {
        const braun_real jnx = -ny, jny = nx;
        bv[0] = -w * (jnx * vx + jny * vy) + w * w * (nx * rx + ny * ry);
    }
}
