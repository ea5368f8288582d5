/*
 * Compare the demo's records from the emulated Cortex-M4 with the host
 * build of the same runs (firmware/demo/fw_demo.c prints them).
 *
 *   fw_compare [--exact MODEL]... [--exact-float MODEL]...
 *              [--bound PREC MODEL PAIR REF]...
 *              DOUBLE_TARGET DOUBLE_HOST FLOAT_TARGET FLOAT_HOST
 *
 * Prints "ok - ..." / "not ok - ..." per check; exit status 1 if any failed.
 * Reals are read from their exact IEEE bit patterns. The bounds (see
 * docs/firmware.md, "Host and target agree"):
 *   double  target vs host, final q and v: ||Δ||∞ <= 2e-14 ||x||∞. The only
 *           difference between the two is libm (newlib's fdlibm sin/cos vs
 *           glibc's, each within 1 ulp): ~1e-16 per call, accumulated over
 *           4000 evaluations and amplified by the flow over 1 s, measured
 *           6.4e-15 (the largest over the runs). Nine orders below what any
 *           float arithmetic would leave.
 *   float   each float run (target and host) within 4e-4 ||x||∞ of the
 *           double host run (measured 1.4e-4); target vs host within 6e-5
 *           (measured 2.0e-5: they differ by their own round-off, amplified
 *           near the slider-crank's bifurcation point).
 *   both    statistics (steps, evaluations, factorizations) equal; maxima of
 *           the residuals within a factor 10 (+ 100 ε): they are round-off
 *           level, so only their order of magnitude is reproducible;
 *           --exact MODEL: every bit equal (a model without transcendental
 *           functions: IEEE arithmetic is the same on both); --exact-float
 *           MODEL: the same in float only (double on the M4F is libgcc's
 *           soft-float, whose __adddf3 misrounds a rare case: `dadd`).
 *   --bound PREC MODEL PAIR REF: this model's own bounds in precision PREC
 *           (double or float) instead of the defaults above (REF: float
 *           only, the distance from the double host run; 0 keeps the
 *           default). Each is set from a measurement (tests/firmware/run.sh).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LINES 4096
#define MAX_TOK 24

typedef struct line {
    char tag[16];
    int ntok;
    char tok[MAX_TOK][48];
} line;

typedef struct file {
    const char *path;
    int n;
    line *l;
} file;

static int passed, failed;

/* Per-model bounds (--bound). */
typedef struct bound {
    const char *prec, *model;
    double pair, ref;
} bound;
#define MAX_BOUNDS 16
static bound bounds[MAX_BOUNDS];
static int nbounds;

static void report(int ok, const char *what, const char *detail)
{
    if (ok) passed++; else failed++;
    printf("%s - %s%s%s\n", ok ? "ok" : "not ok", what, detail && *detail ? ": " : "",
           detail ? detail : "");
}

static int load(file *f, const char *path)
{
    FILE *fp = fopen(path, "r");
    char buf[2048];
    f->path = path;
    f->n = 0;
    f->l = NULL;
    if (!fp) return -1;
    f->l = calloc(MAX_LINES, sizeof *f->l);
    if (!f->l) {
        fclose(fp);
        return -1;
    }
    while (fgets(buf, sizeof buf, fp) && f->n < MAX_LINES) {
        if (buf[0] == '#' || buf[0] == '\n') continue;
        line *ln = &f->l[f->n];
        char *save = NULL, *t = strtok_r(buf, " \n", &save);
        if (!t) continue;
        snprintf(ln->tag, sizeof ln->tag, "%s", t);
        ln->ntok = 0;
        while ((t = strtok_r(NULL, " \n", &save)) && ln->ntok < MAX_TOK)
            snprintf(ln->tok[ln->ntok++], sizeof ln->tok[0], "%s", t);
        f->n++;
    }
    fclose(fp);
    return 0;
}

/* Value of a token "key=0x..." or "0x..." as a double (float widened). */
static int real_of(const char *tok, double *x)
{
    const char *v = strchr(tok, '=');
    v = v ? v + 1 : tok;
    if (strncmp(v, "0x", 2) != 0) return -1;
    size_t len = strlen(v + 2);
    uint64_t bits = strtoull(v + 2, NULL, 16);
    if (len == 8) {
        uint32_t b32 = (uint32_t)bits;
        float f;
        memcpy(&f, &b32, sizeof f);
        *x = f;
    } else if (len == 16) {
        memcpy(x, &bits, sizeof *x);
    } else {
        return -1;
    }
    return 0;
}

/* Value of key in a line, as text; NULL if absent. */
static const char *get(const line *ln, const char *key)
{
    size_t k = strlen(key);
    for (int i = 0; i < ln->ntok; i++)
        if (strncmp(ln->tok[i], key, k) == 0 && ln->tok[i][k] == '=') return ln->tok[i] + k + 1;
    return NULL;
}

