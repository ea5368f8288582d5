/* braun gen-c SCENE [--symbol NAME] [-o FILE]: the scene as a C99 source
 * that defines it statically (braun_gen_c_write, braun_scene.h) — for
 * firmware: no parser, no file, no allocation on the target. The symbol
 * defaults to the file's base name with '-' and '.' turned into '_'. */
#include <ctype.h>
#include <errno.h>
#include <string.h>

#include "braun_cli.h"
#include "braun_scene_file.h"

static void symbol_from_path(const char *path, char *buf, size_t size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t k = 0;
    if (!isalpha((unsigned char)base[0]) && size > 1) buf[k++] = 's';
    for (const char *c = base; *c && k + 1 < size; c++) {
        if (strcmp(c, ".json") == 0) break;
        buf[k++] = isalnum((unsigned char)*c) ? *c : '_';
    }
    buf[k] = '\0';
}

int braun_cli_gen_c(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL, *symbol = NULL;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--out") == 0 ||
            strcmp(argv[i], "--symbol") == 0) {
            if (i + 1 >= argc || argv[i + 1][0] == '\0')
                return braun_cli_error("option %s needs a value", argv[i]);
            if (strcmp(argv[i], "--symbol") == 0) symbol = argv[++i];
            else out = argv[++i];
        } else if (argv[i][0] == '-') {
            return braun_cli_error("unknown option '%s' (see braun --help)", argv[i]);
        } else if (scene) {
            return braun_cli_error("unexpected argument '%s' (one SCENE only)", argv[i]);
        } else {
            scene = argv[i];
        }
    }
    if (!scene) return braun_cli_error("gen-c needs a scene file");
    char sym[128];
    if (!symbol) {
        symbol_from_path(scene, sym, sizeof sym);
        symbol = sym;
    }
    char err[512];
    braun_scene_file *sf = braun_scene_load(scene, err, sizeof err);
    if (!sf) return braun_cli_error("%s", err);
    FILE *f = stdout;
    if (out && strcmp(out, "-") != 0 && !(f = fopen(out, "w"))) {
        braun_scene_free(sf);
        return braun_cli_error("cannot open '%s' for writing: %s", out, strerror(errno));
    }
    int rc = braun_gen_c_write(f, sf, symbol, scene);
    if (fflush(f) != 0 || ferror(f)) rc = -1;
    if (f != stdout && fclose(f) != 0) rc = -1;
    braun_scene_free(sf);
    if (rc) return braun_cli_error("cannot write C for '%s' (is '%s' a C identifier?)", scene, symbol);
    return 0;
}
