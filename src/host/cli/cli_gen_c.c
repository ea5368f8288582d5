/* braun gen-c SCENE [--symbol NAME] [-o FILE] [--header FILE]: the scene as
 * a C99 source that defines it statically (braun_gen_c_write, braun_scene.h)
 * — for firmware: no parser, no file, no allocation on the target — and,
 * with --header, the header that declares it for the program's other files.
 * The symbol defaults to the file's base name without ".json" (rule below
 * and in docs/cli.md). */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "braun_cli.h"
#include "braun_scene_file.h"

static int ascii_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
static int ascii_alnum(char c) { return ascii_alpha(c) || (c >= '0' && c <= '9'); }

/* The default symbol: the base name without a final ".json", as it is when
 * it is a C identifier; '-' and '.' become '_' (1: said on stderr, since
 * my-scene.json and my_scene.json then give one symbol). Refused (-1, the
 * reason in why) when anything else would have to change: another
 * character, a first character that is not a letter, more than
 * BRAUN_GEN_C_SYMBOL_MAX characters. Such a symbol was made up ("é.json"
 * and "--.json" both gave "s___") or cut (..._v1.json and ..._v2.json gave
 * one symbol), and two generated headers with one symbol share their
 * include guard: the second is skipped in silence. A user who builds more
 * than one scene needs distinct symbols, and a refusal asking for --symbol
 * costs one option; a warning in a build log is easily missed. */
static int symbol_from_path(const char *path, char *buf, size_t size, char *why, size_t why_size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t len = strlen(base);
    if (len > 5 && strcmp(base + len - 5, ".json") == 0) len -= 5;
    if (len == 0) {
        snprintf(why, why_size, "it is empty");
        return -1;
    }
    if (!ascii_alpha(base[0])) {
        snprintf(why, why_size, "it does not start with an ASCII letter");
        return -1;
    }
    if (len > BRAUN_GEN_C_SYMBOL_MAX || len >= size) {
        snprintf(why, why_size, "it has more than the symbol's " BRAUN_GEN_C_SYMBOL_MAX_STR
                                " characters: cut, it could be another file's symbol");
        return -1;
    }
    int mapped = 0;
    for (size_t k = 0; k < len; k++) {
        const char c = base[k];
        if (ascii_alnum(c) || c == '_') {
            buf[k] = c;
        } else if (c == '-' || c == '.') {
            buf[k] = '_';
            mapped = 1;
        } else {
            snprintf(why, why_size, "it has characters other than ASCII letters, digits, '_', "
                                    "'-' and '.'");
            return -1;
        }
    }
    buf[len] = '\0';
    return mapped;
}

