/* Input hygiene at the C level (issue 12, item 7; the command line is in
 * tests/cli/hygiene.sh):
 *   - gen-c writes every scene text as comment text that cannot end or
 *     nest a comment, form a trigraph or splice a line, and refuses bad
 *     symbols and class c_names before writing anything;
 *   - the reader's limits: the smallest values it takes work (a pendulum
 *     of mass, length or axis at BRAUN_SCENE_MIN_SCALE moves as the unit
 *     one), the next smaller are refused at their field; subnormals are
 *     refused; the mass matrix's pivot rule is the core's;
 *   - zero-length springs are refused at load and named at any state
 *     (braun_scene_file_diagnose); FIFOs and directories never block. */
#define _POSIX_C_SOURCE 200809L /* mkfifo, mkdtemp, open_memstream */
#include <float.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test_util.h"
#include "braun_scene_file.h"

static braun_scene_file *load(const char *text, char *err, size_t size)
{
    return braun_scene_load_text("t.json", text, strlen(text), err, size);
}

static char *gen(const braun_scene_file *f, const char *sym, const char *source, int *rc)
{
    char *buf = NULL, err[256];
    size_t len = 0;
    FILE *out = open_memstream(&buf, &len);
    assert_non_null(out);
    *rc = braun_gen_c_write_ex(out, f, sym, source, err, sizeof err);
    fclose(out);
    return buf;
}

/* ------------------------------------------------------------- gen-c */
static const char pendulum[] =
    "{\"name\": \"p\", \"description\": \"d\", \"bodies\": [{\"name\": \"bob\", \"type\": "
    "\"particle\", \"mass\": 1, \"position\": [1, 0]}], \"joints\": [{\"name\": \"rod\", "
    "\"type\": \"distance\", \"a\": [0, 0], \"b\": \"bob\"}], \"effects\": [{\"type\": "
    "\"gravity\", \"g\": [0, -9.81]}]}";

/* The description as gen-c writes it (the header comment's second line). */
static void escaped(const char *description, char *line, size_t size)
{
    char err[256];
    int rc;
    braun_scene_file *f = load(pendulum, err, sizeof err);
    assert_non_null(f);
    braun_scene_file copy = *f;
    copy.description = description;
    char *out = gen(&copy, "p", "t.json", &rc);
    assert_int_equal(rc, 0);
    const char *start = strstr(out, "\n * ");
    assert_non_null(start);
    start += 4;
    const char *end = strchr(start, '\n');
    snprintf(line, size, "%.*s", (int)(end - start), start);
    free(out);
    braun_scene_free(f);
}

static void test_gen_c_escapes(void **state)
{
    (void)state;
    static const struct {
        const char *in, *out;
    } cases[] = {
        {"a */ b", "a *\\/ b"},           /* would end the comment */
        {"a /* b", "a /\\* b"},           /* a nested opener (-Wcomment) */
        {"*/*/", "*\\/\\*\\/"},
        {"ends in ?\?/", "ends in ?\\?/"}, /* the trigraph of a backslash */
        {"?\?\?", "?\\?\\?"},
        {"back\\slash\\", "back\\x5Cslash\\x5C"},
        {"two\nlines", "two\\x0Alines"},
        {"tab\tdel\x7f", "tab\\x09del\\x7F"},
        {"caf\xc3\xa9", "caf\\u00E9"},
        {"\xe2\x80\xae" "rlo", "\\u202Erlo"},       /* a bidi override, as text */
        {"\xf0\x9f\x98\x80", "\\U0001F600"},
        {"\xff\xc0\xaf", "\\xFF\\xC0\\xAF"},        /* invalid and overlong UTF-8 */
        {"\xed\xa0\x80", "\\xED\\xA0\\x80"},        /* a surrogate */
    };
    char line[1024];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        escaped(cases[i].in, line, sizeof line);
        if (strcmp(line, cases[i].out) != 0)
            fail_msg("case %zu: got '%s', expected '%s'", i, line, cases[i].out);
    }
    /* At most 160 bytes of a text, then "...". */
    char longer[400];
    memset(longer, 'x', sizeof longer - 1);
    longer[sizeof longer - 1] = '\0';
    escaped(longer, line, sizeof line);
    assert_int_equal(strlen(line), 163);
    assert_string_equal(line + 160, "...");
    /* A multi-byte character is not cut at the limit. */
    memset(longer, 'x', 159);
    memcpy(longer + 159, "\xc3\xa9yyy", 6);
    escaped(longer, line, sizeof line);
    assert_string_equal(line + 159, "...");
}

