/* Names and units of a target's coordinates, for the CSV header, `braun
 * plot --plot` and `--traj`: from its scene — body name and the body
 * class's coordinate ("crank.x" m, "crank.theta" rad; velocities
 * "crank.vx" m/s, "crank.omega" rad/s) — or q[i], v[i] for a system defined
 * in C. A spatial body names its coordinates body.q[k], body.v[k] with
 * their units; a body class the tool does not know (a program's own), the
 * same without units. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_cli.h"

typedef struct coord_names {
    const braun_scene_body_class *kind;
    const char *q[3], *v[3], *q_unit[3], *v_unit[3];
} coord_names;

static const coord_names known[] = {
    {&braun_scene_body_rigid, {"x", "y", "theta"}, {"vx", "vy", "omega"},
     {"m", "m", "rad"}, {"m/s", "m/s", "rad/s"}},
    {&braun_scene_body_particle, {"x", "y", NULL}, {"vx", "vy", NULL},
     {"m", "m", NULL}, {"m/s", "m/s", NULL}},
};

/* The spatial classes keep their coordinates' meaning to themselves
 * (docs/method.md, "Spatial rigid bodies"): body.q[k], body.v[k], with the
 * units they have — a position and a unit quaternion (and their rates). */
typedef struct coord_units {
    const braun_scene_body_class *kind;
    int count;
    const char *q_unit[7], *v_unit[7];
} coord_units;

static const coord_units spatial[] = {
    {&braun_scene_body_rigid3d, 7, {"m", "m", "m", "1", "1", "1", "1"},
     {"m/s", "m/s", "m/s", "1/s", "1/s", "1/s", "1/s"}},
    {&braun_scene_body_particle3d, 3, {"m", "m", "m"}, {"m/s", "m/s", "m/s"}},
};

/* The body whose coordinates hold coordinate i (bodies are numbered in
 * order: iq increases), or -1. */
static int body_of(const braun_scene *s, int i)
{
    int lo = 0, hi = s->nbodies - 1;
    while (lo <= hi) {
        const int mid = lo + (hi - lo) / 2;
        const braun_scene_body *b = &s->bodies[mid];
        if (i < b->iq) hi = mid - 1;
        else if (i >= b->iq + b->kind->dof) lo = mid + 1;
        else return mid;
    }
    return -1;
}

const char *braun_cli_coord_name(const braun_cli_target *t, int i, int velocity, char *name,
                                 size_t size, const char **unit)
{
    const braun_scene_file *f = t->drawing;
    const int b = f ? body_of(&f->scene, i) : -1;
    *unit = NULL;
    if (b < 0) {
        snprintf(name, size, "%s[%d]", velocity ? "v" : "q", i);
        return name;
    }
    const braun_scene_body *body = &f->scene.bodies[b];
    const int k = i - body->iq;
    char own[32];
    const char *bn = f->body_names && f->body_names[b] ? f->body_names[b] : NULL;
    if (!bn) {
        snprintf(own, sizeof own, "body[%d]", b);
        bn = own;
    }
    for (size_t c = 0; c < sizeof known / sizeof known[0]; c++)
        if (known[c].kind == body->kind && k < 3 && known[c].q[k]) {
            *unit = velocity ? known[c].v_unit[k] : known[c].q_unit[k];
            snprintf(name, size, "%s.%s", bn, velocity ? known[c].v[k] : known[c].q[k]);
            return name;
        }
    for (size_t c = 0; c < sizeof spatial / sizeof spatial[0]; c++)
        if (spatial[c].kind == body->kind && k < spatial[c].count)
            *unit = velocity ? spatial[c].v_unit[k] : spatial[c].q_unit[k];
    snprintf(name, size, "%s.%s[%d]", bn, velocity ? "v" : "q", k);
    return name;
}

/* The scene's reported points (docs/scene-format.md, "Reported points"):
 * NAME.x, NAME.y (and NAME.z in a spatial scene) after the other columns,
 * for those with columns of their own (t->reports). */
int braun_cli_report_dim(const braun_cli_target *t)
{
    const braun_scene_file *s = t ? t->scene : NULL;
    return s && t->nreports > 0 ? (s->scene.dim == 3 ? 3 : 2) : 0;
}

int braun_cli_csv_column_count(const braun_cli_target *t, int n)
{
    const int dim = braun_cli_report_dim(t);
    return braun_cli_column_count(n) + (dim ? dim * t->nreports : 0);
}

/* Reported point k is its body's origin and its columns NAME.x, NAME.y
 * (.z) are names of the body's first coordinates: a particle, or a rigid
 * body's centre, reported under the body's name (the loader refuses a
 * body's name for any other point). */
static int repeats_body(const braun_cli_target *t, int k)
{
    const braun_scene_file *sf = t->scene;
    const braun_scene_point *pt = &sf->scene.points[sf->report_points[k]];
    const int dim = sf->scene.dim == 3 ? 3 : 2;
    if (pt->body < 0 || pt->body >= sf->scene.nbodies || pt->x != 0 || pt->y != 0 || pt->z != 0)
        return 0;
    const braun_scene_body *b = &sf->scene.bodies[pt->body];
    if (b->kind->dof < dim) return 0;
    for (int c = 0; c < dim; c++) {
        char own[BRAUN_CLI_COLUMN_NAME], body[BRAUN_CLI_COLUMN_NAME];
        const char *unit;
        snprintf(own, sizeof own, "%s.%c", sf->report_names[k], "xyz"[c]);
        if (strcmp(braun_cli_coord_name(t, b->iq + c, 0, body, sizeof body, &unit), own) != 0)
            return 0;
    }
    return 1;
}

