/* Scene files: every parser error case of tests/scene/ gives exactly its
 * expected one-line message (FILE:LINE:COLUMN: ...), nothing is returned
 * from a file that fails, the format's defaults and references work, and
 * every shipped scene in data/ loads, runs and stays on its constraints. */
#define _POSIX_C_SOURCE 200809L /* opendir */

#include "test_util.h"
#include "test_files.h"
#include "braun_scene_file.h"

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = malloc(1 << 16);
    *len = fread(buf, 1, (1 << 16) - 1, f);
    buf[*len] = '\0';
    fclose(f);
    return buf;
}

/* Sorted list of the files in dir ending in suffix, as dir/name. */
static int list_files(const char *dir, const char *suffix, char names[][128], int max)
{
    char prefix[100];
    snprintf(prefix, sizeof prefix, "%s/", dir);
    const int count = test_list_files(dir, suffix, prefix, names[0], sizeof names[0], max);
    assert_true(count >= 0);
    return count;
}

static void test_error_cases(void **state)
{
    (void)state;
    static char files[64][128];
    const int n = list_files("tests/scene", ".json", files, 64);
    int checked = 0;
    assert_true(n >= 30);
    for (int i = 0; i < n; i++) {
        char expect_path[160], err[512], err2[512];
        size_t len, tlen;
        snprintf(expect_path, sizeof expect_path, "%.*s.err", (int)(strlen(files[i]) - 5), files[i]);
        char *expect = slurp(expect_path, &len);
        if (!expect) fail_msg("%s has no expected message %s", files[i], expect_path);
        while (len > 0 && (expect[len - 1] == '\n' || expect[len - 1] == '\r')) expect[--len] = '\0';
        braun_scene_file *f = braun_scene_load(files[i], err, sizeof err);
        if (f) fail_msg("%s loaded, expected: %s", files[i], expect);
        if (strcmp(err, expect) != 0) fail_msg("%s:\n  got      %s\n  expected %s", files[i], err, expect);
        /* The same text from memory gives the same message. */
        char *text = slurp(files[i], &tlen);
        assert_null(braun_scene_load_text(files[i], text, tlen, err2, sizeof err2));
        assert_string_equal(err2, err);
        free(text);
        free(expect);
        checked++;
    }
    print_message("%d parser error cases, each with its exact message\n", checked);
}

static void test_missing_file(void **state)
{
    (void)state;
    char err[256];
    assert_null(braun_scene_load("tests/scene/no-such-file.json", err, sizeof err));
    assert_string_equal(err, "tests/scene/no-such-file.json: cannot open: No such file or directory");
    /* A short buffer truncates the message, never overflows. */
    char tiny[8];
    assert_null(braun_scene_load("tests/scene/empty.json", tiny, sizeof tiny));
    assert_int_equal(strlen(tiny), 7);
}

static braun_scene_file *from_text(const char *text)
{
    char err[512];
    braun_scene_file *f = braun_scene_load_text("inline.json", text, strlen(text), err, sizeof err);
    if (!f) fail_msg("%s", err);
    return f;
}

/* Lengths, rest lengths and angles left out are taken from the initial
 * configuration; the three spellings of a point reach the same point. */