static void test_gen_c_names_and_symbols(void **state)
{
    (void)state;
    char err[256], why[256];
    int rc;
    braun_scene_file *f = load(pendulum, err, sizeof err);
    assert_non_null(f);
    /* Names go into item comments, escaped the same way. */
    braun_scene_file copy = *f;
    const char *bodies[] = {"b*/ int x; /*"}, *joints[] = {"?\?/"};
    copy.body_names = bodies;
    copy.joint_names = joints;
    copy.name = "n*/";
    char *out = gen(&copy, "p", "dir*/s.json", &rc);
    assert_int_equal(rc, 0);
    assert_non_null(strstr(out, "/* b*\\/ int x; /\\* */"));
    assert_non_null(strstr(out, "/* ?\\?/ */"));
    assert_non_null(strstr(out, "from dir*\\/s.json (scene \"n*\\/\")"));
    free(out);

    static const char *const bad[] = {"", "9x", "a-b", "caf\xc3\xa9", "_x", "braun", "braun_x",
                                      "BRAUN_scene", "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(braun_gen_c_check_symbol(bad[i], why, sizeof why), -1);
        assert_true(strncmp(why, "the symbol ", 11) == 0);
        out = gen(f, bad[i], "s.json", &rc);
        assert_int_equal(rc, BRAUN_GEN_C_INVALID);
        assert_int_equal(strlen(out), 0); /* nothing written */
        free(out);
    }
    static const char *const good[] = {"p", "braunx", "x_braun", "S_9",
                                       "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa"};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++)
        assert_int_equal(braun_gen_c_check_symbol(good[i], why, sizeof why), 0);

    /* A class whose c_name is not an identifier: refused, named, nothing written. */
    braun_scene_joint_class evil = *f->scene.joints[0].type;
    evil.c_name = "&x; int injected; //";
    braun_scene_file bad_class = *f;
    braun_scene_joint j = f->scene.joints[0];
    j.type = &evil;
    bad_class.scene.joints = &j;
    char ebuf[256];
    char *buf = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&buf, &len);
    rc = braun_gen_c_write_ex(mem, &bad_class, "p", "s.json", ebuf, sizeof ebuf);
    fclose(mem);
    assert_int_equal(rc, BRAUN_GEN_C_INVALID);
    assert_int_equal(len, 0);
    assert_string_equal(ebuf, "joint 'rod': the c_name of its class 'distance' is not a C "
                              "identifier or '&identifier'");
    free(buf);
    /* A keyword is no identifier: "&int" was written (extern const
     * braun_scene_joint_class int;) and the output did not compile. */
    static const char *const keywords[] = {"&int", "&while", "static", "&_Bool"};
    for (size_t k = 0; k < sizeof keywords / sizeof keywords[0]; k++) {
        evil.c_name = keywords[k];
        buf = NULL;
        mem = open_memstream(&buf, &len);
        rc = braun_gen_c_write_ex(mem, &bad_class, "p", "s.json", ebuf, sizeof ebuf);
        fclose(mem);
        assert_int_equal(rc, BRAUN_GEN_C_INVALID);
        assert_int_equal(len, 0);
        free(buf);
    }
    assert_int_equal(braun_gen_c_check_symbol("braun", why, sizeof why), -1);
    assert_non_null(strstr(why, "must not be 'braun'")); /* it said "start with 'braun_'" */
    braun_scene_free(f);
    /* −0 keeps its sign: "%.17g" wrote R(-0), an int, whose cast is +0. */
    f = load("{\"name\": \"z\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", "
             "\"mass\": 1, \"position\": [-0.0, 1]}], \"joints\": [{\"type\": \"distance\", "
             "\"a\": [0, 0], \"b\": \"b\"}]}", err, sizeof err);
    if (!f) fail_msg("%s", err);
    out = gen(f, "z", "z.json", &rc);
    assert_int_equal(rc, 0);
    assert_non_null(strstr(out, "R(-0.0)"));
    assert_null(strstr(out, "R(-0)"));
    free(out);
    braun_scene_free(f);
}

