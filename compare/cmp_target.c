/* Targets: the one place that maps a name to a system, its initial state and
 * its reference. Built-in models today; a scene adds one branch in
 * cmp_target_find (see cmp_target_scene below). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp.h"
#include "braun_reference.h"
#ifdef CMP_HAVE_SCENES
#include "braun_scene_file.h"
#endif

/* Slider end of the slider-crank (Fig. 2): x_s = x2 + (l/2)cos θ2,
 * y_s = y2 + (l/2)sin θ2. Not a coordinate of q, hence a function. */
static void slider_point(const cmp_target *tg, const double *q, double *xy)
{
    const braun_link_params *p = tg->builtin->sys.user;
    xy[0] = q[3] + 0.5 * p->l * cos(q[5]);
    xy[1] = q[4] + 0.5 * p->l * sin(q[5]);
}

/* Built-in models that name a point by its two coordinates. */
static void coord_point(const cmp_target *tg, const double *q, double *xy)
{
    xy[0] = q[tg->builtin->point_x];
    xy[1] = q[tg->builtin->point_y];
}

static int target_builtin(const braun_builtin *b, cmp_target *tg)
{
    memset(tg, 0, sizeof *tg);
    snprintf(tg->name, sizeof tg->name, "%s", b->name);
    tg->sys = b->sys;
    tg->q0 = malloc(2 * (size_t)b->sys.n * sizeof(double));
    if (!tg->q0) return -1;
    tg->v0 = tg->q0 + b->sys.n;
    /* braun_real is double here (cmp.h refuses BRAUN_SINGLE). */
    for (int i = 0; i < b->sys.n; i++) {
        tg->q0[i] = (double)b->q0[i];
        tg->v0[i] = (double)b->v0[i];
    }
    tg->builtin = b;
    if (strcmp(b->name, "slider-crank") == 0) {
        tg->has_point = 1;
        tg->point_name = "slider end (x_s, y_s)";
        tg->point = slider_point;
    } else if (b->point_x >= 0 && b->point_y >= 0) {
        tg->has_point = 1;
        tg->point_name = strcmp(b->name, "four-bar") == 0 ? "joint 3 (x3, y3)" : "point";
        tg->point = coord_point;
    }
    tg->paper = strcmp(b->name, "slider-crank") == 0 || strcmp(b->name, "four-bar") == 0;
    tg->T_reduced = 100.0;
    tg->dt_out = 0.05;
    tg->h_scale = 1.0;
    tg->scene_point = -1;
    return 0;
}

static int copy_state(cmp_target *tg, int n, const braun_real *q0, const braun_real *v0)
{
    tg->q0 = malloc(2 * (size_t)n * sizeof(double));
    if (!tg->q0) return -1;
    tg->v0 = tg->q0 + n;
    for (int i = 0; i < n; i++) {
        tg->q0[i] = (double)q0[i];
        tg->v0[i] = (double)v0[i];
    }
    return 0;
}

#ifdef CMP_HAVE_SCENES
/* The last point of a scene: its ε and its "slider" in the plots. */
static void scene_point(const cmp_target *tg, const double *q, double *xy)
{
    const braun_scene_file *f = tg->scene_file;
    braun_scene_point_position(&f->scene, tg->scene_point, q, xy);
}

/* Scene files (issue 3): NAME is data/NAME.json, or a path ending in .json.
 * A scene that names a built-in model as its reference (the paper's two) is
 * compared with that model's minimal-coordinate solution; any other with
 * the harness's RK4 + projection at a small step (CMP_REF_PROJ, never
 * libbraun). Andrews' mechanism too; the test set's published angles at
 * t = 0.03 check that reference. */
