/* Trajectory CSV (RFC 4180): a header of column names with their units in
 * brackets — "t [s]", the coordinates and velocities named from the scene
 * ("crank.x [m]", "crank.theta [rad]", "crank.vx [m/s]"; q[i], v[i] for a
 * system defined in C), "pos_err [Phi_q]", "vel_err [Phi_q/s]",
 * "energy_err [J]" and "traj_err [q]" — then one row per written state,
 * each number the shortest decimal that reads back as the same double;
 * traj_err is empty without a reference; then a scene's reported points,
 * "NAME.x [m]", "NAME.y [m]" (and "NAME.z [m]" in a spatial scene), but
 * for one that is a body's own columns already (braun_cli_report_columns).
 * docs/cli.md lists the columns. */
#include <stdlib.h>
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
    char name[BRAUN_CLI_COLUMN_NAME];
    const char *unit;
    for (int j = 0; j < braun_cli_csv_column_count(t, n); j++) {
        if (j) fputc(',', f);
        braun_cli_column_name(t, n, j, name, sizeof name, &unit);
        cell(f, name, unit);
    }
    fputc('\n', f);
    return ferror(f) ? -1 : 0;
}

int braun_cli_csv_row(FILE *f, const braun_cli_target *tg, int n, double t, const double *q,
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
    const int dim = braun_cli_report_dim(tg);
    if (dim) {
#ifdef BRAUN_SINGLE
        /* The scene evaluates braun_reals; the rows hold doubles. */
        braun_real *qr = malloc((size_t)n * sizeof *qr + 1);
        if (!qr) return -1;
        for (int i = 0; i < n; i++) qr[i] = (braun_real)q[i];
#else
        const braun_real *qr = q;
#endif
        for (int k = 0; k < tg->nreports; k++) {
            braun_real pos[3];
            braun_scene_point_state(&tg->scene->scene, tg->scene->report_points[tg->reports[k]],
                                    qr, NULL, pos, NULL);
            for (int c = 0; c < dim; c++) fputc(',', f), braun_cli_put_number(f, (double)pos[c]);
        }
#ifdef BRAUN_SINGLE
        free(qr);
#endif
    }
    fputc('\n', f);
    return ferror(f) ? -1 : 0;
}
