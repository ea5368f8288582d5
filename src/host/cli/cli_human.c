/* The line for people at the end of a run, on stderr beside the JSON:
 * how it ended, how far it got in how many steps, the CPU time and what
 * it means, the largest residuals and the accuracy guard's bounds. */
#include <math.h>
#include <string.h>

#include "braun_cli.h"

/* "1.3e-07", or "-" for a quantity that does not exist. */
static const char *g3(double x, char *buf, size_t size)
{
    if (isnan(x)) snprintf(buf, size, "-");
    else snprintf(buf, size, "%.2g", x);
    return buf;
}

void braun_cli_write_human(FILE *f, const braun_cli_result *r)
{
    const braun_cli_run_args *a = r->args;
    const braun_cli_monitor *mon = r->mon;
    const braun_cli_bounds *b = &r->stop.bounds;
    char st[64], p[16], v[16], e[16];
    braun_cli_status_name(r->status, st, sizeof st);
    fputs("braun: ", f);
    braun_cli_put_text(f, r->scene); /* the scene's name, escaped as braun check does */
    fprintf(f, ": %s", st);
    if (r->status == BRAUN_OK) {
        fprintf(f, " at t = %.6g s", r->final_t);
    } else if (r->stop.dropped) {
        fprintf(f, " at t = %.6g s (that state refused; kept t = %.6g s, the last that passed)",
                r->stop.dropped_t, r->final_t);
    } else {
        fprintf(f, ", stopped at t = %.6g s of %.6g", r->final_t, a->t_end);
    }
    fprintf(f, ", %ld steps (%s, ", r->stats.steps, braun_method_name(a->method));
    if (a->method == BRAUN_DOPRI5)
        fprintf(f, "rtol %.3g, atol %.3g, %ld rejected)", a->rtol, a->atol,
                r->stats.rejected_steps);
    else
        fprintf(f, "h = %.6g)", a->dt);
    if (isnan(r->cpu_s))
        fprintf(f, ", CPU %.3g s with monitoring", r->cpu_monitored_s);
    else
        fprintf(f, ", CPU %.3g s (cpu_s: the integration alone, timed in a run without "
                   "monitoring; the monitored run took %.3g s)", r->cpu_s, r->cpu_monitored_s);
    fprintf(f, "; max |Phi_q| %s, |dPhi| %s, |Phi_e| %s", g3(mon->max.pos, p, sizeof p),
            g3(mon->max.vel, v, sizeof v), g3(mon->max.energy, e, sizeof e));
    if (mon->has_ref) {
        char q[16];
        fprintf(f, ", |q - q_ref| %s", g3(mon->max.traj, q, sizeof q));
    }
    if (b->on) {
        char bp[16], bv[16], be[16];
        fprintf(f, " (guard bounds %s, %s, %s)", g3(b->pos, bp, sizeof bp),
                g3(b->vel, bv, sizeof bv), g3(b->energy, be, sizeof be));
    } else {
        fputs(" (guard off)", f);
    }
    fputc('\n', f);
    fflush(f);
}
