/* snprintf and strtod in the "C" locale (braun_c_locale.h). */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L /* newlocale, uselocale */
#endif
#include "braun_c_locale.h"

#include <locale.h>
#include <stdlib.h>

/* The calling thread switched to the "C" locale (POSIX 2008: per thread,
 * so another thread's numbers are not touched) until c_end. glibc returns
 * its static C locale object here, with nothing allocated; should
 * newlocale fail, the numbers are the program's locale's, as before. */
typedef struct c_scope {
    locale_t c, old;
} c_scope;

static c_scope c_begin(void)
{
    c_scope s;
    s.c = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    s.old = s.c ? uselocale(s.c) : (locale_t)0;
    return s;
}

static void c_end(c_scope s)
{
    if (!s.c) return;
    uselocale(s.old);
    freelocale(s.c);
}

int braun__c_vsnprintf(char *buf, size_t size, const char *fmt, va_list ap)
{
    c_scope s = c_begin();
    /* NOLINTNEXTLINE(clang-analyzer-valist.Uninitialized): ap is the caller's, started */
    int k = vsnprintf(buf, size, fmt, ap);
    c_end(s);
    return k;
}

int braun__c_snprintf(char *buf, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int k = braun__c_vsnprintf(buf, size, fmt, ap);
    va_end(ap);
    return k;
}

double braun__c_strtod(const char *s, char **end)
{
    c_scope sc = c_begin();
    double x = strtod(s, end);
    c_end(sc);
    return x;
}
