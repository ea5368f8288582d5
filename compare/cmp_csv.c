/* A small reader for the harness's own CSV files: a header line, then rows
 * of fields without quotes or embedded separators (cmp_study.c writes
 * them so). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmp_csv.h"

static char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap + 1);
    while (buf) {
        size_t got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (n < cap) break;
        char *nb = realloc(buf, 2 * cap + 1);
        if (!nb) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = nb;
        cap *= 2;
    }
    fclose(f);
    if (buf) {
        buf[n] = '\0';
        *len = n;
    }
    return buf;
}

/* Split s in place on sep; fields[] points into s. Returns the count. */
static int split(char *s, char sep, char **fields, int max)
{
    int n = 0;
    fields[n++] = s;
    for (char *p = s; *p; p++)
        if (*p == sep) {
            *p = '\0';
            if (n == max) return -1;
            fields[n++] = p + 1;
        }
    return n;
}

int cmp_csv_read(const char *path, cmp_csv *t)
{
    memset(t, 0, sizeof *t);
    size_t len;
    t->text = read_all(path, &len);
    if (!t->text) return -1;
    /* Lines. */
    long lines = 0;
    for (size_t i = 0; i < len; i++) lines += t->text[i] == '\n';
    char **line = malloc((size_t)(lines + 2) * sizeof *line);
    if (!line) return -1;
    long nl = 0;
    char *p = t->text;
    while (*p) {
        char *e = strchr(p, '\n');
        if (e) *e = '\0';
        if (*p) line[nl++] = p;
        if (!e) break;
        p = e + 1;
    }
    if (nl == 0) {
        free(line);
        return -1;
    }
    char *hdr[CMP_CSV_MAX_COLS];
    t->ncols = split(line[0], ',', hdr, CMP_CSV_MAX_COLS);
    if (t->ncols < 1) {
        free(line);
        return -1;
    }
    for (int c = 0; c < t->ncols; c++) t->header[c] = hdr[c];
    t->cells = malloc((size_t)(nl > 1 ? nl - 1 : 1) * (size_t)t->ncols * sizeof(char *));
    if (!t->cells) {
        free(line);
        return -1;
    }
    t->nrows = 0;
    for (long r = 1; r < nl; r++) {
        char *f[CMP_CSV_MAX_COLS];
        int n = split(line[r], ',', f, CMP_CSV_MAX_COLS);
        if (n != t->ncols) {
            t->bad_rows++;
            continue;
        }
        for (int c = 0; c < n; c++) t->cells[(size_t)t->nrows * t->ncols + c] = f[c];
        t->nrows++;
    }
    free(line);
    return 0;
}

void cmp_csv_free(cmp_csv *t)
{
    free(t->text);
    free(t->cells);
    memset(t, 0, sizeof *t);
}

int cmp_csv_col(const cmp_csv *t, const char *name)
{
    for (int c = 0; c < t->ncols; c++)
        if (strcmp(t->header[c], name) == 0) return c;
    return -1;
}

const char *cmp_csv_str(const cmp_csv *t, long row, int col)
{
    if (col < 0 || row < 0 || row >= t->nrows) return "";
    return t->cells[(size_t)row * t->ncols + col];
}

double cmp_csv_num(const cmp_csv *t, long row, int col)
{
    const char *s = cmp_csv_str(t, row, col);
    char *end;
    double x = strtod(s, &end);
    return end == s ? NAN : x;
}
