/* libFuzzer target: the C generator (braun gen-c). Whatever the scene file
 * says in its names, description and path, and whatever symbol is asked
 * for, gen-c either refuses (writing nothing) or writes C whose code is
 * exactly the code it writes for the same scene with harmless names: the
 * texts only ever land inside comments. Checked on the output, without a
 * compiler (tests/cli/hygiene.sh compiles such outputs):
 *   - every byte is printable ASCII or a newline;
 *   - no "??" (a trigraph) and no backslash before a newline (a splice),
 *     so the comment and string boundaries below are the compiler's;
 *   - no "/" "*" inside a comment (a nested opener: -Wcomment);
 *   - with the comments' contents removed, the output equals the one
 *     written with every text replaced by "x".
 * Input: text starting with '{' is a scene file (the reader decides what
 * gets through); anything else is NUL-separated fields: symbol, source
 * path, scene name, description, then names for the elements of a fixed
 * scene (bodies, joints, effects in turn). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "braun_scene_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Every element kind gen-c writes, and names for all. */
static const char base_scene[] =
    "{\"name\": \"fuzz\", \"description\": \"d\","
    " \"ground\": {\"points\": {\"o\": [0, 0]}},"
    " \"bodies\": ["
    "  {\"name\": \"crank\", \"type\": \"rigid\", \"mass\": 1, \"inertia\": 0.1,"
    "   \"position\": [0.5, 0], \"points\": {\"a\": [-0.5, 0], \"b\": [0.5, 0]}},"
    "  {\"name\": \"bob\", \"type\": \"particle\", \"mass\": 1, \"position\": [1, -1]},"
    "  {\"name\": \"end\", \"type\": \"particle\", \"mass\": 0, \"position\": [2, -1]}],"
    " \"rods\": [{\"name\": \"r\", \"a\": \"bob\", \"b\": \"end\", \"mass\": 1}],"
    " \"joints\": ["
    "  {\"name\": \"pivot\", \"type\": \"revolute\", \"a\": \"crank.a\", \"b\": \"ground.o\"},"
    "  {\"name\": \"link\", \"type\": \"distance\", \"a\": \"crank.b\", \"b\": \"bob\"},"
    "  {\"name\": \"rail\", \"type\": \"slider\", \"point\": \"end\", \"line\": [0, -1], \"axis\": [1, 0]},"
    "  {\"name\": \"k\", \"type\": \"knife\", \"body\": \"crank\", \"direction\": [1, 0]}],"
    " \"effects\": ["
    "  {\"name\": \"g\", \"type\": \"gravity\", \"g\": [0, -9.81]},"
    "  {\"name\": \"sp\", \"type\": \"spring\", \"a\": \"crank.b\", \"b\": [3, 0], \"stiffness\": 2},"
    "  {\"name\": \"push\", \"type\": \"force\", \"point\": \"bob\", \"fx\": {\"type\": \"sine\","
    "   \"amplitude\": 1, \"omega\": 2}, \"fy\": 0}]}";

