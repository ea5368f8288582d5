/* Positions for error messages: walk a JSON text that jansson has already
 * accepted along a path of keys and indices, and report the line and
 * column of the key or value found. Because the text is known to be valid
 * JSON, the walk only needs to skip strings (with their escapes) and
 * nested brackets; it never decides what is valid. */
#include <stdio.h>
#include <string.h>

#include "scene_json_internal.h"

typedef struct cursor {
    const char *p, *end;
} cursor;

static void skip_ws(cursor *c) { c->p = sj_skip_ws(c->p, c->end); }
static void skip_string(cursor *c) { c->p = sj_skip_string(c->p, c->end); }

/* Skip one value of any kind. */
static void skip_value(cursor *c)
{
    int depth = 0;
    skip_ws(c);
    do {
        if (c->p >= c->end) return;
        const char ch = *c->p;
        if (ch == '"') {
            skip_string(c);
        } else if (ch == '{' || ch == '[') {
            depth++;
            c->p++;
        } else if (ch == '}' || ch == ']') {
            depth--;
            c->p++;
        } else if (depth == 0) {
            /* A number or literal: up to the next delimiter. */
            while (c->p < c->end && !strchr(",]} \t\r\n", *c->p)) c->p++;
        } else {
            c->p++;
        }
    } while (depth > 0);
}

static int hexval(char ch)
{
    if (ch >= '0' && ch <= '9') return ch - '0';
    if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
    return 0;
}

/* Does the string at c (opening quote) decode to key? Advances past it. */
static int string_equals(cursor *c, const char *key)
{
    const unsigned char *k = (const unsigned char *)key;
    int same = 1;
    c->p++;
    while (c->p < c->end && *c->p != '"') {
        if (*c->p == '\\' && c->p + 1 < c->end) {
            unsigned long cp;
            const char e = c->p[1];
            c->p += 2;
            switch (e) {
            case 'b': cp = '\b'; break;
            case 'f': cp = '\f'; break;
            case 'n': cp = '\n'; break;
            case 'r': cp = '\r'; break;
            case 't': cp = '\t'; break;
            case 'u':
                cp = 0;
                for (int i = 0; i < 4 && c->p < c->end; i++) cp = cp * 16 + (unsigned long)hexval(*c->p++);
                break;
            default: cp = (unsigned char)e; break;
            }
            /* Keys of a scene are ASCII; compare other escapes as one
             * code point against one byte (a mismatch is harmless: the
             * locator then falls back to the enclosing value). */
            if (*k == '\0' || *k != cp) same = 0;
            else k++;
        } else {
            if (*k == '\0' || *k != (unsigned char)*c->p) same = 0;
            else k++;
            c->p++;
        }
    }
    if (c->p < c->end) c->p++;
    return same && *k == '\0';
}

/* Move c to the value of member key in the object at c; *key_at gets the
 * key's opening quote. Returns 0 if absent. */
static int enter_key(cursor *c, const char *key, const char **key_at)
{
    skip_ws(c);
    if (c->p >= c->end || *c->p != '{') return 0;
    c->p++;
    for (;;) {
        skip_ws(c);
        if (c->p >= c->end || *c->p != '"') return 0;
        const char *start = c->p;
        const int match = string_equals(c, key);
        skip_ws(c);
        if (c->p < c->end && *c->p == ':') c->p++;
        skip_ws(c);
        if (match) {
            *key_at = start;
            return 1;
        }
        skip_value(c);
        skip_ws(c);
        if (c->p < c->end && *c->p == ',') c->p++;
        else return 0;
    }
}

static int enter_index(cursor *c, int index)
{
    skip_ws(c);
    if (c->p >= c->end || *c->p != '[') return 0;
    c->p++;
    for (int i = 0;; i++) {
        skip_ws(c);
        if (c->p >= c->end || *c->p == ']') return 0;
        if (i == index) return 1;
        skip_value(c);
        skip_ws(c);
        if (c->p < c->end && *c->p == ',') c->p++;
        else return 0;
    }
}

