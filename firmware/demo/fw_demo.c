/* The demo's commands (see fw_demo.h). */
#include "fw_demo.h"

#include <string.h>

#include "braun_models.h"
#include "fw_minimal.h"
#include "fw_out.h"

#ifdef BRAUN_SINGLE
#define FW_PRECISION "float"
#else
#define FW_PRECISION "double"
#endif

/* ------------------------------------------------------------ parsing */

/* Non-negative decimal integer; -1 if s is not one. */
static long parse_long(const char *s)
{
    long x = 0;
    if (!s || !*s) return -1;
    for (; *s; s++) {
        if (*s < '0' || *s > '9' || x > 100000000L) return -1;
        x = 10 * x + (*s - '0');
    }
    return x;
}

/* Positive decimal "D[.D][e[-]D]", e.g. 1e-3 or 0.01; 0 if malformed. The
 * value is (integer mantissa) / 10^k or * 10^k with both exact in double,
 * so one correctly rounded operation: the same bits as strtod for short
 * inputs, on every platform. */
static double parse_real(const char *s)
{
    double mant = 0, p10 = 1;
    int frac = 0, ex = 0, neg = 0, digits = 0;
    if (!s) return 0;
    for (; *s && *s != 'e' && *s != 'E'; s++) {
        if (*s == '.') {
            if (frac) return 0;
            frac = 1;
            continue;
        }
        if (*s < '0' || *s > '9' || ++digits > 15) return 0;
        mant = 10 * mant + (*s - '0');
        if (frac) ex--;
    }
    if (*s) {
        int e = 0;
        s++;
        if (*s == '-') {
            neg = 1;
            s++;
        }
        if (!*s) return 0;
        for (; *s; s++) {
            if (*s < '0' || *s > '9' || e > 100) return 0;
            e = 10 * e + (*s - '0');
        }
        ex += neg ? -e : e;
    }
    if (ex < -22 || ex > 22) return 0;
    for (int i = 0; i < (ex < 0 ? -ex : ex); i++) p10 *= 10;
    return ex < 0 ? mant / p10 : mant * p10;
}

/* "none" | "pv" (position + velocity) | "all"; -1 otherwise. */
static int parse_corrections(const char *s)
{
    if (strcmp(s, "none") == 0) return BRAUN_CORRECT_NONE;
    if (strcmp(s, "pv") == 0) return BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY;
    if (strcmp(s, "all") == 0) return BRAUN_CORRECT_ALL;
    return -1;
}

static const char *corrections_name(unsigned c)
{
    return c == 0 ? "none" : c == 3u ? "pv" : c == 7u ? "all" : "other";
}

/* ------------------------------------------------------------ set-up */

/* What a run integrates: a built-in model or a scene of this build. */
typedef struct subject {
    const char *name;
    const braun_system *sys;
    const braun_real *q0, *v0;
    unsigned corrections;          /* the default: all it supports */
    const braun_builtin *builtin;  /* NULL for a scene */
} subject;

static int find_subject(const char *name, subject *s)
{
    const braun_builtin *b = braun_builtin_find(name);
    if (b) {
        *s = (subject){b->name, &b->sys, b->q0, b->v0, BRAUN_CORRECT_ALL, b};
        return 0;
    }
    for (int i = 0; fw_platform_scene_at(i); i++) {
        const fw_scene *sc = fw_platform_scene_at(i);
        if (strcmp(sc->label, name) == 0) {
            *s = (subject){sc->label, &sc->sys, sc->q0, sc->v0, sc->corrections, NULL};
            return 0;
        }
    }
    return -1;
}

size_t fw_demo_data_size(const char *name)
{
    subject sub;
    braun_model model;
    if (find_subject(name, &sub) || braun_model_init(&model, sub.sys)) return 0;
    return braun_data_size(&model);
}

/* Model, data and initial state of a subject; corrections as asked, less
 * the energy correction if the system has no energy law. */