static int target_scene(const char *name, cmp_target *tg, char *err, size_t errsize)
{
    memset(tg, 0, sizeof *tg);
    tg->scene_point = -1;
    tg->T_reduced = 10.0;
    tg->dt_out = 0.05;
    tg->h_scale = 1.0;
    if (strcmp(name, "andrews") == 0) {
        snprintf(tg->name, sizeof tg->name, "andrews");
        tg->sys = braun_andrews_system;
        if (copy_state(tg, tg->sys.n, braun_andrews_q0, braun_andrews_v0)) goto oom;
        /* The trajectory from the harness's projection at a small step;
         * the test set's published angles check it at t = 0.03. */
        tg->ref_kind = CMP_REF_PROJ;
        tg->ref_t = BRAUN_ANDREWS_T_REF;
        tg->ref_q = braun_andrews_q_ref;
        /* The test set's interval [0, 0.03]: a stiff spring, small steps. */
        tg->T_reduced = BRAUN_ANDREWS_T_REF;
        tg->dt_out = 5e-5;
        tg->h_scale = 1e-3;
        return 0;
    }
    char path[512];
    size_t len = strlen(name);
    if ((len >= 5 && strcmp(name + len - 5, ".json") == 0) || strchr(name, '/')) {
        snprintf(path, sizeof path, "%s", name);
    } else {
        /* NAME: data/NAME.json, else the IFToMM scene data/iftomm/NAME.json. */
        snprintf(path, sizeof path, "data/%s.json", name);
        FILE *probe = fopen(path, "r");
        if (probe) fclose(probe);
        else snprintf(path, sizeof path, "data/iftomm/%s.json", name);
    }
    char why[512];
    braun_scene_file *f = braun_scene_load(path, why, sizeof why);
    if (!f) {
        snprintf(err, errsize, "unknown target '%s': not a built-in model, and %s", name, why);
        return -1;
    }
    snprintf(tg->name, sizeof tg->name, "%s", name);
    tg->scene_file = f;
    tg->sys = f->sys;
    if (copy_state(tg, f->sys.n, f->q0, f->v0)) goto oom;
    const braun_builtin *b = f->reference ? braun_builtin_find(f->reference) : NULL;
    if (b && b->sys.n == f->sys.n) {
        tg->builtin = b;
        tg->T_reduced = 100.0;
    } else {
        tg->ref_kind = CMP_REF_PROJ;
    }
    /* ε of the last point that moves (ground points do not). */
    for (int i = f->scene.npoints - 1; i >= 0; i--)
        if (f->scene.points[i].body != BRAUN_SCENE_GROUND) {
            tg->has_point = 1;
            tg->scene_point = i;
            tg->point_name = "last moving point of the scene";
            tg->point = scene_point;
            break;
        }
    /* A minimal equation the harness can write (open chains, the
     * parallelogram) beats RK4 + projection at a small step: rk8pd on it. */
    if (!tg->builtin) {
        char why2[256];
        tg->minimal = cmp_minimal_new(tg, why2, sizeof why2);
        if (tg->minimal) tg->ref_kind = CMP_REF_RK8PD;
    }
    /* Chaotic chains: a reference holds for a short horizon only. */
    if (strncmp(tg->name, "chain-", 6) == 0) tg->T_reduced = 3.0;
    /* Andrews' mechanism as a scene (IFToMM A03, absolute coordinates: the
     * peers' Andrews): the test set's interval and step scale, as the
     * built-in `andrews`. */
    if (strcmp(tg->name, "a03-andrews") == 0) {
        tg->T_reduced = BRAUN_ANDREWS_T_REF;
        tg->dt_out = 5e-5;
        tg->h_scale = 1e-3;
    }
    return 0;
oom:
    snprintf(err, errsize, "out of memory");
    return -1;
}
#else
/* Without the scene library only built-in models are targets. */
static int target_scene(const char *name, cmp_target *tg, char *err, size_t errsize)
{
    (void)tg;
    snprintf(err, errsize,
             "unknown target '%s': not a built-in model (slider-crank, four-bar, pendulum); "
             "scenes need the scene library (mk/scenes.mk)", name);
    return -1;
}
#endif

int cmp_target_find(const char *name, cmp_target *tg, char *err, size_t errsize)
{
    const braun_builtin *b = braun_builtin_find(name);
    if (b) {
        if (target_builtin(b, tg) == 0) return 0;
        snprintf(err, errsize, "out of memory");
        return -1;
    }
    return target_scene(name, tg, err, errsize);
}

void cmp_target_free(cmp_target *tg)
{
    free(tg->q0);
    tg->q0 = tg->v0 = NULL;
#ifdef CMP_HAVE_SCENES
    braun_scene_free(tg->scene_file);
#endif
    cmp_minimal_free(tg->minimal);
    tg->minimal = NULL;
    tg->scene_file = NULL;
}

cmp_ref_kind cmp_target_ref_kind(const cmp_target *tg)
{
    if (!tg->builtin) return tg->ref_kind;  /* CMP_REF_RK8PD with tg->minimal */
    if (braun_minimal_find(tg->builtin->name)->exact) return CMP_REF_CLOSED;
    if (braun_minimal_find(tg->builtin->name)->rhs) return CMP_REF_RK8PD;
    return CMP_REF_NONE;
}

/* Units: the built-in models' rows as the paper writes them (the four-bar's
 * and the pendulum's are squared lengths), a scene's from its joints. */
void cmp_target_units(const cmp_target *tg, char *phi, size_t phisize, char *q, size_t qsize)
{
    int m = 0, m2 = 0, rad = 0, rigid = 0, particle = 0;
    if (tg->builtin && !tg->scene_file) {
        const char *nm = tg->builtin->name;
        const int sq = !strcmp(nm, "four-bar") || !strcmp(nm, "pendulum");
        snprintf(phi, phisize, "%s", sq ? "m²" : "m");
        snprintf(q, qsize, "%s", !strcmp(nm, "slider-crank") ? "m; rad" : "m");
        return;
    }
#ifdef CMP_HAVE_SCENES
    if (tg->scene_file) {
        const braun_scene *s = &((const braun_scene_file *)tg->scene_file)->scene;
        for (int i = 0; i < s->njoints; i++) {
            const braun_scene_joint_class *c = s->joints[i].type;
            if (c == BRAUN_JOINT_DISTANCE) m2 = 1;
            else if (c == BRAUN_JOINT_ANGLE) rad = 1;
            else if (c != BRAUN_JOINT_KNIFE) m = 1;
        }
        m2 |= s->nrods > 0;
        for (int i = 0; i < s->nbodies; i++) {
            if (s->bodies[i].kind == BRAUN_BODY_RIGID) rigid = 1;
            else particle = 1;
        }
        char buf[32] = "";
        if (m) strcat(buf, "m");
        if (m2) strcat(buf, *buf ? "; m²" : "m²");
        if (rad) strcat(buf, *buf ? "; rad" : "rad");
        snprintf(phi, phisize, "%s", *buf ? buf : "-");
        snprintf(q, qsize, "%s", rigid ? "m; rad" : "m");
        (void)particle;
        return;
    }
#endif
    /* Andrews' mechanism: joint angles, closure rows in metres. */
    snprintf(phi, phisize, "m");
    snprintf(q, qsize, "rad");
}