/* A stream that fails (/dev/full: every write is ENOSPC) is reported by
 * each writer's return, whatever the text's length: a header and a small
 * scene's source fit stdio's buffer, were not flushed, and returned 0 (the
 * failure only at the caller's fclose). */
static void test_gen_c_stream_failure(void **state)
{
    (void)state;
    char err[256];
    braun_scene_file *f = load(pendulum, err, sizeof err);
    assert_non_null(f);
    FILE *out = fopen("/dev/full", "w");
    if (!out) {
        braun_scene_free(f);
        skip();
    }
    strcpy(err, "unchanged");
    assert_int_equal(braun_gen_c_write_ex(out, f, "p", "t.json", err, sizeof err),
                     BRAUN_GEN_C_WRITE);
    assert_string_equal(err, "write error");
    fclose(out);
    out = fopen("/dev/full", "w");
    assert_non_null(out);
    strcpy(err, "unchanged");
    assert_int_equal(braun_gen_c_write_header(out, f, "p", "t.json", err, sizeof err),
                     BRAUN_GEN_C_WRITE);
    assert_string_equal(err, "write error");
    fclose(out);
    out = fopen("/dev/full", "w");
    assert_non_null(out);
    assert_int_equal(braun_gen_c_write(out, f, "p", "t.json"), -1);
    fclose(out);
    braun_scene_free(f);
}

/* ------------------------------------------------------------ limits */
/* A particle pendulum: mass m, length L (position [L, 0]), gravity g·L so
 * that q / L moves the same for every L; RK4 h = 1e-3 to t = 1. */
static int run_pendulum(double m, double L, double *x, double *y, char *err, size_t size)
{
    char text[512];
    snprintf(text, sizeof text,
             "{\"name\": \"p\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", \"mass\": "
             "%.17g, \"position\": [%.17g, 0]}], \"joints\": [{\"type\": \"distance\", \"a\": "
             "[0, 0], \"b\": \"b\", \"length\": %.17g}], \"effects\": [{\"type\": \"gravity\", "
             "\"g\": [0, %.17g]}]}",
             m, L, L, -9.81 * L);
    braun_scene_file *f = load(text, err, size);
    if (!f) return -100;
    braun_model model;
    assert_int_equal(braun_model_init(&model, &f->sys), BRAUN_OK);
    const size_t bytes = braun_data_size(&model);
    void *buf = malloc(bytes);
    braun_data d;
    int st = braun_data_init(&d, &model, buf, bytes);
    if (!st) st = braun_set_state(&d, 0, f->q0, f->v0);
    if (!st) st = braun_integrate(&d, BRAUN_RK4, 1e-3, 1, 1, NULL, NULL);
    *x = (double)d.q[0] / L;
    *y = (double)d.q[1] / L;
    braun_data_release(&d);
    free(buf);
    braun_scene_free(f);
    return st;
}

