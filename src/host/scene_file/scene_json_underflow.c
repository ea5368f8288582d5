/* Numbers that underflow. jansson reads a real too large for a double
 * ("1e999") as an error, but one too small for it without a word: "1e-400"
 * becomes 0 and "1e-310" a subnormal that keeps a few bits. Its tree holds
 * no text, so the text jansson accepted is walked beside the tree (an
 * object's members in the order jansson keeps them, the order of the text:
 * duplicate keys are refused) and every real whose token has a nonzero
 * digit but whose value is below the smallest normal braun_real is listed.
 * The reader refuses a listed value at its field (number_value), where it
 * knows what the field accepts. One pass over the text. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene_json_internal.h"

typedef struct walk {
    const char *p, *end;
    sj_underflow *list; /* what is found, handed to the reader at the end */
    int count, cap;
    int failed; /* out of memory, or text and tree out of step: stop */
    int oom;
} walk;

static void skip_ws(walk *w) { w->p = sj_skip_ws(w->p, w->end); }
static void skip_string(walk *w) { w->p = sj_skip_string(w->p, w->end); }

/* A mantissa with a nonzero digit: the number written is not 0. */
static int nonzero_digits(const char *s, const char *end)
{
    for (; s < end && *s != 'e' && *s != 'E'; s++)
        if (*s >= '1' && *s <= '9') return 1;
    return 0;
}

static void add(walk *w, const json_t *v, const char *text, size_t len)
{
    if (w->count == w->cap) {
        const int cap = w->cap ? 2 * w->cap : 8;
        sj_underflow *more = realloc(w->list, (size_t)cap * sizeof *more);
        if (!more) {
            w->failed = w->oom = 1;
            return;
        }
        w->list = more;
        w->cap = cap;
    }
    w->list[w->count++] = (sj_underflow){v, text, len};
}

/* The value v, whose text starts at w->p (after white space). jansson
 * limits nesting (2048 levels), and so this recursion. */
static void value(walk *w, json_t *v)
{
    skip_ws(w);
    if (w->failed || w->p >= w->end || !v) {
        w->failed = 1;
        return;
    }
    if (json_is_object(v)) {
        void *it = json_object_iter(v);
        w->p++; /* { */
        for (skip_ws(w); !w->failed && w->p < w->end && *w->p == '"'; skip_ws(w)) {
            skip_string(w); /* the key: its member is the iterator's next */
            skip_ws(w);
            if (w->p < w->end && *w->p == ':') w->p++;
            value(w, it ? json_object_iter_value(it) : NULL);
            it = it ? json_object_iter_next(v, it) : NULL;
            skip_ws(w);
            if (w->p < w->end && *w->p == ',') w->p++;
        }
        if (w->p < w->end && *w->p == '}') w->p++;
    } else if (json_is_array(v)) {
        w->p++; /* [ */
        for (size_t i = 0; skip_ws(w), !w->failed && w->p < w->end && *w->p != ']'; i++) {
            value(w, json_array_get(v, i));
            skip_ws(w);
            if (w->p < w->end && *w->p == ',') w->p++;
        }
        if (w->p < w->end && *w->p == ']') w->p++;
    } else if (json_is_string(v)) {
        skip_string(w);
    } else {
        /* A number or a literal: up to the next delimiter. */
        const char *start = w->p;
        while (w->p < w->end && !strchr(",]} \t\r\n", *w->p)) w->p++;
        const double x = json_is_real(v) ? json_real_value(v) : 1;
        if (fabs(x) < BRAUN_SCENE_MIN_NORMAL && nonzero_digits(start, w->p))
            add(w, v, start, (size_t)(w->p - start));
    }
}

static int by_value(const void *a, const void *b)
{
    const uintptr_t x = (uintptr_t)((const sj_underflow *)a)->value;
    const uintptr_t y = (uintptr_t)((const sj_underflow *)b)->value;
    return x < y ? -1 : x > y;
}

int sj_find_underflows(sj_reader *r, json_t *root)
{
    walk w = {r->text, r->text + r->len, NULL, 0, 0, 0, 0};
    /* Text and tree out of step cannot happen with a tree jansson made from
     * this text; if it did, the values listed until then are still right
     * (and number_value refuses a subnormal by its value anyway). */
    value(&w, root);
    if (w.count > 1) qsort(w.list, (size_t)w.count, sizeof *w.list, by_value);
    r->underflows = w.list;
    r->nunderflows = w.count;
    return w.oom ? -1 : 0;
}

const sj_underflow *sj_underflow_of(const sj_reader *r, const json_t *v)
{
    if (r->nunderflows == 0 || !json_is_real(v)) return NULL;
    const sj_underflow key = {v, NULL, 0};
    return bsearch(&key, r->underflows, (size_t)r->nunderflows, sizeof key, by_value);
}