static int setup(const char *name, unsigned corrections, const fw_workspace *ws,
                 braun_model *model, braun_data *d, subject *out)
{
    if (find_subject(name, out)) return BRAUN_ERR_ARGUMENT;
    int st = braun_model_init(model, out->sys);
    if (st) return st;
    if (!out->sys->energy) corrections &= ~(unsigned)BRAUN_CORRECT_ENERGY;
    model->opt.corrections = corrections;
    if (braun_data_size(model) > ws->bytes) return BRAUN_ERR_BUFFER;
    st = braun_data_init(d, model, ws->buffer, ws->bytes);
    if (!st) st = braun_set_state(d, 0, out->q0, out->v0);
    return st;
}

static void put_status(int st)
{
    fw_puts("status");
    fw_kv_long("code", st);
    fw_putc(' ');
    fw_puts(braun_status_str(st));
    fw_putc('\n');
}

static void put_vector(const char *tag, int n, const braun_real *x)
{
    fw_puts(tag);
    for (int i = 0; i < n; i++) {
        fw_putc(' ');
        fw_put_hex_real(x[i]);
    }
    fw_putc('\n');
}

/* ------------------------------------------------------------ runs */

typedef struct maxima {
    braun_real pos, vel, energy;
} maxima;

static int sample(braun_data *d, maxima *mx, braun_real *pos, braun_real *vel,
                  braun_real *en)
{
    int st = braun_residuals(d, d->t, d->q, d->v, pos, vel, en);
    if (st) return st;
    if (*pos > mx->pos) mx->pos = *pos;
    if (*vel > mx->vel) mx->vel = *vel;
    if (*en > mx->energy) mx->energy = *en;
    return BRAUN_OK;
}

/* Fixed-step run from the paper's initial state; prints its records. The
 * residuals are sampled at the start and after every step (on the run's own
 * data block: braun_residuals only overwrites scratch a step recomputes). */
static int run(const char *name, braun_method method, double h, long steps,
               unsigned corrections, const fw_workspace *ws)
{
    braun_model model;
    braun_data d;
    subject sub = {NULL, NULL, NULL, NULL, 0, NULL};
    maxima mx = {0, 0, 0};
    braun_real pos = 0, vel = 0, en = 0;
    const braun_real hr = (braun_real)h;

    memset(&d, 0, sizeof d);
    int st = setup(name, corrections, ws, &model, &d, &sub);
    const int ready = d.priv != NULL; /* the data block exists: print it */
    fw_puts("run");
    fw_kv_str("model", name);
    fw_kv_str("method", braun_method_name(method));
    fw_kv_str("corrections", corrections_name(corrections));
    fw_kv_long("steps", steps);
    fw_kv_real("h", hr);
    fw_putc('\n');
    if (!st) st = sample(&d, &mx, &pos, &vel, &en);
    for (long i = 0; i < steps && !st; i++) {
        st = braun_step(&d, method, hr);
        if (!st) st = sample(&d, &mx, &pos, &vel, &en);
    }
    if (ready) {
        fw_puts("max");
        fw_kv_real("pos", mx.pos);
        fw_kv_real("vel", mx.vel);
        fw_kv_real("energy", mx.energy);
        fw_putc('\n');
        fw_puts("final");
        fw_kv_real("t", d.t);
        fw_kv_real("pos", pos);
        fw_kv_real("vel", vel);
        fw_kv_real("energy", en);
        fw_putc('\n');
        put_vector("q", sub.sys->n, d.q);
        put_vector("v", sub.sys->n, d.v);
        fw_puts("stats");
        fw_kv_long("steps", d.stats.steps);
        fw_kv_long("rhs", d.stats.rhs_evals);
        fw_kv_long("mass", d.stats.mass_factorizations);
        fw_kv_long("qr", d.stats.constraint_factorizations);
        fw_kv_long("rank_deficient", d.stats.rank_deficient);
        fw_kv_long("guard", d.stats.energy_guard_hits);
        fw_putc('\n');
        fw_puts("# ");
        fw_puts(name);
        fw_puts(" " FW_PRECISION ": t = ");
        fw_put_dec((double)d.t, 6);
        fw_puts("  max |Phi_q| = ");
        fw_put_dec((double)mx.pos, 3);
        fw_puts("  max |dPhi| = ");
        fw_put_dec((double)mx.vel, 3);
        fw_puts("  max |Phi_e| = ");
        fw_put_dec((double)mx.energy, 3);
        fw_puts("\n# q =");
        for (int i = 0; i < sub.sys->n; i++) {
            fw_putc(' ');
            fw_put_dec((double)d.q[i], 9);
        }
        fw_putc('\n');
    }
    put_status(st);
    fw_flush();
    return st;
}

