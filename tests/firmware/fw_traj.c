/*
 * Trajectory errors of a long run printed by the demo's `long` command
 * (firmware/demo/fw_demo.c): every sample of libbraun's q and of RK4 on the
 * minimal-coordinate equation, both in the run's precision, against the
 * model's exact reference (braun_reference, double: Eq. 24 integrated with
 * RK4 substeps <= 1e-4 for the slider-crank, closed form for the four-bar).
 *
 *   fw_traj LONG_OUTPUT [MAX_POS_BOUND [RATIO_BOUND]]
 *
 * The error at a sample is ||q - q_exact(t)||_2 over all coordinates, as
 * `braun run` reports it; t = i·h with h the run's step (exact). Prints the
 * maxima and final values, and "ok - " / "not ok - " lines for the issue's
 * criteria: max ||Φ_q|| <= MAX_POS_BOUND (default 1e-5) and max trajectory
 * error <= RATIO_BOUND (default 2) x that of the minimal-equation RK4.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_reference.h"

static double hex_real(const char *s)
{
    const char *v = strchr(s, '=');
    v = v ? v + 1 : s;
    size_t len = strlen(v);
    while (len && (v[len - 1] == '\n' || v[len - 1] == ' ')) len--;
    uint64_t bits = strtoull(v + 2, NULL, 16);
    if (len == 10) {
        uint32_t b = (uint32_t)bits;
        float f;
        memcpy(&f, &b, sizeof f);
        return f;
    }
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

static const char *field(const char *line, const char *key)
{
    static char buf[64];
    char pat[32];
    snprintf(pat, sizeof pat, " %s=", key);
    const char *p = strstr(line, pat);
    if (!p) return NULL;
    p += strlen(pat);
    size_t k = strcspn(p, " \n");
    if (k >= sizeof buf) k = sizeof buf - 1;
    memcpy(buf, p, k);
    buf[k] = 0;
    return buf;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: fw_traj LONG_OUTPUT [MAX_POS_BOUND [RATIO_BOUND]]\n");
        return 2;
    }
    const double pos_bound = argc > 2 ? strtod(argv[2], NULL) : 1e-5;
    const double ratio_bound = argc > 3 ? strtod(argv[3], NULL) : 2.0;
    FILE *fp = fopen(argv[1], "r");
    if (!fp) {
        perror(argv[1]);
        return 2;
    }
    static char line[4096];
    const braun_builtin *b = NULL;
    braun_reference ref;
    double h = 0, max_pos = NAN, max_b = 0, max_m = 0, fin_b = NAN, fin_m = NAN;
    double t_max_b = 0, t_max_m = 0, t_last = 0, t_max_pos = NAN;
    long samples = 0, steps = 0, done = -1;
    int status = -1;
    char prec[16] = "?";
    while (fgets(line, sizeof line, fp)) {
        if (strncmp(line, "long ", 5) == 0) {
            const char *m = field(line, "model");
            b = m ? braun_builtin_find(m) : NULL;
            if (!b || braun_reference_init(&ref, b, 0) != 0) {
                fprintf(stderr, "fw_traj: unknown model\n");
                return 2;
            }
            h = hex_real(field(line, "h"));
            steps = strtol(field(line, "steps") ? field(line, "steps") : "0", NULL, 10);
            snprintf(prec, sizeof prec, "%s", field(line, "precision") ? field(line, "precision") : "?");
        } else if (line[0] == 's' && line[1] == ' ' && b) {
            const int n = b->sys.n;
            double q[BRAUN_MODEL_MAX_N] = {0}, qr[BRAUN_MODEL_MAX_N] = {0};
            double vr[BRAUN_MODEL_MAX_N] = {0}, y[2] = {0, 0};
            double qm[BRAUN_MODEL_MAX_N] = {0}, vm[BRAUN_MODEL_MAX_N] = {0};
            if (n > BRAUN_MODEL_MAX_N) return 2;
            char *save = NULL, *tok = strtok_r(line + 2, " \n", &save);
            const long i = strtol(tok, NULL, 10);
            for (int k = 0; k < n + 2; k++) {
                tok = strtok_r(NULL, " \n", &save);
                if (!tok) return 2;
                if (k < n) q[k] = hex_real(tok); else y[k - n] = hex_real(tok);
            }
            const double t = (double)i * h;
            if (braun_reference_eval(&ref, t, qr, vr) != 0) return 2;
            braun_minimal_find(b->name)->to_state(y, qm, vm, b->sys.user);
            double eb = 0, em = 0;
            for (int k = 0; k < n; k++) {
                eb += (q[k] - qr[k]) * (q[k] - qr[k]);
                em += (qm[k] - qr[k]) * (qm[k] - qr[k]);
            }
            eb = sqrt(eb);
            em = sqrt(em);
            if (!(eb <= max_b)) { max_b = eb; t_max_b = t; }
            if (!(em <= max_m)) { max_m = em; t_max_m = t; }
            fin_b = eb;
            fin_m = em;
            t_last = t;
            samples++;
        } else if (strncmp(line, "max ", 4) == 0) {
            max_pos = hex_real(field(line, "pos"));
            t_max_pos = hex_real(field(line, "t_max_pos"));
            done = strtol(field(line, "steps_done") ? field(line, "steps_done") : "-1", NULL, 10);
        } else if (strncmp(line, "status ", 7) == 0) {
            status = (int)strtol(field(line, "code") ? field(line, "code") : "-1", NULL, 10);
        }
    }
    fclose(fp);
    if (!b || samples == 0) {
        fprintf(stderr, "fw_traj: no samples in %s\n", argv[1]);
        return 2;
    }
    printf("# %s %s RK4 h = %.6g, %ld of %ld steps (t = %.6g s), %ld samples\n", b->name, prec,
           h, done, steps, t_last, samples);
    printf("# max ||Phi_q|| = %.3g (at t = %.6g s)\n", max_pos, t_max_pos);
    printf("# trajectory error libbraun:     max %.3g (t = %.6g s), final %.3g\n", max_b, t_max_b, fin_b);
    printf("# trajectory error minimal RK4:  max %.3g (t = %.6g s), final %.3g\n", max_m, t_max_m, fin_m);
    printf("# ratio libbraun / minimal RK4:  max %.3g, final %.3g\n", max_b / max_m, fin_b / fin_m);
    int bad = 0;
    bad |= status != 0 || done != steps;
    printf("%s - %s run completes all %ld steps (status %d)\n", status == 0 && done == steps ? "ok" : "not ok", prec, steps, status);
    bad |= !(max_pos <= pos_bound);
    printf("%s - %s max ||Phi_q|| %.3g <= %.0e\n", max_pos <= pos_bound ? "ok" : "not ok", prec, max_pos, pos_bound);
    bad |= !(max_b <= ratio_bound * max_m);
    printf("%s - %s max trajectory error %.3g <= %.3g x minimal-equation RK4 (%.3g)\n",
           max_b <= ratio_bound * max_m ? "ok" : "not ok", prec, max_b, ratio_bound, max_m);
    return bad;
}
