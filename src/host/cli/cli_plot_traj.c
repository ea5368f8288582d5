/* `braun plot MODEL --traj FILE`: a trajectory written by `braun run MODEL
 * --out FILE`, drawn without simulating again. The header must name the
 * model's columns (with or without their units); every row is numbers,
 * traj_err may be empty, times never decrease. Errors name FILE:LINE. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_plot.h"

/* One header cell: unquoted, without " [unit]". */
static const char *header_cell(const char *p, const char *end, char *name, size_t size)
{
    size_t k = 0;
    if (p < end && *p == '"') {
        for (p++; p < end; p++) {
            if (*p == '"' && p + 1 < end && p[1] == '"') p++;
            else if (*p == '"') { p++; break; }
            if (k + 1 < size) name[k++] = *p;
        }
    } else {
        for (; p < end && *p != ','; p++)
            if (k + 1 < size) name[k++] = *p;
    }
    name[k] = '\0';
    char *br = strstr(name, " [");
    if (br) *br = '\0';
    return p;
}

/* A mantissa with a nonzero digit: the number written is not 0. */
static int nonzero_digits(const char *s, const char *end)
{
    for (; s < end && *s != 'e' && *s != 'E'; s++)
        if (*s >= '1' && *s <= '9') return 1;
    return 0;
}

/* One row into row (cols numbers, the CSV's columns; an empty traj_err is
 * NaN): 0, or BRAUN_CLI_USAGE after "FILE:LINE: ..." naming the column. A
 * value must be a finite double: nan, inf and what overflows one (1e999)
 * are refused, as a picture cannot place them. */
static int read_row(const char *p, const char *eol, const braun_cli_target *t, int cols,
                    double *row, const char *path, long line)
{
    const int n = t->sys.n, traj = braun_cli_column_count(n) - 1;
    if (eol > p && eol[-1] == '\r') eol--;
    for (int j = 0; j < cols; j++) {
        char name[BRAUN_CLI_COLUMN_NAME];
        const char *unit, *start = p;
        char *stop = (char *)p;
        const int last = j == cols - 1;
        braun_cli_column_name(t, n, j, name, sizeof name, &unit);
        errno = 0;
        if (j == traj && (p >= eol || *p == ','))
            row[j] = NAN; /* traj_err: empty without a reference */
        else if (braun_cli_hex_or_blank(p) || (row[j] = strtod(p, &stop), stop == p))
            return braun_cli_error("--traj %s:%ld: column %d (%s) is not a number (or the row "
                                   "has fewer than %d columns)", path, line, j + 1, name, cols);
        /* The cell ends at the comma before the next one, or the line's end. */
        if (last ? stop != eol : stop >= eol || *stop != ',') {
            const char *why = "is not a number";
            if (last && stop < eol && *stop == ',') why = "is followed by more columns than the header's";
            else if (!last && stop >= eol) why = "ends the row: fewer columns than the header's";
            return braun_cli_error("--traj %s:%ld: column %d (%s) %s", path, line, j + 1, name, why);
        }
        if (!isfinite(row[j]) && stop != p)
            return braun_cli_error("--traj %s:%ld: column %d (%s) is %.*s: %s", path, line, j + 1,
                                   name, (int)(stop - start > 40 ? 40 : stop - start), start,
                                   errno == ERANGE ? "beyond the range of a double"
                                                   : "not a finite number");
        /* A nonzero number that reads as 0 lost its value; a subnormal is
         * kept: braun run writes one as digits that read back exactly. */
        if (row[j] == 0 && stop != p && errno == ERANGE && nonzero_digits(start, stop))
            return braun_cli_error("--traj %s:%ld: column %d (%s) is %.*s: it underflows (below "
                                   "the smallest double, it would read as 0)", path, line, j + 1,
                                   name, (int)(stop - start > 40 ? 40 : stop - start), start);
        p = last ? eol : stop + 1;
    }
    return 0;
}