/* The runs of `make firmware-test`: 1000 steps of the slider-crank (1 s,
 * through the first turning point), 200 of the four-bar (2 s), RK4 with
 * every correction and without the energy correction — short enough for
 * the emulator in double (soft-float); then every scene of the build with
 * the corrections its file asks for. `which`: "builtin", "scenes" or all. */
static int cmd_test(const char *which, const fw_workspace *ws)
{
    const int builtin = !which || strcmp(which, "scenes") != 0;
    const int scenes = !which || strcmp(which, "builtin") != 0;
    int bad = 0;
    if (builtin) {
        bad |= run("slider-crank", BRAUN_RK4, 1e-3, 1000, BRAUN_CORRECT_ALL, ws) != 0;
        bad |= run("four-bar", BRAUN_RK4, 1e-2, 200, BRAUN_CORRECT_ALL, ws) != 0;
        bad |= run("slider-crank", BRAUN_RK4, 1e-3, 200,
                   BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY, ws) != 0;
    }
    /* 500 steps (0.5 s) of a small scene; 50 of a large one: IFToMM A04
     * (n = 35, 35 rows) costs 2.6M instructions per step in float and 35M
     * in double (soft-float), 1.75e9 instructions for 50 steps, about 3 s
     * of emulation. */
    for (int i = 0; scenes && fw_platform_scene_at(i); i++) {
        const fw_scene *sc = fw_platform_scene_at(i);
        const long steps = sc->sys.n > 16 ? 50 : 500;
        bad |= run(sc->label, BRAUN_RK4, 1e-3, steps, sc->corrections, ws) != 0;
    }
    return bad;
}

/* One run of any built-in model or scene: `run NAME H STEPS [CORR]`, the
 * records of the test runs (default corrections: the model's). */
static int cmd_run(int argc, char **argv, const fw_workspace *ws)
{
    subject sub;
    if (argc < 4 || find_subject(argv[1], &sub)) return 2;
    const double h = parse_real(argv[2]);
    const long steps = parse_long(argv[3]);
    const int corr = argc > 4 ? parse_corrections(argv[4]) : (int)sub.corrections;
    if (!(h > 0) || steps < 0 || corr < 0) return 2;
    return run(argv[1], BRAUN_RK4, h, steps, (unsigned)corr, ws) != 0;
}

/* `trace NAME STEPS [CORR]`: STEPS RK4 steps (h = 1e-3) and nothing else,
 * for an instruction trace of the step path: tests/firmware/run.sh runs it
 * under QEMU -d exec for 1 and for 1 + k steps, and the difference of the
 * two traces is k steps (the board skips its timer calibration). */