static void test_smallest_values_work(void **state)
{
    (void)state;
    char err[512];
    double x0, y0, x, y;
    assert_int_equal(run_pendulum(1, 1, &x0, &y0, err, sizeof err), BRAUN_OK);
    /* Mass and length at the limit (1e-150), and the next decade above
     * (measured: 1e-155 still 8e-15, 1e-160 off by 8e-6, 1e-200 wrong). */
    const double scales[] = {BRAUN_SCENE_MIN_SCALE, 1e-149, 1e12};
    for (int i = 0; i < 3; i++) {
        assert_int_equal(run_pendulum(scales[i], 1, &x, &y, err, sizeof err), BRAUN_OK);
        assert_true(hypot(x - x0, y - y0) < 1e-14);
        if (scales[i] * 9.81 > BRAUN_SCENE_MAX_ABS) continue;
        assert_int_equal(run_pendulum(1, scales[i], &x, &y, err, sizeof err), BRAUN_OK);
        assert_true(hypot(x - x0, y - y0) < 1e-13);
    }
    /* Below the limit: refused at the field. */
    assert_int_equal(run_pendulum(1e-151, 1, &x, &y, err, sizeof err), -100);
    assert_non_null(strstr(err, "body 'b': field 'mass' is too small (1e-151; the limit is 1e-150"));
    assert_int_equal(run_pendulum(1, 1e-151, &x, &y, err, sizeof err), -100);
    assert_non_null(strstr(err, "field 'length' is too small"));
    /* Subnormal anywhere: refused. */
    assert_int_equal(run_pendulum(1e-310, 1, &x, &y, err, sizeof err), -100);
    assert_non_null(strstr(err, "field 'mass' underflows: "));
    assert_non_null(strstr(err, "e-311 is below the smallest normal number"));
}

/* A number too small for a double: jansson reads "1e-400" as 0 without an
 * error (and "1e-999" in any field, a vector's entry or a function's).
 * Each is refused at its field with what it would have read as, and the
 * least magnitude the field takes; a zero written as such still loads. */
static void test_underflow_refused(void **state)
{
    (void)state;
    static const struct {
        const char *field, *want;
    } cases[] = {
        {"\"mass\": 1e-400", "t.json:1:68: body 'b': field 'mass' underflows: 1e-400 is below the "
                             "smallest normal number 2.22507e-308 and would read as 0; the least "
                             "nonzero magnitude it accepts is 1e-150 (BRAUN_SCENE_MIN_SCALE"},
        {"\"mass\": -2.5E-999", "field 'mass' underflows: -2.5E-999 is below"},
        {"\"mass\": 0.00000000000000000000000000000000000000000000000000000000000000000000000000000000"
         "000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
         "000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
         "000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
         "00000000000000000001", "field 'mass' underflows: 0.00000000000000000000000000000000000000..."},
        {"\"mass\": 1, \"velocity\": [0, 1e-400]",
         "field 'velocity' underflows: 1e-400 is below the smallest normal number 2.22507e-308 and "
         "would read as 0; the least nonzero magnitude it accepts is 2.22507e-308 "
         "(BRAUN_SCENE_MIN_NORMAL)"},
    };
    char text[1024], err[512];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(text, sizeof text,
                 "{\"name\": \"u\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", %s, "
                 "\"position\": [1, 0]}], \"joints\": [{\"type\": \"distance\", \"a\": [0, 0], "
                 "\"b\": \"b\"}]}",
                 cases[i].field);
        err[0] = '\0';
        braun_scene_file *f = load(text, err, sizeof err);
        if (f || !strstr(err, cases[i].want))
            fail_msg("case %zu: %s", i, f ? "loaded" : err);
    }
    /* In a function of t, and in a field with no domain of its own. */
    const char *fn = "{\"name\": \"u\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", "
                     "\"mass\": 1, \"position\": [1, 0]}], \"joints\": [{\"name\": \"rod\", \"type\": "
                     "\"distance\", \"a\": [0, 0], \"b\": \"b\", \"drive\": {\"type\": \"sine\", "
                     "\"offset\": 1, \"amplitude\": 0.1, \"omega\": 1, \"phase\": 1e-330}}], "
                     "\"effects\": [{\"type\": \"gravity\", \"g\": [0, -9.81]}]}";
    assert_null(load(fn, err, sizeof err));
    assert_non_null(strstr(err, "joint 'rod', field 'drive': field 'phase' underflows: 1e-330"));
    /* Zeros written as such are zeros: 0.0, -0e-999, 0.000e5. */
    const char *zeros = "{\"name\": \"z\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", "
                        "\"mass\": 1, \"position\": [1, 0.0], \"velocity\": [-0e-999, 0.000e5]}], "
                        "\"joints\": [{\"type\": \"distance\", \"a\": [0, 0], \"b\": \"b\"}]}";
    braun_scene_file *f = load(zeros, err, sizeof err);
    if (!f) fail_msg("%s", err);
    braun_scene_free(f);
}

