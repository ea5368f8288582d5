/* braun gen chain N [--rods] [--angle DEG] [-o FILE]: an N-link pendulum
 * chain scene for scaling studies. Links of 1 m and 1 kg hang from the
 * origin as one straight line DEG degrees below the horizontal (default 0:
 * horizontal), at rest, under gravity. By default each link is a rigid body
 * (3 coordinates, 2 revolute rows per joint: n = 3N, m = 2N); with --rods
 * the links are uniform rods between particles in natural coordinates
 * (n = 2N, m = N).
 *
 * braun gen ladder N [--angle DEG] [-o FILE]: a closed-loop ladder with
 * redundant rungs. Three rails — chains of N rigid links (1 m, 1 kg) —
 * hang from the ground pivots (0, 0), (d, 0), (2d, 0), d = 0.5; rung k
 * (rigid, 2d long, 1 kg) is pinned at its left end, middle and right end to
 * the lower ends of the k-th links of the three rails and to the upper ends
 * of their (k+1)-th links. Every cell is a parallelogram with a third crank
 * (a double parallelogram): of its 12 rows one is redundant, so
 * n = m = 12N, rank 11N, N degrees of freedom. The rails start tilted DEG
 * degrees from the vertical (default 30), at rest, on the constraints.
 *
 * braun gen n-four-bar N [-o FILE]: the IFToMM benchmark problem A02
 * (docs/iftomm.md): N four-bar windows of 2N + 1 uniform rods (1 m, 1 kg)
 * in natural coordinates, cranks from the ground points A_i = (i, 0) up to
 * the particles B_i = (i, 1), couplers B_(i-1) B_i; every B_i moves at
 * (1, 0) m/s, gravity -y; B0 is reported. n = 2N + 2, m = 2N + 1: one
 * degree of freedom, N + 1 whenever the links are horizontal.
 *
 * braun gen spatial-chain N [--angle DEG] [-o FILE]: N rigid3d bars (1 m,
 * 0.1 m x 0.1 m section, 1 kg) on spherical joints, hanging from the
 * origin as one straight line DEG degrees below the horizontal in the x-y
 * plane (default 0), turning as one body about the vertical y axis at
 * 1 rad/s (so the motion is spatial; the start is on the constraints):
 * n = 7N (Euler parameters), m = 4N (3 rows a joint, 1 a quaternion).
 *
 * Rigid chains and ladders have no rods: above n = 4096 they run only as
 * sparse systems (braun run --sparse). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "braun_cli.h"

#define GEN_MAX_LINKS 2000 /* chain: n = 6000 rigid (sparse), 4000 with rods (dense) */
#define GEN_MAX_ANGLE 180.0
#define LADDER_D 0.5       /* rail spacing; rung length 2d */
#define PI 3.14159265358979323846

static void write_rigid(FILE *f, long N, double deg)
{
    /* Link direction (cos φ, -sin φ): θ = -φ, centre (i - 1/2)·direction. */
    const double phi = deg * PI / 180, c = cos(phi), s = sin(phi);
    fprintf(f, "{\n  \"name\": \"chain-%ld\",\n", N);
    if (deg == 0)
        fprintf(f, "  \"description\": \"%ld-link pendulum chain of rigid links (1 m, 1 kg), "
                   "horizontal at rest; written by braun gen chain %ld\",\n", N, N);
    else
        fprintf(f, "  \"description\": \"%ld-link pendulum chain of rigid links (1 m, 1 kg), "
                   "straight, %.17g degrees below the horizontal at rest; written by braun gen "
                   "chain %ld --angle %.17g\",\n", N, deg, N, deg);
    fputs("  \"bodies\": [\n", f);
    for (long i = 1; i <= N; i++) {
        fprintf(f, "    {\"name\": \"link%ld\", \"type\": \"rigid\", \"mass\": 1, "
                   "\"inertia\": 0.083333333333333329, ", i);
        if (deg == 0)
            fprintf(f, "\"position\": [%ld.5, 0], ", i - 1);
        else
            fprintf(f, "\"position\": [%.17g, %.17g], \"angle\": %.17g, ",
                    ((double)i - 0.5) * c, -((double)i - 0.5) * s, -phi);
        fprintf(f, "\"points\": {\"a\": [-0.5, 0], \"b\": [0.5, 0]}}%s\n", i < N ? "," : "");
    }
    fputs("  ],\n  \"joints\": [\n", f);
    fprintf(f, "    {\"name\": \"pivot\", \"type\": \"revolute\", \"a\": \"link1.a\", "
               "\"b\": [0, 0]}%s\n", N > 1 ? "," : "");
    for (long i = 2; i <= N; i++)
        fprintf(f, "    {\"name\": \"hinge%ld\", \"type\": \"revolute\", \"a\": \"link%ld.b\", "
                   "\"b\": \"link%ld.a\"}%s\n", i, i - 1, i, i < N ? "," : "");
    fputs("  ],\n", f);
}

