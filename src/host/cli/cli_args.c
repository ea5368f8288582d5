/* Option parsing of `braun run`: every mistake is one "braun: ..." line and
 * exit status 2, before anything is computed. */
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_cli.h"
#include "braun_math.h" /* BRAUN_EPS: braun_integrate's step count */

static const struct {
    const char *name;
    unsigned bit;
} correction_names[] = {
    {"position", BRAUN_CORRECT_POSITION},
    {"velocity", BRAUN_CORRECT_VELOCITY},
    {"energy", BRAUN_CORRECT_ENERGY},
};
#define N_CORRECTIONS (sizeof correction_names / sizeof correction_names[0])

const char *braun_cli_corrections_str(unsigned bits, char *buf, size_t size)
{
    size_t len = 0;
    if (size == 0) return buf;
    buf[0] = '\0';
    for (size_t i = 0; i < N_CORRECTIONS; i++) {
        if (!(bits & correction_names[i].bit)) continue;
        int k = snprintf(buf + len, size - len, "%s%s", len ? "," : "",
                         correction_names[i].name);
        if (k < 0 || (size_t)k >= size - len) break;
        len += (size_t)k;
    }
    if (len == 0) snprintf(buf, size, "none");
    return buf;
}

static int parse_positive(const char *opt, const char *s, double *out)
{
    int rc = braun_cli_parse_real(opt, s, out);
    if (rc) return rc;
    if (!(*out > 0)) return braun_cli_error("%s must be > 0 (got %s)", opt, s);
    return 0;
}

/* Tolerances where 0 asks for the library's default. */
static int parse_nonnegative(const char *opt, const char *s, double *out)
{
    int rc = braun_cli_parse_real(opt, s, out);
    if (rc) return rc;
    if (!(*out >= 0)) return braun_cli_error("%s must be >= 0 (got %s)", opt, s);
    return 0;
}

static int parse_every(const char *s, long *out)
{
    char *end;
    errno = 0;
    long k = braun_cli_integer_text(s) ? strtol(s, &end, 10) : (end = (char *)s, 0);
    if (end != s && *end == '\0' && errno == ERANGE && k > 0)
        return braun_cli_error("--every %s is too large: at most %ld (every row but the first and "
                               "the last is left out beyond the run's steps anyway)", s, LONG_MAX);
    if (end == s || *end != '\0' || errno == ERANGE || k < 1)
        return braun_cli_error("--every must be an integer >= 1 (got '%s')", s);
    *out = k;
    return 0;
}

/* --max-steps: a whole number from 1 to LONG_MAX (braun_adaptive's
 * max_steps is a long), as digits or as a number whose value is whole
 * (1e8). */
static int parse_max_steps(const char *s, long *out)
{
    static const char *const opt = "--max-steps";
    char *end;
    errno = 0;
    const long k = braun_cli_integer_text(s) ? strtol(s, &end, 10) : (end = (char *)s, 0);
    if (end != s && *end == '\0' && errno != ERANGE) {
        if (k < 1) return braun_cli_error("%s must be >= 1 (got %s)", opt, s);
        *out = k;
        return 0;
    }
    double x;
    if (end != s && *end == '\0') x = k > 0 ? HUGE_VAL : -HUGE_VAL; /* digits beyond a long */
    else if (braun_cli_parse_real(opt, s, &x)) return BRAUN_CLI_USAGE;
    if (x < 1) return braun_cli_error("%s must be >= 1 (got %s)", opt, s);
    /* (double)LONG_MAX rounds up to 2^63 (2^31 + 1 with a 32-bit long is exact). */
    if (x >= (double)LONG_MAX + 1.0)
        return braun_cli_error("%s %s: more than the library's step limit can hold (%ld)", opt,
                               s, LONG_MAX);
    if (x != floor(x)) return braun_cli_error("%s must be a whole number of steps (got %s)", opt, s);
    *out = (long)x;
    return 0;
}

double braun_cli_adaptive_h_min(double t_end)
{
    /* braun_integrate_adaptive's default (braun_adaptive.c), for a run from
     * t = 0 to t_end as the library holds it (a braun_real): 1e-12 of the
     * span, but at least 16 eps t_end. In float the floor always decides
     * (1.9e-6 t_end); the summary gave 1e-12 span there, below the h the
     * run's own error said was under the minimum. */
    const double span = (double)(braun_real)t_end;
    const double floor_ = 16 * (double)BRAUN_EPS * span;
    return 1e-12 * span > floor_ ? 1e-12 * span : floor_;
}