/* A particle on a slider whose axis has the given length (measured: below
 * 1e-154 its squared length underflows and the row is NaN); gravity pulls
 * along and across it. */
static void test_axis_limits(void **state)
{
    (void)state;
    char text[512], err[512];
    double ref[2] = {0, 0};
    const double lens[] = {1, BRAUN_SCENE_MIN_SCALE, 1e12, 1e-151};
    for (int i = 0; i < 4; i++) {
        snprintf(text, sizeof text,
                 "{\"name\": \"s\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", "
                 "\"mass\": 1, \"position\": [0, 0]}], \"joints\": [{\"type\": \"slider\", "
                 "\"point\": \"b\", \"line\": [0, 0], \"axis\": [%.17g, 0]}], \"effects\": "
                 "[{\"type\": \"gravity\", \"g\": [1, -9.81]}]}",
                 lens[i]);
        braun_scene_file *f = load(text, err, sizeof err);
        if (!f && i != 3) fail_msg("axis of length %g: %s", lens[i], err);
        if (i == 3) {
            assert_null(f);
            assert_non_null(strstr(err, "joint #1: field 'axis' is too small (length 1e-151"));
            continue;
        }
        assert_non_null(f);
        braun_model model;
        assert_int_equal(braun_model_init(&model, &f->sys), BRAUN_OK);
        const size_t bytes = braun_data_size(&model);
        void *buf = malloc(bytes);
        braun_data d;
        assert_int_equal(braun_data_init(&d, &model, buf, bytes), BRAUN_OK);
        assert_int_equal(braun_set_state(&d, 0, f->q0, f->v0), BRAUN_OK);
        assert_int_equal(braun_integrate(&d, BRAUN_RK4, 1e-3, 1, 1, NULL, NULL), BRAUN_OK);
        if (i == 0) ref[0] = (double)d.q[0], ref[1] = (double)d.q[1];
        else assert_true(hypot((double)d.q[0] - ref[0], (double)d.q[1] - ref[1]) < 1e-14);
        braun_data_release(&d);
        free(buf);
        braun_scene_free(f);
    }
}

/* The mass matrix's pivot rule at load is the core's: each pivot above
 * n·ε·M_jj, its own diagonal entry, whatever the units. A rigid body of mass
 * 1 whose inertia is below n·ε = 6.7e-16 (a radius of gyration below 2.6e-8
 * m) was refused against its mass, n·ε·max M_ii: the 100 nm slider-crank. */
