/* What `braun plot` draws of a scene: items and their anchors (cli_plot.h),
 * from the scene's elements by their classes — a rigid body as the outline
 * of its named points (a bar when they are in a line), a particle as a
 * disc (a ring when massless: a joint of rods), rods as bars, revolute
 * joints as rings, distance joints as thin lines, sliders as a guide and
 * a block, knife edges as blades, springs as zigzags, motors, torques and
 * driven angles as arcs about the body, ground points as hatched marks. A
 * joint or effect class the tool does not know is drawn as rings at its
 * points. Point names ("crank.A") come from the scene's text. */
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_plot.h"

static int add_anchor(plot_drawing *dr, int scene_point, int body, double x, double y)
{
    if (dr->nanchors == dr->cap_anchors) {
        const int cap = dr->cap_anchors ? 2 * dr->cap_anchors : 64;
        plot_anchor *a = realloc(dr->anchors, (size_t)cap * sizeof *a);
        if (!a) return -1;
        dr->anchors = a;
        dr->cap_anchors = cap;
    }
    plot_anchor *a = &dr->anchors[dr->nanchors];
    memset(a, 0, sizeof *a);
    a->scene_point = scene_point;
    a->own.body = body;
    a->own.x = (braun_real)x;
    a->own.y = (braun_real)y;
    return dr->nanchors++;
}

static int body_of_anchor(const plot_drawing *dr, int i)
{
    const plot_anchor *a = &dr->anchors[i];
    return a->scene_point >= 0 ? dr->scene->points[a->scene_point].body : a->own.body;
}

static int add_item(plot_drawing *dr, int kind, int a, int b, int c, int count)
{
    if (a < 0 || b < 0 || c < 0) return -1;
    if (dr->nitems == dr->cap_items) {
        const int cap = dr->cap_items ? 2 * dr->cap_items : 64;
        plot_item *it = realloc(dr->items, (size_t)cap * sizeof *it);
        if (!it) return -1;
        dr->items = it;
        dr->cap_items = cap;
    }
    plot_item *it = &dr->items[dr->nitems++];
    it->kind = kind;
    it->a = a;
    it->b = b;
    it->c = c;
    it->count = count;
    it->fn = NULL;
    it->fn_rate = 0;
    it->sense = 1;
    /* The anchors the kind uses: on the ground, the item is drawn once. */
    const int used = kind == PLOT_OUTLINE ? count
                     : kind == PLOT_BLOCK ? 3
                     : kind == PLOT_BAR || kind == PLOT_LINK || kind == PLOT_GUIDE ||
                               kind == PLOT_BLADE || kind == PLOT_SPRING
                         ? 2
                         : 1;
    it->fixed = 1;
    for (int k = 0; k < used; k++) {
        const int idx = kind == PLOT_OUTLINE ? a + k : (k == 0 ? a : k == 1 ? b : c);
        if (body_of_anchor(dr, idx) != BRAUN_SCENE_GROUND) it->fixed = 0;
    }
    return 0;
}

