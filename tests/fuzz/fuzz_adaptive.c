/* libFuzzer target: the adaptive driver's options. rtol, atol, h0, h_min,
 * h_max and t_end are read as raw doubles from the input (any bit pattern:
 * NaN, ±Inf, subnormals, huge), max_steps as an integer bounded to
 * [1, 500] (the limit of the attempts is what keeps a run finite; <= 0
 * would mean 10^8), then a byte each for the corrections and `every`.
 * braun_integrate_adaptive on the built-in pendulum and on the four-bar
 * (singular configurations) must never crash or hang, and BRAUN_OK must
 * mean t_end reached with a finite state within max_steps attempts. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "braun.h"
#include "braun_models.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static double take_double(const uint8_t **p, size_t *left)
{
    double x = 0;
    if (*left >= sizeof x) {
        memcpy(&x, *p, sizeof x);
        *p += sizeof x;
        *left -= sizeof x;
    }
    return x;
}

static int finite_all(const braun_real *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite((double)x[i])) return 0;
    return 1;
}

static int on_step(const braun_data *d, void *user)
{
    long *calls = (long *)user;
    (*calls)++;
    if (!isfinite((double)d->t)) abort();
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *p = data;
    size_t left = size;
    braun_adaptive ctl;
    ctl.rtol = (braun_real)take_double(&p, &left);
    ctl.atol = (braun_real)take_double(&p, &left);
    ctl.h0 = (braun_real)take_double(&p, &left);
    ctl.h_min = (braun_real)take_double(&p, &left);
    ctl.h_max = (braun_real)take_double(&p, &left);
    const braun_real t_end = (braun_real)take_double(&p, &left);
    uint32_t steps = 0;
    if (left >= sizeof steps) {
        memcpy(&steps, p, sizeof steps);
        p += sizeof steps;
        left -= sizeof steps;
    }
    ctl.max_steps = 1 + (long)(steps % 500u);
    const unsigned corr = left > 0 ? p[0] & BRAUN_CORRECT_ALL : BRAUN_CORRECT_ALL;
    const long every = left > 1 ? (long)p[1] - 8 : 1; /* 0 and negative too */
    const braun_builtin *b = braun_builtin_find(left > 2 && (p[2] & 1) ? "four-bar" : "pendulum");
    if (!b) abort();

    braun_model model;
    if (braun_model_init(&model, &b->sys) != BRAUN_OK) abort();
    model.opt.corrections = corr & model.opt.corrections;
    const size_t bytes = braun_data_size(&model);
    void *buf = malloc(bytes);
    if (!buf) return 0;
    braun_data d;
    if (braun_data_init(&d, &model, buf, bytes) != BRAUN_OK ||
        braun_set_state(&d, 0, b->q0, b->v0) != BRAUN_OK)
        abort();
    long calls = 0;
    const int st = braun_integrate_adaptive(&d, &ctl, t_end, every, on_step, &calls);
    const long attempts = d.stats.steps + d.stats.rejected_steps;
    if (attempts > ctl.max_steps) abort(); /* the limit bounds every call */
    if (st == BRAUN_OK) {
        if (!(d.t == t_end)) abort();
        if (!finite_all(d.q, model.sys.n) || !finite_all(d.v, model.sys.n)) abort();
        if (calls < 1) abort(); /* the first and last states at least */
    }
    braun_data_release(&d);
    free(buf);
    return 0;
}