int braun_cli_report_columns(braun_cli_target *t)
{
    const braun_scene_file *sf = t->scene;
    t->reports = NULL;
    t->nreports = 0;
    if (!sf || sf->nreports <= 0) return 0;
    t->reports = malloc((size_t)sf->nreports * sizeof *t->reports);
    if (!t->reports) return -1;
    for (int k = 0; k < sf->nreports; k++)
        if (!repeats_body(t, k)) t->reports[t->nreports++] = k;
    return 0;
}

/* Column j of the trajectory CSV: t, the n coordinates, the n velocities,
 * the residuals, then the reported points. */
const char *braun_cli_column_name(const braun_cli_target *t, int n, int j, char *name,
                                  size_t size, const char **unit)
{
    static const char *const tail[] = {"pos_err", "vel_err", "energy_err", "traj_err"};
    static const char *const tail_unit[] = {"Phi_q", "Phi_q/s", "E", "q"};
    *unit = NULL;
    if (j == 0) {
        *unit = "s";
        snprintf(name, size, "t");
        return name;
    }
    if (j <= 2 * n) return braun_cli_coord_name(t, (j - 1) % n, j > n, name, size, unit);
    j -= 2 * n + 1;
    const int dim = braun_cli_report_dim(t);
    if (j >= 4 && dim && j - 4 < dim * t->nreports) {
        *unit = "m";
        snprintf(name, size, "%s.%c", t->scene->report_names[t->reports[(j - 4) / dim]],
                 "xyz"[(j - 4) % dim]);
        return name;
    }
    if (j < 0 || j >= 4) return NULL;
    /* A scene's energy is in joules; a C system's in its own units. */
    *unit = j == 2 && t->drawing ? "J" : tail_unit[j];
    snprintf(name, size, "%s", tail[j]);
    return name;
}

int braun_cli_column_count(int n) { return 1 + 2 * n + 4; }

typedef struct column_entry {
    char name[BRAUN_CLI_COLUMN_NAME];
    int j;
} column_entry;

static int column_order(const void *a, const void *b)
{
    const column_entry *x = a, *y = b;
    const int c = strcmp(x->name, y->name);
    return c ? c : (x->j > y->j) - (x->j < y->j);
}

/* The header names every column whole and apart, as it writes them
 * (control bytes as '?'): bodies named "a\x01" and "a\x02", or two long
 * names cut to the same first bytes, would give two columns one name, and
 * --plot, --traj and every other reader of the CSV would take one for the
 * other. Sorted, so that a 2000-body chain's 12k columns cost no more than
 * reading the scene. */
int braun_cli_columns_distinct(const braun_cli_target *t)
{
    const braun_scene_file *sf = t->scene;
    if (!sf) return 0;
    const int n = t->sys.n, cols = braun_cli_csv_column_count(t, n);
    column_entry *e = malloc((size_t)cols * sizeof *e);
    if (!e) return braun_cli_error("out of memory");
    const char *unit;
    int rc = 0;
    for (int j = 0; j < cols && !rc; j++) {
        braun_cli_column_name(t, n, j, e[j].name, sizeof e[j].name, &unit);
        e[j].j = j;
        braun_cli_mask_controls(e[j].name);
        if (strlen(e[j].name) >= sizeof e[j].name - 1)
            rc = braun_cli_error("%s: column %d of the trajectory CSV would be named '%.60s...', "
                                 "longer than the %d bytes a column name keeps: shorten the "
                                 "name of its body or reported point", sf->path, j + 1,
                                 e[j].name, (int)sizeof e[j].name - 2);
    }
    if (!rc) {
        /* The first clash in the header's order: the pair whose later
         * column comes first. */
        qsort(e, (size_t)cols, sizeof *e, column_order);
        int first = -1, second = cols;
        for (int k = 1, start = 0; k < cols; k++) {
            if (strcmp(e[k - 1].name, e[k].name) != 0) {
                start = k;
                continue;
            }
            if (e[k].j < second) {
                first = e[start].j;
                second = e[k].j;
            }
        }
        if (first >= 0) {
            char name[BRAUN_CLI_COLUMN_NAME];
            braun_cli_column_name(t, n, first, name, sizeof name, &unit);
            braun_cli_mask_controls(name);
            rc = braun_cli_error("%s: columns %d and %d of the trajectory CSV would both be named "
                                 "'%s' (a name's control characters are written as '?'): give the "
                                 "bodies or reported points names that differ in printable "
                                 "characters", sf->path, first + 1, second + 1, name);
        }
    }
    free(e);
    return rc;
}

/* Column index of a name (with or without its " [unit]"), or -1. */
int braun_cli_column_find(const braun_cli_target *t, int n, const char *want)
{
    char name[BRAUN_CLI_COLUMN_NAME];
    const char *unit;
    size_t len = strlen(want);
    const char *br = strstr(want, " [");
    if (br) len = (size_t)(br - want);
    for (int j = 0; j < braun_cli_column_count(n); j++) {
        braun_cli_column_name(t, n, j, name, sizeof name, &unit);
        if (strlen(name) == len && strncmp(name, want, len) == 0) return j;
    }
    return -1;
}
