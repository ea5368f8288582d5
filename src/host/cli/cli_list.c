/* braun list: the built-in models, one line each (name, n, m, p,
 * description), then the shipped scenes that run by their file name from
 * any directory (name.json, or group/name.json for data/iftomm/; n, m, p,
 * description). */
#include <string.h>

#include "braun_cli.h"

/* A file name as braun check prints it (control bytes as \xNN): a name
 * in the data directory cannot add a line or colour the terminal. */
static const char *escaped(const char *s, char *buf, size_t size)
{
    size_t k = 0;
    char one[5];
    buf[0] = '\0';
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        const char *e = braun_cli_text_byte(*p, one);
        const size_t len = strlen(e);
        if (k + len + 4 >= size) {
            memcpy(buf + k, "...", 4);
            return buf;
        }
        memcpy(buf + k, e, len + 1);
        k += len;
    }
    return buf;
}

/* user: the data directory; a scene in a group is named GROUP/FILE. */
static void scene_line(const char *path, void *user)
{
    char err[512], name[256];
    const char *dir = user;
    const size_t dlen = strlen(dir);
    braun_scene_file *f = braun_scene_load(path, err, sizeof err);
    const char *file = strncmp(path, dir, dlen) == 0 && path[dlen] == '/' ? path + dlen + 1 : path;
    escaped(file, name, sizeof name);
    if (!f) {
        braun_cli_mask_controls(err);
        printf("%-22s (does not load: %s)\n", name, err);
        return;
    }
    /* The scene's texts are data: escaped as braun check shows them. */
    printf("%-22s n=%d m=%d p=%d  ", name, f->scene.n, f->scene.m, f->scene.p);
    braun_cli_put_text(stdout, f->description);
    putchar('\n');
    braun_scene_free(f);
}

int braun_cli_list(void)
{
    const braun_builtin *b;
    for (int i = 0; (b = braun_builtin_at(i)) != NULL; i++)
        printf("%-14s n=%d m=%d p=%d  %s\n", b->name, b->sys.n, b->sys.m, b->sys.p,
               b->description ? b->description : "");
    const braun_cli_target *t;
    for (int i = 0; (t = braun_cli_extra_at(i)) != NULL; i++)
        printf("%-14s n=%d m=%d p=%d  %s\n", t->name, t->sys.n, t->sys.m, t->sys.p,
               t->description ? t->description : "");
    const char *dir = braun_cli_data_dir();
    if (dir) {
        char shown[512];
        printf("\nshipped scenes (%s; run them by name from any directory):\n",
               escaped(dir, shown, sizeof shown));
        braun_cli_data_each(scene_line, (void *)dir);
        /* A BRAUN_DATA_DIR that is not a directory listed nothing, without a word. */
        if (!braun_cli_is_directory(dir))
            fprintf(stderr, "braun: note: the data directory '%s' is not a directory that can be "
                            "read (BRAUN_DATA_DIR?): no shipped scenes\n", shown);
    }
    return fflush(stdout) == 0 ? 0 : BRAUN_CLI_FAILED;
}
