/* Loading a scene file: read the text, let jansson parse it (duplicate
 * keys refused), read the scene, build it — and hand out nothing unless all
 * of it succeeded. Every message is one line "FILE:LINE:COLUMN: ...". */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* open, fstat, read: the file is checked without blocking */
#endif
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene_json_internal.h"
#include "braun_c_locale.h"

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
        braun__c_vsnprintf(r->err + len, r->err_size - (size_t)len, fmt, ap);
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
    free(s->q_scale);
    free(f->q0);
    free(f->v0);
    free((void *)f->body_names);
    free((void *)f->joint_names);
    free((void *)f->effect_names);
    free((void *)f->report_names);
    free(f->report_points);
    if (o->root) json_decref(o->root);
    free(o->text);
    free(o);
}

/* Takes ownership of text (malloc'd, len bytes plus a NUL). */
/* A program's class without a name could never be a file's "type" (and
 * the lookup compared it as a string: a crash). 1 with the message. */
#define UNNAMED(field, what)                                                                 \
    for (int k = 0; extra->field && extra->field[k]; k++)                                    \
        if (!extra->field[k]->name || !extra->field[k]->name[0]) {                           \
            snprintf(msg, size, "program %s class %d (braun_scene_classes." #field "[%d]) has " \
                                "no name: a file names its class by it (\"type\")", what, k + 1, \
                     k);                                                                     \
            return 1;                                                                        \
        }
static int unnamed_class(const braun_scene_classes *extra, char *msg, size_t size)
{
    UNNAMED(bodies, "body")
    UNNAMED(joints, "joint")
    UNNAMED(effects, "effect")
    return 0;
}
#undef UNNAMED

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
    char bad[160];
    int st = -1;
    if (extra && unnamed_class(extra, bad, sizeof bad)) set_err(err, err_size, path, 1, 1, bad);
    else if (sj_find_underflows(&r, root)) set_err(err, err_size, path, 1, 1, "out of memory");
    else st = sj_read_scene(&r, root);
    free(r.underflows);
    free(r.point_names);
    sj_index_free(&r);
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
    /* Without a path the messages name the text "(text)". */
    if (!path) path = "(text)";
    if (!text) {
        set_err(err, err_size, path, 1, 1, "no text (NULL)");
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

static const char *file_kind(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISFIFO(m) ? "a FIFO" : S_ISCHR(m) ? "a character device"
           : S_ISBLK(m) ? "a block device" : S_ISSOCK(m) ? "a socket" : "not a regular file";
}

/* The whole of a regular file, NUL-terminated, into *text (malloc'd).
 * Opened with O_NONBLOCK so that a FIFO, a terminal or a device never
 * blocks the open; the descriptor itself is then checked with fstat (no
 * window between a check and the read) and anything but a regular file is
 * refused. 0, or -1 with one line in err. */
static int read_regular(const char *path, char **text, size_t *len, char *err, size_t size)
{
    *text = NULL;
    *len = 0;
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    struct stat st;
    if (fd < 0) {
        const int e = errno;
        /* A socket (or a device without a driver) fails the open itself
         * (ENXIO): named by its kind, as the descriptor's check names it. */
        if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
            if (err && size) snprintf(err, size, "%s: is %s, not a scene file (a regular file)", path,
                                      file_kind(st.st_mode));
        } else if (err && size) {
            snprintf(err, size, "%s: cannot open: %s", path, strerror(e));
        }
        return -1;
    }
    if (fstat(fd, &st) != 0) {
        if (err && size) snprintf(err, size, "%s: cannot open: %s", path, strerror(errno));
        close(fd);
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        if (err && size) snprintf(err, size, "%s: is %s, not a scene file (a regular file)", path,
                                  file_kind(st.st_mode));
        close(fd);
        return -1;
    }
    if (st.st_size > MAX_FILE_BYTES) {
        if (err && size) snprintf(err, size, "%s: larger than 64 MiB", path);
        close(fd);
        return -1;
    }
    /* A regular file never blocks; read until EOF (it may have grown). */
    size_t cap = (size_t)st.st_size + 1, used = 0;
    char *buf = malloc(cap + 1);
    for (;;) {
        if (!buf) {
            if (err && size) snprintf(err, size, "%s: out of memory", path);
            close(fd);
            return -1;
        }
        if (used == cap) {
            if (cap >= (size_t)MAX_FILE_BYTES) {
                if (err && size) snprintf(err, size, "%s: larger than 64 MiB", path);
                free(buf);
                close(fd);
                return -1;
            }
            char *bigger = realloc(buf, 2 * cap + 1);
            if (!bigger) free(buf);
            buf = bigger;
            cap *= 2;
            continue;
        }
        const ssize_t got = read(fd, buf + used, cap - used);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            if (err && size) snprintf(err, size, "%s: cannot read: %s", path, strerror(errno));
            free(buf);
            close(fd);
            return -1;
        }
        if (got == 0) break;
        used += (size_t)got;
    }
    close(fd);
    buf[used] = '\0';
    *text = buf;
    *len = used;
    return 0;
}

braun_scene_file *braun_scene_load_ex(const char *path, const braun_scene_classes *extra,
                                      char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    if (!path) {
        set_err(err, err_size, "(no path)", 1, 1, "no file name (NULL path)");
        return NULL;
    }
    char *text;
    size_t len;
    if (read_regular(path, &text, &len, err, err_size)) {
        if (err && err_size) one_line(err);
        return NULL;
    }
    return load_owned(path, text, len, extra, err, err_size);
}

braun_scene_file *braun_scene_load(const char *path, char *err, size_t err_size)
{
    return braun_scene_load_ex(path, NULL, err, err_size);
}
