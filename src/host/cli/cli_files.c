/* The files the tool writes (--out, --summary, gen -o, gen-c -o, plot -o).
 * An output is "-" (stdout), a regular file or a character device such as
 * /dev/null; a FIFO, socket, directory or block device is refused without
 * blocking: the file is opened with O_NONBLOCK (a FIFO without a reader
 * fails at once instead of waiting for one) and checked with fstat on the
 * descriptor itself, so nothing can be swapped in between the check and the
 * writing. A regular file is truncated only after every check, and two
 * outputs of one command, or an output and the command's input, must not
 * be one file (the input would be destroyed before it was read, or two
 * streams would interleave). An output written whole (gen, gen-c, plot:
 * braun_cli_output_open_whole) goes to a temporary file beside it, renamed
 * onto it only once complete: a failed write leaves the file as it was.
 * The POSIX feature macros are confined to this file and cli_clock.c. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#ifndef _XOPEN_SOURCE
#define _XOPEN_SOURCE 700 /* realpath */
#endif
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "braun_cli.h"

static void set_id(braun_cli_id *id, const struct stat *st)
{
    id->valid = S_ISREG(st->st_mode);
    id->dev = (unsigned long long)st->st_dev;
    id->ino = (unsigned long long)st->st_ino;
}

void braun_cli_path_id(const char *path, braun_cli_id *id)
{
    struct stat st;
    memset(id, 0, sizeof *id);
    if (path && stat(path, &st) == 0) set_id(id, &st);
}

int braun_cli_same_file(const braun_cli_id *a, const braun_cli_id *b)
{
    return a->valid && b->valid && a->dev == b->dev && a->ino == b->ino;
}

const char *braun_cli_file_kind(unsigned long mode)
{
    const mode_t m = (mode_t)mode;
    if (S_ISDIR(m)) return "a directory";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISSOCK(m)) return "a socket";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISLNK(m)) return "a symbolic link";
    return "not a regular file";
}

int braun_cli_output_open(braun_cli_output *o, const char *path, const char *what)
{
    struct stat st;
    memset(o, 0, sizeof *o);
    o->path = path;
    o->what = what;
    if (strcmp(path, "-") == 0) {
        o->f = stdout;
        if (fstat(STDOUT_FILENO, &st) == 0) set_id(&o->id, &st);
        return 0;
    }
    const int flags = O_WRONLY | O_NOCTTY | O_NONBLOCK;
    int fd = open(path, flags | O_CREAT | O_EXCL, 0666);
    if (fd >= 0) o->created = 1;
    else if (errno == EEXIST) fd = open(path, flags);
    if (fd < 0) {
        const int e = errno;
        /* What is there, named by its kind: open fails with ENXIO on a FIFO
         * that nobody reads and on a socket alike, EISDIR on a directory. */
        if (stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISCHR(st.st_mode))
            return braun_cli_error("%s '%s' is %s (not a regular file): refused", what, path,
                                   braun_cli_file_kind((unsigned long)st.st_mode));
        return braun_cli_error("%s: cannot open '%s' for writing: %s", what, path, strerror(e));
    }
    if (fstat(fd, &st) != 0) {
        const int e = errno;
        close(fd);
        return braun_cli_error("%s: cannot open '%s' for writing: %s", what, path, strerror(e));
    }
    if (!S_ISREG(st.st_mode) && !S_ISCHR(st.st_mode)) {
        close(fd);
        return braun_cli_error("%s '%s' is %s (not a regular file): refused", what, path,
                               braun_cli_file_kind((unsigned long)st.st_mode));
    }
    set_id(&o->id, &st);
    /* Blocking writes from here on: a full disk is an error, not EAGAIN. */
    const int fl = fcntl(fd, F_GETFL);
    if (fl == -1 || fcntl(fd, F_SETFL, fl & ~O_NONBLOCK) == -1 || !(o->f = fdopen(fd, "w"))) {
        const int e = errno;
        close(fd);
        if (o->created) unlink(path);
        return braun_cli_error("%s: cannot open '%s' for writing: %s", what, path, strerror(e));
    }
    return 0;
}

int braun_cli_output_open_whole(braun_cli_output *o, const char *path, const char *what)
{
    const int rc = braun_cli_output_open(o, path, what);
    o->whole = !rc && o->f != stdout && o->id.valid;
    return rc;
}

int braun_cli_output_distinct(braun_cli_output *a, braun_cli_output *b, const braun_cli_id *input,
                              const char *input_path)
{
    braun_cli_output *outs[2] = {a, b};
    for (int i = 0; i < 2; i++)
        if (outs[i] && outs[i]->f && input && braun_cli_same_file(&outs[i]->id, input))
            return braun_cli_error("%s '%s' is the input '%s': refused (it would be "
                                   "overwritten)", outs[i]->what, outs[i]->path, input_path);
    if (a && b && a->f && b->f && braun_cli_same_file(&a->id, &b->id))
        return braun_cli_error("%s '%s' and %s '%s' are the same file: give two files",
                               a->what, a->path, b->what, b->path);
    return 0;
}

/* A temporary file beside the output (its symbolic link followed: the link
 * stays a link), with the output's permissions: o->f writes it and
 * o->tmp, o->final name it. 0; -1 with errno when none can be made. */
