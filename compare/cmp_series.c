/* The series table (cmp_series.h), compiled in from compare/series.tsv. */
#include <string.h>

#include "cmp_series.h"

const cmp_series cmp_series_table[] = {
#include "cmp_series.inc" /* generated from compare/series.tsv by compare/series.awk */
};
const int cmp_series_count = (int)(sizeof cmp_series_table / sizeof cmp_series_table[0]);

int cmp_series_is(const cmp_series *s, const char *method, const char *integ, const char *variant)
{
    return strcmp(s->method, method) == 0 && strcmp(s->integ, integ) == 0 &&
           strcmp(s->variant, variant) == 0;
}

const cmp_series *cmp_series_of(const char *method, const char *integ, const char *variant)
{
    for (int i = 0; i < cmp_series_count; i++)
        if (cmp_series_is(&cmp_series_table[i], method, integ, variant))
            return &cmp_series_table[i];
    return NULL;
}

const cmp_series *cmp_series_find(const char *key)
{
    for (int i = 0; i < cmp_series_count; i++)
        if (strcmp(cmp_series_table[i].key, key) == 0) return &cmp_series_table[i];
    return NULL;
}

int cmp_series_in(const cmp_series *s, const char *tag)
{
    const size_t n = strlen(tag);
    for (const char *p = s->in; *p;) {
        const size_t len = strcspn(p, ",");
        if (len == n && strncmp(p, tag, n) == 0) return 1;
        p += len;
        if (*p == ',') p++;
    }
    return 0;
}

void cmp_series_print(FILE *f)
{
    for (int i = 0; i < cmp_series_count; i++) {
        const cmp_series *s = &cmp_series_table[i];
        fprintf(f, "%s|%s|%s|%d|%d|%s\n", s->key, s->label, s->colour, s->dash, s->point, s->in);
    }
}