static int cmd_trace(int argc, char **argv, const fw_workspace *ws)
{
    braun_model model;
    braun_data d;
    subject sub;
    if (argc < 3 || find_subject(argv[1], &sub)) return 2;
    const long steps = parse_long(argv[2]);
    const int corr = argc > 3 ? parse_corrections(argv[3]) : (int)sub.corrections;
    const braun_real h = BRAUN_R(1e-3);
    if (steps < 0 || corr < 0) return 2;
    memset(&d, 0, sizeof d);
    int st = setup(argv[1], (unsigned)corr, ws, &model, &d, &sub);
    long i = 0;
    for (; i < steps && !st; i++) st = braun_step(&d, BRAUN_RK4, h);
    fw_puts("trace");
    fw_kv_str("model", argv[1]);
    fw_kv_str("corrections", corrections_name((unsigned)corr));
    fw_kv_long("steps", i);
    fw_kv_long("rank_deficient", d.priv ? d.stats.rank_deficient : -1);
    fw_kv_long("guard", d.priv ? d.stats.energy_guard_hits : -1);
    fw_kv_long("status", st);
    fw_putc('\n');
    fw_flush();
    return st != 0;
}

/* ------------------------------------------------------------ bench */

/* Ticks of an empty measurement (two consecutive reads), minimum of 64. */
static unsigned long tick_overhead(void)
{
    unsigned long best = (unsigned long)-1;
    for (int i = 0; i < 64; i++) {
        unsigned long a = fw_platform_ticks();
        unsigned long b = fw_platform_ticks();
        if (b - a < best) best = b - a;
    }
    return best;
}

/* `steps` RK4 steps from the paper's state, each timed on its own; the
 * record counts the steps done (a run that fails stops early and says so
 * in status). On the host, callgrind counts the instructions of braun_step. */
static int bench_one(const char *name, unsigned corrections, long steps,
                     double h, const fw_workspace *ws)
{
    braun_model model;
    braun_data d;
    subject sub = {NULL, NULL, NULL, NULL, 0, NULL};
    unsigned long tmin = (unsigned long)-1, tmax = 0, tsum = 0;
    const unsigned long over = tick_overhead();
    long done = 0, imax = -1;
    /* Converted once, outside the timed window (a double-to-float call on
     * the M4F). */
    const braun_real hr = (braun_real)h;
    memset(&d, 0, sizeof d);
    int st = setup(name, corrections, ws, &model, &d, &sub);
    const int ready = d.priv != NULL;
    for (long i = 0; i < steps && !st; i++) {
        const unsigned long t0 = fw_platform_ticks();
        st = braun_step(&d, BRAUN_RK4, hr);
        const unsigned long dt = fw_platform_ticks() - t0 - over;
        if (st) break; /* a failed step is not a step */
        if (dt < tmin) tmin = dt;
        if (dt > tmax) {
            tmax = dt;
            imax = i;
        }
        tsum += dt;
        done++;
    }
    fw_puts("bench");
    fw_kv_str("model", name);
    fw_kv_str("precision", FW_PRECISION);
    fw_kv_str("corrections", corrections_name(corrections));
    fw_kv_long("steps", done);
    fw_kv_long("ticks_min", (long)tmin);
    fw_kv_long("ticks_max", (long)tmax);
    fw_kv_long("ticks_sum", (long)tsum);
    fw_kv_long("step_max", imax); /* 0-based index of the dearest step */
    fw_kv_long("tick_overhead", (long)over);
    fw_kv_long("rank_deficient", ready ? d.stats.rank_deficient : -1);
    fw_kv_long("guard", ready ? d.stats.energy_guard_hits : -1);
    fw_kv_long("status", st);
    fw_putc('\n');
    fw_flush();
    return st;
}