static void write_rods(FILE *f, long N, double deg)
{
    const double phi = deg * PI / 180, c = cos(phi), s = sin(phi);
    fprintf(f, "{\n  \"name\": \"chain-%ld\",\n", N);
    if (deg == 0)
        fprintf(f, "  \"description\": \"%ld-link pendulum chain of uniform rods (1 m, 1 kg) in "
                   "natural coordinates, horizontal at rest; written by braun gen chain %ld "
                   "--rods\",\n", N, N);
    else
        fprintf(f, "  \"description\": \"%ld-link pendulum chain of uniform rods (1 m, 1 kg) in "
                   "natural coordinates, straight, %.17g degrees below the horizontal at rest; "
                   "written by braun gen chain %ld --rods --angle %.17g\",\n", N, deg, N, deg);
    fputs("  \"bodies\": [\n", f);
    for (long i = 1; i <= N; i++) {
        fprintf(f, "    {\"name\": \"P%ld\", \"type\": \"particle\", \"mass\": 0, ", i);
        if (deg == 0) fprintf(f, "\"position\": [%ld, 0]}", i);
        else fprintf(f, "\"position\": [%.17g, %.17g]}", (double)i * c, -(double)i * s);
        fputs(i < N ? ",\n" : "\n", f);
    }
    fputs("  ],\n  \"rods\": [\n", f);
    fprintf(f, "    {\"name\": \"link1\", \"a\": [0, 0], \"b\": \"P1\", \"mass\": 1, "
               "\"length\": 1}%s\n", N > 1 ? "," : "");
    for (long i = 2; i <= N; i++)
        fprintf(f, "    {\"name\": \"link%ld\", \"a\": \"P%ld\", \"b\": \"P%ld\", \"mass\": 1, "
                   "\"length\": 1}%s\n", i, i - 1, i, i < N ? "," : "");
    fputs("  ],\n", f);
}

