/* Private to `braun plot` (cli_plot*.c): what a drawing is made of.
 *
 * A drawing is a list of items (a body's outline, a rod, a pin, a slider's
 * guide and block, a spring, a ground mark, ...) whose geometry is given by
 * anchors: points fixed on a body (or on the ground) whose world positions
 * at a state come from the body class's own point kinematics — the same
 * code the joints use. Positions are 3-D; a view projects them onto one of
 * the coordinate planes (--view xy, the default, for planar scenes; xz or
 * yz for spatial ones), so a spatial body class draws without new code
 * here: its points and outline come from its class. */
#ifndef BRAUN_CLI_PLOT_H
#define BRAUN_CLI_PLOT_H

#include "braun_cli.h"

/* An anchor: a point of the scene (index), or a point of our own on a body
 * or the ground (a guide's end, a blade's tip). */
typedef struct plot_anchor {
    int scene_point;          /* >= 0: point index of the scene; -1: own */
    braun_scene_point own;    /* body (or BRAUN_SCENE_GROUND) and body-frame x, y */
} plot_anchor;

enum plot_item_kind {
    PLOT_OUTLINE, /* a rigid body's outline: polygon through anchors a .. a + count - 1 */
    PLOT_BAR,     /* a rigid body with two points, or a rod: a thick bar a-b */
    PLOT_LINK,    /* a distance joint: a thin line a-b */
    PLOT_MASS,    /* a particle with mass: a disc at a */
    PLOT_PIN,     /* a joint (revolute, a particle carried by rods): a ring at a */
    PLOT_GUIDE,   /* a slider's line: a dashed line a-b (long: not part of the extent) */
    PLOT_BLOCK,   /* a slider's block at a, along the guide b-c */
    PLOT_BLADE,   /* a knife edge: a short thick line a-b */
    PLOT_SPRING,  /* a spring or damper: a zigzag a-b */
    PLOT_ROTOR,   /* a motor, a torque or a driven angle: an arrowed arc about a */
    PLOT_GROUND   /* a ground point: a hatched mark under a */
};

typedef struct plot_item {
    int kind;          /* plot_item_kind */
    int a, b, c;       /* anchors */
    int count;         /* PLOT_OUTLINE: anchors a .. a + count - 1 */
    int fixed;         /* every anchor on the ground: drawn once, not per frame */
    /* PLOT_ROTOR: its sense at time t — the sign of *fn(t) (a torque), of
     * its rate (a drive: fn_rate), else of sense (a motor's stall
     * torque); counter-clockwise when positive (plot_item_sense). */
    const braun_scene_fn *fn;
    int fn_rate;
    double sense;
} plot_item;
/* +1 counter-clockwise, -1 clockwise, 0 none: a rotor's arrow at time t. */
int plot_item_sense(const plot_item *it, double t);

/* A traced point (--points): an anchor and its name. */
typedef struct plot_trace {
    int anchor;
    char name[96];
} plot_trace;

typedef struct plot_drawing {
    const braun_scene *scene;
    int nanchors, cap_anchors;
    plot_anchor *anchors;
    int nitems, cap_items;
    plot_item *items;
    int ntraces;
    plot_trace traces[16];
    int axis_u, axis_v;       /* the view: world axes shown across and up (0 x, 1 y, 2 z) */
    char view[4];             /* "xy" */
} plot_drawing;

/* The drawing of target t's scene (t->drawing must be set): 0, or an exit
 * status after one message. */
int plot_drawing_build(plot_drawing *dr, const braun_cli_target *t, const char *view);
void plot_drawing_free(plot_drawing *dr);
/* Add --points' references ("crank.A", "rod", "ground.O"): 0 or exit status. */
int plot_drawing_trace(plot_drawing *dr, const braun_cli_target *t, const char *list);
/* An anchor for one point reference, for --plot POINT.x: index, or -1
 * after one message. */
int plot_drawing_point(plot_drawing *dr, const braun_cli_target *t, const char *ref);
/* World positions (3 each) of every anchor at q (n doubles). */
void plot_drawing_eval(const plot_drawing *dr, const double *q, braun_real *qr, double *pos);
/* Each slider's guide long enough for the travel of the kept states. */
struct plot_samples;
int plot_drawing_fit_guides(plot_drawing *dr, const struct plot_samples *s);

