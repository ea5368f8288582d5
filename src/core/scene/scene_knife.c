/* Knife edge / sleigh (nonholonomic, Sec. 2.2): the contact point P — point
 * a, on a rigid body — cannot move across the blade, whose direction (axis)
 * is fixed in the body. With the unit normal n = R(θ) n_L (n_L = blade
 * direction turned by +90°):
 *   Φ_v  = n·P' = n·(r' + jt ω)                       (1 row, linear in v)
 *   A_vv = [n_x, n_y, n·jt]
 *   b_vv = -(∂Φ_v/∂q) v = -ω (Jn·P' - ω n·Rp) = -ω Jn·P' - n·cc
 * using ∂n/∂θ = Jn (n turned by +90°), ∂jt/∂θ = -Rp and cc = -Rp ω². */
#include "scene_internal.h"

static const char *knife_check(const braun_scene *s, const braun_scene_joint *j)
{
    if (!braun_scene__is_rigid(s, braun_scene__body_of(s, j->a)))
        return "knife edge needs a rigid body";
    if (j->axis[0] == 0 && j->axis[1] == 0) return "knife edge direction is the zero vector";
    if (j->driven) return "a knife edge cannot be driven";
    return NULL;
}

static int knife_rows(const braun_scene_joint *j)
{
    (void)j;
    return 1;
}

static int knife_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                      const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
                      braun_real *b, braun_real *bv)
{
    const braun_scene_point *pt = &s->points[j->a];
    const braun_scene_body *bd = &s->bodies[pt->body];
    const int ix = bd->iq;
    (void)t;
    (void)b;
    const braun_real th = q[ix + 2], w = v[ix + 2];
    braun_real c, sn;
    braun_sincos(th, &sn, &c);
    const braun_real norm = braun_sqrt(j->axis[0] * j->axis[0] + j->axis[1] * j->axis[1]);
    const braun_real nlx = -j->axis[1] / norm, nly = j->axis[0] / norm;
    const braun_real nx = c * nlx - sn * nly, ny = sn * nlx + c * nly;
    /* Contact point relative to the centre of mass, world frame: R p. */
    const braun_real rx = c * pt->x - sn * pt->y, ry = sn * pt->x + c * pt->y;
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
    return 0;
}

/* The scene file names the body and the contact point in its frame:
 * "body" makes the joint's own point a on it, "at" places it. */
static const braun_scene_field knife_fields[] = {
    {"body", BRAUN_FIELD_BODY_POINT, 0, offsetof(braun_scene_joint, a),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_ANGLE, NULL},
    {"at", BRAUN_FIELD_OFFSET, 2, offsetof(braun_scene_joint, a), 0, NULL},
    {"direction", BRAUN_FIELD_REAL, 2, offsetof(braun_scene_joint, axis),
     BRAUN_FIELD_REQUIRED | BRAUN_FIELD_NONZERO, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

const braun_scene_joint_class braun_scene_joint_knife = {
    "knife", "BRAUN_JOINT_KNIFE", 1, knife_fields, NULL, knife_check, knife_rows, NULL,
    knife_eval, 2};
