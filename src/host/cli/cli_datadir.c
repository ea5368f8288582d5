/* Where the shipped scenes are, so that `braun run four-bar.json` works
 * from any directory: $BRAUN_DATA_DIR if set, else share/braun/data next
 * to the executable's bin/ (PREFIX/bin/braun -> PREFIX/share/braun/data;
 * the build tree's BUILD/bin/braun -> BUILD/share/braun/data, a link to
 * the repository's data/ made by mk/cli.mk). POSIX (readlink of
 * /proc/self/exe, Linux), confined to this file. */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "braun_cli.h"

const char *braun_cli_data_dir(void)
{
    static char dir[4096];
    const char *env = getenv("BRAUN_DATA_DIR");
    if (env && *env) {
        if ((size_t)snprintf(dir, sizeof dir, "%s", env) >= sizeof dir) return NULL;
        return dir;
    }
    ssize_t len = readlink("/proc/self/exe", dir, sizeof dir - 1);
    if (len <= 0) return NULL;
    dir[len] = '\0';
    /* .../bin/braun -> .../share/braun/data */
    for (int up = 0; up < 2; up++) {
        char *slash = strrchr(dir, '/');
        if (!slash) return NULL;
        *slash = '\0';
    }
    static const char tail[] = "/share/braun/data";
    const size_t used = strlen(dir);
    if ((size_t)snprintf(dir + used, sizeof dir - used, "%s", tail) >= sizeof dir - used) return NULL;
    struct stat st;
    return stat(dir, &st) == 0 && S_ISDIR(st.st_mode) ? dir : NULL;
}

/* A regular file? */
static int is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* DIR/NAME or DIR/NAME.json when it is a regular file there. */
static int file_in(const char *dir, const char *name, int has_ext, char *path, size_t size)
{
    for (int ext = 0; ext < 2; ext++) {
        if (ext && has_ext) break;
        if ((size_t)snprintf(path, size, "%s/%s%s", dir, name, ext ? ".json" : "") >= size) return 0;
        if ((ext || has_ext) && is_file(path)) return 1;
    }
    return 0;
}

static int sub_dir(const struct dirent *e)
{
    return e->d_name[0] != '.';
}

/* The shipped scene NAME (with or without .json): DIR/NAME, a group's
 * GROUP/NAME as written ("iftomm/a01-pendulum"), else the first group
 * (in name order) that has it ("a01-pendulum"). */
int braun_cli_data_file(const char *name, char *path, size_t size)
{
    const char *dir = braun_cli_data_dir();
    if (!dir || !*name || name[0] == '/' || strstr(name, "..")) return 0;
    const size_t len = strlen(name);
    const int has_ext = len >= 5 && strcmp(name + len - 5, ".json") == 0;
    const char *slash = strchr(name, '/');
    if (slash) /* one group deep at most */
        return !strchr(slash + 1, '/') && slash != name && file_in(dir, name, has_ext, path, size);
    if (file_in(dir, name, has_ext, path, size)) return 1;
    struct dirent **list;
    const int count = scandir(dir, &list, sub_dir, alphasort);
    int found = 0;
    char group[8192];
    for (int i = 0; i < count; i++) {
        if (!found && (size_t)snprintf(group, sizeof group, "%s/%s", dir, list[i]->d_name) < sizeof group) {
            struct stat st;
            if (stat(group, &st) == 0 && S_ISDIR(st.st_mode))
                found = file_in(group, name, has_ext, path, size);
        }
        free(list[i]);
    }
    if (count >= 0) free(list);
    return found;
}

static int json_entry(const struct dirent *e)
{
    const size_t len = strlen(e->d_name);
    return e->d_name[0] != '.' && len > 5 && strcmp(e->d_name + len - 5, ".json") == 0;
}

/* The scenes of one directory, in name order. */
static int each_in(const char *dir, void (*fn)(const char *path, void *user), void *user)
{
    struct dirent **list;
    char path[8192];
    const int count = scandir(dir, &list, json_entry, alphasort);
    int shown = 0;
    for (int i = 0; i < count; i++) {
        if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, list[i]->d_name) < sizeof path &&
            is_file(path)) {
            fn(path, user);
            shown++;
        }
        free(list[i]);
    }
    if (count >= 0) free(list);
    return shown;
}

/* The top level's scenes, then each group's (data/iftomm/...). */
int braun_cli_data_each(void (*fn)(const char *path, void *user), void *user)
{
    const char *dir = braun_cli_data_dir();
    struct dirent **list;
    char group[8192];
    if (!dir) return 0;
    int shown = each_in(dir, fn, user);
    const int count = scandir(dir, &list, sub_dir, alphasort);
    for (int i = 0; i < count; i++) {
        struct stat st;
        if ((size_t)snprintf(group, sizeof group, "%s/%s", dir, list[i]->d_name) < sizeof group &&
            stat(group, &st) == 0 && S_ISDIR(st.st_mode))
            shown += each_in(group, fn, user);
        free(list[i]);
    }
    if (count >= 0) free(list);
    return shown;
}

int braun_cli_is_directory(const char *path)
{
    struct stat st;
    return path && stat(path, &st) == 0 && S_ISDIR(st.st_mode) && access(path, R_OK | X_OK) == 0;
}