/* The output of gen-c into a malloc'd string (NULL if the stream failed). */
static char *generate(const braun_scene_file *sf, const char *sym, const char *source, int *rc,
                      size_t *len)
{
    char *buf = NULL;
    *len = 0;
    FILE *f = open_memstream(&buf, len);
    if (!f) return NULL;
    char err[256];
    *rc = braun_gen_c_write_ex(f, sf, sym, source, err, sizeof err);
    if (fclose(f) != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

/* The output with every comment's contents removed ("/ * * /" kept);
 * aborts on a byte, trigraph, splice or nested opener gen-c must not write. */
static char *skeleton(const char *s, size_t len)
{
    char *out = malloc(len + 1);
    size_t k = 0;
    int comment = 0, string = 0;
    if (!out) abort();
    for (size_t i = 0; i < len; i++) {
        const unsigned char c = (unsigned char)s[i];
        if (!(c == '\n' || (c >= 0x20 && c < 0x7f))) abort();
        if (c == '?' && i + 1 < len && s[i + 1] == '?') abort();
        if (c == '\\' && i + 1 < len && s[i + 1] == '\n') abort();
        if (comment) {
            if (c == '/' && i + 1 < len && s[i + 1] == '*') abort();
            if (c == '*' && i + 1 < len && s[i + 1] == '/') {
                comment = 0;
                out[k++] = '*';
                out[k++] = '/';
                i++;
            }
            continue;
        }
        if (string) {
            if (c == '\n') abort(); /* an unterminated string literal */
            if (c == '\\' && i + 1 < len) out[k++] = s[i++];
            else if (c == '"') string = 0;
            out[k++] = s[i];
            continue;
        }
        if (c == '/' && i + 1 < len && s[i + 1] == '*') {
            comment = 1;
            out[k++] = '/';
            out[k++] = '*';
            i++;
            continue;
        }
        if (c == '/' && i + 1 < len && s[i + 1] == '/') abort(); /* gen-c writes no // */
        if (c == '"') string = 1;
        if (c == '\'') abort(); /* nor character constants */
        out[k++] = (char)c;
    }
    if (comment || string) abort();
    out[k] = '\0';
    return out;
}

/* gen-c of sf with its texts, against sf with every text "x". */
static void check(const braun_scene_file *sf, const char *sym, const char *source)
{
    char why[256];
    const int sym_ok = braun_gen_c_check_symbol(sym, why, sizeof why) == 0;
    if (!sym_ok && (!why[0] || strchr(why, '\n'))) abort();
    int rc;
    size_t len;
    char *text = generate(sf, sym, source, &rc, &len);
    if (!text) return;
    if (!sym_ok) {
        /* Refused before anything was written. */
        if (rc != BRAUN_GEN_C_INVALID || len != 0) abort();
        free(text);
        return;
    }
    if (rc != 0) abort(); /* a valid symbol and built-in classes: must write */

    braun_scene_file plain = *sf;
    const braun_scene *s = &sf->scene;
    const char **bn = malloc(((size_t)s->nbodies + 1) * sizeof *bn);
    const char **jn = malloc(((size_t)s->njoints + 1) * sizeof *jn);
    const char **en = malloc(((size_t)s->neffects + 1) * sizeof *en);
    if (!bn || !jn || !en) abort();
    /* A name gets a comment when it is non-empty: keep which ones do. */
    for (int i = 0; i < s->nbodies; i++) bn[i] = sf->body_names[i] && sf->body_names[i][0] ? "x" : NULL;
    for (int i = 0; i < s->njoints; i++) jn[i] = sf->joint_names[i] && sf->joint_names[i][0] ? "x" : NULL;
    for (int i = 0; i < s->neffects; i++) en[i] = sf->effect_names[i] && sf->effect_names[i][0] ? "x" : NULL;
    plain.body_names = bn;
    plain.joint_names = jn;
    plain.effect_names = en;
    plain.name = "x";
    plain.description = sf->description && sf->description[0] ? "x" : "";
    int rc2;
    size_t len2;
    char *ref = generate(&plain, sym, "x", &rc2, &len2);
    if (ref && rc2 == 0) {
        char *a = skeleton(text, len), *b = skeleton(ref, len2);
        if (strcmp(a, b) != 0) abort(); /* a text escaped its comment */
        free(a);
        free(b);
    }
    free(ref);
    free((void *)bn);
    free((void *)jn);
    free((void *)en);
    free(text);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[512];
    if (size > 0 && data[0] == '{') {
        braun_scene_file *f = braun_scene_load_text("fuzz.json", (const char *)data, size, err,
                                                    sizeof err);
        if (!f) return 0;
        check(f, "fz", "fuzz.json");
        braun_scene_free(f);
        return 0;
    }
    static braun_scene_file *base;
    if (!base) {
        base = braun_scene_load_text("base.json", base_scene, sizeof base_scene - 1, err, sizeof err);
        if (!base) abort();
    }
    /* NUL-separated fields (the last one need not be terminated). */
    char *copy = malloc(size + 1);
    if (!copy) return 0;
    memcpy(copy, data, size);
    copy[size] = '\0';
    const char *field[32];
    int nf = 0;
    for (size_t i = 0; i <= size && nf < 32;) {
        field[nf++] = copy + i;
        i += strlen(copy + i) + 1;
    }
    braun_scene_file sf = *base;
    const braun_scene *s = &base->scene;
    const char *bn[8], *jn[8], *en[8];
    int k = 4;
    for (int i = 0; i < s->nbodies && i < 8; i++) bn[i] = k < nf ? field[k++] : base->body_names[i];
    for (int i = 0; i < s->njoints && i < 8; i++) jn[i] = k < nf ? field[k++] : base->joint_names[i];
    for (int i = 0; i < s->neffects && i < 8; i++) en[i] = k < nf ? field[k++] : base->effect_names[i];
    sf.body_names = bn;
    sf.joint_names = jn;
    sf.effect_names = en;
    if (nf > 2) sf.name = field[2];
    if (nf > 3) sf.description = field[3];
    check(&sf, nf > 0 ? field[0] : "", nf > 1 ? field[1] : "?");
    free(copy);
    return 0;
}