static void write_ladder(FILE *f, long N, double deg)
{
    /* Rails along (sin α, -cos α), α from the vertical: θ = α - 90°. */
    const double alpha = deg * PI / 180, s = sin(alpha), c = cos(alpha);
    const double theta = alpha - PI / 2, d = LADDER_D;
    static const char *const side[3] = {"left", "mid", "right"};
    fprintf(f, "{\n  \"name\": \"ladder-%ld\",\n", N);
    fprintf(f, "  \"description\": \"closed-loop ladder: three rails of %ld rigid links (1 m, "
               "1 kg) %g m apart and %ld rungs (1 m, 1 kg) pinned at both ends and the middle; "
               "every cell a double parallelogram with one redundant row (n = m = %ld, rank "
               "%ld); rails %.17g degrees from the vertical at rest; written by braun gen "
               "ladder %ld --angle %.17g\",\n", N, d, N, 12 * N, 11 * N, deg, N, deg);
    fprintf(f, "  \"ground\": {\"points\": {\"left\": [0, 0], \"mid\": [%g, 0], "
               "\"right\": [%g, 0]}},\n", d, 2 * d);
    fputs("  \"bodies\": [\n", f);
    /* Body order: cell by cell (its three links, then its rung), so the
     * coordinates of neighbours stay close. */
    for (long k = 1; k <= N; k++) {
        for (int r = 0; r < 3; r++)
            fprintf(f, "    {\"name\": \"%s%ld\", \"type\": \"rigid\", \"mass\": 1, "
                       "\"inertia\": 0.083333333333333329, \"position\": [%.17g, %.17g], "
                       "\"angle\": %.17g, \"points\": {\"a\": [-0.5, 0], \"b\": [0.5, 0]}},\n",
                    side[r], k, r * d + ((double)k - 0.5) * s, -((double)k - 0.5) * c, theta);
        fprintf(f, "    {\"name\": \"rung%ld\", \"type\": \"rigid\", \"mass\": 1, "
                   "\"inertia\": 0.083333333333333329, \"position\": [%.17g, %.17g], "
                   "\"points\": {\"left\": [%g, 0], \"mid\": [0, 0], \"right\": [%g, 0]}}%s\n",
                k, d + (double)k * s, -(double)k * c, -d, d, k < N ? "," : "");
    }
    fputs("  ],\n  \"joints\": [\n", f);
    for (int r = 0; r < 3; r++)
        fprintf(f, "    {\"name\": \"pivot-%s\", \"type\": \"revolute\", \"a\": \"%s1.a\", "
                   "\"b\": \"ground.%s\"},\n", side[r], side[r], side[r]);
    for (long k = 1; k <= N; k++)
        for (int r = 0; r < 3; r++) {
            fprintf(f, "    {\"name\": \"%s%ld-rung%ld\", \"type\": \"revolute\", "
                       "\"a\": \"%s%ld.b\", \"b\": \"rung%ld.%s\"}", side[r], k, k, side[r], k,
                    k, side[r]);
            if (k < N)
                fprintf(f, ",\n    {\"name\": \"rung%ld-%s%ld\", \"type\": \"revolute\", "
                           "\"a\": \"%s%ld.a\", \"b\": \"rung%ld.%s\"}", k, side[r], k + 1,
                        side[r], k + 1, k, side[r]);
            fputs(k < N || r < 2 ? ",\n" : "\n", f);
        }
    fputs("  ],\n", f);
}

static void write_n_four_bar(FILE *f, long N)
{
    fprintf(f, "{\n  \"name\": \"a02-n-four-bar-%ld\",\n", N);
    fprintf(f, "  \"description\": \"IFToMM benchmark A02 (docs/iftomm.md): %ld four-bar windows, "
               "%ld uniform rods of 1 m and 1 kg, cranks vertical, every top point moving at 1 m/s "
               "in +x, gravity -y; singular whenever the links are horizontal; 20 s for N = 40 "
               "(10 s variant: N = 2); reported: B0, error max |B0 - B0_ref| over 400 "
               "output steps <= 1e-3; written by braun gen n-four-bar %ld\",\n", N, 2 * N + 1, N);
    fputs("  \"ground\": {\"points\": {", f);
    for (long i = 0; i <= N; i++) fprintf(f, "%s\"A%ld\": [%ld, 0]", i ? ", " : "", i, i);
    fputs("}},\n  \"bodies\": [\n", f);
    for (long i = 0; i <= N; i++)
        fprintf(f, "    {\"name\": \"B%ld\", \"type\": \"particle\", \"mass\": 0, "
                   "\"position\": [%ld, 1], \"velocity\": [1, 0]}%s\n", i, i, i < N ? "," : "");
    fputs("  ],\n  \"rods\": [\n", f);
    for (long i = 0; i <= N; i++)
        fprintf(f, "    {\"name\": \"crank%ld\", \"a\": \"ground.A%ld\", \"b\": \"B%ld\", "
                   "\"mass\": 1, \"length\": 1},\n", i, i, i);
    for (long i = 1; i <= N; i++)
        fprintf(f, "    {\"name\": \"coupler%ld\", \"a\": \"B%ld\", \"b\": \"B%ld\", "
                   "\"mass\": 1, \"length\": 1}%s\n", i, i - 1, i, i < N ? "," : "");
    fputs("  ],\n  \"report\": {\"B0\": \"B0\"},\n", f);
}