/* Index of the r-th "run" line, and of the record `tag` after it (before
 * the next run); -1 if none. */
static int run_index(const file *f, int r)
{
    for (int i = 0; i < f->n; i++)
        if (strcmp(f->l[i].tag, "run") == 0 && r-- == 0) return i;
    return -1;
}

static int record(const file *f, int run, const char *tag)
{
    for (int i = run + 1; i < f->n && strcmp(f->l[i].tag, "run") != 0; i++)
        if (strcmp(f->l[i].tag, tag) == 0) return i;
    return -1;
}

static int count_runs(const file *f)
{
    int k = 0;
    for (int i = 0; i < f->n; i++) k += strcmp(f->l[i].tag, "run") == 0;
    return k;
}

/* ||a - b||∞ / ||ref||∞ over the values of two vector records. */
static double vec_rel(const line *a, const line *b, const line *ref)
{
    double dmax = 0, rmax = 0;
    if (a->ntok != b->ntok || a->ntok != ref->ntok) return INFINITY;
    for (int i = 0; i < a->ntok; i++) {
        double x, y, r;
        if (real_of(a->tok[i], &x) || real_of(b->tok[i], &y) || real_of(ref->tok[i], &r))
            return INFINITY;
        if (!(fabs(x - y) <= dmax)) dmax = fabs(x - y);
        if (fabs(r) > rmax) rmax = fabs(r);
    }
    return rmax > 0 ? dmax / rmax : dmax;
}

static int lines_equal(const line *a, const line *b)
{
    if (strcmp(a->tag, b->tag) != 0 || a->ntok != b->ntok) return 0;
    for (int i = 0; i < a->ntok; i++)
        if (strcmp(a->tok[i], b->tok[i]) != 0) return 0;
    return 1;
}

/* Compare the runs of a target file with a host file of the same precision;
 * ref: the double host file (reference for float runs), or NULL. */
static void compare(const file *tg, const file *ho, const file *ref, const char *prec,
                    double def_pair, double def_ref, double eps, char **exact, int nexact)
{
    char what[256], detail[256];
    int nr = count_runs(ho);
    snprintf(what, sizeof what, "%s: target and host made the same runs", prec);
    snprintf(detail, sizeof detail, "%d and %d", count_runs(tg), nr);
    report(nr > 0 && count_runs(tg) == nr, what, detail);
    for (int r = 0; r < nr; r++) {
        int it = run_index(tg, r), ih = run_index(ho, r);
        if (it < 0 || ih < 0) break;
        const line *hr = &ho->l[ih];
        const char *model = get(hr, "model");
        char name[128];
        snprintf(name, sizeof name, "%s %s %s %s steps", prec, model ? model : "?",
                 get(hr, "corrections") ? get(hr, "corrections") : "?",
                 get(hr, "steps") ? get(hr, "steps") : "?");
        snprintf(what, sizeof what, "%s: same run header", name);
        report(lines_equal(&tg->l[it], hr), what, NULL);

        int st = record(tg, it, "status"), sh = record(ho, ih, "status");
        snprintf(what, sizeof what, "%s: both runs end with BRAUN_OK", name);
        report(st >= 0 && sh >= 0 && get(&tg->l[st], "code") && get(&ho->l[sh], "code") &&
                   strcmp(get(&tg->l[st], "code"), "0") == 0 &&
                   strcmp(get(&ho->l[sh], "code"), "0") == 0,
               what, NULL);

        int at = record(tg, it, "stats"), ah = record(ho, ih, "stats");
        snprintf(what, sizeof what, "%s: same statistics", name);
        report(at >= 0 && ah >= 0 && lines_equal(&tg->l[at], &ho->l[ah]), what,
               at >= 0 && ah >= 0 && !lines_equal(&tg->l[at], &ho->l[ah]) ? "differ" : NULL);

        int exact_model = 0;
        for (int k = 0; k < nexact; k++) exact_model |= model && strcmp(model, exact[k]) == 0;
        double tol_pair = def_pair, tol_ref = def_ref;
        for (int k = 0; k < nbounds; k++)
            if (model && strcmp(bounds[k].prec, prec) == 0 && strcmp(bounds[k].model, model) == 0) {
                if (bounds[k].pair > 0) tol_pair = bounds[k].pair;
                if (bounds[k].ref > 0) tol_ref = bounds[k].ref;
            }
        if (exact_model) {
            int same = 1;
            const char *tags[] = {"max", "final", "q", "v"};
            for (int k = 0; k < 4; k++) {
                int a = record(tg, it, tags[k]), b = record(ho, ih, tags[k]);
                same &= a >= 0 && b >= 0 && lines_equal(&tg->l[a], &ho->l[b]);
            }
            snprintf(what, sizeof what, "%s: every bit of the state and residuals equal", name);
            report(same, what, NULL);
        }

        for (int k = 0; k < 2; k++) {
            const char *tag = k ? "v" : "q";
            int a = record(tg, it, tag), b = record(ho, ih, tag);
            if (a < 0 || b < 0) {
                snprintf(what, sizeof what, "%s: final %s printed", name, tag);
                report(0, what, NULL);
                continue;
            }
            double rel = vec_rel(&tg->l[a], &ho->l[b], &ho->l[b]);
            snprintf(what, sizeof what, "%s: final %s target vs host <= %.0e", name, tag, tol_pair);
            snprintf(detail, sizeof detail, "%.2e", rel);
            report(rel <= tol_pair, what, detail);
            if (ref) {
                int rr = run_index(ref, r), c = rr >= 0 ? record(ref, rr, tag) : -1;
                const line *refl = c >= 0 ? &ref->l[c] : NULL;
                for (int w = 0; w < 2; w++) {
                    const line *x = w ? &ho->l[b] : &tg->l[a];
                    double e = refl ? vec_rel(x, refl, refl) : INFINITY;
                    snprintf(what, sizeof what, "%s: final %s of the %s within %.0e of double",
                             name, tag, w ? "host" : "target", tol_ref);
                    snprintf(detail, sizeof detail, "%.2e", e);
                    report(e <= tol_ref, what, detail);
                }
            }
        }

        int mt = record(tg, it, "max"), mh = record(ho, ih, "max");
        const char *keys[] = {"pos", "vel", "energy"};
        for (int k = 0; k < 3; k++) {
            double x = NAN, y = NAN;
            if (mt >= 0 && mh >= 0 && get(&tg->l[mt], keys[k]) && get(&ho->l[mh], keys[k])) {
                real_of(get(&tg->l[mt], keys[k]), &x);
                real_of(get(&ho->l[mh], keys[k]), &y);
            }
            double lo = x < y ? x : y, hi = x < y ? y : x;
            snprintf(what, sizeof what, "%s: max residual %s same order (x10 + 100 eps)", name, keys[k]);
            snprintf(detail, sizeof detail, "target %.3g host %.3g", x, y);
            report(hi <= 10 * lo + 100 * eps, what, detail);
        }
    }
}