int braun_cli_gen_c(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL, *symbol = NULL, *header = NULL;
    const char *seen[4];
    int nseen = 0, options_end = 0;
    for (int i = 0; i < argc; i++) {
        if (!options_end && strcmp(argv[i], "--") == 0) { /* a scene named "-x.json" after it */
            options_end = 1;
            continue;
        }
        if (!options_end && argv[i][0] == '-' && argv[i][1] != '\0') {
            char name[32];
            const char *val = NULL;
            int rc = braun_cli_option(argc, argv, &i, name, sizeof name, NULL);
            if (rc) return rc;
            const int is_out = strcmp(name, "-o") == 0 || strcmp(name, "--out") == 0;
            if (!is_out && strcmp(name, "--symbol") != 0 && strcmp(name, "--header") != 0)
                return braun_cli_error("unknown option '%s' (see braun --help)", argv[i]);
            if ((rc = braun_cli_option(argc, argv, &i, name, sizeof name, &val)) != 0 ||
                (rc = braun_cli_option_once(is_out ? "-o" : name[2] == 's' ? "--symbol" : "--header",
                                            name, seen, &nseen, 4)) != 0)
                return rc;
            if (is_out) out = val;
            else if (name[2] == 's') symbol = val;
            else header = val;
        } else if (!options_end && argv[i][0] == '-') {
            return braun_cli_error("unknown option '%s' (see braun --help)", argv[i]);
        } else if (scene) {
            return braun_cli_error("unexpected argument '%s' (one SCENE only)", argv[i]);
        } else {
            scene = argv[i];
        }
    }
    if (!scene) return braun_cli_error("gen-c needs a scene file");
    char sym[BRAUN_GEN_C_SYMBOL_MAX + 1], why[256];
    if (!symbol) {
        const int mapped = symbol_from_path(scene, sym, sizeof sym, why, sizeof why);
        if (mapped < 0 || braun_gen_c_check_symbol(sym, why, sizeof why))
            return braun_cli_error("gen-c: no symbol from the file name '%s' (%s): give --symbol "
                                   "NAME", scene, why);
        symbol = sym;
        if (mapped)
            fprintf(stderr, "braun: note: gen-c: symbol '%s' from the file name ('-' and '.' "
                            "made '_': another name can give it too; --symbol NAME to choose)\n",
                    sym);
    } else if (braun_gen_c_check_symbol(symbol, why, sizeof why)) {
        return braun_cli_error("gen-c --symbol: %s", why);
    }
    /* Not a file here: a shipped scene by its name ("damped-motor",
     * "four-bar.json"), as run, plot and check find it. */
    static char found[4096];
    struct stat st_in;
    const char *path = scene;
    if (stat(scene, &st_in) != 0 && braun_cli_data_file(scene, found, sizeof found)) path = found;
    /* A built-in model without a scene file (andrews): say that, not
     * "cannot open". */
    if (path == scene && stat(scene, &st_in) != 0 && braun_cli_is_model_name(scene))
        return braun_cli_error("gen-c: '%s' is a built-in model with no scene file: gen-c writes "
                               "a scene (.json; the shipped ones: braun list)", scene);
    char err[512];
    braun_scene_file *sf = braun_scene_load(path, err, sizeof err);
    if (!sf) return braun_cli_error("%s", err);
    braun_cli_id input;
    braun_cli_path_id(path, &input);
    /* The header goes to a file of its own: on stdout it would mix with the
     * source. */
    if (header && strcmp(header, "-") == 0) {
        braun_scene_free(sf);
        return braun_cli_error("gen-c --header: give a file (stdout is the source's)");
    }
    braun_cli_output o, ho = {0};
    int rc = braun_cli_output_open_whole(&o, out ? out : "-", "gen-c -o");
    if (!rc && header) rc = braun_cli_output_open_whole(&ho, header, "gen-c --header");
    if (!rc && (rc = braun_cli_output_distinct(&o, header ? &ho : NULL, &input, scene)) == 0)
        rc = braun_cli_output_begin(&o);
    if (!rc && header) rc = braun_cli_output_begin(&ho);
    if (rc) {
        braun_cli_output_abandon(&o);
        if (header) braun_cli_output_abandon(&ho);
        braun_scene_free(sf);
        return rc;
    }
    errno = 0;
    int st = braun_gen_c_write_ex(o.f, sf, symbol, scene, err, sizeof err);
    const char *failed = out && strcmp(out, "-") != 0 ? out : "stdout";
    if (!st && header) {
        errno = 0;
        st = braun_gen_c_write_header(ho.f, sf, symbol, scene, err, sizeof err);
        failed = header;
    }
    braun_scene_free(sf);
    if (st) {
        const int e = errno;
        braun_cli_output_abandon(&o);
        if (header) braun_cli_output_abandon(&ho);
        if (st == BRAUN_GEN_C_INVALID) return braun_cli_error("gen-c: '%s': %s", scene, err);
        /* A write error shows up here (or in the close: a full disk). */
        braun_cli_error("error writing '%s'%s%s", failed, e ? ": " : "", e ? strerror(e) : "");
        return BRAUN_CLI_FAILED;
    }
    /* Both complete before either is put in place: one that cannot be
     * written (a full disk) leaves both files as they were — the source
     * left without its header (or the reverse) exited 1 beside a file
     * that looked complete, and a file that existed was left cut short. */
    if (braun_cli_output_complete(&o) || (header && braun_cli_output_complete(&ho))) {
        braun_cli_output_abandon(&o);
        if (header) braun_cli_output_abandon(&ho);
        return BRAUN_CLI_FAILED;
    }
    const int bad = braun_cli_output_commit(&o);
    const int hbad = header ? braun_cli_output_commit(&ho) : 0;
    return bad || hbad ? BRAUN_CLI_FAILED : 0;
}
