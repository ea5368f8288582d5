/*
 * Private to the host tier (libbraun_host.a): numbers written the same
 * whatever the program's locale.
 *
 * printf writes a number with the radix character of the locale the
 * program set (setlocale(LC_ALL, "") under de_DE: "0,5"), and strtod reads
 * it so. What the library writes is read by C compilers (gen-c's R(0.5)),
 * by its own loader and by people comparing messages: braun__c_snprintf is
 * snprintf, and braun__c_strtod strtod, in the "C" locale for this call
 * only (the program's locale, and other threads', untouched).
 */
#ifndef BRAUN_C_LOCALE_H
#define BRAUN_C_LOCALE_H

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

int braun__c_vsnprintf(char *buf, size_t size, const char *fmt, va_list ap);
int braun__c_snprintf(char *buf, size_t size, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
double braun__c_strtod(const char *s, char **end);

#endif /* BRAUN_C_LOCALE_H */