static int cmd_bench(int argc, char **argv, const fw_workspace *ws)
{
    static const struct {
        const char *model;
        double h;
    } models[] = {{"slider-crank", 1e-3}, {"four-bar", 1e-2}};
    static const unsigned corr[] = {BRAUN_CORRECT_NONE,
                                    BRAUN_CORRECT_POSITION | BRAUN_CORRECT_VELOCITY,
                                    BRAUN_CORRECT_ALL};
    long steps = argc > 1 ? parse_long(argv[1]) : 100;
    int only_corr = argc > 3 ? parse_corrections(argv[3]) : -1;
    int bad = 0, listed = 0;
    if (steps <= 0 || (argc > 3 && only_corr < 0)) return 2;
    for (size_t m = 0; argc > 2 && m < sizeof models / sizeof models[0]; m++)
        listed |= strcmp(argv[2], models[m].model) == 0;
    if (argc > 2 && !listed) {
        /* Any other built-in model or scene of this build, at h = 1e-3. */
        subject sub;
        if (find_subject(argv[2], &sub)) return 2;
        for (size_t c = 0; c < sizeof corr / sizeof corr[0]; c++) {
            if (only_corr >= 0 && (unsigned)only_corr != corr[c]) continue;
            bad |= bench_one(argv[2], corr[c], steps, 1e-3, ws) != 0;
        }
        return bad;
    }
    for (size_t m = 0; m < sizeof models / sizeof models[0]; m++) {
        if (argc > 2 && strcmp(argv[2], models[m].model) != 0) continue;
        for (size_t c = 0; c < sizeof corr / sizeof corr[0]; c++) {
            if (only_corr >= 0 && (unsigned)only_corr != corr[c]) continue;
            bad |= bench_one(models[m].model, corr[c], steps, models[m].h, ws) != 0;
        }
    }
    return bad;
}

/* ------------------------------------------------------------ long run */

/* libbraun (all corrections) and RK4 on the minimal equation side by side;
 * every `every` steps a record "s i q[0..n) theta omega". */
static int cmd_long(int argc, char **argv, const fw_workspace *ws)
{
    if (argc < 5) return 2;
    const double h = parse_real(argv[2]);
    const long steps = parse_long(argv[3]), every = parse_long(argv[4]);
    if (!(h > 0) || steps <= 0 || every <= 0) return 2;
    braun_model model;
    braun_data d;
    subject sub = {NULL, NULL, NULL, NULL, 0, NULL};
    fw_minimal mini = {0, 0, {0, 0}};
    maxima mx = {0, 0, 0};
    braun_real pos = 0, vel = 0, en = 0, t_max_pos = 0;
    memset(&d, 0, sizeof d);
    int st = setup(argv[1], BRAUN_CORRECT_ALL, ws, &model, &d, &sub);
    const braun_builtin *b = sub.builtin;
    if (!st && (!b || fw_minimal_init(&mini, b) != 0)) st = BRAUN_ERR_ARGUMENT;
    fw_puts("long");
    fw_kv_str("model", argv[1]);
    fw_kv_str("precision", FW_PRECISION);
    fw_kv_real("h", (braun_real)h);
    fw_kv_long("steps", steps);
    fw_kv_long("every", every);
    fw_putc('\n');
    if (!st) st = sample(&d, &mx, &pos, &vel, &en);
    long i = 0;
    for (;;) {
        if (st || i % every == 0 || i == steps) {
            fw_putc('s');
            fw_putc(' ');
            fw_put_long(i);
            for (int k = 0; b && !st && k < b->sys.n; k++) {
                fw_putc(' ');
                fw_put_hex_real(d.q[k]);
            }
            fw_putc(' ');
            fw_put_hex_real(mini.y[0]);
            fw_putc(' ');
            fw_put_hex_real(mini.y[1]);
            fw_putc('\n');
        }
        if (st || i == steps) break;
        st = braun_step(&d, BRAUN_RK4, (braun_real)h);
        fw_minimal_step(&mini, (braun_real)h);
        i++;
        if (!st) {
            const braun_real before = mx.pos;
            st = sample(&d, &mx, &pos, &vel, &en);
            if (mx.pos > before) t_max_pos = (braun_real)((double)i * h);
        }
    }
    fw_puts("max");
    fw_kv_real("pos", mx.pos);
    fw_kv_real("vel", mx.vel);
    fw_kv_real("energy", mx.energy);
    fw_kv_real("t_max_pos", t_max_pos);
    fw_kv_long("steps_done", i);
    fw_kv_long("rank_deficient", d.stats.rank_deficient);
    fw_kv_long("guard", d.stats.energy_guard_hits);
    fw_putc('\n');
    put_status(st);
    fw_flush();
    return st != 0;
}

