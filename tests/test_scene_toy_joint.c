/* A joint class defined outside libbraun, in this file alone, from the
 * class interface of braun_scene.h: a point held on a circle of radius R
 * about a ground point,
 *   Φ = |P - C|² - R² = 0                       (1 row)
 *   A_q = 2 (P - C)ᵀ J_P,  b_q = 0,  b_qv = -2|P'|² - 2 (P - C)·cc
 * (Φ'' = 2|P'|² + 2 (P - C)·(J_P v' + cc)). A particle on the circle under
 * gravity is a pendulum:
 *   - A_q and the b-terms agree with finite differences (scene_fd.h), on a
 *     particle and on a point of a rigid body;
 *   - its motion is the exact pendulum's (braun_pendulum_exact) to the
 *     integration error, and a distance-joint pendulum's to round-off;
 *   - the sparse system (its bodies from its fields) gives the dense rows;
 *   - scene files take it through braun_scene_load_ex, its defaults hook
 *     supplies a radius left out, and braun gen-c writes it by c_name. */
#include "test_util.h"
#include "braun_reference.h"
#include "braun_scene.h"
#include "braun_scene_file.h"
#include "scene/scene_fd.h"

#define PI 3.14159265358979323846

/* ------------------------------------------------------------ the class */
enum { F_POINT, F_CENTRE, F_RADIUS };

static int circle_rows(const braun_scene_joint *j)
{
    (void)j;
    return 1;
}

/* a: the point held; b: the centre, a ground point; value: R. */
static int circle_eval(const braun_scene *s, const braun_scene_joint *j, braun_real t,
                       const braun_real *q, const braun_real *v, braun_real *phi, braun_real *A,
                       braun_real *b, braun_real *bv)
{
    braun_scene_pt P, C;
    (void)t;
    braun_scene_pt_eval(s, j->a, q, v, &P);
    braun_scene_pt_eval(s, j->b, q, v, &C);
    const braun_real dx = P.pos[0] - C.pos[0], dy = P.pos[1] - C.pos[1];
    if (phi) phi[0] = dx * dx + dy * dy - j->value * j->value;
    if (A) {
        const braun_real g[2] = {2 * dx, 2 * dy};
        braun_scene_pt_grad(&P, g, A);
    }
    if (b) b[0] = 0;
    if (bv)
        bv[0] = -2 * (P.vel[0] * P.vel[0] + P.vel[1] * P.vel[1]) -
                2 * (dx * P.cc[0] + dy * P.cc[1]);
    return 0;
}

static const char *circle_check(const braun_scene *s, const braun_scene_joint *j)
{
    if (s->points[j->b].body != BRAUN_SCENE_GROUND) return "the centre of a circle is a ground point";
    if (s->points[j->a].body == BRAUN_SCENE_GROUND) return "the point on a circle is on the ground";
    if (!(j->value > 0)) return "a circle's radius must be > 0";
    return NULL;
}

/* Scene files: a radius left out is the initial distance. */
static void circle_defaults(const braun_scene *s, braun_scene_joint *j, unsigned given)
{
    if (!BRAUN_FIELD_GIVEN(given, F_RADIUS)) j->value = braun_scene_initial_distance(s, j->a, j->b);
}

static const braun_scene_field circle_fields[] = {
    [F_POINT] = {"point", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, a),
                 BRAUN_FIELD_REQUIRED, NULL},
    [F_CENTRE] = {"centre", BRAUN_FIELD_POINT, 0, offsetof(braun_scene_joint, b),
                  BRAUN_FIELD_REQUIRED, NULL},
    [F_RADIUS] = {"radius", BRAUN_FIELD_REAL, 1, offsetof(braun_scene_joint, value),
                  BRAUN_FIELD_POSITIVE, NULL},
    {NULL, 0, 0, 0, 0, NULL}};

/* Not static: gen-c's output names it (c_name "&toy_circle"). */
extern const braun_scene_joint_class toy_circle;
const braun_scene_joint_class toy_circle = {"circle", "&toy_circle", 0, circle_fields,
                                            circle_defaults, circle_check, circle_rows,
                                            NULL, circle_eval, 0};

/* ------------------------------------------------------------ scenes */
/* A particle of 1 kg at angle phi0 from the downward vertical on a circle
 * of radius R about the origin, under g = 9.81 — or the same pendulum on a
 * built-in distance joint. */
typedef struct pendulum {
    braun_scene_body bodies[1];
    braun_scene_point points[2];
    braun_scene_joint joints[1];
    braun_scene_effect effects[1];
    braun_scene s;
    braun_system sys;
} pendulum;

