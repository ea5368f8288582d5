/*
 * Private to src/host/scene_file, the host-only scene file reader.
 *
 * jansson parses and validates the JSON text; its json_t values carry no
 * positions. To name FILE:LINE:COLUMN for an error found after parsing,
 * the reader keeps the JSON path of what it is reading (keys and array
 * indices) and, only when it reports an error, walks the already-validated
 * text along that path (scene_json_locate.c) to the key or the value.
 */
#ifndef BRAUN_SCENE_JSON_INTERNAL_H
#define BRAUN_SCENE_JSON_INTERNAL_H

#include <stddef.h>
#include <jansson.h>

#include "braun_models.h"
#include "braun_scene_file.h"

/* The reader's functions shared between its files have external linkage:
 * in the static library they are named braun__sj_* (a program's own
 * sj_fail would clash with them at link time; the shared library exports
 * braun_* only). */
#define sj_check_initial braun__sj_check_initial
#define sj_check_mass braun__sj_check_mass
#define sj_check_reference braun__sj_check_reference
#define sj_context braun__sj_context
#define sj_duplicate_joint braun__sj_duplicate_joint
#define sj_fail braun__sj_fail
#define sj_find_body braun__sj_find_body
#define sj_find_joint braun__sj_find_joint
#define sj_find_point braun__sj_find_point
#define sj_find_underflows braun__sj_find_underflows
#define sj_index_bodies braun__sj_index_bodies
#define sj_index_free braun__sj_index_free
#define sj_index_points braun__sj_index_points
#define sj_locate braun__sj_locate
#define sj_pop braun__sj_pop
#define sj_push_index braun__sj_push_index
#define sj_push_key braun__sj_push_key
#define sj_read_scene braun__sj_read_scene
#define sj_set_centre braun__sj_set_centre
#define sj_underflow_of braun__sj_underflow_of

#define SJ_MAX_DEPTH 8

/* One step of a JSON path: an object key, or an array index (key NULL). */
typedef struct sj_seg {
    const char *key;
    int index;
} sj_seg;

/* Where in the text an error points: the key of the path's last step, or
 * the start of its value. */
enum { SJ_AT_VALUE = 0, SJ_AT_KEY = 1 };

/* Line and column (1-based, column in characters) of the path's value or
 * key in a text jansson has accepted; 1:1 when the path is not found. */
void sj_locate(const char *text, size_t len, const sj_seg *path, int depth, int at, int *line,
               int *column);

/* The JSON path ("bodies[0].mass") leading to byte offset pos of a text
 * that is valid up to pos, and the offset where the last token before pos
 * starts: the field and position of a syntax error. */
void sj_context(const char *text, size_t len, size_t pos, char *path, size_t size,
                size_t *token_start);

/* A name and what it names, for the sorted indexes (scene_json_index.c). */
typedef struct sj_name {
    const char *s;
    size_t len;
    int index;
} sj_name;

/* A real of the text that underflows (scene_json_underflow.c): jansson's
 * value for it and its token. */
typedef struct sj_underflow {
    const json_t *value;
    const char *text;
    size_t len;
} sj_underflow;

/* The reader's state: the text, the path being read, the scene being
 * filled, and the first error. */
typedef struct sj_reader {
    const char *file;
    const char *text;
    size_t len;
    char *err;
    size_t err_size;
    sj_seg path[SJ_MAX_DEPTH];
    int depth;
    braun_scene_file *out;
    /* Point table under construction. */
    int npoints, cap_points;
    const char **point_names;   /* name within its body ("" for implicit ones) */
    const char **rod_names;
    /* Indexes (scene_json_index.c): bodies by name; per body slot (0 the
     * ground, k + 1 body k) its centre point and the range of its named
     * points in point_sorted, sorted by name there. */
    sj_name *body_index, *point_sorted;
    int nbody_index, nslots;
    int *centre, *pt_first, *pt_count;
    /* Joints by name (sj_find_joint), built on first use. */
    sj_name *joint_index;
    int njoint_index;
    /* The scene's dimension (2 planar, 3 spatial), from its bodies' types
     * before anything is read: the length of ground points and vectors. */
    int dim;
    /* The program's own classes, besides the built-in ones (lists NULL or
     * NULL-terminated). */
    braun_scene_classes extra;
    /* The element being read, for messages: "body 'crank'", "joint #3". */
    char who[160];
    /* The reals that underflow, sorted by value (sj_find_underflows). */
    sj_underflow *underflows;
    int nunderflows;
} sj_reader;

/* Format "FILE:LINE:COL: message" at the current path; returns -1. */
int sj_fail(sj_reader *r, int at, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

void sj_push_key(sj_reader *r, const char *key);
void sj_push_index(sj_reader *r, int index);
void sj_pop(sj_reader *r);

/* Name lookups in O(log n) (scene_json_index.c). sj_index_bodies sorts the
 * names of the bodies array before any is read (-1: out of memory);
 * sj_find_body finds a body already read (-2 if none); sj_index_points
 * indexes the named points body (or the ground) got from point `first` up
 * to the last one added; sj_find_point finds a named point of a body, or
 * with name "" its centre (sj_set_centre), -1 if none. */
int sj_index_bodies(sj_reader *r, json_t *bodies);
int sj_find_body(const sj_reader *r, const char *name, size_t len);
void sj_index_points(sj_reader *r, int body, int first);
int sj_find_point(const sj_reader *r, int body, const char *name);
void sj_set_centre(sj_reader *r, int body, int point);
/* The first joint named name (joints read so far), -1 if none, -2 out of
 * memory. */
int sj_find_joint(sj_reader *r, const char *name);
/* Two joints of one name (effects refer to joints by name, messages name
 * them): 1 with the later one's index and the first's, 0 if none, -2 out
 * of memory. After every joint is read. */
int sj_duplicate_joint(sj_reader *r, int *later, int *first);
void sj_index_free(sj_reader *r);

/* After the build (scene_json_check.c): the mass matrix's pivots, and
 * every joint and effect evaluated at the initial state (q0, v0 set);
 * 0, or -1 after a message at the element. */
int sj_check_mass(sj_reader *r);
int sj_check_initial(sj_reader *r);
/* The scene's motion is the reference model's (its "reference" field):
 * the same initial state and the same ideal acceleration along the
 * reference's motion; 0, or -1 after a message at "reference". */
int sj_check_reference(sj_reader *r, const braun_builtin *b);

/* List the reals of the text whose token is not 0 but whose value is
 * below BRAUN_SCENE_MIN_NORMAL (jansson reads "1e-400" as 0 and "1e-310"
 * as a subnormal without an error) into r->underflows: 0, or -1 out of
 * memory. sj_underflow_of: the entry of value v, or NULL. */
int sj_find_underflows(sj_reader *r, json_t *root);
const sj_underflow *sj_underflow_of(const sj_reader *r, const json_t *v);

/* Read every element of the root object into r->out (scene_json_read.c). */
int sj_read_scene(sj_reader *r, json_t *root);

/* Walking a JSON text jansson has accepted (scene_json_locate.c,
 * scene_json_underflow.c): past white space, and past a string from its
 * opening quote (escapes included). */
static inline const char *sj_skip_ws(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')) p++;
    return p;
}

static inline const char *sj_skip_string(const char *p, const char *end)
{
    p++;
    while (p < end && *p != '"') p += *p == '\\' ? 2 : 1;
    return p < end ? p + 1 : p;
}

#endif
