/* A growing text buffer written printf-style (cmp_text.c): the MJCF
 * writers (cmp_mujoco.c, cmp_mujoco3.c) build their model text with it. */
#ifndef CMP_TEXT_H
#define CMP_TEXT_H

#include <stddef.h>

typedef struct cmp_text {
    char *s;
    size_t len, cap;
    int failed;   /* an allocation or format error: the text is incomplete */
} cmp_text;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void cmp_text_put(cmp_text *t, const char *fmt, ...);

#endif