/* ------------------------------------------------------------ limits */

/* `limits`: braun_integrate refuses a span of more steps than its counter
 * (a long: 32 bits here) holds — 1e10 steps of 1e-10 s — with
 * BRAUN_ERR_TOO_MANY_STEPS and the state untouched, instead of running
 * 2^31 steps and a last one of most of the span. */
static int cmd_limits(const fw_workspace *ws)
{
    braun_model model;
    braun_data d;
    subject sub;
    memset(&d, 0, sizeof d);
    int st = setup("pendulum", BRAUN_CORRECT_ALL, ws, &model, &d, &sub);
    if (!st) st = braun_integrate(&d, BRAUN_RK4, BRAUN_R(1e-10), BRAUN_R(1.0), 0, NULL, NULL);
    fw_puts("limits");
    fw_kv_long("long_bits", (long)(sizeof(long) * 8));
    fw_kv_long("status", st);
    fw_kv_long("t_untouched", d.priv ? d.t == 0 : 0);
    fw_putc('\n');
    fw_flush();
    return 0;
}

/* ------------------------------------------------------------ dadd */

/* `dadd`: how many of 20000 sums 1 + b, b uniform in -[2^-33, 2^-32), this
 * platform's double addition rounds wrongly. On the M4F double is libgcc's
 * __adddf3 (libgcc/config/arm/ieee754-df.S): for an alignment shift of 33
 * it keeps one bit of the smaller operand's low word plus a sticky bit, so
 * when the difference then normalises left by one bit (1 − b < 1) the
 * rounding bit is lost; x86-64 (SSE2) rounds all correctly. The check is
 * exact: r = 1 + b lies in [1/2, 1], so 1 − r is exact (Sterbenz), and
 * e = (1 − r) + b, two numbers within a factor 4 of each other, is the
 * exact rounding error, which must not exceed half an ulp (2^-54; a tie
 * goes to even). */
static int cmd_dadd(void)
{
    unsigned long long x = 88172645463325252ull;
    long bad = 0;
    const long samples = 20000;
    for (long i = 0; i < samples; i++) {
        volatile double one = 1.0, b;
        unsigned long long bits;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        /* sign 1, exponent 1023 - 33, a random significand */
        bits = (x & 0x000FFFFFFFFFFFFFull) | (990ull << 52) | 0x8000000000000000ull;
        double bv;
        memcpy(&bv, &bits, sizeof bv);
        b = bv;
        const double r = one + b;
        const double e = (one - r) + b, half = 5.551115123125783e-17; /* 2^-54 */
        unsigned long long rbits;
        memcpy(&rbits, &r, sizeof rbits);
        if (e > half || e < -half || ((e == half || e == -half) && (rbits & 1u))) bad++;
    }
    fw_puts("dadd");
    fw_kv_long("samples", samples);
    fw_kv_long("misrounded", bad);
    fw_putc('\n');
    fw_flush();
    return 0;
}

/* ------------------------------------------------------------ sizes */

static int count_builtins(void)
{
    int k = 0;
    while (braun_builtin_at(k)) k++;
    return k;
}

/* braun_data_size() of every built-in model and scene this build supports (a library
 * built for fixed sizes refuses the others); with `header` as C #defines:
 * FW_DATA_BYTES_<MODEL>, FW_DATA_BYTES_MAX and FW_DATA_BYTES_TABLE. */