static void write_spatial(FILE *f, long N, double deg)
{
    /* Bar direction d = (cos φ, -sin φ, 0): body x turned by -φ about z;
     * centre (i - 1/2) d, velocity ω × centre with ω = (0, 1, 0). */
    const double phi = deg * PI / 180, c = cos(phi), s = sin(phi);
    const double qw = cos(-phi / 2), qz = sin(-phi / 2);
    fprintf(f, "{\n  \"name\": \"spatial-chain-%ld\",\n", N);
    fprintf(f, "  \"description\": \"%ld rigid3d bars (1 m, 0.1 m square section, 1 kg) on spherical "
               "joints, straight, %.17g degrees below the horizontal, turning about the vertical at "
               "1 rad/s; written by braun gen spatial-chain %ld",
            N, deg, N);
    /* the option only when it was not the default */
    if (deg != 0) fprintf(f, " --angle %.17g", deg);
    fputs("\",\n", f);
    fputs("  \"bodies\": [\n", f);
    for (long i = 1; i <= N; i++) {
        const double x = ((double)i - 0.5) * c, y = -((double)i - 0.5) * s;
        /* (0, 1, 0) × (x, y, 0) = (0, 0, -x) */
        fprintf(f, "    {\"name\": \"bar%ld\", \"type\": \"rigid3d\", \"mass\": 1, "
                   "\"inertia\": [0.0016666666666666668, 0.084166666666666667, 0.084166666666666667], "
                   "\"position\": [%.17g, %.17g, 0], ", i, x, y + 0.0);
        if (deg != 0) fprintf(f, "\"orientation\": [%.17g, 0, 0, %.17g], ", qw, qz);
        fprintf(f, "\"velocity\": [0, 0, %.17g], \"omega\": [0, 1, 0], "
                   "\"points\": {\"a\": [-0.5, 0, 0], \"b\": [0.5, 0, 0]}}%s\n",
                -x + 0.0, i < N ? "," : "");
    }
    fputs("  ],\n  \"joints\": [\n", f);
    fprintf(f, "    {\"name\": \"pivot\", \"type\": \"spherical\", \"a\": \"bar1.a\", "
               "\"b\": [0, 0, 0]}%s\n", N > 1 ? "," : "");
    for (long i = 2; i <= N; i++)
        fprintf(f, "    {\"name\": \"ball%ld\", \"type\": \"spherical\", \"a\": \"bar%ld.b\", "
                   "\"b\": \"bar%ld.a\"}%s\n", i, i - 1, i, i < N ? "," : "");
    fputs("  ],\n", f);
}

static int parse_angle(const char *s, double *deg)
{
    double x;
    const int rc = braun_cli_parse_real("--angle", s, &x);
    if (rc) return rc;
    if (fabs(x) > GEN_MAX_ANGLE)
        return braun_cli_error("--angle must be a number of degrees in [-%g, %g] (got '%s')",
                               GEN_MAX_ANGLE, GEN_MAX_ANGLE, s);
    *deg = x + 0.0; /* -0 prints as 0 */
    return 0;
}

#define GEN_USAGE                                                                             \
    "braun gen chain N [--rods] [--angle DEG] [-o FILE] | ladder N [--angle DEG] [-o FILE] | " \
    "n-four-bar N [-o FILE] | spatial-chain N [--angle DEG] [-o FILE]"