static void test_mass_pivots(void **state)
{
    (void)state;
    char text[512], err[512];
    const double n_eps = 3 * DBL_EPSILON; /* n = 3 */
    const double inertia[] = {2 * n_eps, 0.5 * n_eps, 1e-20};
    for (int i = 0; i < 3; i++) {
        snprintf(text, sizeof text,
                 "{\"name\": \"r\", \"bodies\": [{\"name\": \"b\", \"type\": \"rigid\", \"mass\": "
                 "1, \"inertia\": %.17g, \"position\": [0.5, 0], \"points\": {\"o\": [-0.5, 0]}}], "
                 "\"joints\": [{\"type\": \"revolute\", \"a\": \"b.o\", \"b\": [0, 0]}]}",
                 inertia[i]);
        braun_scene_file *f = load(text, err, sizeof err);
        braun_model model;
        /* Loads, and the core factors it. */
        assert_non_null(f);
        assert_int_equal(braun_model_init(&model, &f->sys), BRAUN_OK);
        const size_t bytes = braun_data_size(&model);
        void *buf = malloc(bytes);
        braun_data d;
        assert_int_equal(braun_data_init(&d, &model, buf, bytes), BRAUN_OK);
        braun_data_release(&d);
        free(buf);
        braun_scene_free(f);
    }
    /* A tensor singular to working precision (I_xy = 1 − 2^-53 beside I_xx =
     * I_yy = 1: a pivot of 2^-50 beside its entry 4) is refused, and so is
     * the same body 2^-66 times as large (inertias 1.4e-20). */
    for (int i = 0; i < 2; i++) {
        const double u = ldexp(1, i ? -66 : 0);
        snprintf(text, sizeof text,
                 "{\"name\": \"r\", \"bodies\": [{\"name\": \"b\", \"type\": \"rigid3d\", "
                 "\"mass\": 1, \"inertia\": [%.17g, %.17g, %.17g], \"products\": [%.17g, 0, 0], "
                 "\"position\": [0, 0, -0.5], \"points\": {\"top\": [0, 0, 0.5]}}], \"joints\": "
                 "[{\"type\": \"spherical\", \"a\": \"b.top\", \"b\": [0, 0, 0]}]}",
                 u, u, 2 * u, (1 - ldexp(1, -53)) * u);
        assert_null(load(text, err, sizeof err));
        assert_non_null(strstr(err, "t.json:1:26: body 'b': its inertia gives the mass matrix "
                                    "a pivot of"));
        assert_non_null(strstr(err, "not above n*eps*M_jj"));
        assert_non_null(strstr(err, "M would be singular to working precision"));
    }
    /* A massless particle carried by a rod: the rod's m/3 on its diagonal. */
    const char *rods = "{\"name\": \"r\", \"bodies\": [{\"name\": \"a\", \"type\": \"particle\", "
                       "\"mass\": 0, \"position\": [1, 0]}], \"rods\": [{\"a\": [0, 0], \"b\": "
                       "\"a\", \"mass\": 3}]}";
    braun_scene_file *f = load(rods, err, sizeof err);
    assert_non_null(f);
    braun_scene_free(f);
}

/* ----------------------------------------------------------- springs */
static void test_zero_length_spring(void **state)
{
    (void)state;
    char err[512], msg[320];
    const char *at_start =
        "{\"name\": \"z\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", \"mass\": 1, "
        "\"position\": [0, 0]}],\n \"effects\": [{\"name\": \"sp\", \"type\": \"spring\", \"a\": "
        "[0, 0], \"b\": \"b\", \"stiffness\": 1}]}";
    assert_null(load(at_start, err, sizeof err));
    assert_string_equal(err, "t.json:2:14: effect 'sp' (spring) cannot be evaluated at the "
                             "initial state: its forces hook returns 1 at t = 0, where its "
                             "points 'a' and 'b' coincide");
    const char *later =
        "{\"name\": \"z\", \"bodies\": [{\"name\": \"b\", \"type\": \"particle\", \"mass\": 1, "
        "\"position\": [1, 0]}], \"effects\": [{\"type\": \"gravity\", \"g\": [0, -1]}, "
        "{\"type\": \"spring\", \"a\": [0, 0], \"b\": \"b\", \"stiffness\": 1}]}";
    braun_scene_file *f = load(later, err, sizeof err);
    assert_non_null(f);
    const braun_real ok[2] = {1, 0}, bad[2] = {0, 0}, v[2] = {0, 0};
    assert_int_equal(braun_scene_file_diagnose(f, 0, ok, v, msg, sizeof msg), 0);
    assert_string_equal(msg, "");
    assert_int_equal(braun_scene_file_diagnose(f, 0.5, bad, v, msg, sizeof msg), 1);
    assert_string_equal(msg, "effect #2 (spring): its forces hook returns 1 at t = 0.5, where "
                             "its points 'a' and 'b' coincide");
    /* The callback the core sees fails recoverably there. */
    braun_real Q[2];
    assert_int_equal(f->sys.forces(0.5, bad, v, Q, f->sys.user), 1);
    braun_scene_free(f);
}

