/* The long-run matrix (issue 12; docs/robustness.md, "The long-run matrix"):
 * every built-in model and shipped scene under RK4 at h = 1e-3, 5e-3, 1e-2
 * and DOPRI5 at rtol = 1e-6, 1e-8, 1e-10. A run either completes with every
 * residual within the accuracy guard's bound at every state it reported, or
 * stops with a documented status that says why (a recorded error, the state
 * finite and at a step that passed). Nothing else passes.
 *
 *   matrix [--t-end T] [--markdown FILE] [--iftomm] [DATA_DIR]
 * T is 1000 s for make stress and shorter in make test. Prints one
 * "ok"/"not ok" line per run and "N passed, M failed". */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "braun.h"
#include "braun_host.h"
#include "braun_models.h"
#include "braun_scene_file.h"
#include "../test_files.h"

typedef struct subject {
    char name[64];
    const braun_system *sys;
    const braun_real *q0, *v0;
    unsigned corrections;
    braun_scene_file *file;
    double t_max; /* the subject's own horizon, if shorter than T (0: none) */
} subject;

typedef struct watch {
    double pos, vel, energy; /* largest residuals reported */
    int nonfinite;
} watch;

static int on_step(const braun_data *d, void *user)
{
    watch *w = user;
    braun_real p, v, e;
    if (braun_residuals((braun_data *)d, d->t, d->q, d->v, &p, &v, &e) != BRAUN_OK ||
        !isfinite((double)p) || !isfinite((double)v) || !isfinite((double)e)) {
        w->nonfinite = 1;
        return 0;
    }
    if (p > w->pos) w->pos = p;
    if (v > w->vel) w->vel = v;
    if (e > w->energy) w->energy = e;
    return 0;
}

static double cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The guard's bound of a residual, as the library applies it (braun.h). */
static double bound(double g, double scale, double r0)
{
    return g * scale > r0 ? g * scale : r0;
}

/* The statuses a run may stop with, each meaning what braun.h says. */
static int documented_stop(int st)
{
    return st == BRAUN_ERR_ACCURACY || st == BRAUN_ERR_DIVERGED || st == BRAUN_ERR_STEP_TOO_SMALL ||
           st == BRAUN_ERR_TIME_RESOLUTION || st == BRAUN_ERR_INCONSISTENT ||
           st == BRAUN_ERR_TOO_MANY_STEPS;
}

/* The *.json files of dir (names prefixed with prefix), sorted; at most max. */
static int list_scenes(const char *dir, const char *prefix, char (*out)[96], int max)
{
    const int k = test_list_files(dir, ".json", prefix, out[0], sizeof out[0], max);
    return k > 0 ? k : 0;
}

