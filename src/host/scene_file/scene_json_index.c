/* The reader's name lookups in O(log n): body names sorted once before the
 * bodies are read, each body's named points sorted once when its "points"
 * are read, one centre per body. A scene's load is then O(n log n) in its
 * size, whatever the names and references (no hash to flood: the worst
 * case is the sort's). */
#include <stdlib.h>
#include <string.h>

#include "scene_json_internal.h"

/* Byte order, then length (a name is never a prefix match). */
static int name_cmp(const char *a, size_t alen, const char *b, size_t blen)
{
    const int c = memcmp(a, b, alen < blen ? alen : blen);
    if (c) return c;
    return alen < blen ? -1 : alen > blen;
}

static int entry_cmp(const void *pa, const void *pb)
{
    const sj_name *a = (const sj_name *)pa, *b = (const sj_name *)pb;
    const int c = name_cmp(a->s, a->len, b->s, b->len);
    if (c) return c;
    return a->index < b->index ? -1 : a->index > b->index;
}

/* First entry not less than (name, len): a lower bound. */
static int lower_bound(const sj_name *v, int n, const char *name, size_t len)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (name_cmp(v[mid].s, v[mid].len, name, len) < 0) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

int sj_index_bodies(sj_reader *r, json_t *bodies)
{
    const size_t nb = json_array_size(bodies);
    r->body_index = malloc((nb + 1) * sizeof *r->body_index);
    r->centre = malloc((nb + 1) * sizeof *r->centre);
    r->pt_first = malloc((nb + 1) * sizeof *r->pt_first);
    r->pt_count = calloc(nb + 1, sizeof *r->pt_count);
    if (!r->body_index || !r->centre || !r->pt_first || !r->pt_count) return -1;
    r->nslots = (int)nb + 1;
    r->nbody_index = 0;
    for (size_t k = 0; k <= nb; k++) r->centre[k] = r->pt_first[k] = -1;
    /* Every body object with a string name; what is wrong with a name is
     * found when its body is read, in file order. */
    for (size_t k = 0; k < nb; k++) {
        json_t *name = json_object_get(json_array_get(bodies, k), "name");
        if (!json_is_string(name)) continue;
        sj_name *e = &r->body_index[r->nbody_index++];
        e->s = json_string_value(name);
        e->len = json_string_length(name);
        e->index = (int)k;
    }
    qsort(r->body_index, (size_t)r->nbody_index, sizeof *r->body_index, entry_cmp);
    return 0;
}

int sj_find_body(const sj_reader *r, const char *name, size_t len)
{
    const int i = lower_bound(r->body_index, r->nbody_index, name, len);
    if (i == r->nbody_index ||
        name_cmp(r->body_index[i].s, r->body_index[i].len, name, len) != 0)
        return -2;
    /* The first body of that name, once it has been read: bodies become
     * visible in file order (a body's twin is an earlier one). */
    const int k = r->body_index[i].index;
    return k < r->out->scene.nbodies ? k : -2;
}

/* Slot of a body (or the ground) in the per-body tables; -1 if none. */
static int slot(const sj_reader *r, int body)
{
    if (body == BRAUN_SCENE_GROUND) return 0;
    return body >= 0 && body < r->nslots - 1 ? body + 1 : -1;
}

void sj_index_points(sj_reader *r, int body, int first)
{
    const int sl = slot(r, body);
    if (sl < 0 || first >= r->npoints) return;
    if (r->pt_first[sl] < 0) {
        r->pt_first[sl] = first;
    } else if (r->pt_first[sl] + r->pt_count[sl] != first) {
        /* A second, separate range of named points for one body (a class
         * with two POINTS fields and points between them): not indexed. */
        return;
    }
    r->pt_count[sl] = r->npoints - r->pt_first[sl];
    for (int i = r->pt_first[sl]; i < r->npoints; i++) {
        sj_name *e = &r->point_sorted[i];
        e->s = r->point_names[i];
        e->len = strlen(e->s);
        e->index = i;
    }
    qsort(r->point_sorted + r->pt_first[sl], (size_t)r->pt_count[sl], sizeof *r->point_sorted,
          entry_cmp);
}

int sj_find_point(const sj_reader *r, int body, const char *name)
{
    const int sl = slot(r, body);
    if (sl < 0) return -1;
    if (name[0] == '\0') return r->centre[sl];
    if (r->pt_first[sl] < 0) return -1;
    const sj_name *v = r->point_sorted + r->pt_first[sl];
    const size_t len = strlen(name);
    const int i = lower_bound(v, r->pt_count[sl], name, len);
    return i < r->pt_count[sl] && name_cmp(v[i].s, v[i].len, name, len) == 0 ? v[i].index : -1;
}

void sj_set_centre(sj_reader *r, int body, int point)
{
    const int sl = slot(r, body);
    if (sl > 0) r->centre[sl] = point;
}

/* Joints by name: sorted once, on the first lookup (effects on a joint's
 * axis are read after every joint). */
int sj_find_joint(sj_reader *r, const char *name)
{
    const braun_scene_file *f = r->out;
    const int nj = f->scene.njoints;
    if (!r->joint_index) {
        r->joint_index = malloc(((size_t)nj + 1) * sizeof *r->joint_index);
        if (!r->joint_index) return -2;
        r->njoint_index = 0;
        for (int k = 0; k < nj; k++) {
            const char *n = f->joint_names[k];
            if (!n) continue;
            sj_name *e = &r->joint_index[r->njoint_index++];
            e->s = n;
            e->len = strlen(n);
            e->index = k;
        }
        qsort(r->joint_index, (size_t)r->njoint_index, sizeof *r->joint_index, entry_cmp);
    }
    const size_t len = strlen(name);
    const int i = lower_bound(r->joint_index, r->njoint_index, name, len);
    if (i == r->njoint_index || name_cmp(r->joint_index[i].s, r->joint_index[i].len, name, len))
        return -1;
    return r->joint_index[i].index; /* the first of that name */
}

int sj_duplicate_joint(sj_reader *r, int *later, int *first)
{
    if (sj_find_joint(r, "") == -2) return -2; /* builds the sorted index */
    /* Sorted by name, then index: each run of one name starts at the joint
     * that has it first, and every other entry of the run repeats it. The
     * repeat a reader meets first is the one of the lowest index. */
    int found = 0, start = 0;
    for (int i = 1; i < r->njoint_index; i++) {
        const sj_name *a = &r->joint_index[i - 1], *b = &r->joint_index[i];
        if (name_cmp(a->s, a->len, b->s, b->len) != 0) {
            start = i;
        } else if (!found || b->index < *later) {
            *later = b->index;
            *first = r->joint_index[start].index;
            found = 1;
        }
    }
    return found;
}

void sj_index_free(sj_reader *r)
{
    free(r->joint_index);
    r->joint_index = NULL;
    free(r->body_index);
    free(r->centre);
    free(r->pt_first);
    free(r->pt_count);
    free(r->point_sorted);
    r->body_index = r->point_sorted = NULL;
    r->centre = r->pt_first = r->pt_count = NULL;
}
