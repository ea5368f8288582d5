/* braun-ida-run: IDA (GGL) with KLU on one scene, for timing scaling
 * studies (cmp_ida_run_cli in compare/cmp_ida_jac.c; docs/compare.md). */
#include <gsl/gsl_errno.h>

#include "cmp.h"

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    return cmp_ida_run_cli(argc - 1, argv + 1);
}