double braun_cli_fixed_steps(double h, double t_end)
{
    /* braun_integrate's count (braun__fixed_step_count, braun_internal.h):
     * a span that is a whole number of steps up to round-off takes that
     * many, else one more; the round-off allowed is never half a step (it
     * was uncapped here: 1e-9 to 1 s counted 999999999 steps, the library
     * takes 1e9). */
    const double ratio = t_end / h;
    const double slack = 8.0 * (double)BRAUN_EPS > 1e-9 ? 8.0 * (double)BRAUN_EPS : 1e-9;
    double allowance = slack * ratio;
    if (allowance > 0.5) allowance = 0.5;
    const double steps = ceil(ratio - allowance);
    return steps < 1 ? 1 : steps;
}

static int parse_corrections(const char *s, braun_cli_run_args *a)
{
    if (strcmp(s, "all") == 0) {
        a->corrections_mode = BRAUN_CLI_CORR_ALL;
        return 0;
    }
    a->corrections_mode = BRAUN_CLI_CORR_LIST;
    a->corrections = BRAUN_CORRECT_NONE;
    if (strcmp(s, "none") == 0) return 0;
    /* Walk the comma list without copying: each item is [s, comma). */
    for (const char *p = s;; p++) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        size_t i = 0;
        while (i < N_CORRECTIONS && !(strlen(correction_names[i].name) == len &&
                                      strncmp(correction_names[i].name, p, len) == 0))
            i++;
        if (i == N_CORRECTIONS)
            return braun_cli_error("unknown correction '%.*s' in '%s' (position, velocity, "
                                   "energy, or all | none)", (int)len, p, s);
        a->corrections |= correction_names[i].bit;
        if (!comma) return 0;
        p = comma;
    }
}

static int parse_discretization(const char *s, braun_discretization *out)
{
    if (strcmp(s, "per-step") == 0) *out = BRAUN_PER_STEP;
    else if (strcmp(s, "per-stage") == 0) *out = BRAUN_PER_STAGE;
    else return braun_cli_error("unknown discretization '%s' (per-step, per-stage)", s);
    return 0;
}

static int parse_count(const char *opt, const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long k = braun_cli_integer_text(s) ? strtol(s, &end, 10) : (end = (char *)s, 0);
    if (end == s || *end != '\0' || errno == ERANGE || k < lo || k > hi)
        return braun_cli_error("%s must be an integer from %ld to %ld (got '%s')", opt, lo, hi, s);
    *out = k;
    return 0;
}

/* Options of braun plot (plot mode only). */
static int apply_plot(const char *opt, const char *val, braun_cli_run_args *a)
{
    if (strcmp(opt, "-o") == 0) return a->plot_path = val, 0;
    if (strcmp(opt, "--traj") == 0) return a->traj_path = val, 0;
    if (strcmp(opt, "--points") == 0) return a->points = val, 0;
    if (strcmp(opt, "--plot") == 0) return a->plot_columns = val, 0;
    if (strcmp(opt, "--view") == 0) return a->view = val, 0;
    if (strcmp(opt, "--frames") == 0) return parse_count(opt, val, 1, 1000, &a->frames);
    if (strcmp(opt, "--samples") == 0) return parse_count(opt, val, 2, 100000, &a->samples);
    if (strcmp(opt, "--from") == 0) {
        const int rc = braun_cli_parse_real(opt, val, &a->from);
        if (!rc && a->from < 0) return braun_cli_error("--from must be >= 0 (got %s)", val);
        return rc;
    }
    return 1; /* not a plot option */
}