static void make_pendulum(pendulum *p, const braun_scene_joint_class *cls, double R, double phi0)
{
    memset(p, 0, sizeof *p);
    p->bodies[0] = (braun_scene_body){BRAUN_BODY_PARTICLE, 1.0, 0.0,
                                      {R * sin(phi0), -R * cos(phi0), 0}, {0, 0, 0}, 0, {0}, 0};
    p->points[0] = (braun_scene_point){0, 0.0, 0.0, 0.0};
    p->points[1] = (braun_scene_point){BRAUN_SCENE_GROUND, 0.0, 0.0, 0.0};
    /* The distance joint measures d = P_b - P_a: its a is the centre. */
    if (cls == &toy_circle) p->joints[0] = (braun_scene_joint){.type = cls, .a = 0, .b = 1, .value = R};
    else p->joints[0] = (braun_scene_joint){.type = cls, .a = 1, .b = 0, .value = R};
    p->effects[0] = (braun_scene_effect){.type = BRAUN_EFFECT_GRAVITY, .g = {0.0, -9.81}};
    p->s = (braun_scene){.nbodies = 1, .bodies = p->bodies, .npoints = 2, .points = p->points,
                         .njoints = 1, .joints = p->joints, .neffects = 1, .effects = p->effects};
    braun_scene_error err;
    if (braun_scene_build(&p->s, &p->sys, &err)) fail_msg("build: %s", err.what);
}

/* A_q, b_q, b_qv and the energy law against finite differences, on a
 * particle and on an offset point of a rigid body, at random states. */
