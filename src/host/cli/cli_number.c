/* Numbers people read: the shortest decimal that reads back as the same
 * double (0.1, not 0.10000000000000001), so that files stay exact and
 * short. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "braun_cli.h"

/* A p-digit decimal that reads back as x is, when p <= 15, what %.15g
 * prints once its trailing zeros are gone (15 digits cannot straddle a
 * double's rounding interval); else the correctly rounded 16 or 17 digits,
 * the nearest of their length, are the shortest that can. */
const char *braun_cli_number(double x, char *buf)
{
    if (isnan(x)) return snprintf(buf, BRAUN_CLI_NUMBER_SIZE, "nan"), buf;
    if (isinf(x)) return snprintf(buf, BRAUN_CLI_NUMBER_SIZE, x > 0 ? "inf" : "-inf"), buf;
    for (int p = 15; p < 17; p++) {
        snprintf(buf, BRAUN_CLI_NUMBER_SIZE, "%.*g", p, x);
        if (strtod(buf, NULL) == x) return buf;
    }
    snprintf(buf, BRAUN_CLI_NUMBER_SIZE, "%.17g", x);
    return buf;
}

void braun_cli_put_number(FILE *f, double x)
{
    char buf[BRAUN_CLI_NUMBER_SIZE];
    fputs(braun_cli_number(x, buf), f);
}