/* Apply one "--name value" pair. */
static int apply(const char *opt, const char *val, braun_cli_run_args *a, int plot)
{
    if (plot) {
        const int rc = apply_plot(opt, val, a);
        if (rc != 1) return rc;
    }
    a->run_given = 1;
    if (strcmp(opt, "--dt") == 0) return parse_positive(opt, val, &a->dt);
    if (strcmp(opt, "--t-end") == 0) return parse_positive(opt, val, &a->t_end);
    if (strcmp(opt, "--integrator") == 0) {
        int m = braun_method_from_name(val);
        if (m < 0)
            return braun_cli_error("unknown integrator '%s' (euler, heun, rk4, dopri5)", val);
        a->method = (braun_method)m;
        return 0;
    }
    if (strcmp(opt, "--corrections") == 0) return parse_corrections(val, a);
    if (strcmp(opt, "--discretization") == 0) return parse_discretization(val, &a->discretization);
    if (strcmp(opt, "--rank-tol") == 0) {
        /* The core refuses rank_tol >= 1 (every pivot would count as 0). */
        const int rc = parse_nonnegative(opt, val, &a->rank_tol);
        if (!rc && !(a->rank_tol < 1))
            return braun_cli_error("--rank-tol must be < 1 (got %s): a relative tolerance of 1 "
                                   "or more counts every pivot as zero", val);
        return rc;
    }
    if (strcmp(opt, "--energy-max-rel") == 0) return parse_nonnegative(opt, val, &a->energy_max_rel);
    /* 0 is the library's default, a negative value turns the guard off. */
    if (strcmp(opt, "--guard") == 0) return braun_cli_parse_real(opt, val, &a->guard);
    /* 0 is the library's default, a negative value turns the filter off. */
    if (strcmp(opt, "--soft-tol") == 0) {
        const int rc = braun_cli_parse_real(opt, val, &a->soft_tol);
        if (!rc && a->soft_tol >= 1)
            return braun_cli_error("--soft-tol %s: must be < 1 (relative to the constraint "
                                   "matrix's norm)", val);
        return rc;
    }
    if (strcmp(opt, "--rtol") == 0) return parse_nonnegative(opt, val, &a->rtol);
    if (strcmp(opt, "--atol") == 0) return parse_nonnegative(opt, val, &a->atol);
    if (strcmp(opt, "--ref-h") == 0) return parse_positive(opt, val, &a->ref_h);
    if (strcmp(opt, "--max-steps") == 0) {
        a->max_steps_given = 1;
        return parse_max_steps(val, &a->max_steps);
    }
    if (strcmp(opt, "--every") == 0) {
        a->every_given = 1;
        return parse_every(val, &a->every);
    }
    if (strcmp(opt, "--out") == 0) {
        a->out_path = val;
        return 0;
    }
    if (strcmp(opt, "--summary") == 0) {
        a->summary_path = val;
        return 0;
    }
    if (strcmp(opt, "--backend") == 0) {
        /* The names only: whether one is built in and takes the system is
         * decided when the run selects it (braun_linsolver_select). */
        static const char *const names[] = {"dense", "lapack", "suitesparse", "auto"};
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
            if (strcmp(val, names[i]) == 0) {
                a->backend = names[i];
                return 0;
            }
        return braun_cli_error("unknown backend '%s' (dense, lapack, suitesparse, auto)", val);
    }
    return braun_cli_error("unknown option '%s' (see braun --help)", opt);
}

static int takes_value(const char *opt, int plot)
{
    static const char *const names[] = {
        "--dt", "--t-end", "--integrator", "--corrections", "--discretization",
        "--rank-tol", "--energy-max-rel", "--guard", "--soft-tol", "--rtol", "--atol", "--ref-h",
        "--every", "--out", "--summary", "--backend", "--max-steps"};
    static const char *const plot_names[] = {"-o", "--traj", "--points", "--plot", "--frames",
                                             "--from", "--samples", "--view"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcmp(opt, names[i]) == 0) return 1;
    for (size_t i = 0; plot && i < sizeof plot_names / sizeof plot_names[0]; i++)
        if (strcmp(opt, plot_names[i]) == 0) return 1;
    return 0;
}

