/* Process CPU time. The POSIX feature macro is confined to this file so the
 * rest of the bench stays plain C99. */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "bench.h"

double bench_cpu_ns(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return -1.0;
    return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
}
