/*
 * libbraun scene files and scene-to-C (host tier: libbraun_host.a, links
 * jansson; uses stdio and the allocator). The scenes themselves, their
 * builder and their callbacks are core tier: braun_scene.h.
 */
#ifndef BRAUN_SCENE_FILE_H
#define BRAUN_SCENE_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "braun_scene.h"

/* The float build's link names: every public function and object of
 * this header carries the precision (braun.h, "link names"). */
#ifdef BRAUN_SINGLE
#define braun_gen_c_check_symbol braun_gen_c_check_symbol_float
#define braun_gen_c_write braun_gen_c_write_float
#define braun_gen_c_write_ex braun_gen_c_write_ex_float
#define braun_gen_c_write_header braun_gen_c_write_header_float
#define braun_scene_file_diagnose braun_scene_file_diagnose_float
#define braun_scene_free braun_scene_free_float
#define braun_scene_load braun_scene_load_float
#define braun_scene_load_ex braun_scene_load_ex_float
#define braun_scene_load_text braun_scene_load_text_float
#define braun_scene_load_text_ex braun_scene_load_text_ex_float
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Numbers a scene file may hold besides |x| <= BRAUN_SCENE_MAX_ABS
 * (docs/scene-format.md, "Limits"): nonzero numbers at least the smallest
 * normal braun_real; parameters with a domain (> 0, >= 0, != 0: masses,
 * inertias, lengths, axes, stiffnesses, speeds), when not 0, at least
 * BRAUN_SCENE_MIN_SCALE in magnitude (a vector in length): their squares
 * are then normal numbers. */
#ifdef BRAUN_SINGLE
#define BRAUN_SCENE_MIN_NORMAL 1.1754943508222875e-38 /* FLT_MIN */
#define BRAUN_SCENE_MIN_SCALE 1e-18
#else
#define BRAUN_SCENE_MIN_NORMAL 2.2250738585072014e-308 /* DBL_MIN */
#define BRAUN_SCENE_MIN_SCALE 1e-150
#endif

/* A scene read from a JSON file (docs/scene-format.md) with everything
 * the file says beyond the mechanism. */
typedef struct braun_scene_file {
    braun_scene scene;        /* built: sizes and rows are set */
    braun_system sys;         /* its callbacks; sys.user = &scene */
    const char *path;         /* as given to braun_scene_load */
    const char *name;         /* "name" of the file */
    const char *description;  /* "description", "" if none */
    unsigned corrections;     /* braun_corrections the file asks for */
    const char *reference;    /* "reference": built-in model name, or NULL */
    braun_real *q0, *v0;      /* initial state, n entries each */
    /* Names of the elements, for messages (same order as the arrays; NULL
     * for an element without "name"). Knife edges are joints. */
    const char **body_names, **joint_names, **effect_names;
    /* Reported points ("report", docs/scene-format.md): nreports names
     * and the scene's point each names (braun_scene_point_state gives its
     * position and velocity at a state). */
    int nreports;
    const char **report_names;
    int *report_points;
} braun_scene_file;

/* Classes a program adds to the built-in ones (braun_scene.h) for the
 * reader: each list NULL-terminated, or NULL for none. A file's "type" is
 * looked up among the built-in classes first, then these; the fields of a
 * class's descriptors are read as for any built-in type, and its defaults
 * hook fills what the file leaves out. The classes must outlive the
 * loaded scene. */
typedef struct braun_scene_classes {
    const braun_scene_body_class *const *bodies;
    const braun_scene_joint_class *const *joints;
    const braun_scene_effect_class *const *effects;
} braun_scene_classes;

/* Read, validate and build a scene file. On failure returns NULL and writes
 * one line "FILE:LINE:COLUMN: message" (no newline) into err; nothing is
 * returned from a half-read file. */
braun_scene_file *braun_scene_load(const char *path, char *err, size_t err_size);

/* The same from text in memory; path names it in messages ("(text)" when
 * NULL). */
braun_scene_file *braun_scene_load_text(const char *path, const char *text, size_t len,
                                        char *err, size_t err_size);

/* braun_scene_load and braun_scene_load_text with the program's own
 * classes besides the built-in ones (extra may be NULL). */
braun_scene_file *braun_scene_load_ex(const char *path, const braun_scene_classes *extra,
                                      char *err, size_t err_size);
braun_scene_file *braun_scene_load_text_ex(const char *path, const char *text, size_t len,
                                           const braun_scene_classes *extra, char *err,
                                           size_t err_size);

void braun_scene_free(braun_scene_file *f);

/* Which element makes the scene's callbacks fail at (t, q, v): evaluates
 * every joint's rows and every effect's forces, potential and power there,
 * in file order, and describes the first that fails (returns non-zero, or
 * gives a non-finite value) in msg, one line: "effect 'sp' (spring): its
 * forces return 1 at t = 0.5, where its points 'a' and 'b' coincide".
 * Returns 1 if one failed, 0 if none does, -1 out of memory or sf or q
 * NULL. v may be NULL.
 * For messages after a callback failed (the core's error record names the
 * callback, not the element); the loader makes the same check at the
 * initial state, so a scene that loads evaluates there. */