void sj_locate(const char *text, size_t len, const sj_seg *path, int depth, int at, int *line,
               int *column)
{
    cursor c = {text, text + len};
    const char *found = NULL, *key_at = NULL;
    skip_ws(&c);
    found = c.p;
    for (int i = 0; i < depth; i++) {
        const char *k = NULL;
        const int ok = path[i].key ? enter_key(&c, path[i].key, &k) : enter_index(&c, path[i].index);
        if (!ok) break; /* not in the text: point at the deepest value found */
        found = c.p;
        key_at = i == depth - 1 ? k : NULL;
    }
    const char *target = at == SJ_AT_KEY && key_at ? key_at : found;
    if (target > c.end) target = c.end;
    int ln = 1, col = 1;
    for (const char *p = text; p < target; p++) {
        if (*p == '\n') {
            ln++;
            col = 1;
        } else if (((unsigned char)*p & 0xC0) != 0x80) {
            col++; /* count characters, not UTF-8 continuation bytes */
        }
    }
    *line = ln;
    *column = col;
}

/* The JSON path leading to byte offset pos of a text that may be invalid
 * from pos on (jansson stopped there), e.g. "bodies[0].mass", and where
 * the last token before pos starts. Used to name the field of a syntax
 * error; a string met where a comma was due is taken as the next key (the
 * usual mistake is a missing comma). */
void sj_context(const char *text, size_t len, size_t pos, char *path, size_t size,
                size_t *token_start)
{
    struct level {
        int object, index, expect_key;
        const char *key;
        size_t key_len;
    } st[SJ_MAX_DEPTH * 4];
    int depth = 0;
    memset(st, 0, sizeof st);
    const int max_depth = (int)(sizeof st / sizeof st[0]);
    size_t i = 0, last = 0;
    if (pos > len) pos = len;
    while (i < pos) {
        const char ch = text[i];
        if (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r') {
            i++;
            continue;
        }
        last = i;
        if (ch == '"') {
            const size_t start = i++;
            while (i < pos && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
            i++;
            if (depth > 0 && depth <= max_depth && st[depth - 1].object &&
                st[depth - 1].expect_key >= 0) {
                st[depth - 1].key = text + start + 1;
                st[depth - 1].key_len = (i <= pos ? i - 1 : pos) - (start + 1);
                st[depth - 1].expect_key = -1; /* a key: its value comes next */
            } else if (depth > 0 && depth <= max_depth && st[depth - 1].object) {
                st[depth - 1].expect_key = 0; /* a value: a comma is due */
            }
        } else if (ch == '{' || ch == '[') {
            if (depth > 0 && depth <= max_depth && st[depth - 1].object) st[depth - 1].expect_key = 0;
            if (depth < max_depth) st[depth] = (struct level){ch == '{', 0, 1, NULL, 0};
            depth++;
            i++;
        } else if (ch == '}' || ch == ']') {
            if (depth > 0) depth--;
            if (depth > 0 && depth <= max_depth && st[depth - 1].object) st[depth - 1].expect_key = 0;
            i++;
        } else if (ch == ',') {
            if (depth > 0 && depth <= max_depth) {
                if (st[depth - 1].object) st[depth - 1].expect_key = 1;
                else st[depth - 1].index++;
            }
            i++;
        } else if (ch == ':') {
            i++;
        } else {
            while (i < pos && !strchr(",]}: \t\r\n", text[i])) i++;
            if (depth > 0 && depth <= max_depth && st[depth - 1].object) st[depth - 1].expect_key = 0;
            if (i == last) i++;
        }
    }
    *token_start = last;
    size_t used = 0;
    if (size) path[0] = '\0';
    for (int d = 0; d < depth && d < max_depth && used + 1 < size; d++) {
        int k;
        if (st[d].object && st[d].key)
            k = snprintf(path + used, size - used, "%s%.*s", used ? "." : "", (int)st[d].key_len,
                         st[d].key);
        else if (!st[d].object)
            k = snprintf(path + used, size - used, "[%d]", st[d].index);
        else
            k = 0;
        if (k < 0) break;
        used += (size_t)k;
        if (used >= size) used = size - 1;
    }
}
