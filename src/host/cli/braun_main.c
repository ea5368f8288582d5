/* braun: command-line front end of libbraun. Dispatches the subcommands. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "braun_backends.h"
#include "braun_cli.h"

static int dispatch(int argc, char **argv);

/* Whatever a command wrote to stdout — the usage, a version, check's
 * lines, a list — is flushed here and a failed write said (a full disk,
 * /dev/full, a closed pipe): exit 1 with one line, never 0 with the text
 * lost, nor 1 in silence. */
int main(int argc, char **argv)
{
    int rc = dispatch(argc, argv);
    errno = 0;
    const int bad = fflush(stdout) != 0 || ferror(stdout);
    if (bad) {
        const int e = errno;
        braun_cli_error("error writing stdout%s%s", e ? ": " : "", e ? strerror(e) : "");
        if (rc == 0 || rc == BRAUN_CLI_FAILED) rc = BRAUN_CLI_FAILED;
    }
    return rc;
}

static int dispatch(int argc, char **argv)
{
    /* Usage errors are one line, so scripts can show them as they are. */
    if (argc < 2) return braun_cli_error("missing command: run, plot, check, gen, gen-c, list, --help or --version");
    const char *cmd = argv[1];
    /* braun --help and --version take nothing more: a word after them is
     * a mistake (a command meant before them), not something to ignore. */
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        if (argc > 2) return braun_cli_error("%s takes no arguments (got '%s')", cmd, argv[2]);
        braun_cli_usage(stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0) {
        if (argc > 2) return braun_cli_error("%s takes no arguments (got '%s')", cmd, argv[2]);
        /* What this build holds: the library's version and precision
         * (asked of it), and the backends. */
        const int lapack = braun_linsolver_lapack() != NULL;
        const int ss = braun_linsolver_suitesparse() != NULL;
        printf("braun %s (libbraun %s, %s; backends: dense%s%s)\n", BRAUN_VERSION, braun_version(),
               braun_precision(), lapack ? ", lapack" : "", ss ? ", suitesparse" : "");
        return 0;
    }
    /* Every command's --help: alone, the usage (exit 0); with other
     * arguments a usage error, as for the tool's own --help. */
    static const char *const commands[] = {"run", "plot", "check", "gen", "gen-c", "list"};
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(cmd, commands[i]) == 0) {
            const int help = braun_cli_help_asked(cmd, argc - 2, argv + 2);
            if (help) return help < 0 ? 0 : help;
        }
    if (strcmp(cmd, "list") == 0) {
        if (argc > 2) return braun_cli_error("list takes no arguments (got '%s')", argv[2]);
        return braun_cli_list();
    }
    if (strcmp(cmd, "run") == 0) {
        braun_cli_run_args a;
        int rc = braun_cli_parse_run(argc - 2, argv + 2, &a, 0);
        if (rc) return rc;
        return braun_cli_run(&a);
    }
    if (strcmp(cmd, "plot") == 0) return braun_cli_plot(argc - 2, argv + 2);
    if (strcmp(cmd, "check") == 0) return braun_cli_check(argc - 2, argv + 2);
    if (strcmp(cmd, "gen") == 0) return braun_cli_gen(argc - 2, argv + 2);
    if (strcmp(cmd, "gen-c") == 0) return braun_cli_gen_c(argc - 2, argv + 2);
    if (cmd[0] == '-') return braun_cli_error("unknown option '%s' (see braun --help)", cmd);
    return braun_cli_error("unknown command '%s' (see braun --help)", cmd);
}
