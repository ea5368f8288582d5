/* Trajectory CSV (RFC 4180): a header of column names with their units in
 * brackets — "t [s]", the coordinates and velocities named from the scene
 * ("crank.x [m]", "crank.theta [rad]", "crank.vx [m/s]"; q[i], v[i] for a
 * system defined in C), "pos_err [Phi_q]", "vel_err [Phi_q/s]",
 * "energy_err [J]" and "traj_err [q]" — then one row per written state,
 * each number the shortest decimal that reads back as the same double;
 * traj_err is empty without a reference. docs/cli.md lists the columns. */
#include <string.h>

#include "braun_cli.h"

/* A header cell, quoted when it holds a comma, a quote or a line break;
 * control bytes (from a scene's names) become '?'. */
static void cell(FILE *f, const char *name, const char *unit)
{
    const int quote = strpbrk(name, ",\"\r\n") != NULL;
    if (quote) fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)name; *p; p++) {
        if (*p == '"') fputs("\"\"", f);
        else fputc(*p < 0x20 || *p == 0x7f ? '?' : *p, f);
    }
    if (unit) fprintf(f, " [%s]", unit);
    if (quote) fputc('"', f);
}

int braun_cli_csv_header(FILE *f, const braun_cli_target *t, int n)
{
    char name[160];
    const char *unit;
    for (int j = 0; j < braun_cli_column_count(n); j++) {
        if (j) fputc(',', f);
        braun_cli_column_name(t, n, j, name, sizeof name, &unit);
        cell(f, name, unit);
    }
    fputc('\n', f);
    return ferror(f) ? -1 : 0;
}

int braun_cli_csv_row(FILE *f, int n, double t, const double *q,
                      const double *v, const braun_cli_errors *e, int has_ref)
{
    braun_cli_put_number(f, t);
    for (int i = 0; i < n; i++) fputc(',', f), braun_cli_put_number(f, q[i]);
    for (int i = 0; i < n; i++) fputc(',', f), braun_cli_put_number(f, v[i]);
    fputc(',', f), braun_cli_put_number(f, e->pos);
    fputc(',', f), braun_cli_put_number(f, e->vel);
    fputc(',', f), braun_cli_put_number(f, e->energy);
    fputc(',', f);
    if (has_ref) braun_cli_put_number(f, e->traj);
    fputc('\n', f);
    return ferror(f) ? -1 : 0;
}
