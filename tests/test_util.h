/* Shared helpers for the cmocka tests. */
#ifndef BRAUN_TEST_UTIL_H
#define BRAUN_TEST_UTIL_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "braun.h"

/* |a - b| <= tol, with a readable failure message. */
#define assert_near(a, b, tol)                                                   \
    do {                                                                         \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);           \
        if (!(fabs(a_ - b_) <= t_)) {                                            \
            print_error("%s = %.17g, %s = %.17g, |diff| = %.3g > %.3g\n", #a,    \
                        a_, #b, b_, fabs(a_ - b_), t_);                          \
            fail();                                                              \
        }                                                                        \
    } while (0)

/* a <= bound, with a readable failure message. */
#define assert_le(a, bound)                                                      \
    do {                                                                         \
        double a_ = (double)(a), b_ = (double)(bound);                           \
        if (!(a_ <= b_)) {                                                       \
            print_error("%s = %.6g exceeds bound %s = %.6g\n", #a, a_, #bound,   \
                        b_);                                                     \
            fail();                                                              \
        }                                                                        \
    } while (0)

/* A reproducible uniform number in [-1, 1) (64-bit LCG, state *s). */
static inline double test_frand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) / 4503599627370496.0 - 1.0;
}

/* A braun_data with its buffer from malloc (tests only). */
typedef struct test_sim {
    braun_model model;
    braun_data data;
    void *buffer;
} test_sim;

static inline int test_sim_open(test_sim *s, const braun_system *sys,
                                unsigned corrections)
{
    int st = braun_model_init(&s->model, sys);
    if (st != BRAUN_OK) return st;
    s->model.opt.corrections = corrections;
    size_t bytes = braun_data_size(&s->model);
    s->buffer = malloc(bytes);
    if (!s->buffer) return BRAUN_ERR_BUFFER;
    return braun_data_init(&s->data, &s->model, s->buffer, bytes);
}

static inline void test_sim_close(test_sim *s)
{
    if (s->buffer) braun_data_release(&s->data);
    free(s->buffer);
    s->buffer = NULL;
}

#endif
