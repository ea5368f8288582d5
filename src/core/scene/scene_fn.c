/* Functions of time for drives and applied loads: constant, linear ramp,
 * sine and step, with their first two derivatives (a drive's b_q = f' and
 * b_qv = f'' terms, Sec. 2.2). */
#include <math.h> /* NAN */
#include "scene_internal.h"

int braun_scene_fn_eval(const braun_scene_fn *f, braun_real t, braun_real *value,
                        braun_real *rate, braun_real *accel)
{
    braun_real x = 0, dx = 0, ddx = 0;
    int st = BRAUN_OK;
    switch (f ? (int)f->kind : -1) {
    case BRAUN_FN_LINEAR:
        x = f->a + f->b * t;
        dx = f->b;
        break;
    case BRAUN_FN_SINE: {
        const braun_real arg = f->c * t + f->d;
        braun_real s, c;
        braun_sincos(arg, &s, &c);
        x = f->a + f->b * s;
        dx = f->b * f->c * c;
        ddx = -f->b * f->c * f->c * s;
        break;
    }
    case BRAUN_FN_STEP:
        /* Derivatives are 0 away from the jump; the builder keeps steps
         * out of drives, where a jump would need a Dirac b_qv. */
        x = t < f->c ? f->a : f->b;
        break;
    case BRAUN_FN_CONSTANT:
        x = f->a;
        break;
    default: /* no function, or a kind that is none: NaN, not a silent 0 */
        x = dx = ddx = (braun_real)NAN;
        st = BRAUN_ERR_ARGUMENT;
        break;
    }
    if (value) *value = x;
    if (rate) *rate = dx;
    if (accel) *accel = ddx;
    return st;
}