int braun_cli_parse_run(int argc, char **argv, braun_cli_run_args *a, int plot)
{
    memset(a, 0, sizeof *a);
    a->dt = a->t_end = NAN;
    a->method = BRAUN_RK4;
    a->corrections_mode = BRAUN_CLI_CORR_TARGET;
    a->discretization = BRAUN_PER_STEP;
    a->rtol = 1e-8;
    a->atol = 1e-10;
    a->max_steps = BRAUN_CLI_MAX_STEPS;
    a->every = 1;
    a->summary_path = plot ? NULL : "-";
    a->backend = "dense";
    a->progress = -1;
    a->timing = !plot;
    a->from = NAN;
    int quiet = 0, loud = 0, tol_given = 0;
    /* An option given twice is refused, not settled by the last one: a
     * script's "--dt 1e-3 ... --dt 1e-2" is a mistake one of them hides. */
    char seen[48][32];
    int nseen = 0;

    int options_end = 0;
    for (int i = 0; i < argc; i++) {
        const char *arg = argv[i];
        /* "--" ends the options: a scene file named "-x.json" after it. */
        if (!options_end && strcmp(arg, "--") == 0) {
            options_end = 1;
            continue;
        }
        /* "-" alone and negative numbers are values, not options. */
        if (options_end || arg[0] != '-' || strcmp(arg, "-") == 0) {
            if (a->model) return braun_cli_error("unexpected argument '%s' (one MODEL only)", arg);
            a->model = arg;
            continue;
        }
        if (strncmp(arg, "--", 2) != 0 && !(plot && strcmp(arg, "-o") == 0))
            return braun_cli_error("unknown option '%s' (see braun --help)", arg);
        /* Both "--dt 1e-3" and "--dt=1e-3" (braun_cli_option, as gen's). */
        char name[32];
        const char *val;
        int rc = braun_cli_option(argc, argv, &i, name, sizeof name, NULL);
        if (rc) return rc;
        const size_t len = strlen(name);
        if (strcmp(name, "--sparse") == 0 || strcmp(name, "--progress") == 0 ||
            strcmp(name, "--quiet") == 0) { /* the flags */
            if (arg[len] == '=') return braun_cli_error("option %s takes no value", name);
            /* Once, as every option (`--rods --rods` is refused too). */
            for (int k = 0; k < nseen; k++)
                if (strcmp(seen[k], name) == 0)
                    return braun_cli_error("option %s given twice: give it once", name);
            if (nseen < (int)(sizeof seen / sizeof seen[0])) memcpy(seen[nseen++], name, len + 1);
            if (name[2] == 's') a->sparse = 1, a->run_given = 1;
            else if (name[2] == 'p') loud = 1;
            else quiet = 1;
            continue;
        }
        if (!takes_value(name, plot))
            return braun_cli_error("unknown option '%s' (see braun --help)", name);
        if ((rc = braun_cli_option(argc, argv, &i, name, sizeof name, &val)) != 0) return rc;
        rc = apply(name, val, a, plot);
        if (rc) return rc;
        for (int k = 0; k < nseen; k++)
            if (strcmp(seen[k], name) == 0)
                return braun_cli_error("option %s given twice: give it once", name);
        if (nseen < (int)(sizeof seen / sizeof seen[0])) memcpy(seen[nseen++], name, len + 1);
        if (strcmp(name, "--rtol") == 0 || strcmp(name, "--atol") == 0) tol_given = 1;
    }

    const char *cmd = plot ? "plot" : "run";
    if (quiet && loud) return braun_cli_error("--progress and --quiet contradict each other");
    a->progress = quiet ? 0 : loud ? 1 : -1;
    if (!a->model) return braun_cli_error("%s needs a MODEL (see braun list)", cmd);
    if (plot) {
        /* A picture on stdout would interleave with a CSV or summary there. */
        if (a->plot_path && strcmp(a->plot_path, "-") == 0 &&
            ((a->out_path && strcmp(a->out_path, "-") == 0) ||
             (a->summary_path && strcmp(a->summary_path, "-") == 0)))
            return braun_cli_error("-o - and --out - or --summary - both write to stdout");
        if (!a->plot_path)
            return braun_cli_error("plot needs -o FILE (.svg drawing, .html animation, .png)");
        if (a->traj_path) {
            /* The trajectory is given: nothing is simulated. */
            if (a->run_given)
                return braun_cli_error("--traj draws a trajectory already computed: it takes "
                                       "no simulation options (--dt, --t-end, ...)");
            return 0;
        }
    }
    if (isnan(a->dt)) return braun_cli_error("%s needs --dt H", cmd);
    if (isnan(a->t_end)) return braun_cli_error("%s needs --t-end T", cmd);
    /* The adaptive driver corrects once per accepted step whatever the
     * option says (Δ = Φ/h is ill-posed with a varying h): refuse rather
     * than report a discretization that was not used. */
    if (a->method == BRAUN_DOPRI5 && a->discretization == BRAUN_PER_STAGE)
        return braun_cli_error("--discretization per-stage does not apply to dopri5 "
                               "(the adaptive driver corrects per step)");
    /* Tolerances steer the adaptive driver only: given to a fixed-step
     * run they would be ignored in silence. */
    if (tol_given && a->method != BRAUN_DOPRI5)
        return braun_cli_error("--rtol and --atol apply to --integrator dopri5 only (a fixed-step run "
                               "takes its accuracy from --dt)");
    /* A reference integrated with substeps no finer than the run's step is
     * no reference: the trajectory error would measure it as much as the
     * run (--ref-h 10 at --dt 1e-3 moved the error from 1e-3 to 2.9e-2). */
    if (a->ref_h > 0 && a->method != BRAUN_DOPRI5 && a->dt == a->dt && !(a->ref_h < a->dt))
        return braun_cli_error("--ref-h %g: the reference's substep must be finer than --dt %g (the "
                               "trajectory error would measure the reference)", a->ref_h, a->dt);
    /* The adaptive driver's default minimum step, 1e-12 of the span (at
     * least 16 eps t_end; the run starts at 0): a first step --dt below it
     * is raised to it, and a step there that fails is the end of the run
     * (--dt 1 --t-end 1e15 stopped with BRAUN_ERR_STEP_TOO_SMALL, h = 100,
     * at t = 0, exit 1). */
    if (a->method == BRAUN_DOPRI5 && a->dt > 0 && a->t_end > 0) {
        const double h_min = braun_cli_adaptive_h_min(a->t_end);
        const double rel = h_min / (double)(braun_real)a->t_end; /* 1e-12, or 16 eps in float */
        if (a->dt < h_min)
            return braun_cli_error("--dt %g is below the adaptive step's minimum %g at --t-end %g "
                                   "(%s): dopri5 would take no step below %g; "
                                   "give --t-end <= %g or --dt >= %g", a->dt, h_min, a->t_end,
                                   rel > 1e-12 ? "16 eps of the span in this float build" : "1e-12 of the span",
                                   h_min, a->dt / rel, h_min);
    }
    if (a->method == BRAUN_DOPRI5 && a->rtol == 0 && a->atol == 0)
        return braun_cli_error("--rtol and --atol cannot both be 0");
    /* rtol >= 1 asks for no correct digit (the library refuses it too). */
    if (a->method == BRAUN_DOPRI5 && a->rtol >= 1)
        return braun_cli_error("--rtol %g: must be < 1 (a relative tolerance of 1 asks for no digit)", a->rtol);
    if (a->out_path && strcmp(a->out_path, "-") == 0 && a->summary_path &&
        strcmp(a->summary_path, "-") == 0)
        return braun_cli_error("--out - and the summary both write to stdout; give --summary FILE");
    if (a->every_given && !a->out_path)
        return braun_cli_error("--every %ld without --out: it sets the rows of the trajectory "
                               "CSV, which only --out FILE writes", a->every);
    /* Step times t0 + i·h must differ: below a few ulps of t_end they
     * repeat (and t_end/h steps would never end). */
    if (a->dt < 4 * DBL_EPSILON * a->t_end)
        return braun_cli_error("--dt %g is below the time resolution at --t-end %g (%g): the "
                               "steps' times would not advance", a->dt, a->t_end,
                               4 * DBL_EPSILON * a->t_end);
    /* A fixed-step run's length is known before it starts: one beyond the
     * step limit is refused rather than left to run for hours (dopri5
     * counts its attempts against the same limit as it goes). */
    if (a->method != BRAUN_DOPRI5 && braun_cli_fixed_steps(a->dt, a->t_end) > (double)a->max_steps)
        return braun_cli_error("--dt %g to --t-end %g is a fixed-step run of %.15g steps (T/H = "
                               "%g), more than --max-steps %ld allows: give a larger --dt, or "
                               "raise --max-steps", a->dt, a->t_end,
                               braun_cli_fixed_steps(a->dt, a->t_end), a->t_end / a->dt,
                               a->max_steps);
    /* The integrated references take t_end / ref_h substeps. */
    if (a->ref_h > 0 && a->t_end / a->ref_h > BRAUN_CLI_MAX_REF_STEPS)
        return braun_cli_error("--ref-h %g: the reference would take %g substeps to --t-end %g "
                               "(at most %g)", a->ref_h, a->t_end / a->ref_h, a->t_end,
                               BRAUN_CLI_MAX_REF_STEPS);
    return 0;
}
