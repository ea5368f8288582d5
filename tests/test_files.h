/* Shared by the tests with and without cmocka: the files of a directory. */
#ifndef BRAUN_TEST_FILES_H
#define BRAUN_TEST_FILES_H

#include <dirent.h> /* the including file defines _POSIX_C_SOURCE */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int test_files__cmp(const void *a, const void *b) { return strcmp(a, b); }

/* The names in dir ending in suffix (and longer than it), each written as
 * prefix + name into names[k][0 .. width), sorted; at most max. Names that
 * do not fit are left out. Returns their number, -1 when dir cannot be
 * opened. */
static int test_list_files(const char *dir, const char *suffix, const char *prefix, char *names,
                           size_t width, int max)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int count = 0;
    const size_t sl = strlen(suffix), pl = strlen(prefix);
    struct dirent *e;
    while ((e = readdir(d)) != NULL && count < max) {
        const size_t len = strlen(e->d_name);
        if (len > sl && strcmp(e->d_name + len - sl, suffix) == 0 && pl + len < width) {
            memcpy(names + (size_t)count * width, prefix, pl);
            memcpy(names + (size_t)count * width + pl, e->d_name, len + 1);
            count++;
        }
    }
    closedir(d);
    qsort(names, (size_t)count, width, test_files__cmp);
    return count;
}

#endif