static void test_defaults_and_references(void **state)
{
    (void)state;
    braun_scene_file *f = from_text(
        "{\"name\": \"defaults\", \"ground\": {\"points\": {\"O\": [0, 0]}},\n"
        " \"bodies\": [{\"name\": \"arm\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": 0.1,\n"
        "   \"position\": [1, 2], \"angle\": 0.5, \"points\": {\"tip\": [1, 0]}},\n"
        "  {\"name\": \"P\", \"type\": \"particle\", \"mass\": 0, \"position\": [3, 4]}],\n"
        " \"rods\": [{\"a\": \"ground.O\", \"b\": \"P\", \"mass\": 2}],\n"
        " \"joints\": [{\"type\": \"distance\", \"a\": \"arm.tip\", \"b\": [0, 0]},\n"
        "   {\"type\": \"angle\", \"a\": \"ground\", \"b\": \"arm\"}],\n"
        " \"effects\": [{\"type\": \"spring\", \"a\": \"arm\", \"b\": \"P\", \"stiffness\": 1},\n"
        "   {\"type\": \"torsion\", \"a\": \"arm\", \"b\": \"ground\", \"stiffness\": 1}]}");
    const braun_scene *s = &f->scene;
    assert_near(s->rods[0].length, 5, 1e-15);
    const double tx = 1 + cos(0.5), ty = 2 + sin(0.5);
    assert_near(s->joints[0].value, hypot(tx, ty), 1e-15);
    assert_near(s->joints[1].value, 0.5, 0);
    assert_near(s->effects[0].rest, hypot(2, 2), 1e-15);
    assert_near(s->effects[1].rest, -0.5, 0);
    assert_int_equal(f->corrections, BRAUN_CORRECT_ALL);
    assert_string_equal(f->description, "");
    assert_null(f->reference);
    /* At its own initial state the scene satisfies its rows. */
    double phi[4];
    assert_int_equal(f->sys.holonomic(0, f->q0, f->v0, phi, NULL, NULL, NULL, f->sys.user), 0);
    for (int i = 0; i < f->sys.m; i++) assert_near(phi[i], 0, 1e-14);
    braun_scene_free(f);

    /* "corrections": "none" and a knife edge among the joints. */
    f = from_text("{\"name\": \"k\", \"corrections\": \"none\", \"bodies\": [{\"name\": \"s\",\n"
                  "\"type\": \"rigid\", \"mass\": 1, \"inertia\": 1, \"position\": [0, 0]}],\n"
                  "\"joints\": [{\"name\": \"blade\", \"type\": \"knife\", \"body\": \"s\",\n"
                  "\"direction\": [0, 1]}]}");
    assert_int_equal(f->corrections, BRAUN_CORRECT_NONE);
    assert_int_equal(f->sys.p, 1);
    assert_string_equal(f->joint_names[0], "blade");
    assert_ptr_equal(f->scene.joints[0].type, BRAUN_JOINT_KNIFE);
    braun_scene_free(f);
}

typedef struct watch {
    double pos, vel, energy;
} watch;

static int watch_out(const braun_data *d, void *u)
{
    watch *w = u;
    braun_real p, v, e;
    assert_int_equal(braun_residuals((braun_data *)d, d->t, d->q, d->v, &p, &v, &e), BRAUN_OK);
    w->pos = fmax(w->pos, p);
    w->vel = fmax(w->vel, v);
    w->energy = fmax(w->energy, e);
    return 0;
}

/* Every shipped scene: loads, describes itself, runs 2 s of RK4 with the
 * corrections it declares and stays on its constraints. */
static void test_shipped_scenes(void **state)
{
    (void)state;
    static char files[64][128];
    const int n = list_files("data", ".json", files, 64);
    assert_true(n >= 9);
    for (int i = 0; i < n; i++) {
        char err[512];
        braun_scene_file *f = braun_scene_load(files[i], err, sizeof err);
        if (!f) fail_msg("%s", err);
        assert_true(strlen(f->description) > 10);
        test_sim sim;
        watch w = {0, 0, 0};
        assert_int_equal(test_sim_open(&sim, &f->sys, f->corrections), BRAUN_OK);
        assert_int_equal(braun_set_state(&sim.data, 0, f->q0, f->v0), BRAUN_OK);
        const int st = braun_integrate(&sim.data, BRAUN_RK4, 1e-3, 2.0, 1, watch_out, &w);
        print_message("%-40s n=%2d m=%2d p=%d  max |Phi_q| %.2g  |[dPhi_q; Phi_v]| %.2g  "
                      "|Phi_e| %.2g\n", files[i], f->sys.n, f->sys.m, f->sys.p, w.pos, w.vel,
                      w.energy);
        assert_int_equal(st, BRAUN_OK);
        assert_le(w.pos, 1e-8);
        assert_le(w.vel, 1e-6);
        if (f->corrections & BRAUN_CORRECT_ENERGY) assert_le(w.energy, 1e-4);
        test_sim_close(&sim);
        braun_scene_free(f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_error_cases),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_defaults_and_references),
        cmocka_unit_test(test_shipped_scenes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