int plot_traj_read(const char *path, const braun_cli_target *t, plot_samples *s)
{
    char err[512];
    size_t len;
    char *text = braun_cli_read_file(path, (size_t)1 << 30, &len, err, sizeof err);
    if (!text) return braun_cli_error("--traj %s", err);
    /* Every column of the CSV is read and checked; the samples keep the
     * state's (the reported points are drawn from q). */
    const int n = t->sys.n, cols = braun_cli_csv_column_count(t, n);
    double *row = calloc((size_t)cols, sizeof *row);
    if (!row) {
        free(text);
        return braun_cli_error("out of memory");
    }
    int rc = 0;
    const char *p = text, *end = text + len;
    /* The header. */
    const char *eol = memchr(p, '\n', (size_t)(end - p));
    if (!eol) eol = end;
    for (int j = 0; !rc && j < cols; j++) {
        char want[BRAUN_CLI_COLUMN_NAME], got[BRAUN_CLI_COLUMN_NAME];
        const char *unit;
        braun_cli_column_name(t, n, j, want, sizeof want, &unit);
        /* As the CSV's header writes it (cli_csv.c): a name's control
         * bytes as '?', or run's own CSV of a scene with a tab in a body's
         * name could not be read back. */
        braun_cli_mask_controls(want);
        if (p >= eol) {
            rc = braun_cli_error("--traj %s:1: %d columns, '%s' needs %d (the columns of braun "
                                 "run %s --out)", path, j, t->name, cols, t->name);
            break;
        }
        p = header_cell(p, eol, got, sizeof got);
        if (strcmp(want, got) != 0)
            rc = braun_cli_error("--traj %s:1: column %d is '%s', '%s' has '%s' there (the "
                                 "columns of braun run %s --out)", path, j + 1, got, t->name,
                                 want, t->name);
        if (p < eol && *p == ',') p++;
        else if (j + 1 < cols && !rc)
            rc = braun_cli_error("--traj %s:1: %d columns, '%s' needs %d", path, j + 1,
                                 t->name, cols);
    }
    if (!rc && p < eol && *p != '\r')
        rc = braun_cli_error("--traj %s:1: more columns than '%s' has (%d)", path, t->name, cols);
    /* Two passes over the rows: the first checks every one and finds the
     * last time (the window of the samples), the second keeps them. */
    const char *body = eol < end ? eol + 1 : end;
    double t_first = NAN, t_last = NAN;
    long rows = 0;
    for (int pass = 0; !rc && pass < 2; pass++) {
        double t_prev = -HUGE_VAL;
        long line = 1;
        for (p = body; !rc && p < end; p = eol + 1) {
            line++;
            eol = memchr(p, '\n', (size_t)(end - p));
            if (!eol) eol = end;
            if (eol == p || (eol == p + 1 && *p == '\r')) continue;
            rc = read_row(p, eol, t, cols, row, path, line);
            if (!rc && !(row[0] >= t_prev))
                rc = braun_cli_error("--traj %s:%ld: t = %g comes after t = %g", path, line, row[0],
                                     t_prev);
            if (rc) break;
            t_prev = row[0];
            if (pass == 0 && rows++ == 0) t_first = row[0];
            if (pass == 0) t_last = row[0];
            else plot_samples_add(s, row);
        }
        if (!rc && pass == 0 && rows == 0)
            rc = braun_cli_error("--traj %s: no rows after the header", path);
        /* The samples' spacing is a fraction of the span of times. */
        if (!rc && pass == 0 && !isfinite(t_last - t_first))
            rc = braun_cli_error("--traj %s: t runs from %g to %g, a span beyond the range of a "
                                 "double", path, t_first, t_last);
        if (!rc && pass == 0) {
            /* Without --from the window starts at the first row (not at
             * -inf, whose span would make the spacing NaN). */
            const double from = isnan(s->from) ? t_first : s->from;
            const long cap = s->cap;
            if (plot_samples_init(s, n, cap, from, t_last)) rc = braun_cli_error("out of memory");
        }
    }
    if (!rc) plot_samples_finish(s);
    if (!rc && s->count == 0)
        rc = braun_cli_error("--traj %s: no rows at or after --from %g", path, s->from);
    free(row);
    free(text);
    return rc;
}