int braun_cli_gen(int argc, char **argv)
{
    const char *out = NULL, *count = NULL;
    int rods = 0, ladder = 0, fourbar = 0, spatial = 0, rc;
    double deg;
    if (argc < 1) return braun_cli_error("gen needs a kind: " GEN_USAGE);
    if (strcmp(argv[0], "chain") == 0) ladder = 0;
    else if (strcmp(argv[0], "ladder") == 0) ladder = 1;
    else if (strcmp(argv[0], "n-four-bar") == 0) fourbar = 1;
    else if (strcmp(argv[0], "spatial-chain") == 0) spatial = 1;
    else return braun_cli_error("unknown scene kind '%s' (chain, ladder, n-four-bar, "
                                "spatial-chain)", argv[0]);
    deg = ladder ? 30 : 0;
    const char *seen[4];
    int nseen = 0;
    for (int i = 1; i < argc; i++) {
        char name[32] = ""; /* a negative N leaves it unread */
        const char *val = NULL;
        /* A negative N is N out of range, not an unknown option "-1". */
        const int negative_n = argv[i][0] == '-' && argv[i][1] >= '0' && argv[i][1] <= '9';
        if (argv[i][0] == '-' && argv[i][1] != '\0' && !negative_n) {
            /* "--angle=30" as "--angle 30" (run's forms); each option once. */
            if ((rc = braun_cli_option(argc, argv, &i, name, sizeof name, NULL)) != 0) return rc;
            const int is_out = strcmp(name, "-o") == 0 || strcmp(name, "--out") == 0;
            if (is_out || strcmp(name, "--angle") == 0 || strcmp(name, "--rods") == 0) {
                if ((rc = braun_cli_option_once(is_out ? "-o" : name[2] == 'a' ? "--angle" : "--rods",
                                                name, seen, &nseen, 4)) != 0)
                    return rc;
            }
            if (strcmp(name, "--rods") == 0 && strchr(argv[i], '='))
                return braun_cli_error("option --rods takes no value");
        }
        if (strcmp(argv[i], "--rods") == 0) {
            if (ladder || fourbar || spatial)
                return braun_cli_error("--rods applies to gen chain only (%s)",
                                       ladder    ? "a ladder's rungs are rigid"
                                       : spatial ? "a spatial chain's bars are rigid3d bodies"
                                                 : "an n-four-bar is made of rods already");
            rods = 1;
        } else if (argv[i][0] == '-' && strcmp(name, "--angle") == 0) {
            if (fourbar)
                return braun_cli_error("--angle does not apply to gen n-four-bar (it starts "
                                       "with its cranks vertical, as the benchmark)");
            if ((rc = braun_cli_option(argc, argv, &i, name, sizeof name, &val)) != 0) return rc;
            if ((rc = parse_angle(val, &deg)) != 0) return rc;
        } else if (argv[i][0] == '-' && (strcmp(name, "-o") == 0 || strcmp(name, "--out") == 0)) {
            if ((rc = braun_cli_option(argc, argv, &i, name, sizeof name, &val)) != 0) return rc;
            out = val;
        } else if (argv[i][0] == '-' && !negative_n) {
            return braun_cli_error("unknown option '%s' (see braun --help)", argv[i]);
        } else if (count) {
            return braun_cli_error("unexpected argument '%s' (one N only)", argv[i]);
        } else {
            count = argv[i];
        }
    }
    if (!count)
        return braun_cli_error("gen %s needs the number of %s N", argv[0],
                               ladder ? "cells" : fourbar ? "four-bar windows" : spatial ? "bars" : "links");
    char *end;
    errno = 0;
    long N = braun_cli_integer_text(count) ? strtol(count, &end, 10) : (end = (char *)count, 0);
    if (end == count || *end != '\0' || errno == ERANGE || N < 1 || N > GEN_MAX_LINKS)
        return braun_cli_error("N must be an integer in [1, %d] (got '%s')", GEN_MAX_LINKS, count);

    /* Opened without blocking (a FIFO is refused); a file is written whole
     * (a failed write leaves it as it was). */
    braun_cli_output o;
    if ((rc = braun_cli_output_open_whole(&o, out ? out : "-", "gen -o")) != 0 ||
        (rc = braun_cli_output_begin(&o)) != 0) {
        braun_cli_output_abandon(&o);
        return rc;
    }
    FILE *f = o.f;
    if (fourbar) write_n_four_bar(f, N);
    else if (ladder) write_ladder(f, N, deg);
    else if (spatial) write_spatial(f, N, deg);
    else if (rods) write_rods(f, N, deg);
    else write_rigid(f, N, deg);
    fprintf(f, "  \"effects\": [\n    {\"type\": \"gravity\", \"g\": [0, -9.81%s]}\n  ]\n}\n",
            spatial ? ", 0" : "");
    if (ferror(f)) braun_cli_output_failed(&o);
    return braun_cli_output_close(&o) ? BRAUN_CLI_FAILED : 0;
}