/* The states a plot draws: rows of the trajectory CSV's columns (t, q, v,
 * pos_err, vel_err, energy_err, traj_err), kept evenly in time. */
typedef struct plot_samples {
    int n, cols;              /* coordinates; columns per row */
    long count, cap;
    double *rows;             /* count x cols */
    double from, to;          /* the time window kept */
    double next, step;        /* next time to keep, spacing */
    int have_last;            /* last: the latest state, kept at the end */
    int have_prev;            /* a state before last (its envelope values: last_ex) */
    double *last;
    /* Beside the grid over the window asked for, every state at least
     * fine_step apart, the spacing doubled (every other row dropped) when
     * cap are kept: a run that stops early is drawn from these (17 grid
     * rows of 80 274 states, a zig-zag across the picture, otherwise). */
    double *fine;
    long fine_count;
    double fine_step, fine_next;
    /* The envelope: nextra values of each state (extra(), set before
     * plot_samples_init, which keeps them), their least and greatest over
     * each kept row's bin — the states from it to the next kept row — so a
     * picture can tell where joining kept rows by straight lines would
     * show a motion that did not happen (a pendulum of period 2.37 s drawn
     * as one of 335 s from rows 2.35 s apart). Per row 2 * nextra doubles:
     * the lows, then the highs; env beside rows, fine_env beside fine.
     * paired: the values are (u, v) pairs of points, and each row also
     * has, per pair, the length the point travelled from it to the next
     * kept row (a chord of a monotone arc stays in the arc's box). */
    int nextra, paired;
    void (*extra)(void *ctx, const double *row, double *out);
    void *extra_ctx;
    double *env, *fine_env, *ex, *last_ex;
} plot_samples;

int plot_samples_init(plot_samples *s, int n, long cap, double from, double to);
void plot_samples_add(plot_samples *s, const double *row);
/* After the last state: keep the latest one too. */
void plot_samples_finish(plot_samples *s);
void plot_samples_free(plot_samples *s);
/* Row r's envelope: nextra lows, nextra highs, then (paired) nextra / 2
 * lengths travelled; NULL without one. */
const double *plot_samples_env(const plot_samples *s, long r);

/* --traj FILE: read a CSV written by `braun run --out` (its header must be
 * the target's columns) into s. 0, or an exit status after one message. */
int plot_traj_read(const char *path, const braun_cli_target *t, plot_samples *s);

/* What --plot asks for: columns of the rows or coordinates of points. */
typedef struct plot_series {
    int column;               /* >= 0: a column of the rows */
    int anchor, axis;         /* else: anchor's world coordinate axis (0 x, 1 y, 2 z) */
    char label[128];
    const char *unit;
} plot_series;

/* Everything the writers need. */
typedef struct plot_job {
    const braun_cli_target *target;
    const braun_cli_run_args *args;
    plot_drawing *drawing;    /* NULL for --plot */
    plot_samples *samples;
    int nseries;
    plot_series series[16];
    long frames;              /* configurations drawn */
    /* Series k (a chart) or trace k (paths) strays between kept rows from
     * the straight line joining them (plot_job_resolution): a chart shades
     * its envelope, a path is broken there and its rows drawn as dots. */
    int strays[16];
    /* A straying series' kept rows left off the chart's line, count ×
     * nseries (NULL: none): a row next to a segment that strays. Joined,
     * they drew a wave that did not happen (a pendulum's 2.37 s swings
     * kept every 2.35 s drew a 335 s swing, thin over the envelope). */
    unsigned char *hide;
    const char *caption;      /* one line under the picture */
} plot_job;

/* Writers: 0, or -1 after one message (cli_plot_svg.c, cli_plot_html.c,
 * cli_plot_gnuplot.c): a picture that could not be drawn. The stream's
 * own failure is braun_cli_output_close's to report (it flushes). */
int plot_write_svg(FILE *f, const plot_job *job);
int plot_write_html(FILE *f, const plot_job *job);
/* The PNG through gnuplot, into a temporary file checked to hold a PNG
 * (NULL after a message); then copied to the output (closes img). */