/* --------------------------------------------------- references, files */
static void test_references(void **state)
{
    (void)state;
    char err[512];
    /* "b.." once found a knife edge's own contact point (named "."). */
    const char *own = "{\"name\": \"k\", \"bodies\": [{\"name\": \"b\", \"type\": \"rigid\", "
                      "\"mass\": 1, \"inertia\": 1, \"position\": [0, 0]}], \"joints\": [{\"type\": "
                      "\"knife\", \"body\": \"b\", \"direction\": [1, 0]}, {\"type\": \"revolute\", "
                      "\"a\": \"b..\", \"b\": [0, 0]}]}";
    assert_null(load(own, err, sizeof err));
    assert_non_null(strstr(err, "joint #2 refers to unknown point 'b..' (b has no points)"));
    /* A duplicate body name is reported at the second body, naming the first. */
    const char *twin = "{\"name\": \"t\", \"bodies\": [{\"name\": \"z\", \"type\": \"particle\", "
                       "\"mass\": 1, \"position\": [0, 0]}, {\"name\": \"a\", \"type\": "
                       "\"particle\", \"mass\": 1, \"position\": [1, 0]}, {\"name\": \"z\", "
                       "\"type\": \"particle\", \"mass\": 1, \"position\": [2, 0]}]}";
    assert_null(load(twin, err, sizeof err));
    assert_non_null(strstr(err, "body #3: field 'name': 'z' is already the name of body #1"));
    /* Points are found by name on their own body only, and the centre. */
    const char *pts = "{\"name\": \"p\", \"ground\": {\"points\": {\"o\": [0, 0], \"q\": [1, 0]}},"
                      " \"bodies\": [{\"name\": \"a\", \"type\": \"rigid\", \"mass\": 1, "
                      "\"inertia\": 1, \"position\": [1, 0], \"points\": {\"z\": [1, 0], \"m\": "
                      "[0, 1], \"b\": [2, 2]}}, {\"name\": \"b\", \"type\": \"rigid\", \"mass\": "
                      "1, \"inertia\": 1, \"position\": [3, 0]}], \"joints\": [{\"type\": "
                      "\"revolute\", \"a\": \"a.m\", \"b\": \"ground.q\"}, {\"type\": \"distance\", "
                      "\"a\": \"a\", \"b\": \"b\"}, {\"type\": \"distance\", \"a\": \"a\", \"b\": "
                      "\"ground.o\"}, {\"type\": \"distance\", \"a\": \"b.z\", \"b\": \"a.z\"}]}";
    assert_null(load(pts, err, sizeof err));
    assert_non_null(strstr(err, "joint #4 refers to unknown point 'b.z' (b has no points)"));
}

static void test_special_files(void **state)
{
    (void)state;
    char dir[] = "/tmp/braun-hyg.XXXXXX", path[64], err[512];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/fifo.json", dir);
    assert_int_equal(mkfifo(path, 0600), 0);
    /* No writer: a blocking open would wait for ever. */
    assert_null(braun_scene_load(path, err, sizeof err));
    assert_non_null(strstr(err, "fifo.json: is a FIFO"));
    assert_null(braun_scene_load(dir, err, sizeof err));
    assert_non_null(strstr(err, ": is a directory"));
    assert_null(braun_scene_load("/dev/null", err, sizeof err));
    assert_string_equal(err, "/dev/null: is a character device, not a scene file (a regular file)");
    unlink(path);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gen_c_escapes),        cmocka_unit_test(test_gen_c_names_and_symbols),
        cmocka_unit_test(test_gen_c_stream_failure),
        cmocka_unit_test(test_smallest_values_work), cmocka_unit_test(test_axis_limits),
        cmocka_unit_test(test_underflow_refused),
        cmocka_unit_test(test_mass_pivots),          cmocka_unit_test(test_zero_length_spring),
        cmocka_unit_test(test_references),           cmocka_unit_test(test_special_files),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
