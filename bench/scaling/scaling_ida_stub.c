/* Placeholder until the compare harness exposes its IDA+KLU entry point. */
#include <string.h>

#include "scaling.h"

int sc_ida_run(const sc_scene *s, double T, double rtol, int samples, double *q_out,
               sc_ida_result *res)
{
    (void)s, (void)T, (void)rtol, (void)samples, (void)q_out;
    memset(res, 0, sizeof *res);
    return -1;
}