int braun_scene_file_diagnose(const braun_scene_file *sf, braun_real t, const braun_real *q,
                              const braun_real *v, char *msg, size_t size);

/* Scene to C (`braun gen-c`): write a C99 source that defines a
 * scene statically — its element arrays as initialised data and a function
 * that builds the braun_system at start-up with braun_scene_build() — so
 * that firmware runs a scene with no parser, no file and no allocation.
 * Host only (stdio); the output compiles in double and in float
 * (BRAUN_SINGLE): numbers are written as the exact double the host read,
 * cast to braun_real, which is what the host's own float build does.
 *
 * The generated file defines, for SYMBOL (SYMBOL_N etc. in upper case; the
 * declarations also in a header: braun_gen_c_write_header):
 *   #define SYMBOL_N, SYMBOL_M, SYMBOL_P        sizes (for static buffers and
 *                                               BRAUN_FIXED_N/ROWS builds)
 *   extern const unsigned SYMBOL_corrections;   what the scene file asks for
 *   int SYMBOL_build(braun_system *sys, braun_real *q0, braun_real *v0);
 *       braun_scene_build() on the static arrays, then the initial state
 *       (SYMBOL_N entries each; either may be NULL, the other is still
 *       written); returns braun_scene_build's status, then
 *       braun_scene_initial_state's.
 * Each element is written with its class's c_name; a class of the program
 * (c_name "&symbol") is declared extern in the file, and the program links
 * its definition. Returns -1 for an element whose class has no c_name.
 */
/* Everything gen-c writes from the scene file — names, the description,
 * the source path — goes into comments as printable ASCII that cannot end
 * or nest a comment, form a trigraph or splice a line (other bytes as
 * \xNN, UTF-8 as \uXXXX; "*\/", "/\*", "?\?"; at most 160 bytes of each
 * text, then "..."). The only identifiers it writes are the symbol's
 * (checked here) and the classes' c_names, checked before anything is
 * written: a C identifier, not a keyword, or "&identifier"; none of the
 * names the file itself defines or uses — SYMBOL_build, SYMBOL_scene,
 * SYMBOL_corrections, SYMBOL_bodies/_points/_rods/_joints/_effects,
 * SYMBOL_N/_M/_P, BRAUN_GEN_SYMBOL_H, R, RD, SYMBOL_build's sys, q0, v0,
 * st and unused, <stddef.h>'s NULL, offsetof, size_t, ptrdiff_t, wchar_t
 * and max_align_t; for "&identifier" (the program's class, declared by the
 * file) also not libbraun's (braun_..., BRAUN_...) nor starting with '_',
 * and one class per name. The error names the element, the class and
 * the clash. It writes no string literals. */
#define BRAUN_GEN_C_SYMBOL_MAX 48 /* + "_corrections": within C99's 63 */
#define BRAUN_GEN_C_SYMBOL_MAX_STR "48"

/* 0 if symbol can prefix the generated names: an ASCII C identifier of at
 * most BRAUN_GEN_C_SYMBOL_MAX characters, not 'braun' and not starting
 * with '_' or 'braun_' (any case). Else -1 and why ("the symbol must ...")
 * in why. */
int braun_gen_c_check_symbol(const char *symbol, char *why, size_t size);

/* braun_gen_c_write_ex's failures. */
enum {
    BRAUN_GEN_C_INVALID = -1, /* the symbol or a class's c_name; nothing written */
    BRAUN_GEN_C_WRITE = -2    /* the stream failed (errno from the stream) */
};

/* Write the C source of a loaded scene. symbol: a C identifier prefix;
 * source: the file it came from (for the header comment). Returns 0, or -1
 * if the symbol or a class cannot be written or writing failed. */
int braun_gen_c_write(FILE *out, const braun_scene_file *sf, const char *symbol,
                      const char *source);

/* The same with the reason of a failure in err (one line): 0,
 * BRAUN_GEN_C_INVALID (nothing was written) or BRAUN_GEN_C_WRITE (also
 * out of memory, before anything is written). The writers flush out
 * before they return: 0 means every byte reached the file, not only
 * stdio's buffer; closing it is the caller's. */
int braun_gen_c_write_ex(FILE *out, const braun_scene_file *sf, const char *symbol,
                         const char *source, char *err, size_t err_size);

/* The header for the source above (`braun gen-c --header FILE`): an
 * include guard BRAUN_GEN_SYMBOL_H, braun.h, SYMBOL_N/M/P, the declarations
 * of SYMBOL_corrections and SYMBOL_build — what the program's other files
 * need. Comments written as the source's; the same returns as
 * braun_gen_c_write_ex (BRAUN_GEN_C_INVALID for a bad symbol). */
int braun_gen_c_write_header(FILE *out, const braun_scene_file *sf, const char *symbol,
                             const char *source, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif
#endif /* BRAUN_SCENE_FILE_H */
