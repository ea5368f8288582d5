/* braun gen chain N [--rods] [-o FILE]: an N-link pendulum chain scene for
 * scaling studies. Links of 1 m and 1 kg hang from the origin, start
 * horizontal at rest, under gravity. By default each link is a rigid body
 * (3 coordinates, 2 revolute rows per joint: n = 3N, m = 2N); with --rods
 * the links are uniform rods between particles in natural coordinates
 * (n = 2N, m = N). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "braun_cli.h"

#define GEN_MAX_LINKS 1000 /* n = 3000 rigid: within the library's 4096 */

static void write_rigid(FILE *f, long N)
{
    fprintf(f, "{\n  \"name\": \"chain-%ld\",\n", N);
    fprintf(f, "  \"description\": \"%ld-link pendulum chain of rigid links (1 m, 1 kg), "
               "horizontal at rest; written by braun gen chain %ld\",\n", N, N);
    fputs("  \"bodies\": [\n", f);
    for (long i = 1; i <= N; i++)
        fprintf(f, "    {\"name\": \"link%ld\", \"type\": \"rigid\", \"mass\": 1, "
                   "\"inertia\": 0.083333333333333329, \"position\": [%ld.5, 0], "
                   "\"points\": {\"a\": [-0.5, 0], \"b\": [0.5, 0]}}%s\n",
                i, i - 1, i < N ? "," : "");
    fputs("  ],\n  \"joints\": [\n", f);
    fprintf(f, "    {\"name\": \"pivot\", \"type\": \"revolute\", \"a\": \"link1.a\", "
               "\"b\": [0, 0]}%s\n", N > 1 ? "," : "");
    for (long i = 2; i <= N; i++)
        fprintf(f, "    {\"name\": \"hinge%ld\", \"type\": \"revolute\", \"a\": \"link%ld.b\", "
                   "\"b\": \"link%ld.a\"}%s\n", i, i - 1, i, i < N ? "," : "");
    fputs("  ],\n", f);
}

static void write_rods(FILE *f, long N)
{
    fprintf(f, "{\n  \"name\": \"chain-%ld\",\n", N);
    fprintf(f, "  \"description\": \"%ld-link pendulum chain of uniform rods (1 m, 1 kg) in "
               "natural coordinates, horizontal at rest; written by braun gen chain %ld "
               "--rods\",\n", N, N);
    fputs("  \"bodies\": [\n", f);
    for (long i = 1; i <= N; i++)
        fprintf(f, "    {\"name\": \"P%ld\", \"type\": \"particle\", \"mass\": 0, "
                   "\"position\": [%ld, 0]}%s\n", i, i, i < N ? "," : "");
    fputs("  ],\n  \"rods\": [\n", f);
    fprintf(f, "    {\"name\": \"link1\", \"a\": [0, 0], \"b\": \"P1\", \"mass\": 1, "
               "\"length\": 1}%s\n", N > 1 ? "," : "");
    for (long i = 2; i <= N; i++)
        fprintf(f, "    {\"name\": \"link%ld\", \"a\": \"P%ld\", \"b\": \"P%ld\", \"mass\": 1, "
                   "\"length\": 1}%s\n", i, i - 1, i, i < N ? "," : "");
    fputs("  ],\n", f);
}

int braun_cli_gen(int argc, char **argv)
{
    const char *out = NULL, *count = NULL;
    int rods = 0;
    if (argc < 1) return braun_cli_error("gen needs a kind: braun gen chain N [--rods] [-o FILE]");
    if (strcmp(argv[0], "--help") == 0 || strcmp(argv[0], "-h") == 0) {
        braun_cli_usage(stdout);
        return 0;
    }
    if (strcmp(argv[0], "chain") != 0)
        return braun_cli_error("unknown scene kind '%s' (chain)", argv[0]);
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--rods") == 0) {
            rods = 1;
        } else if (strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--out") == 0) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0')
                return braun_cli_error("option %s needs a value", argv[i]);
            out = argv[++i];
        } else if (argv[i][0] == '-') {
            return braun_cli_error("unknown option '%s' (see braun --help)", argv[i]);
        } else if (count) {
            return braun_cli_error("unexpected argument '%s' (one N only)", argv[i]);
        } else {
            count = argv[i];
        }
    }
    if (!count) return braun_cli_error("gen chain needs the number of links N");
    char *end;
    errno = 0;
    long N = strtol(count, &end, 10);
    if (end == count || *end != '\0' || errno == ERANGE || N < 1 || N > GEN_MAX_LINKS)
        return braun_cli_error("N must be an integer in [1, %d] (got '%s')", GEN_MAX_LINKS, count);

    FILE *f = stdout;
    if (out && strcmp(out, "-") != 0 && !(f = fopen(out, "w")))
        return braun_cli_error("cannot open '%s' for writing: %s", out, strerror(errno));
    if (rods) write_rods(f, N);
    else write_rigid(f, N);
    fputs("  \"effects\": [\n    {\"type\": \"gravity\", \"g\": [0, -9.81]}\n  ]\n}\n", f);
    int bad = fflush(f) != 0 || ferror(f);
    if (f != stdout && fclose(f) != 0) bad = 1;
    if (bad) {
        braun_cli_error("error writing '%s'", out ? out : "stdout");
        return BRAUN_CLI_FAILED;
    }
    return 0;
}