static int make_temporary(braun_cli_output *o)
{
    struct stat st, lst;
    char *final = NULL;
    if (lstat(o->path, &lst) == 0 && S_ISLNK(lst.st_mode)) final = realpath(o->path, NULL);
    else final = strdup(o->path);
    if (!final || fstat(fileno(o->f), &st) != 0) {
        free(final);
        return -1;
    }
    const char *slash = strrchr(final, '/');
    const size_t dir = slash ? (size_t)(slash - final) + 1 : 0;
    const char *base = final + dir;
    /* ".NAME.XXXXXX", hidden and named after its output; a long name as
     * ".braun.XXXXXX" (within NAME_MAX). */
    const int short_base = strlen(base) <= 200;
    const size_t size = dir + (short_base ? strlen(base) : 5) + 10;
    char *tmp = malloc(size);
    if (!tmp) {
        free(final);
        return -1;
    }
    snprintf(tmp, size, "%.*s.%s.XXXXXX", (int)dir, final, short_base ? base : "braun");
    const int fd = mkstemp(tmp);
    FILE *f = NULL;
    if (fd < 0 || fchmod(fd, st.st_mode & 0777) != 0 || !(f = fdopen(fd, "w"))) {
        const int e = errno;
        if (fd >= 0) {
            close(fd);
            unlink(tmp);
        }
        free(tmp);
        free(final);
        errno = e;
        return -1;
    }
    fclose(o->f); /* the output itself, untouched */
    o->f = f;
    o->tmp = tmp;
    o->final = final;
    return 0;
}

int braun_cli_output_begin(braun_cli_output *o)
{
    if (!o->f || o->f == stdout || !o->id.valid) return 0;
    if (o->whole) {
        if (make_temporary(o) == 0) return 0;
        /* A directory that takes no new file (a writable file in a
         * directory that is not): written in place, as run's outputs. */
        if (errno != EACCES && errno != EPERM) {
            const int e = errno;
            braun_cli_error("%s: cannot make a temporary file beside '%s': %s", o->what, o->path,
                            strerror(e));
            return BRAUN_CLI_FAILED;
        }
        o->whole = 0;
    }
    if (ftruncate(fileno(o->f), 0) != 0)
        return braun_cli_error("%s: cannot truncate '%s': %s", o->what, o->path, strerror(errno));
    return 0;
}

void braun_cli_output_failed(braun_cli_output *o)
{
    if (!o->err) o->err = errno;
}

static void say_write_error(const braun_cli_output *o, int e)
{
    braun_cli_error("error writing '%s'%s%s", strcmp(o->path, "-") == 0 ? "stdout" : o->path,
                    e ? ": " : "", e ? strerror(e) : "");
}

int braun_cli_output_complete(braun_cli_output *o)
{
    if (!o->f) return 0;
    errno = 0;
    int bad = ferror(o->f) != 0;
    if (fflush(o->f) != 0) bad = 1;
    int e = o->err ? o->err : errno;
    if (o->f != stdout && fclose(o->f) != 0) {
        if (!bad) e = errno;
        bad = 1;
    }
    /* Reported here: main's last check of stdout must not say it again. */
    if (o->f == stdout) clearerr(stdout);
    o->f = NULL;
    if (bad) say_write_error(o, e);
    return bad;
}

int braun_cli_output_commit(braun_cli_output *o)
{
    int bad = 0;
    if (o->tmp && rename(o->tmp, o->final) != 0) {
        const int e = errno;
        unlink(o->tmp);
        if (o->created) unlink(o->path);
        braun_cli_error("%s: cannot put the written file in place of '%s': %s", o->what, o->path,
                        strerror(e));
        bad = 1;
    }
    free(o->tmp);
    free(o->final);
    o->tmp = o->final = NULL;
    o->committed = 1;
    return bad;
}

int braun_cli_output_close(braun_cli_output *o)
{
    if (!o->f && !o->tmp) return 0;
    if (braun_cli_output_complete(o)) {
        /* Written whole: the file stays as it was. In place (run's
         * outputs): kept up to the failed write. */
        if (o->tmp) braun_cli_output_abandon(o);
        else o->committed = 1;
        return 1;
    }
    return braun_cli_output_commit(o);
}

void braun_cli_output_abandon(braun_cli_output *o)
{
    if (o->f && o->f != stdout) fclose(o->f);
    o->f = NULL;
    if (o->tmp) unlink(o->tmp);
    free(o->tmp);
    free(o->final);
    o->tmp = o->final = NULL;
    if (o->created && !o->committed && strcmp(o->path, "-") != 0) unlink(o->path);
    o->created = 0;
}

/* An input of the tool beside the scene loader's own (a scene's text again
 * for its point names, a --traj CSV): a regular file of at most max bytes,
 * opened without blocking and checked on the descriptor. */
char *braun_cli_read_file(const char *path, size_t max, size_t *len, char *err, size_t size)
{
    struct stat st;
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) {
        const int e = errno;
        /* A socket fails the open itself (ENXIO): named, as below. */
        if (stat(path, &st) == 0 && !S_ISREG(st.st_mode))
            snprintf(err, size, "%s: is %s, not a regular file", path,
                     braun_cli_file_kind((unsigned long)st.st_mode));
        else
            snprintf(err, size, "%s: cannot open: %s", path, strerror(e));
        return NULL;
    }
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        snprintf(err, size, "%s: is %s, not a regular file", path,
                 fstat(fd, &st) == 0 ? braun_cli_file_kind((unsigned long)st.st_mode)
                                     : "unreadable");
        close(fd);
        return NULL;
    }
    if ((unsigned long long)st.st_size > (unsigned long long)max) {
        snprintf(err, size, "%s: larger than %zu bytes", path, max);
        close(fd);
        return NULL;
    }
    char *text = malloc((size_t)st.st_size + 1);
    size_t got = 0;
    if (!text) {
        snprintf(err, size, "%s: out of memory", path);
        close(fd);
        return NULL;
    }
    while (got < (size_t)st.st_size) {
        const ssize_t k = read(fd, text + got, (size_t)st.st_size - got);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) break;
        got += (size_t)k;
    }
    close(fd);
    text[got] = '\0';
    *len = got;
    return text;
}
