/* Process CPU time. The POSIX feature macro is confined to this file so the
 * rest of the tool stays plain C99. */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "braun_cli.h"

double braun_cli_cpu_seconds(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return -1.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
