/* MODEL on the command line -> the target to simulate: a built-in model of
 * braun_models.h, one of this tool's extra models (Andrews' squeezing
 * mechanism), or a scene file — as given, or one of the shipped scenes
 * (braun_cli_data_dir) by its file name. Nothing else in the tool knows how
 * MODEL is resolved. */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "braun_cli.h"
#include "braun_scene_file.h"

/* Models the tool adds to braun_models.h: no minimal-coordinate reference. */
static const struct {
    const char *name, *description;
    const braun_system *sys;
    const braun_real *q0, *v0;
} extras[] = {
    {"andrews", "Andrews' squeezing mechanism (Test Set for IVP Solvers): 7 angles, 6 rows",
     &braun_andrews_system, braun_andrews_q0, braun_andrews_v0},
};

int braun_cli_extra_count(void) { return (int)(sizeof extras / sizeof extras[0]); }

static void extra_target(int i, braun_cli_target *t)
{
    memset(t, 0, sizeof *t);
    t->name = extras[i].name;
    t->description = extras[i].description;
    t->sys = *extras[i].sys;
    t->q0 = extras[i].q0;
    t->v0 = extras[i].v0;
    t->corrections = BRAUN_CORRECT_ALL;
}

const braun_cli_target *braun_cli_extra_at(int i)
{
    static braun_cli_target t;
    if (i < 0 || i >= braun_cli_extra_count()) return NULL;
    extra_target(i, &t);
    return &t;
}

/* A scene file: ends in .json or names a path. */
static int is_scene_file(const char *arg)
{
    size_t len = strlen(arg);
    return (len >= 5 && strcmp(arg + len - 5, ".json") == 0) || strchr(arg, '/') != NULL;
}

/* The scene of a built-in model that has one (names, drawings), or NULL. */
static braun_scene_file *builtin_drawing(const char *name, const char **text)
{
    char err[512];
    *text = braun_cli_builtin_scene(name);
    return *text ? braun_scene_load_text(name, *text, strlen(*text), err, sizeof err) : NULL;
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* A built-in model's or an extra model's name. */
int braun_cli_is_model_name(const char *arg)
{
    if (braun_builtin_find(arg)) return 1;
    for (int i = 0; i < braun_cli_extra_count(); i++)
        if (strcmp(extras[i].name, arg) == 0) return 1;
    return 0;
}

int braun_cli_target_open(const char *arg, braun_cli_target *t)
{
    memset(t, 0, sizeof *t);
    /* Not a built-in name and not a file here: a shipped scene by name
     * ("four-bar.json", "damped-motor", "a01-pendulum" or
     * "iftomm/a01-pendulum"). */
    if (!braun_cli_is_model_name(arg) && !exists(arg) &&
        braun_cli_data_file(arg, t->path_buf, sizeof t->path_buf))
        arg = t->path_buf;
    if (is_scene_file(arg) || (!braun_cli_is_model_name(arg) && exists(arg))) {
        char err[512];
        braun_scene_file *f = braun_scene_load(arg, err, sizeof err);
        if (!f) return braun_cli_error("%s", err);
        t->name = f->name;
        t->source = f->path;
        t->description = f->description;
        t->sys = f->sys;
        t->q0 = f->q0;
        t->v0 = f->v0;
        t->reference = f->reference ? braun_builtin_find(f->reference) : NULL;
        t->corrections = f->corrections;
        t->scene = f;
        t->drawing = f;
        braun_cli_path_id(arg, &t->id);
        if (braun_cli_report_columns(t)) {
            braun_cli_target_close(t);
            return braun_cli_error("out of memory");
        }
        const int clash = braun_cli_columns_distinct(t);
        if (clash) {
            braun_cli_target_close(t);
            return clash;
        }
        return 0;
    }
    const braun_builtin *b = braun_builtin_find(arg);
    if (b) {
        t->name = b->name;
        t->description = b->description;
        t->sys = b->sys;
        t->q0 = b->q0;
        t->v0 = b->v0;
        t->reference = b;
        t->corrections = BRAUN_CORRECT_ALL;
        t->drawing = builtin_drawing(b->name, &t->drawing_text);
        /* Only a scene with exactly the model's coordinates names them. */
        if (t->drawing && t->drawing->scene.n != b->sys.n) {
            braun_scene_free(t->drawing);
            t->drawing = NULL;
        }
        return 0;
    }
    for (int i = 0; i < braun_cli_extra_count(); i++)
        if (strcmp(extras[i].name, arg) == 0) {
            extra_target(i, t);
            return 0;
        }
    return braun_cli_error("unknown model '%s' (see braun list: built-in models and shipped "
                           "scenes; or give a scene file)", arg);
}

void braun_cli_target_close(braun_cli_target *t)
{
    free(t->reports);
    t->reports = NULL;
    t->nreports = 0;
    if (t->drawing != t->scene) braun_scene_free(t->drawing);
    braun_scene_free(t->scene);
    t->scene = NULL;
    t->drawing = NULL;
}
