/* braun gen-c SCENE [--symbol NAME] [-o FILE] [--header FILE]: the scene as
 * a C99 source that defines it statically (braun_gen_c_write, braun_scene.h)
 * — for firmware: no parser, no file, no allocation on the target — and,
 * with --header, the header that declares it for the program's other files.
 * The symbol defaults to the file's base name with '-' and '.' turned into
 * '_'. */
#include <errno.h>
#include <string.h>
#include <sys/stat.h>

#include "braun_cli.h"
#include "braun_scene_file.h"

static int ascii_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/* At most size - 1 characters: a long file name gives a truncated symbol. */
static void symbol_from_path(const char *path, char *buf, size_t size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t k = 0;
    if (!ascii_alpha(base[0]) && size > 1) buf[k++] = 's';
    for (const char *c = base; *c && k + 1 < size; c++) {
        if (strcmp(c, ".json") == 0) break;
        buf[k++] = ascii_alpha(*c) || (*c >= '0' && *c <= '9') ? *c : '_';
    }
    buf[k] = '\0';
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
        symbol_from_path(scene, sym, sizeof sym);
        symbol = sym;
        if (braun_gen_c_check_symbol(symbol, why, sizeof why))
            return braun_cli_error("gen-c: no symbol from the file name '%s' (%s): give --symbol "
                                   "NAME", scene, why);
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