static double cross(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static int by_xy(const void *pa, const void *pb)
{
    const double *a = (const double *)pa, *b = (const double *)pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return a[1] < b[1] ? -1 : a[1] > b[1];
}

/* A planar rigid body: the convex hull of its points and its centre in the
 * body frame (monotone chain); a bar between the two farthest when they
 * are in a line; a disc when it has no point. */
static int rigid_outline(plot_drawing *dr, int body)
{
    const braun_scene *s = dr->scene;
    int np = 1;
    for (int i = 0; i < s->npoints; i++) np += s->points[i].body == body;
    double *pts = malloc((size_t)np * 2 * sizeof *pts), *hull = malloc((size_t)(2 * np + 1) * 2 * sizeof *hull);
    if (!pts || !hull) {
        free(pts);
        free(hull);
        return -1;
    }
    int k = 0;
    pts[k++] = 0, pts[k++] = 0;
    for (int i = 0; i < s->npoints; i++)
        if (s->points[i].body == body) pts[k++] = (double)s->points[i].x, pts[k++] = (double)s->points[i].y;
    qsort(pts, (size_t)np, 2 * sizeof *pts, by_xy);
    int h = 0;
    for (int i = 0; i < np; i++) {
        while (h >= 2 && cross(hull + 2 * (h - 2), hull + 2 * (h - 1), pts + 2 * i) <= 0) h--;
        hull[2 * h] = pts[2 * i], hull[2 * h + 1] = pts[2 * i + 1], h++;
    }
    for (int i = np - 2, lo = h + 1; i >= 0; i--) {
        while (h >= lo && cross(hull + 2 * (h - 2), hull + 2 * (h - 1), pts + 2 * i) <= 0) h--;
        hull[2 * h] = pts[2 * i], hull[2 * h + 1] = pts[2 * i + 1], h++;
    }
    if (h > 1) h--; /* the chain ends where it began */
    double span = 0, area = 0;
    int fa = 0, fb = 0;
    for (int i = 0; i < np; i++)
        for (int j = i + 1; j < np; j++) {
            const double d = hypot(pts[2 * i] - pts[2 * j], pts[2 * i + 1] - pts[2 * j + 1]);
            if (d > span) span = d, fa = i, fb = j;
        }
    for (int i = 0; i < h; i++) {
        const int j = (i + 1) % h;
        area += hull[2 * i] * hull[2 * j + 1] - hull[2 * j] * hull[2 * i + 1];
    }
    int rc;
    if (span == 0) {
        rc = add_item(dr, PLOT_MASS, add_anchor(dr, -1, body, 0, 0), 0, 0, 0);
    } else if (h < 3 || fabs(area) <= 1e-3 * span * span) {
        const int a = add_anchor(dr, -1, body, pts[2 * fa], pts[2 * fa + 1]);
        const int b = add_anchor(dr, -1, body, pts[2 * fb], pts[2 * fb + 1]);
        rc = add_item(dr, PLOT_BAR, a, b, 0, 0);
    } else {
        const int first = dr->nanchors;
        rc = 0;
        for (int i = 0; i < h && !rc; i++) rc = add_anchor(dr, -1, body, hull[2 * i], hull[2 * i + 1]) < 0;
        if (!rc) rc = add_item(dr, PLOT_OUTLINE, first, first, first, h);
    }
    free(pts);
    free(hull);
    return rc;
}

/* A body of a class drawn from its points only (a spatial one): bars
 * from its centre to each of its points. */
static int star_outline(plot_drawing *dr, int body)
{
    const int c = add_anchor(dr, -1, body, 0, 0);
    int rc = 0, any = 0;
    for (int i = 0; i < dr->scene->npoints && !rc; i++)
        if (dr->scene->points[i].body == body) {
            rc = add_item(dr, PLOT_BAR, c, add_anchor(dr, i, body, 0, 0), 0, 0);
            any = 1;
        }
    return rc ? rc : any ? 0 : add_item(dr, PLOT_MASS, c, 0, 0, 0);
}

/* The scene's size at its initial state: guides reach this far. */
static double scene_size(const braun_scene *s)
{
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    braun_real pos[3];
    for (int i = 0; i < s->npoints; i++) {
        braun_scene_initial_point(s, i, pos);
        for (int k = 0; k < 2; k++) {
            if ((double)pos[k] < lo[k]) lo[k] = (double)pos[k];
            if ((double)pos[k] > hi[k]) hi[k] = (double)pos[k];
        }
    }
    const double d = s->npoints ? hypot(hi[0] - lo[0], hi[1] - lo[1]) : 1;
    return d > 0 ? d : 1;
}

/* A slider or prismatic joint: its guide through the line point along the
 * axis (in the line's body frame), and the block at the sliding point. */
static int slider(plot_drawing *dr, const braun_scene_joint *j, double reach)
{
    const braun_scene_point *A = &dr->scene->points[j->b];
    const double ax = (double)j->axis[0], ay = (double)j->axis[1], len = hypot(ax, ay);
    if (!(len > 0)) return 0;
    const double ux = reach * ax / len, uy = reach * ay / len;
    const int g0 = add_anchor(dr, -1, A->body, (double)A->x - ux, (double)A->y - uy);
    const int g1 = add_anchor(dr, -1, A->body, (double)A->x + ux, (double)A->y + uy);
    if (add_item(dr, PLOT_GUIDE, g0, g1, 0, 0)) return -1;
    return add_item(dr, PLOT_BLOCK, add_anchor(dr, j->a, 0, 0, 0), g0, g1, 0);
}

static int blade(plot_drawing *dr, const braun_scene_joint *j, double reach)
{
    const braun_scene_point *P = &dr->scene->points[j->a];
    const double ax = (double)j->axis[0], ay = (double)j->axis[1], len = hypot(ax, ay);
    const double l = 0.08 * reach;
    if (!(len > 0)) return 0;
    return add_item(dr, PLOT_BLADE,
                    add_anchor(dr, -1, P->body, (double)P->x - l * ax / len, (double)P->y - l * ay / len),
                    add_anchor(dr, -1, P->body, (double)P->x + l * ax / len, (double)P->y + l * ay / len),
                    0, 0);
}

/* A ground point an element uses gets a ground mark. */
static void mark(char *grounded, const braun_scene *s, int i)
{
    if (i >= 0 && i < s->npoints && s->points[i].body == BRAUN_SCENE_GROUND) grounded[i] = 1;
}

/* Rings at every point field of an element of a class the tool does not know. */
static int unknown_points(plot_drawing *dr, const braun_scene_field *fields, const void *element,
                          char *grounded)
{
    for (const braun_scene_field *f = fields; f && f->key; f++)
        if (f->kind == BRAUN_FIELD_POINT || f->kind == BRAUN_FIELD_BODY_POINT) {
            int idx;
            memcpy(&idx, (const char *)element + f->offset, sizeof idx);
            if (idx < 0 || idx >= dr->scene->npoints) continue;
            /* Its ground points get their marks, as a planar joint's do (a
             * spatial hinge's pivot had a ring and no mark). */
            mark(grounded, dr->scene, idx);
            if (add_item(dr, PLOT_PIN, add_anchor(dr, idx, 0, 0, 0), 0, 0, 0)) return -1;
        }
    return 0;
}

/* A rotor turns the way its torque (fn), its drive's rate (fn, rate) or a
 * motor's stall torque (sense) says: the arrow was counter-clockwise for
 * every one, a torque of -1 and a drive run backwards alike. */
static int rotor(plot_drawing *dr, int body, const braun_scene_fn *fn, int rate, double sense)
{
    if (body < 0 || body >= dr->scene->nbodies) return 0;
    const int rc = add_item(dr, PLOT_ROTOR, add_anchor(dr, -1, body, 0, 0), 0, 0, 0);
    if (rc) return rc;
    plot_item *it = &dr->items[dr->nitems - 1];
    it->fn = fn;
    it->fn_rate = rate;
    it->sense = sense;
    return 0;
}

int plot_item_sense(const plot_item *it, double t)
{
    double s = it->sense;
    if (it->fn) {
        braun_real v = 0, r = 0;
        if (braun_scene_fn_eval(it->fn, (braun_real)t, &v, &r, NULL) == BRAUN_OK)
            s = (double)(it->fn_rate ? r : v);
    }
    /* No torque at t: no arrow (a zero was drawn counter-clockwise). */
    return s < 0 ? -1 : s > 0 ? 1 : 0;
}

#define MARK(i) mark(grounded, s, (i))

static int build(plot_drawing *dr)
{
    const braun_scene *s = dr->scene;
    const double reach = scene_size(s);
    char *grounded = calloc((size_t)s->npoints + 1, 1);
    int rc = grounded ? 0 : -1;
    /* Springs and guides first: bodies are drawn over them. */
    for (int e = 0; e < s->neffects && !rc; e++) {
        const braun_scene_effect *ef = &s->effects[e];
        if (ef->type == BRAUN_EFFECT_SPRING) {
            rc = add_item(dr, PLOT_SPRING, add_anchor(dr, ef->a, 0, 0, 0), add_anchor(dr, ef->b, 0, 0, 0), 0, 0);
            MARK(ef->a), MARK(ef->b);
        }
    }
    for (int k = 0; k < s->njoints && !rc; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (j->type == BRAUN_JOINT_SLIDER || j->type == BRAUN_JOINT_PRISMATIC) rc = slider(dr, j, reach);
    }
    for (int r = 0; r < s->nrods && !rc; r++) {
        rc = add_item(dr, PLOT_BAR, add_anchor(dr, s->rods[r].a, 0, 0, 0), add_anchor(dr, s->rods[r].b, 0, 0, 0), 0, 0);
        MARK(s->rods[r].a), MARK(s->rods[r].b);
    }
    for (int k = 0; k < s->njoints && !rc; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (j->type == BRAUN_JOINT_DISTANCE) {
            rc = add_item(dr, PLOT_LINK, add_anchor(dr, j->a, 0, 0, 0), add_anchor(dr, j->b, 0, 0, 0), 0, 0);
            MARK(j->a), MARK(j->b);
        }
    }
    for (int b = 0; b < s->nbodies && !rc; b++) {
        const braun_scene_body *body = &s->bodies[b];
        if (body->kind->flags & BRAUN_BODY_CLASS_POINT_MASS)
            rc = add_item(dr, body->mass > 0 ? PLOT_MASS : PLOT_PIN, add_anchor(dr, -1, b, 0, 0), 0, 0, 0);
        else if (body->kind->dim == 2)
            rc = rigid_outline(dr, b);
        else
            rc = star_outline(dr, b);
    }
    for (int k = 0; k < s->njoints && !rc; k++) {
        const braun_scene_joint *j = &s->joints[k];
        if (j->type == BRAUN_JOINT_REVOLUTE) {
            rc = add_item(dr, PLOT_PIN, add_anchor(dr, j->a, 0, 0, 0), 0, 0, 0);
            MARK(j->a), MARK(j->b);
        } else if (j->type == BRAUN_JOINT_SLIDER || j->type == BRAUN_JOINT_PRISMATIC) {
            MARK(j->b);
        } else if (j->type == BRAUN_JOINT_KNIFE) {
            rc = blade(dr, j, reach);
        } else if (j->type == BRAUN_JOINT_ANGLE) {
            if (j->driven) rc = rotor(dr, j->b, &j->drive, 1, 1);
        } else if (j->type != BRAUN_JOINT_DISTANCE) {
            rc = unknown_points(dr, j->type->fields, j, grounded);
        }
    }
    for (int e = 0; e < s->neffects && !rc; e++) {
        const braun_scene_effect *ef = &s->effects[e];
        if (ef->type == BRAUN_EFFECT_MOTOR) rc = rotor(dr, ef->a, NULL, 0, (double)ef->tau0); /* its torque at rest */
        else if (ef->type == BRAUN_EFFECT_TORQUE) rc = rotor(dr, ef->a, &ef->f[0], 0, 1);
        else if (ef->type != BRAUN_EFFECT_SPRING && ef->type != BRAUN_EFFECT_GRAVITY &&
                 ef->type != BRAUN_EFFECT_TORSION && ef->type != BRAUN_EFFECT_FORCE)
            rc = unknown_points(dr, ef->type->fields, ef, grounded);
    }
    for (int i = 0; i < s->npoints && !rc; i++)
        if (grounded[i]) rc = add_item(dr, PLOT_GROUND, add_anchor(dr, i, 0, 0, 0), 0, 0, 0);
    free(grounded);
    return rc;
}

int plot_drawing_build(plot_drawing *dr, const braun_cli_target *t, const char *view)
{
    memset(dr, 0, sizeof *dr);
    if (!t->drawing)
        return braun_cli_error("'%s' is a system defined in C without a scene: nothing to draw "
                               "(plot its coordinates against time with --plot q[0],q[1])",
                               t->name);
    dr->scene = &t->drawing->scene;
    static const char *const views[] = {"xy", "yx", "xz", "zx", "yz", "zy"};
    const char *v = view ? view : "xy";
    size_t i = 0;
    while (i < sizeof views / sizeof views[0] && strcmp(views[i], v) != 0) i++;
    if (i == sizeof views / sizeof views[0])
        return braun_cli_error("--view '%s': give the plane as two axes, across then up "
                               "(xy, xz, yz, yx, zx, zy)", v);
    /* A planar scene has no z: a plane with it drew everything on a line. */
    if (t->drawing->scene.dim != 3 && strchr(v, 'z'))
        return braun_cli_error("--view '%s': '%s' is planar (its plane is xy or yx)", v, t->name);
    dr->axis_u = v[0] - 'x';
    dr->axis_v = v[1] - 'x';
    memcpy(dr->view, v, 3);
    if (build(dr)) {
        plot_drawing_free(dr);
        braun_cli_error("out of memory");
        return BRAUN_CLI_FAILED;
    }
    return 0;
}

void plot_drawing_free(plot_drawing *dr)
{
    free(dr->anchors);
    free(dr->items);
    dr->anchors = NULL;
    dr->items = NULL;
    dr->nanchors = dr->nitems = 0;
}

/* Each slider's guide made long enough for the travel the kept states show
 * (it reached as far as the scene's initial size: the slider-crank's block
 * ran 0.4 m past both ends of its rail), with a 5 % margin. The guide's
 * anchors are in the line body's frame; the block's place along them is
 * affine in that frame, so they are stretched there. */
int plot_drawing_fit_guides(plot_drawing *dr, const plot_samples *s)
{
    int nblocks = 0;
    for (int i = 0; i < dr->nitems; i++) nblocks += dr->items[i].kind == PLOT_BLOCK;
    if (!nblocks || s->count < 1) return 0;
    braun_real *qr = malloc((size_t)dr->scene->n * sizeof *qr);
    double *pos = malloc((size_t)dr->nanchors * 3 * sizeof *pos);
    double *lo = calloc((size_t)dr->nitems, sizeof *lo), *hi = malloc((size_t)dr->nitems * sizeof *hi);
    if (!qr || !pos || !lo || !hi) {
        free(qr), free(pos), free(lo), free(hi);
        return -1;
    }
    for (int i = 0; i < dr->nitems; i++) hi[i] = 1;
    for (long r = 0; r < s->count; r++) {
        plot_drawing_eval(dr, s->rows + (size_t)r * (size_t)s->cols + 1, qr, pos);
        for (int i = 0; i < dr->nitems; i++) {
            const plot_item *it = &dr->items[i];
            if (it->kind != PLOT_BLOCK) continue;
            const double *P = pos + 3 * it->a, *G0 = pos + 3 * it->b, *G1 = pos + 3 * it->c;
            double dd = 0, dp = 0;
            for (int k = 0; k < 3; k++) {
                dd += (G1[k] - G0[k]) * (G1[k] - G0[k]);
                dp += (P[k] - G0[k]) * (G1[k] - G0[k]);
            }
            if (!(dd > 0)) continue;
            const double u = dp / dd;
            if (u < lo[i]) lo[i] = u;
            if (u > hi[i]) hi[i] = u;
        }
    }
    for (int i = 0; i < dr->nitems; i++) {
        const plot_item *it = &dr->items[i];
        if (it->kind != PLOT_BLOCK || (lo[i] >= 0 && hi[i] <= 1) || !isfinite(lo[i]) || !isfinite(hi[i]))
            continue;
        plot_anchor *a0 = &dr->anchors[it->b], *a1 = &dr->anchors[it->c];
        if (a0->scene_point >= 0 || a1->scene_point >= 0 || a0->own.body != a1->own.body) continue;
        const double pad = 0.05 * (hi[i] - lo[i]);
        const double u0 = lo[i] < 0 ? lo[i] - pad : 0, u1 = hi[i] > 1 ? hi[i] + pad : 1;
        const double x0 = (double)a0->own.x, y0 = (double)a0->own.y;
        const double dx = (double)a1->own.x - x0, dy = (double)a1->own.y - y0;
        a0->own.x = (braun_real)(x0 + u0 * dx), a0->own.y = (braun_real)(y0 + u0 * dy);
        a1->own.x = (braun_real)(x0 + u1 * dx), a1->own.y = (braun_real)(y0 + u1 * dy);
    }
    free(qr), free(pos), free(lo), free(hi);
    return 0;
}

void plot_drawing_eval(const plot_drawing *dr, const double *q, braun_real *qr, double *pos)
{
    const braun_scene *s = dr->scene;
    for (int i = 0; i < s->n; i++) qr[i] = (braun_real)q[i];
    for (int i = 0; i < dr->nanchors; i++) {
        const plot_anchor *a = &dr->anchors[i];
        braun_scene_pt P;
        memset(&P, 0, sizeof P);
        if (a->scene_point >= 0) {
            braun_scene_pt_eval(s, a->scene_point, qr, NULL, &P);
        } else if (a->own.body == BRAUN_SCENE_GROUND) {
            P.pos[0] = a->own.x;
            P.pos[1] = a->own.y;
        } else {
            const braun_scene_body *b = &s->bodies[a->own.body];
            P.body = b;
            P.col = b->iq;
            b->kind->point(b, &a->own, qr + b->iq, NULL, &P);
        }
        for (int k = 0; k < 3; k++) pos[3 * i + k] = (double)P.pos[k];
    }
}

/* ------------------------------------------------------------ point names */
/* The scene's text: the file again, or a built-in's own. */
static json_t *scene_json(const braun_cli_target *t)
{
    char err[512];
    size_t len = 0;
    json_error_t je;
    if (t->drawing_text) return json_loads(t->drawing_text, 0, &je);
    if (!t->source) return NULL;
    char *text = braun_cli_read_file(t->source, (size_t)64 << 20, &len, err, sizeof err);
    if (!text) return NULL;
    json_t *doc = json_loadb(text, len, 0, &je);
    free(text);
    return doc;
}

static int body_index(const braun_scene_file *f, const char *name, size_t len)
{
    for (int b = 0; b < f->scene.nbodies; b++)
        if (f->body_names && f->body_names[b] && strlen(f->body_names[b]) == len &&
            strncmp(f->body_names[b], name, len) == 0)
            return b;
    return -1;
}

/* "body.point", "body" (its centre, or the particle), "ground.NAME", or a
 * reported point's NAME (its CSV columns NAME.x, ...: a name without '.'
 * that no body has, docs/scene-format.md). */
int plot_drawing_point(plot_drawing *dr, const braun_cli_target *t, const char *ref)
{
    const braun_scene_file *sf = t->scene;
    for (int k = 0; sf && k < sf->nreports; k++)
        if (strcmp(sf->report_names[k], ref) == 0) {
            const int i = add_anchor(dr, sf->report_points[k], 0, 0, 0);
            if (i < 0) braun_cli_error("out of memory");
            return i;
        }
    const char *dot = strchr(ref, '.');
    const size_t blen = dot ? (size_t)(dot - ref) : strlen(ref);
    const int ground = blen == 6 && strncmp(ref, "ground", 6) == 0;
    const int b = ground ? BRAUN_SCENE_GROUND : body_index(t->drawing, ref, blen);
    if (!ground && b < 0) {
        braun_cli_error("point '%s': no body '%.*s' in '%s'", ref, (int)blen, ref, t->name);
        return -1;
    }
    if (!dot) {
        if (ground) {
            braun_cli_error("point '%s': name a ground point (ground.NAME)", ref);
            return -1;
        }
        const int i = add_anchor(dr, -1, b, 0, 0);
        if (i < 0) braun_cli_error("out of memory");
        return i;
    }
    json_t *doc = scene_json(t);
    json_t *pts = NULL;
    if (doc && ground) pts = json_object_get(json_object_get(doc, "ground"), "points");
    else if (doc) pts = json_object_get(json_array_get(json_object_get(doc, "bodies"), (size_t)b), "points");
    json_t *xy = json_object_get(pts, dot + 1);
    if (!json_is_array(xy) || json_array_size(xy) < 2 || !json_is_number(json_array_get(xy, 0)) ||
        !json_is_number(json_array_get(xy, 1))) {
        braun_cli_error("point '%s': %s has no point '%s'", ref,
                        ground ? "the ground" : "the body", dot + 1);
        json_decref(doc);
        return -1;
    }
    const int i = add_anchor(dr, -1, b, json_number_value(json_array_get(xy, 0)),
                             json_number_value(json_array_get(xy, 1)));
    json_decref(doc);
    if (i < 0) braun_cli_error("out of memory");
    return i;
}

int plot_drawing_trace(plot_drawing *dr, const braun_cli_target *t, const char *list)
{
    for (const char *p = list; p && *p;) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char ref[96];
        if (len == 0 || len >= sizeof ref)
            return braun_cli_error("--points '%s': give point names separated by commas "
                                   "(crank.A,rod.B)", list);
        if (dr->ntraces == (int)(sizeof dr->traces / sizeof dr->traces[0]))
            return braun_cli_error("--points: at most %d points",
                                   (int)(sizeof dr->traces / sizeof dr->traces[0]));
        memcpy(ref, p, len);
        ref[len] = '\0';
        const int a = plot_drawing_point(dr, t, ref);
        if (a < 0) return BRAUN_CLI_USAGE;
        dr->traces[dr->ntraces].anchor = a;
        memcpy(dr->traces[dr->ntraces].name, ref, len + 1);
        dr->ntraces++;
        p = comma ? comma + 1 : p + len;
    }
    return 0;
}
