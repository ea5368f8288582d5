/* What the host library writes does not depend on the program's locale: a
 * program that calls setlocale(LC_ALL, "") under de_DE got gen-c output
 * with R(0,083333333333333329), which does not compile, and messages with
 * decimal commas. Each writer is run under a locale whose decimal point is
 * ',' and must write what it writes in the "C" locale. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, setenv */
#include <locale.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test_util.h"
#include "braun_host.h"
#include "braun_scene_file.h"
#include "test_systems.h"

/* glibc's compiled LC_NUMERIC of de_DE.UTF-8 (decimal point ',', thousands
 * separator '.'), written to a temporary LOCPATH when no comma locale is
 * installed (a container has C and POSIX only). */
static const unsigned char lc_numeric[54] = {
    0x14, 0x11, 0x03, 0x20, 0x06, 0x00, 0x00, 0x00, 0x20, 0x00, 0x00, 0x00, 0x22, 0x00,
    0x00, 0x00, 0x24, 0x00, 0x00, 0x00, 0x28, 0x00, 0x00, 0x00, 0x2c, 0x00, 0x00, 0x00,
    0x30, 0x00, 0x00, 0x00, 0x2c, 0x00, 0x2e, 0x00, 0x03, 0x03, 0x00, 0x00, 0x2c, 0x00,
    0x00, 0x00, 0x2e, 0x00, 0x00, 0x00, 0x55, 0x54, 0x46, 0x2d, 0x38, 0x00};
static char locpath[64], numeric_file[96], comma_dir[80];

static int comma(void) { return strcmp(localeconv()->decimal_point, ",") == 0; }

static int comma_locale(void)
{
    static const char *const names[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8",
                                        "de_DE", "fr_FR"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (setlocale(LC_NUMERIC, names[i]) && comma()) return 1;
    if (!locpath[0]) {
        strcpy(locpath, "/tmp/braun-locale-XXXXXX");
        if (!mkdtemp(locpath)) return locpath[0] = 0, 0;
        snprintf(comma_dir, sizeof comma_dir, "%s/comma", locpath);
        snprintf(numeric_file, sizeof numeric_file, "%s/LC_NUMERIC", comma_dir);
        FILE *f = mkdir(comma_dir, 0700) == 0 ? fopen(numeric_file, "wb") : NULL;
        if (!f) return 0;
        fwrite(lc_numeric, 1, sizeof lc_numeric, f);
        fclose(f);
        setenv("LOCPATH", locpath, 1);
    }
    return setlocale(LC_NUMERIC, "comma") && comma();
}

static void c_locale(void) { setlocale(LC_NUMERIC, "C"); }

static int setup(void **state)
{
    (void)state;
    if (comma_locale()) c_locale();
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    c_locale();
    if (locpath[0]) {
        remove(numeric_file);
        rmdir(comma_dir);
        rmdir(locpath);
    }
    return 0;
}

#define NEED_COMMA()                                                                     \
    do {                                                                                 \
        if (!comma_locale()) {                                                           \
            print_message("no locale with a decimal comma can be set here\n");           \
            skip();                                                                      \
        }                                                                                \
        c_locale();                                                                      \
    } while (0)

/* The whole of a stream written so far. */
static char *contents(FILE *f)
{
    long len = ftell(f);
    char *s = malloc((size_t)len + 1);
    rewind(f);
    size_t got = fread(s, 1, (size_t)len, f);
    s[got] = 0;
    return s;
}

/* braun_gen_c_write_ex: the same bytes in both locales, R(0.08...). */
static void test_gen_c(void **state)
{
    (void)state;
    NEED_COMMA();
    char err[256];
    braun_scene_file *sf = braun_scene_load("data/slider-crank.json", err, sizeof err);
    assert_non_null(sf);
    char *text[2];
    for (int k = 0; k < 2; k++) {
        if (k) assert_true(comma_locale());
        FILE *f = tmpfile();
        assert_non_null(f);
        assert_int_equal(braun_gen_c_write_ex(f, sf, "sc", "slider-crank.json", err, sizeof err), 0);
        text[k] = contents(f);
        fclose(f);
        c_locale();
    }
    assert_non_null(strstr(text[0], "R(0."));
    assert_null(strstr(text[1], "R(0,"));
    assert_string_equal(text[1], text[0]);
    free(text[0]);
    free(text[1]);
    braun_scene_free(sf);
}

/* braun_error_format, a scene file's message, braun_check_callbacks. */
static void test_error_format(void **state)
{
    (void)state;
    NEED_COMMA();
    pendulum_params prm = {1.0, 1.0, 9.81, 0, 0, 0, 0, 0, 0};
    braun_system s = pendulum_system(&prm);
    test_sim sim;
    assert_int_equal(test_sim_open(&sim, &s, BRAUN_CORRECT_ALL), BRAUN_OK);
    const double q0[2] = {1, 0}, v0[2] = {0, 0};
    assert_int_equal(braun_set_state(&sim.data, 0.25, q0, v0), BRAUN_OK);
    assert_int_equal(braun_integrate(&sim.data, BRAUN_RK4, 1e-3, -1.5, 1, NULL, NULL), BRAUN_ERR_TIME);
    char what[2][300];
    for (int k = 0; k < 2; k++) {
        if (k) assert_true(comma_locale());
        braun_error_format(&sim.data, what[k], sizeof what[k]);
        c_locale();
    }
    assert_non_null(strstr(what[0], "-1.5"));
    assert_string_equal(what[1], what[0]);
    test_sim_close(&sim);
}

static void test_scene_message(void **state)
{
    (void)state;
    NEED_COMMA();
    static const char text[] =
        "{\"name\": \"m\", \"bodies\": [{\"name\": \"bob\", \"type\": \"particle\", \"mass\": -0.5, "
        "\"position\": [1, 0]}]}";
    char err[2][300];
    for (int k = 0; k < 2; k++) {
        if (k) assert_true(comma_locale());
        braun_scene_file *sf = braun_scene_load_text("m.json", text, strlen(text), err[k], sizeof err[k]);
        c_locale();
        assert_null(sf);
    }
    assert_non_null(strstr(err[0], "-0.5"));
    assert_string_equal(err[1], err[0]);
}

static int refuse(braun_real t, const braun_real *q, const braun_real *v, braun_real *phi,
                  braun_real *A, braun_real *b, braun_real *bv, void *user)
{
    (void)t, (void)q, (void)v, (void)phi, (void)A, (void)b, (void)bv, (void)user;
    return -1;
}

static void test_callback_report(void **state)
{
    (void)state;
    NEED_COMMA();
    pendulum_params prm = {1.0, 1.0, 9.81, 0, 0, 0, 0, 0, 0};
    braun_system s = pendulum_system(&prm);
    s.holonomic = refuse;
    const braun_real q[2] = {1, 0}, v[2] = {0, 0};
    braun_callback_report rep[2];
    for (int k = 0; k < 2; k++) {
        if (k) assert_true(comma_locale());
        assert_int_equal(braun_check_callbacks(&s, 0.5, q, v, 0, &rep[k]), BRAUN_ERR_CALLBACK);
        c_locale();
    }
    assert_non_null(strstr(rep[0].worst, "t = 0.5"));
    assert_string_equal(rep[1].worst, rep[0].worst);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gen_c),
        cmocka_unit_test(test_error_format),
        cmocka_unit_test(test_scene_message),
        cmocka_unit_test(test_callback_report),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
