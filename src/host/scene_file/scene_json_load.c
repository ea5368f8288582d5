/* Loading a scene file: read the text, let jansson parse it (duplicate
 * keys refused), read the scene, build it — and hand out nothing unless all
 * of it succeeded. Every message is one line "FILE:LINE:COLUMN: ...". */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_json_internal.h"

#define MAX_FILE_BYTES (64L << 20)

/* The file's text and jansson tree stay with the scene: names point into it. */
typedef struct sj_owned {
    braun_scene_file file;
    json_t *root;
    char *text;
} sj_owned;

void sj_push_key(sj_reader *r, const char *key)
{
    if (r->depth < SJ_MAX_DEPTH) r->path[r->depth] = (sj_seg){key, -1};
    r->depth++;
}

void sj_push_index(sj_reader *r, int index)
{
    if (r->depth < SJ_MAX_DEPTH) r->path[r->depth] = (sj_seg){NULL, index};
    r->depth++;
}

void sj_pop(sj_reader *r)
{
    if (r->depth > 0) r->depth--;
}

/* Messages are one line: control bytes a file smuggles in through a key
 * or a string (a "\n" escape) are shown as '?'. Found by fuzz_scene. */
static void one_line(char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f) *s = '?';
}

int sj_fail(sj_reader *r, int at, const char *fmt, ...)
{
    int line, col, len;
    const int depth = r->depth < SJ_MAX_DEPTH ? r->depth : SJ_MAX_DEPTH;
    sj_locate(r->text, r->len, r->path, depth, at, &line, &col);
    if (!r->err || r->err_size == 0) return -1;
    len = snprintf(r->err, r->err_size, "%s:%d:%d: ", r->file, line, col);
    if (len >= 0 && (size_t)len < r->err_size) {
        va_list ap;
        va_start(ap, fmt);
        /* NOLINTNEXTLINE(clang-analyzer-valist.Uninitialized): misfires over several files */
        vsnprintf(r->err + len, r->err_size - (size_t)len, fmt, ap);
        va_end(ap);
    }
    one_line(r->err);
    return -1;
}

static void set_err(char *err, size_t size, const char *file, int line, int col, const char *msg)
{
    if (err && size) {
        snprintf(err, size, "%s:%d:%d: %s", file, line, col, msg);
        one_line(err);
    }
}

void braun_scene_free(braun_scene_file *f)
{
    if (!f) return;
    sj_owned *o = (sj_owned *)(void *)f;
    braun_scene *s = &f->scene;
    free(s->bodies);
    free(s->points);
    free(s->rods);
    free(s->joints);
    free(s->effects);
    free(f->q0);
    free(f->v0);
    free((void *)f->body_names);
    free((void *)f->joint_names);
    free((void *)f->effect_names);
    if (o->root) json_decref(o->root);
    free(o->text);
    free(o);
}

/* Takes ownership of text (malloc'd, len bytes plus a NUL). */
static braun_scene_file *load_owned(const char *path, char *text, size_t len,
                                    const braun_scene_classes *extra, char *err, size_t err_size)
{
    size_t i = 0;
    while (i < len && strchr(" \t\r\n", text[i])) i++;
    if (i == len) {
        set_err(err, err_size, path, 1, 1, "empty file: expected a scene object");
        free(text);
        return NULL;
    }
    json_error_t jerr;
    json_t *root = json_loadb(text, len, JSON_REJECT_DUPLICATES, &jerr);
    if (!root) {
        /* jansson reports the position after the offending token and no
         * field: find the token's start and the path that leads to it. */
        char where[160], msg[512];
        size_t start = 0;
        int line = 1, col = 1;
        sj_context(text, len, jerr.position > 0 ? (size_t)jerr.position : 0, where, sizeof where,
                   &start);
        for (size_t k = 0; k < start; k++) {
            if (text[k] == '\n') line++, col = 1;
            else if (((unsigned char)text[k] & 0xC0) != 0x80) col++;
        }
        if (where[0]) snprintf(msg, sizeof msg, "at %.160s: %.300s", where, jerr.text);
        else snprintf(msg, sizeof msg, "%s", jerr.text);
        set_err(err, err_size, path, line, col, msg);
        free(text);
        return NULL;
    }
    sj_owned *o = calloc(1, sizeof *o);
    if (!o) {
        set_err(err, err_size, path, 1, 1, "out of memory");
        json_decref(root);
        free(text);
        return NULL;
    }
    o->root = root;
    o->text = text;
    o->file.path = path;
    sj_reader r;
    memset(&r, 0, sizeof r);
    r.file = path;
    r.text = text;
    r.len = len;
    r.err = err;
    r.err_size = err_size;
    r.out = &o->file;
    if (extra) r.extra = *extra;
    int st = sj_read_scene(&r, root);
    free(r.point_names);
    free((void *)r.rod_names);
    if (st) {
        braun_scene_free(&o->file);
        return NULL;
    }
    return &o->file;
}

braun_scene_file *braun_scene_load_text_ex(const char *path, const char *text, size_t len,
                                           const braun_scene_classes *extra, char *err,
                                           size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    if (!path || !text) {
        set_err(err, err_size, path ? path : "(null)", 1, 1, "no text");
        return NULL;
    }
    char *copy = malloc(len + 1);
    if (!copy) {
        set_err(err, err_size, path, 1, 1, "out of memory");
        return NULL;
    }
    memcpy(copy, text, len);
    copy[len] = '\0';
    return load_owned(path, copy, len, extra, err, err_size);
}

braun_scene_file *braun_scene_load_text(const char *path, const char *text, size_t len,
                                        char *err, size_t err_size)
{
    return braun_scene_load_text_ex(path, text, len, NULL, err, err_size);
}

braun_scene_file *braun_scene_load_ex(const char *path, const braun_scene_classes *extra,
                                      char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    if (!path) {
        set_err(err, err_size, "(null)", 1, 1, "no file name");
        return NULL;
    }
    FILE *f = fopen(path, "rb");
    if (!f) {
        if (err && err_size) snprintf(err, err_size, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    size_t cap = 4096, len = 0;
    char *text = malloc(cap + 1);
    while (text) {
        const size_t got = fread(text + len, 1, cap - len, f);
        len += got;
        if (len < cap) break;
        if ((long)cap >= MAX_FILE_BYTES) {
            free(text);
            text = NULL;
            fclose(f);
            if (err && err_size) snprintf(err, err_size, "%s: larger than 64 MiB", path);
            return NULL;
        }
        char *bigger = realloc(text, 2 * cap + 1);
        if (!bigger) free(text);
        text = bigger;
        cap *= 2;
    }
    const int bad = ferror(f);
    fclose(f);
    if (!text || bad) {
        free(text);
        if (err && err_size) snprintf(err, err_size, "%s: cannot read", path);
        return NULL;
    }
    text[len] = '\0';
    return load_owned(path, text, len, extra, err, err_size);
}

braun_scene_file *braun_scene_load(const char *path, char *err, size_t err_size)
{
    return braun_scene_load_ex(path, NULL, err, err_size);
}
