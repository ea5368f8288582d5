/* The library's version and precision, asked at run time (braun.h). */
#include "braun.h"

const char *braun_version(void)
{
    return BRAUN_VERSION;
}

const char *braun_precision(void)
{
#ifdef BRAUN_SINGLE
    return "float";
#else
    return "double";
#endif
}
