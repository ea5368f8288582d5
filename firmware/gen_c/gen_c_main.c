/*
 * fw-gen-c SCENE.json SYMBOL [OUT.c]: the scene-to-C generator as a
 * standalone host tool (the same function `braun gen-c` is meant to call;
 * docs/firmware.md, "Scene to C"). Exit status 0, 1 (scene not readable),
 * 2 (usage).
 */
#include <stdio.h>

#include "braun_gen_c.h"

int main(int argc, char **argv)
{
    char err[512];
    if (argc < 3 || argc > 4) {
        fprintf(stderr, "usage: fw-gen-c SCENE.json SYMBOL [OUT.c]\n");
        return 2;
    }
    braun_scene_file *sf = braun_scene_load(argv[1], err, sizeof err);
    if (!sf) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    FILE *out = argc == 4 ? fopen(argv[3], "w") : stdout;
    if (!out) {
        perror(argv[3]);
        braun_scene_free(sf);
        return 1;
    }
    int rc = braun_gen_c_write(out, sf, argv[2], argv[1]);
    if (out != stdout && fclose(out) != 0) rc = -1;
    braun_scene_free(sf);
    if (rc) fprintf(stderr, "fw-gen-c: cannot write %s (is '%s' a C identifier?)\n",
                    argc == 4 ? argv[3] : "stdout", argv[2]);
    return rc ? 2 : 0;
}