FILE *plot_render_png(const plot_job *job);
int plot_copy_png(FILE *img, FILE *out);

/* Shared by the writers (cli_plot_svg.c). */
typedef struct plot_canvas {
    double width, height, margin, bottom; /* px; bottom: room for the caption */
    double scale;                         /* px per metre */
    double u0, v0;                        /* world coordinates at the plot's lower left */
    double caption_width;                 /* px left of the scale bar for the caption */
    int caption_lines;                    /* lines it wraps to (bottom grows with them) */
} plot_canvas;
/* The caption wrapped to lines of at most width px at font px (an
 * estimate of sans-serif's widest letters): line k of them into out (NULL:
 * only count); a word longer than a line keeps its ends around "...".
 * Returns the number of lines. */
int plot_caption_wrap(const char *caption, double width, double font, int k, char *out,
                      size_t size);
/* The canvas fitting every frame's extent (guides and ground marks aside). */
void plot_canvas_fit(plot_canvas *cv, const plot_job *job);
/* Screen position of a world point. */
void plot_canvas_xy(const plot_canvas *cv, const plot_drawing *dr, const double *pos,
                    double *x, double *y);
/* The rows drawn as configurations: indices into the samples. */
long plot_frame_row(const plot_job *job, long k);
/* One configuration's items of a layer as SVG elements; pos:
 * plot_drawing_eval's output. */
enum {
    PLOT_LAYER_UNDER,       /* on the ground, drawn first: guides, springs to the ground */
    PLOT_LAYER_MOVING,      /* moving items but motors and torques */
    PLOT_LAYER_ALL_MOVING,  /* every moving item */
    PLOT_LAYER_MARKS        /* the ground marks, drawn last */
};
void plot_svg_items(FILE *f, const plot_job *job, const plot_canvas *cv, const double *pos,
                    double t, int layer, const char *indent);
/* XML text: &, <, >, " as entities, control bytes and backslashes as
 * braun_cli_put_text shows them (\xNN, \\). */
void plot_xml_text(FILE *f, const char *s);
/* The paths of the traced points (polylines), the time chart of --plot. */
void plot_svg_paths(FILE *f, const plot_job *job, const plot_canvas *cv, const char *style);
int plot_svg_chart(FILE *f, const plot_job *job, double width, double height, int inline_html);
/* The chart's values (range[0], range[1], at whole ticks) and times
 * (range[2], range[3]); pos, qr: scratch for the points' series (pos NULL
 * without a drawing). 0, or -1 when a span is beyond a double. */
int plot_chart_range(const plot_job *job, double *pos, braun_real *qr, double range[4]);
/* Whether every number the picture places is finite (cli_plot_fits.c):
 * 0, or BRAUN_CLI_USAGE after one message. */
int plot_job_fits(const plot_job *job);
/* <svg ...><title/><rect/> (inline_html: without the namespace attribute). */
void plot_svg_header(FILE *f, double width, double height, const char *title, int inline_html);
/* The caption line, the traced points' names, the scale bar. */
void plot_svg_caption(FILE *f, const plot_job *job, const plot_canvas *cv);
void plot_svg_scale_bar(FILE *f, const plot_canvas *cv);
/* Trace i's path from kept row r to r + 1, at world (u, v) a and b:
 * whether the point may have left that line by more than tol (m). */
int plot_path_strays(const plot_samples *s, int i, long r, const double *a, const double *b,
                     double tol);
/* ... by more than 3 px of the canvas (less is hardly seen). */
#define PLOT_PATH_TOL_PX 3.0
/* Chart ticks: a step of 1, 2 or 5 times a power of ten, about six over
 * lo ... hi; the %g digits (4 or more) that tell ticks first + i step, i =
 * 0 ... n, apart. */
double plot_tick_step(double lo, double hi);
int plot_tick_digits(double first, double step, long n);
/* Fills job->strays; the number of series or traces that stray. */
int plot_job_resolution(plot_job *job);
/* Colour of trace or series i. */
const char *plot_colour(int i);

#endif /* BRAUN_CLI_PLOT_H */