static int cmd_sizes(int header)
{
    size_t biggest = 0;
    for (int pass = 0; pass < (header ? 2 : 1); pass++) {
        if (pass == 1) fw_puts("#define FW_DATA_BYTES_TABLE");
        const int nb = count_builtins();
        for (int i = 0; i < nb || fw_platform_scene_at(i - nb); i++) {
            const braun_builtin *bi = i < nb ? braun_builtin_at(i) : NULL;
            const fw_scene *sc = bi ? NULL : fw_platform_scene_at(i - nb);
            const char *name = bi ? bi->name : sc->label;
            const braun_system *sys = bi ? &bi->sys : &sc->sys;
            braun_model model;
            const int st = braun_model_init(&model, sys);
            const size_t bytes = st ? 0 : braun_data_size(&model);
            if (bytes > biggest) biggest = bytes;
            if (header && st) continue;
            if (pass == 1) {
                fw_puts(" {\"");
                fw_puts(name);
                fw_puts("\", ");
                fw_put_ulong((unsigned long)bytes);
                fw_puts("},");
            } else if (header) {
                fw_puts("#define FW_DATA_BYTES_");
                for (const char *c = name; *c; c++)
                    fw_putc(*c == '-' || *c == ':' ? '_' : (char)(*c >= 'a' && *c <= 'z' ? *c - 'a' + 'A' : *c));
                fw_putc(' ');
                fw_put_ulong((unsigned long)bytes);
                fw_putc('\n');
            } else {
                fw_puts("sizes");
                fw_kv_str("model", name);
                fw_kv_str("kind", bi ? "builtin" : "scene");
                fw_kv_str("precision", FW_PRECISION);
                fw_kv_long("n", sys->n);
                fw_kv_long("m", sys->m);
                fw_kv_long("p", sys->p);
                if (st)
                    fw_kv_str("data_bytes", "unsupported");
                else
                    fw_kv_long("data_bytes", (long)bytes);
                fw_kv_long("sizeof_model", (long)sizeof(braun_model));
                fw_kv_long("sizeof_data", (long)sizeof(braun_data));
                fw_putc('\n');
            }
        }
        if (pass == 1) fw_putc('\n');
    }
    if (header) {
        fw_puts("#define FW_DATA_BYTES_MAX ");
        fw_put_ulong((unsigned long)biggest);
        fw_putc('\n');
    }
    fw_flush();
    return 0;
}

/* ------------------------------------------------------------ main */

int fw_demo_main(int argc, char **argv, const fw_workspace *ws)
{
    const char *cmd = argc > 0 ? argv[0] : "test";
    int rc;
    if (strcmp(cmd, "sizes-header") != 0) {
        fw_puts("platform");
        fw_kv_str("name", fw_platform_name);
        fw_kv_str("precision", FW_PRECISION);
        fw_kv_str("version", BRAUN_VERSION);
        fw_kv_long("workspace_bytes", (long)ws->bytes);
        fw_putc('\n');
    }
    if (strcmp(cmd, "test") == 0)
        rc = cmd_test(argc > 1 ? argv[1] : NULL, ws);
    else if (strcmp(cmd, "run") == 0)
        rc = cmd_run(argc, argv, ws);
    else if (strcmp(cmd, "trace") == 0)
        rc = cmd_trace(argc, argv, ws);
    else if (strcmp(cmd, "bench") == 0)
        rc = cmd_bench(argc, argv, ws);
    else if (strcmp(cmd, "long") == 0)
        rc = cmd_long(argc, argv, ws);
    else if (strcmp(cmd, "dadd") == 0)
        rc = cmd_dadd();
    else if (strcmp(cmd, "limits") == 0)
        rc = cmd_limits(ws);
    else if (strcmp(cmd, "sizes") == 0)
        rc = cmd_sizes(0);
    else if (strcmp(cmd, "sizes-header") == 0)
        rc = cmd_sizes(1);
    else
        rc = 2;
    if (rc == 2) fw_puts("usage: test [builtin|scenes] | run NAME H STEPS [CORR] | trace NAME STEPS [CORR] | bench STEPS [MODEL [CORR]] | long MODEL H STEPS EVERY | dadd | limits | sizes | sizes-header\n");
    fw_flush();
    return rc;
}