int main(int argc, char **argv)
{
    char *exact[8], *exact_f[16];
    int nexact = 0, nexact_f = 0, i = 1;
    for (;;) {
        if (i + 1 < argc && strcmp(argv[i], "--exact") == 0 && nexact < 8) {
            exact[nexact++] = argv[i + 1];
            exact_f[nexact_f++] = argv[i + 1];
            i += 2;
        } else if (i + 1 < argc && strcmp(argv[i], "--exact-float") == 0 && nexact_f < 16) {
            exact_f[nexact_f++] = argv[i + 1];
            i += 2;
        } else if (i + 4 < argc && strcmp(argv[i], "--bound") == 0 && nbounds < MAX_BOUNDS) {
            char *end1, *end2;
            bound *b = &bounds[nbounds++];
            b->prec = argv[i + 1];
            b->model = argv[i + 2];
            b->pair = strtod(argv[i + 3], &end1);
            b->ref = strtod(argv[i + 4], &end2);
            if (*end1 || *end2 || !(b->pair >= 0) || !(b->ref >= 0) ||
                (strcmp(b->prec, "double") != 0 && strcmp(b->prec, "float") != 0)) {
                fprintf(stderr, "fw_compare: --bound %s %s %s %s: PREC is double or float, PAIR and REF numbers >= 0\n",
                        argv[i + 1], argv[i + 2], argv[i + 3], argv[i + 4]);
                return 2;
            }
            i += 5;
        } else {
            break;
        }
    }
    if (argc - i != 4) {
        fprintf(stderr, "usage: fw_compare [--exact MODEL]... [--exact-float MODEL]... "
                        "[--bound PREC MODEL PAIR REF]... DOUBLE_TARGET DOUBLE_HOST FLOAT_TARGET FLOAT_HOST\n");
        return 2;
    }
    file dt = {0}, dh = {0}, ft = {0}, fh = {0};
    int bad = load(&dt, argv[i]) | load(&dh, argv[i + 1]) | load(&ft, argv[i + 2]) |
              load(&fh, argv[i + 3]);
    if (bad) {
        fprintf(stderr, "fw_compare: cannot read the outputs\n");
        free(dt.l);
        free(dh.l);
        free(ft.l);
        free(fh.l);
        return 2;
    }
    compare(&dt, &dh, NULL, "double", 2e-14, 0, 2.220446049250313e-16, exact, nexact);
    compare(&ft, &fh, &dh, "float", 6e-5, 4e-4, 1.1920928955078125e-07, exact_f, nexact_f);
    free(dt.l);
    free(dh.l);
    free(ft.l);
    free(fh.l);
    return failed ? 1 : 0;
}