static void test_derivatives(void **state)
{
    (void)state;
    pendulum p;
    make_pendulum(&p, &toy_circle, 0.8, 0.3);
    assert_int_equal(p.sys.m, 1);
    assert_int_equal(p.sys.p, 0);
    for (int trial = 0; trial < 3; trial++) {
        double q[FD_NMAX], v[FD_NMAX];
        for (int i = 0; i < p.s.n; i++) q[i] = 1.5 * fd_urand(), v[i] = 2 * fd_urand();
        fd_check_system("circle, particle", &p.sys, 0.3 + trial, q, v, 2e-6);
    }
    /* A point off the centre of a rigid body: J_P has a θ column and the
     * velocity product cc enters b_qv. */
    p.bodies[0] = (braun_scene_body){BRAUN_BODY_RIGID, 2.0, 0.3, {0.4, -0.5, 0.7}, {0}, 0, {0}, 0};
    p.points[0] = (braun_scene_point){0, 0.3, -0.2, 0};
    assert_int_equal(braun_scene_build(&p.s, &p.sys, NULL), BRAUN_OK);
    assert_int_equal(p.sys.n, 3);
    for (int trial = 0; trial < 3; trial++) {
        double q[FD_NMAX], v[FD_NMAX];
        for (int i = 0; i < p.s.n; i++) q[i] = 1.5 * fd_urand(), v[i] = 2 * fd_urand();
        fd_check_system("circle, rigid body", &p.sys, 0.3 + trial, q, v, 2e-6);
    }
    /* The builder runs the class's check. */
    braun_scene_error err;
    p.points[1].body = 0;
    assert_int_equal(braun_scene_build(&p.s, &p.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_int_equal(err.element, BRAUN_SCENE_ELEM_JOINT);
    assert_string_equal(err.what, "the centre of a circle is a ground point");
    p.points[1].body = BRAUN_SCENE_GROUND;
    p.joints[0].b = 7; /* a reference of its fields out of range: the builder's own check */
    assert_int_equal(braun_scene_build(&p.s, &p.sys, &err), BRAUN_ERR_ARGUMENT);
    assert_string_equal(err.what, "joint refers to an unknown point");
}

/* RK4 with all corrections from the horizontal: the exact pendulum to the
 * integration error, the distance-joint pendulum to round-off. */
static void test_motion(void **state)
{
    (void)state;
    const double R = 1.0, phi0 = PI / 2, h = 1e-3;
    pendulum toy, ref;
    make_pendulum(&toy, &toy_circle, R, phi0);
    make_pendulum(&ref, BRAUN_JOINT_DISTANCE, R, phi0);
    test_sim a, b;
    double q0[2], v0[2];
    braun_scene_initial_state(&toy.s, q0, v0);
    assert_int_equal(test_sim_open(&a, &toy.sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(test_sim_open(&b, &ref.sys, BRAUN_CORRECT_ALL), BRAUN_OK);
    assert_int_equal(braun_set_state(&a.data, 0, q0, v0), BRAUN_OK);
    assert_int_equal(braun_set_state(&b.data, 0, q0, v0), BRAUN_OK);
    double exact = 0, twin = 0;
    for (int k = 1; k <= 40; k++) {
        const double t = 0.05 * k;
        assert_int_equal(braun_integrate(&a.data, BRAUN_RK4, h, t, 0, NULL, NULL), BRAUN_OK);
        assert_int_equal(braun_integrate(&b.data, BRAUN_RK4, h, t, 0, NULL, NULL), BRAUN_OK);
        double phi, dphi;
        assert_int_equal(braun_pendulum_exact(9.81 / R, phi0, 0, t, &phi, &dphi), 0);
        const double x = R * sin(phi), y = -R * cos(phi);
        const double vx = R * cos(phi) * dphi, vy = R * sin(phi) * dphi;
        exact = fmax(exact, fmax(fabs(a.data.q[0] - x), fabs(a.data.q[1] - y)));
        exact = fmax(exact, fmax(fabs(a.data.v[0] - vx), fabs(a.data.v[1] - vy)));
        for (int i = 0; i < 2; i++)
            twin = fmax(twin, fmax(fabs(a.data.q[i] - b.data.q[i]), fabs(a.data.v[i] - b.data.v[i])));
    }
    print_message("circle pendulum, RK4 h = 1e-3, 2 s: max |q, v - exact| %.3g, "
                  "max |q, v - distance joint| %.3g\n", exact, twin);
    assert_le(exact, 2e-10); /* measured 6.3e-11 */
    assert_le(twin, 1e-13);
    test_sim_close(&a);
    test_sim_close(&b);
}

/* The sparse system: the pattern comes from the class's point fields (no
 * bodies hook), and its values scatter to the dense rows exactly. */
static void test_sparse(void **state)
{
    (void)state;
    pendulum p;
    make_pendulum(&p, &toy_circle, 0.8, 0.3);
    p.bodies[0] = (braun_scene_body){BRAUN_BODY_RIGID, 2.0, 0.3, {0.4, -0.5, 0.7}, {0.1, 0.2, 0.3}, 0, {0}, 0};
    p.points[0] = (braun_scene_point){0, 0.3, -0.2, 0};
    assert_int_equal(braun_scene_build(&p.s, &p.sys, NULL), BRAUN_OK);
    void *buf = malloc(braun_scene_sparse_size(&p.s));
    braun_system sp;
    assert_non_null(buf);
    assert_int_equal(braun_scene_build_sparse(&p.s, &sp, buf, braun_scene_sparse_size(&p.s), NULL),
                     BRAUN_OK);
    const int *rp = sp.sparsity->row_ptr, *col = sp.sparsity->col;
    assert_int_equal(rp[1] - rp[0], 3);
    for (int k = 0; k < 3; k++) assert_int_equal(col[k], k);
    double q[3] = {0.2, -0.6, 1.1}, v[3] = {0.3, 0.1, -0.4};
    double phi[1], A[3], bq[1], bv[1], vals[3], phs[1], bqs[1], bvs[1];
    assert_int_equal(p.sys.holonomic(0, q, v, phi, A, bq, bv, p.sys.user), 0);
    assert_int_equal(sp.holonomic(0, q, v, phs, vals, bqs, bvs, sp.user), 0);
    for (int k = 0; k < 3; k++) assert_true(vals[k] == A[col[k]]);
    assert_true(phs[0] == phi[0] && bqs[0] == bq[0] && bvs[0] == bv[0]);
    free(buf);
}

/* ------------------------------------------------------------ scene files */
static const char circle_text[] =
    "{\"name\": \"circle-pendulum\",\n"
    " \"bodies\": [{\"name\": \"bob\", \"type\": \"particle\", \"mass\": 1, \"position\": [0.6, -0.8]}],\n"
    " \"joints\": [{\"name\": \"track\", \"type\": \"circle\", \"point\": \"bob\", \"centre\": [0, 0]}],\n"
    " \"effects\": [{\"type\": \"gravity\", \"g\": [0, -9.81]}]}\n";

static const braun_scene_joint_class *const extra_joints[] = {&toy_circle, NULL};

static void test_scene_file(void **state)
{
    (void)state;
    char err[512];
    const braun_scene_classes extra = {NULL, extra_joints, NULL};
    /* Without the class the type is unknown, and the message lists the
     * built-in ones; with it, the file loads. */
    braun_scene_file *f = braun_scene_load_text("circle.json", circle_text, strlen(circle_text),
                                                err, sizeof err);
    assert_null(f);
    assert_string_equal(err, "circle.json:3:39: joint 'track': unknown joint type 'circle' "
                             "(revolute, distance, slider, prismatic, angle, knife, spherical, "
                             "revolute3d, prismatic3d, cylindrical, universal, weld, point_line, "
                             "point_plane)");
    f = braun_scene_load_text_ex("circle.json", circle_text, strlen(circle_text), &extra, err,
                                 sizeof err);
    if (!f) fail_msg("%s", err);
    const braun_scene_joint *j = &f->scene.joints[0];
    assert_ptr_equal(j->type, &toy_circle);
    assert_string_equal(f->joint_names[0], "track");
    /* The defaults hook: the radius is the initial distance, 1. */
    assert_near(j->value, 1.0, 1e-15);
    assert_int_equal(f->sys.n, 2);
    assert_int_equal(f->sys.m, 1);
    double phi[1];
    assert_int_equal(f->sys.holonomic(0, f->q0, f->v0, phi, NULL, NULL, NULL, f->sys.user), 0);
    assert_near(phi[0], 0, 1e-15);

    /* gen-c writes the class by its c_name and declares it. */
    FILE *out = tmpfile();
    assert_non_null(out);
    assert_int_equal(braun_gen_c_write(out, f, "circle", "circle.json"), 0);
    const long len = ftell(out);
    char *text = calloc((size_t)len + 1, 1);
    assert_non_null(text);
    rewind(out);
    assert_int_equal(fread(text, 1, (size_t)len, out), (size_t)len);
    fclose(out);
    assert_non_null(strstr(text, "extern const braun_scene_joint_class toy_circle;\n"));
    assert_non_null(strstr(text, "{.type = &toy_circle, .a = 0, .b = 1,"));
    assert_non_null(strstr(text, "{.kind = BRAUN_BODY_PARTICLE,"));
    free(text);
    braun_scene_free(f);

    /* A c_name that is a name the generated file defines or uses: refused
     * before anything is written, naming the clash (the file was written
     * and did not compile: uc_build redeclared, "extern ... NULL", or the
     * build function's local st hid the class). */
    {
        static const char *const clashes[][2] = {
            {"&circle_build", "circle_build, the build function the generated file defines"},
            {"&circle_scene", "circle_scene, the static scene the generated file defines"},
            {"&circle_corrections", "circle_corrections, the corrections constant"},
            {"&circle_joints", "circle_joints, an array the generated file defines"},
            {"&CIRCLE_N", "CIRCLE_N, a size macro the generated file defines"},
            {"&BRAUN_GEN_circle_H", "the generated header's include guard"},
            {"&RD", "RD, a macro the generated file defines"},
            {"&NULL", "NULL, a name of <stddef.h>"},
            {"&size_t", "size_t, a name of <stddef.h>"},
            {"&st", "st, a local of circle_build (it would hide the class there)"},
            {"&unused", "unused, a local of circle_build"},
            {"&q0", "q0, a parameter of circle_build"},
            {"&sys", "sys, a parameter of circle_build"},
            {"&braun_scene_joint_distance", "libbraun's names (braun_..., BRAUN_...)"},
            {"&_circle", "reserved for the implementation"},
            {"st", "st, a local of circle_build"}};
        for (size_t k = 0; k < sizeof clashes / sizeof clashes[0]; k++) {
            braun_scene_joint_class cls = toy_circle;
            cls.c_name = clashes[k][0];
            const braun_scene_joint_class *const js[] = {&cls, NULL};
            const braun_scene_classes ex = {NULL, js, NULL};
            f = braun_scene_load_text_ex("circle.json", circle_text, strlen(circle_text), &ex, err,
                                         sizeof err);
            if (!f) fail_msg("%s", err);
            FILE *o = tmpfile();
            assert_non_null(o);
            assert_int_equal(braun_gen_c_write_ex(o, f, "circle", "circle.json", err, sizeof err),
                             BRAUN_GEN_C_INVALID);
            assert_int_equal(ftell(o), 0);
            fclose(o);
            if (!strstr(err, clashes[k][1]) || !strstr(err, "joint 'track': the c_name '") ||
                !strstr(err, "give the class another c_name"))
                fail_msg("%s: %s", clashes[k][0], err);
            braun_scene_free(f);
        }
        /* Names near them are the program's own. */
        static const char *const fine[] = {"&circle_builder", "&circle", "&CIRCLE_NX", "&Rx",
                                           "&stx", "&Braun_x"};
        for (size_t k = 0; k < sizeof fine / sizeof fine[0]; k++) {
            braun_scene_joint_class cls = toy_circle;
            cls.c_name = fine[k];
            const braun_scene_joint_class *const js[] = {&cls, NULL};
            const braun_scene_classes ex = {NULL, js, NULL};
            f = braun_scene_load_text_ex("circle.json", circle_text, strlen(circle_text), &ex, err,
                                         sizeof err);
            if (!f) fail_msg("%s", err);
            FILE *o = tmpfile();
            assert_non_null(o);
            if (braun_gen_c_write_ex(o, f, "circle", "circle.json", err, sizeof err))
                fail_msg("%s: %s", fine[k], err);
            fclose(o);
            braun_scene_free(f);
        }
        /* Two classes of one name: one extern object for both. */
        static const char two[] =
            "{\"name\": \"c\", \"bodies\": [{\"name\": \"bob\", \"type\": \"particle\", \"mass\": 1,\n"
            " \"position\": [1, 0]}], \"joints\": [{\"name\": \"a\", \"type\": \"circle\", \"point\": \"bob\",\n"
            " \"centre\": [0, 0]}, {\"name\": \"b\", \"type\": \"circle2\", \"point\": \"bob\", \"centre\": [0, 0]}]}";
        braun_scene_joint_class second = toy_circle;
        second.name = "circle2";
        const braun_scene_joint_class *const js[] = {&toy_circle, &second, NULL};
        const braun_scene_classes ex = {NULL, js, NULL};
        f = braun_scene_load_text_ex("two.json", two, strlen(two), &ex, err, sizeof err);
        if (!f) fail_msg("%s", err);
        FILE *o = tmpfile();
        assert_non_null(o);
        assert_int_equal(braun_gen_c_write_ex(o, f, "two", "two.json", err, sizeof err),
                         BRAUN_GEN_C_INVALID);
        assert_int_equal(ftell(o), 0);
        fclose(o);
        assert_string_equal(err, "joint 'b': the c_name '&toy_circle' of its class 'circle2' is "
                                 "also that of class 'circle': one name declares one class");
        braun_scene_free(f);
    }

    /* Its fields are read and checked as a built-in's. */
    static const char bad[] =
        "{\"name\": \"c\", \"bodies\": [{\"name\": \"bob\", \"type\": \"particle\", \"mass\": 1,\n"
        " \"position\": [1, 0]}], \"joints\": [{\"type\": \"circle\", \"point\": \"bob\",\n"
        " \"centre\": [0, 0], \"radius\": -1}]}";
    assert_null(braun_scene_load_text_ex("c.json", bad, strlen(bad), &extra, err, sizeof err));
    assert_string_equal(err, "c.json:3:30: joint #1: field 'radius' must be > 0 (got -1)");
    /* A program class without a name: refused, naming it (the lookup
     * compared its NULL name with strcmp: a crash). */
    braun_scene_joint_class unnamed = toy_circle;
    unnamed.name = NULL;
    const braun_scene_joint_class *const unnamed_joints[] = {&toy_circle, &unnamed, NULL};
    const braun_scene_classes extra2 = {NULL, unnamed_joints, NULL};
    assert_null(braun_scene_load_text_ex("u.json", circle_text, strlen(circle_text), &extra2, err,
                                         sizeof err));
    assert_string_equal(err, "u.json:1:1: program joint class 2 (braun_scene_classes.joints[1]) has "
                             "no name: a file names its class by it (\"type\")");
    /* No path: the text is named "(text)" (it said "no text"). */
    f = braun_scene_load_text_ex(NULL, circle_text, strlen(circle_text), &extra, err, sizeof err);
    if (!f) fail_msg("%s", err);
    braun_scene_free(f);
    assert_null(braun_scene_load_text_ex(NULL, bad, strlen(bad), &extra, err, sizeof err));
    assert_string_equal(err, "(text):3:30: joint #1: field 'radius' must be > 0 (got -1)");
    assert_null(braun_scene_load_text(NULL, NULL, 3, err, sizeof err));
    assert_string_equal(err, "(text):1:1: no text (NULL)");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_derivatives),
        cmocka_unit_test(test_motion),
        cmocka_unit_test(test_sparse),
        cmocka_unit_test(test_scene_file),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