int main(int argc, char **argv)
{
    double T = 1000;
    const char *md_path = NULL, *dir = "data";
    int iftomm = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--t-end") == 0 && i + 1 < argc) T = atof(argv[++i]);
        else if (strcmp(argv[i], "--markdown") == 0 && i + 1 < argc) md_path = argv[++i];
        else if (strcmp(argv[i], "--iftomm") == 0) iftomm = 1;
        else dir = argv[i];
    }
    subject subs[40];
    int ns = 0;
    const char *builtins[] = {"slider-crank", "four-bar", "pendulum"};
    for (int i = 0; i < 3; i++) {
        const braun_builtin *b = braun_builtin_find(builtins[i]);
        subs[ns] = (subject){"", &b->sys, b->q0, b->v0, BRAUN_CORRECT_ALL, NULL, 0};
        snprintf(subs[ns++].name, sizeof subs[0].name, "%s", b->name);
    }
    /* Andrews' motor torque spins the mechanism up without bound (the crank
     * turns at 1.3e4 rad/s after 1 s, 2.2e4 after 1.7 s): its step shrinks
     * like 1/omega and 1000 s would take ~1e9 steps. It runs 1 s, 33 times
     * its benchmark horizon of 0.03 s. */
    subs[ns] = (subject){"andrews", &braun_andrews_system, braun_andrews_q0, braun_andrews_v0,
                         BRAUN_CORRECT_ALL, NULL, 1.0};
    ns++;
    /* Every shipped scene in name order: the *.json files of DIR and, with
     * --iftomm, of DIR/iftomm (the benchmark problems: make stress). */
    char scenes[24][96];
    int nsc = list_scenes(dir, "", scenes, 24);
    if (iftomm) {
        char sub[600];
        snprintf(sub, sizeof sub, "%s/iftomm", dir);
        nsc += list_scenes(sub, "iftomm/", scenes + nsc, 24 - nsc);
    }
    for (int i = 0; i < nsc && ns < (int)(sizeof subs / sizeof subs[0]); i++) {
        char path[1024], err[512];
        snprintf(path, sizeof path, "%.500s/%.95s", dir, scenes[i]);
        braun_scene_file *f = braun_scene_load(path, err, sizeof err);
        if (!f) {
            printf("not ok - load %s: %s\n", path, err);
            printf("0 passed, 1 failed\n");
            return 1;
        }
        /* A03 is Andrews' mechanism as a scene: 1 s, as the built-in above.
         * A02 runs its benchmark's 20 s (N = 40: 2.4 ms per RK4 step at
         * h = 1e-3); A05, the stiff governor, the IFToMM variant's 10 s (its
         * DOPRI5 takes ~13 000 steps per simulated second at rtol 1e-10;
         * make iftomm runs the 350 s). */
        const double t_max = strstr(scenes[i], "andrews")     ? 1.0
                             : strstr(scenes[i], "n-four-bar") ? 20.0
                             : strstr(scenes[i], "flyball")    ? 10.0
                                                               : 0;
        subs[ns] = (subject){"", &f->sys, f->q0, f->v0, f->corrections, f, t_max};
        snprintf(subs[ns++].name, sizeof subs[0].name, "%.63s", scenes[i]);
    }
    const struct {
        braun_method method;
        double h_or_rtol;
    } settings[] = {{BRAUN_RK4, 1e-3},    {BRAUN_RK4, 5e-3},    {BRAUN_RK4, 1e-2},
                    {BRAUN_DOPRI5, 1e-6}, {BRAUN_DOPRI5, 1e-8}, {BRAUN_DOPRI5, 1e-10}};
    const int nset = (int)(sizeof settings / sizeof settings[0]);
    FILE *md = md_path ? fopen(md_path, "w") : NULL;
    if (md) {
        fprintf(md, "| model | integrator | setting | status | t reached / end [s] | max ‖Φ_q‖ | bound | "
                    "max ‖[Φ̇_q; Φ_v]‖ | bound | max \\|Φ_e\\| [J] | bound | steps | CPU [s] | why it stopped |\n");
        fprintf(md, "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    }
    int passed = 0, failed = 0;
    static unsigned char buf[1 << 20];
    for (int s = 0; s < ns; s++) {
        for (int k = 0; k < nset; k++) {
            braun_model model;
            braun_data d;
            watch w = {0, 0, 0, 0};
            int st = braun_model_init(&model, subs[s].sys);
            if (!st) {
                model.opt.corrections = subs[s].corrections;
                if (!subs[s].sys->energy) model.opt.corrections &= ~(unsigned)BRAUN_CORRECT_ENERGY;
                st = braun_data_init(&d, &model, buf, sizeof buf);
            }
            if (!st) st = braun_set_state(&d, 0, subs[s].q0, subs[s].v0);
            if (st) {
                printf("not ok - %s: setup failed: %s\n", subs[s].name, braun_status_str(st));
                failed++;
                continue;
            }
            const double Ts = subs[s].t_max > 0 && subs[s].t_max < T ? subs[s].t_max : T;
            const double c0 = cpu();
            if (settings[k].method == BRAUN_DOPRI5) {
                braun_adaptive ctl = {(braun_real)settings[k].h_or_rtol,
                                      (braun_real)(settings[k].h_or_rtol * 1e-2), 0, 0, 0, 0};
                st = braun_integrate_adaptive(&d, &ctl, (braun_real)Ts, 1, on_step, &w);
            } else {
                st = braun_integrate(&d, BRAUN_RK4, (braun_real)settings[k].h_or_rtol, (braun_real)Ts, 1,
                                     on_step, &w);
            }
            const double secs = cpu() - c0;
            const double g = model.opt.guard > 0 ? (double)model.opt.guard : 1e-3;
            const unsigned corr = model.opt.corrections;
            const double bp = bound(g, (double)d.guard.pos, (double)d.guard.pos0);
            const double bv = bound(g, (double)d.guard.vel, (double)d.guard.vel0);
            const double be = bound(g, (double)d.guard.energy, (double)d.guard.energy0);
            /* The residuals the corrections keep are the guarded ones. */
            const int pos_ok = !(corr & BRAUN_CORRECT_POSITION) || w.pos <= bp * (1 + 1e-9);
            const int vel_ok = !(corr & BRAUN_CORRECT_VELOCITY) || w.vel <= bv * (1 + 1e-9);
            const int en_ok = !(corr & BRAUN_CORRECT_ENERGY) || w.energy <= be * (1 + 1e-9);
            char why[300] = "";
            int ok;
            if (st == BRAUN_OK) {
                ok = !w.nonfinite && pos_ok && vel_ok && en_ok && d.t == (braun_real)Ts;
                if (!ok)
                    snprintf(why, sizeof why, "BRAUN_OK outside its bounds (pos %.3g/%.3g vel %.3g/%.3g energy %.3g/%.3g%s)",
                             w.pos, bp, w.vel, bv, w.energy, be, w.nonfinite ? ", non-finite" : "");
            } else {
                /* A documented stop: recorded, the state finite. */
                int finite = 1;
                for (int i = 0; i < model.sys.n; i++) finite &= isfinite((double)d.q[i]) && isfinite((double)d.v[i]);
                ok = documented_stop(st) && d.error.status == st && d.error.where != NULL && finite;
                if (ok) braun_error_format(&d, why, sizeof why);
                else snprintf(why, sizeof why, "undocumented stop %s (recorded %d)", braun_status_str(st), d.error.status);
            }
            const char *iname = settings[k].method == BRAUN_DOPRI5 ? "dopri5" : "rk4";
            char setting[32];
            snprintf(setting, sizeof setting, "%s %.0e", settings[k].method == BRAUN_DOPRI5 ? "rtol" : "h",
                     settings[k].h_or_rtol);
            char status[64];
            const char *sn = braun_status_str(st);
            snprintf(status, sizeof status, "%.*s", (int)strcspn(sn, ":"), sn);
            printf("%s - %s %s %s: %s, t = %.6g, max |Phi_q| %.3g (bound %.3g), |dPhi| %.3g (%.3g), "
                   "|Phi_e| %.3g (%.3g), %ld steps, %.2f s%s%s\n",
                   ok ? "ok" : "not ok", subs[s].name, iname, setting, status, (double)d.t, w.pos, bp,
                   w.vel, bv, w.energy, be, d.stats.steps, secs, why[0] ? ": " : "", why);
            /* a '|' would end the table cell */
            char cell[600];
            size_t c = 0;
            for (const char *p = st == BRAUN_OK ? "" : why; *p && c + 3 < sizeof cell; p++) {
                if (*p == '|') cell[c++] = '\\';
                cell[c++] = *p;
            }
            cell[c] = 0;
            if (md)
                fprintf(md, "| %s | %s | %s | %s | %.6g / %g | %.2g | %.2g | %.2g | %.2g | %.2g | %.2g | %ld | %.2f | %s |\n",
                        subs[s].name, iname, setting, status, (double)d.t, Ts, w.pos, bp, w.vel, bv, w.energy, be,
                        d.stats.steps, secs, cell);
            if (ok) passed++;
            else failed++;
            braun_data_release(&d);
        }
    }
    if (md) fclose(md);
    for (int s = 0; s < ns; s++)
        if (subs[s].file) braun_scene_free(subs[s].file);
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
