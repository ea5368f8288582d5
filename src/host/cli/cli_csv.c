/* Trajectory CSV: t, q0..q{n-1}, v0..v{n-1}, pos_err, vel_err, energy_err,
 * traj_err (empty without a reference). %.17g: rows read back bit-exact. */
#include "braun_cli.h"

int braun_cli_csv_header(FILE *f, int n)
{
    fputs("t", f);
    for (int i = 0; i < n; i++) fprintf(f, ",q%d", i);
    for (int i = 0; i < n; i++) fprintf(f, ",v%d", i);
    fputs(",pos_err,vel_err,energy_err,traj_err\n", f);
    return ferror(f) ? -1 : 0;
}

int braun_cli_csv_row(FILE *f, int n, double t, const double *q,
                      const double *v, const braun_cli_errors *e, int has_ref)
{
    fprintf(f, "%.17g", t);
    for (int i = 0; i < n; i++) fprintf(f, ",%.17g", q[i]);
    for (int i = 0; i < n; i++) fprintf(f, ",%.17g", v[i]);
    fprintf(f, ",%.17g,%.17g,%.17g,", e->pos, e->vel, e->energy);
    if (has_ref) fprintf(f, "%.17g", e->traj);
    fputc('\n', f);
    return ferror(f) ? -1 : 0;
}
