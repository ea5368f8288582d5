/* Scene to C: a loaded scene as static C data (braun_scene.h, braun_gen_c_write).
 * It knows no element type: each element is written with its class's
 * c_name, and a and b as body references or point indices as the class's
 * field descriptors say. */
#include "braun_scene_file.h"
#include "braun_c_locale.h"

#include <ctype.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A real as the exact double the host holds ("%.17g" round-trips), cast to
 * braun_real by the generated R() macro. A value a float cannot hold —
 * beyond FLT_MAX, or nonzero below FLT_MIN, which the cast would make Inf,
 * 0 or a subnormal of a few bits in silence — is written RD(), which a
 * BRAUN_SINGLE build refuses (the preamble). */
static void real(FILE *f, braun_real x)
{
    const double a = fabs((double)x);
    const int outside = a > FLT_MAX || (a != 0 && a < FLT_MIN);
    /* "%.17g" writes −0 as "-0", an int, whose cast is +0: the sign kept
     * as a double constant. */
    if (x == 0 && signbit((double)x)) fputs("R(-0.0)", f);
    else {
        char text[40];
        /* In the "C" locale: a program's setlocale(LC_ALL, "") under
         * de_DE wrote R(0,083333333333333329), a macro call of two
         * arguments. */
        braun__c_snprintf(text, sizeof text, outside ? "RD(%.17g)" : "R(%.17g)", (double)x);
        fputs(text, f);
    }
}

static void reals(FILE *f, const braun_real *x, int n)
{
    fputc('{', f);
    for (int i = 0; i < n; i++) {
        if (i) fputs(", ", f);
        real(f, x[i]);
    }
    fputc('}', f);
}

/* Enumerator names of the functions of time (braun_scene.h); a number if
 * the header has grown a kind this generator does not know. */
static void kind(FILE *f, const char *const *names, int count, int k)
{
    if (k >= 0 && k < count && names[k])
        fputs(names[k], f);
    else
        fprintf(f, "%d", k);
}

static const char *const fn_kinds[] = {"BRAUN_FN_CONSTANT", "BRAUN_FN_LINEAR", "BRAUN_FN_SINE",
                                       "BRAUN_FN_STEP"};
#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* Does a class's table describe the int at offset as a body reference? */
static int body_field(const braun_scene_field *f, size_t offset)
{
    for (; f && f->key; f++)
        if (f->offset == offset) return f->kind == BRAUN_FIELD_BODY;
    return 0;
}

static void fn(FILE *f, const braun_scene_fn *g)
{
    fputs("{.kind = ", f);
    kind(f, fn_kinds, COUNT(fn_kinds), g->kind);
    fputs(", .a = ", f);
    real(f, g->a);
    fputs(", .b = ", f);
    real(f, g->b);
    fputs(", .c = ", f);
    real(f, g->c);
    fputs(", .d = ", f);
    real(f, g->d);
    fputc('}', f);
}

/* A body or ground reference. */
static void ref(FILE *f, int body)
{
    if (body == BRAUN_SCENE_GROUND)
        fputs("BRAUN_SCENE_GROUND", f);
    else
        fprintf(f, "%d", body);
}

/* "static braun_scene_TYPE SYMBOL_NAME[COUNT] = {"; nothing for an empty
 * array (the scene then holds NULL). */
static int open_array(FILE *f, const char *type, const char *sym, const char *name, int count)
{
    if (count <= 0) return 0;
    fprintf(f, "\nstatic braun_scene_%s %s_%s[%d] = {\n", type, sym, name, count);
    return 1;
}

/* Text from the scene file (names, the description, the source path) in a
 * comment: printable ASCII only, and nothing that could end the comment,
 * open a nested one, form a trigraph or splice a line. Other bytes become
 * \xNN, valid UTF-8 sequences \uXXXX or \UXXXXXXXX; a '*' before '/', a
 * '/' before '*' and a '?' before '?' are followed by a backslash ("*\/",
 * "/\*", "?\?"); a backslash is \x5c. At most GEN_C_TEXT_MAX bytes of
 * the text are written (then "..."), so a line stays well under C99's
 * 4095 characters (each byte gives at most 10). */
#define GEN_C_TEXT_MAX 160

/* Length of the valid UTF-8 sequence at s (2..4) and its code point, or 0. */
static int utf8_seq(const unsigned char *s, unsigned long *cp)
{
    int len;
    unsigned long c;
    if (s[0] >= 0xC2 && s[0] <= 0xDF) len = 2, c = s[0] & 0x1Fu;
    else if (s[0] >= 0xE0 && s[0] <= 0xEF) len = 3, c = s[0] & 0x0Fu;
    else if (s[0] >= 0xF0 && s[0] <= 0xF4) len = 4, c = s[0] & 0x07u;
    else return 0;
    for (int i = 1; i < len; i++) {
        if ((s[i] & 0xC0) != 0x80) return 0;
        c = (c << 6) | (s[i] & 0x3Fu);
    }
    /* Overlong forms, surrogates and code points past U+10FFFF are invalid. */
    if ((len == 3 && c < 0x800) || (len == 4 && (c < 0x10000 || c > 0x10FFFF)) ||
        (c >= 0xD800 && c <= 0xDFFF))
        return 0;
    *cp = c;
    return len;
}

static void comment_text(FILE *f, const char *text)
{
    if (!text) return;
    const unsigned char *s = (const unsigned char *)text;
    size_t i = 0;
    while (i < GEN_C_TEXT_MAX && s[i]) {
        const unsigned char c = s[i];
        unsigned long cp;
        int len;
        if (c >= 0x20 && c < 0x7F && c != '\\') {
            fputc(c, f);
            if ((c == '*' && s[i + 1] == '/') || (c == '/' && s[i + 1] == '*') ||
                (c == '?' && s[i + 1] == '?'))
                fputc('\\', f);
            i++;
        } else if (c >= 0x80 && (len = utf8_seq(s + i, &cp)) > 0) {
            if (i + (size_t)len > GEN_C_TEXT_MAX) break;
            if (cp > 0xFFFF) fprintf(f, "\\U%08lX", cp);
            else fprintf(f, "\\u%04lX", cp);
            i += (size_t)len;
        } else {
            fprintf(f, "\\x%02X", (unsigned)c);
            i++;
        }
    }
    if (s[i]) fputs("...", f);
}

static void item_end(FILE *f, const char *const *names, int i)
{
    fputs("},", f);
    if (names && names[i] && names[i][0]) {
        fputs(" /* ", f);
        comment_text(f, names[i]);
        fputs(" */", f);
    }
    fputc('\n', f);
}

/* ".nNAME = COUNT, .NAME = SYMBOL_NAME," (NULL for an empty array). */
static void array_field(FILE *f, const char *sym, const char *name, int count)
{
    if (count > 0)
        fprintf(f, "    .n%s = %d, .%s = %s_%s,\n", name, count, name, sym, name);
    else
        fprintf(f, "    .n%s = 0, .%s = NULL,\n", name, name);
}

static int identifier(const char *s)
{
    if (!s || !(isalpha((unsigned char)*s) || *s == '_')) return 0;
    for (; *s; s++)
        if (!(isalnum((unsigned char)*s) || *s == '_')) return 0;
    return 1;
}

/* Plain ASCII letters and digits: isalpha may accept more in other locales. */
static int ascii_identifier(const char *s)
{
    for (const char *c = s; *c; c++)
        if ((unsigned char)*c >= 0x80) return 0;
    return identifier(s);
}

int braun_gen_c_check_symbol(const char *symbol, char *why, size_t size)
{
    const char *problem = NULL;
    if (!symbol || !ascii_identifier(symbol))
        problem = "must be a C identifier (ASCII letters, digits and '_', not starting with a "
                  "digit)";
    else if (strlen(symbol) > BRAUN_GEN_C_SYMBOL_MAX)
        problem = "is longer than " BRAUN_GEN_C_SYMBOL_MAX_STR " characters ('_corrections' is "
                  "appended: within the 63 significant characters of GCC's and Clang's, and C99's "
                  "for macro names; C99 promises external names only 31)";
    else if (symbol[0] == '_')
        problem = "must not start with '_' (reserved for the implementation)";
    else if ((symbol[0] | 0x20) == 'b' && (symbol[1] | 0x20) == 'r' &&
             (symbol[2] | 0x20) == 'a' && (symbol[3] | 0x20) == 'u' &&
             (symbol[4] | 0x20) == 'n' && (symbol[5] == '\0' || symbol[5] == '_'))
        problem = symbol[5] ? "must not start with 'braun_' (libbraun's own names: SYMBOL_build "
                              "could be one of them)"
                            : "must not be 'braun' (libbraun's own names: 'braun_scene' and the "
                              "other names made from it are libbraun's)";
    if (why && size) {
        why[0] = '\0';
        if (problem) snprintf(why, size, "the symbol %s", problem);
    }
    return problem ? -1 : 0;
}

/* What gen-c writes for a class: a C identifier (a macro of braun_scene.h)
 * or "&identifier" (the program's own class, declared extern). */
static int keyword(const char *id)
{
    /* C99's keywords and C11's (an identifier cannot be one). */
    static const char *const words[] = {
        "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else",
        "enum", "extern", "float", "for", "goto", "if", "inline", "int", "long", "register",
        "restrict", "return", "short", "signed", "sizeof", "static", "struct", "switch", "typedef",
        "union", "unsigned", "void", "volatile", "while", "_Bool", "_Complex", "_Imaginary",
        "_Alignas", "_Alignof", "_Atomic", "_Generic", "_Noreturn", "_Static_assert",
        "_Thread_local"};
    for (size_t k = 0; k < sizeof words / sizeof words[0]; k++)
        if (strcmp(id, words[k]) == 0) return 1;
    return 0;
}

static int c_name_ok(const char *c_name)
{
    if (!c_name) return 0;
    const char *id = c_name[0] == '&' ? c_name + 1 : c_name;
    return ascii_identifier(id) && strlen(id) <= 63 && !keyword(id);
}

/* The symbol in upper case, for its macros (SYMBOL_N). */
static void upper_symbol(const char *sym, char upper[BRAUN_GEN_C_SYMBOL_MAX + 1])
{
    for (size_t i = 0; i <= strlen(sym); i++) upper[i] = (char)toupper((unsigned char)sym[i]);
}

/* The names the generated file defines or uses besides the classes': a
 * c_name equal to one of them gave a file that does not compile (uc_build
 * redeclared, NULL as a declarator) or whose build function's locals hid
 * the class (st). In what, "name, what it is" for the message; 0 if none. */
static int c_name_clash(const char *c_name, const char *sym, const char *upper, char *what,
                        size_t size)
{
    static const char *const defined[][2] = {
        {"build", "the build function"},       {"scene", "the static scene"},
        {"corrections", "the corrections constant"}, {"bodies", "an array"},
        {"points", "an array"},                {"rods", "an array"},
        {"joints", "an array"},                {"effects", "an array"}};
    static const char *const macros[] = {"R", "RD",
                                         "value_outside_the_range_of_float_in_a_BRAUN_SINGLE_build"};
    static const char *const locals[] = {"sys", "q0", "v0", "st", "unused"};
    static const char *const stddef_names[] = {"NULL", "offsetof", "size_t", "ptrdiff_t",
                                               "wchar_t", "max_align_t"};
    const int declared = c_name[0] == '&';
    const char *id = declared ? c_name + 1 : c_name;
    const size_t n = strlen(sym);
    if (strncmp(id, sym, n) == 0 && id[n] == '_')
        for (size_t k = 0; k < sizeof defined / sizeof defined[0]; k++)
            if (strcmp(id + n + 1, defined[k][0]) == 0) {
                snprintf(what, size, "%s, %s the generated file defines", id, defined[k][1]);
                return 1;
            }
    if (strncmp(id, upper, n) == 0 && id[n] == '_' && id[n + 1] && strchr("NMP", id[n + 1]) &&
        id[n + 2] == '\0') {
        snprintf(what, size, "%s, a size macro the generated file defines", id);
        return 1;
    }
    if (strncmp(id, "BRAUN_GEN_", 10) == 0 && strncmp(id + 10, sym, n) == 0 &&
        strcmp(id + 10 + n, "_H") == 0) {
        snprintf(what, size, "%s, the generated header's include guard", id);
        return 1;
    }
    for (size_t k = 0; k < sizeof macros / sizeof macros[0]; k++)
        if (strcmp(id, macros[k]) == 0) {
            snprintf(what, size, "%s, a macro the generated file defines", id);
            return 1;
        }
    for (size_t k = 0; k < sizeof locals / sizeof locals[0]; k++)
        if (strcmp(id, locals[k]) == 0) {
            snprintf(what, size, "%s, a %s of %s_build (it would hide the class there)", id,
                     k < 3 ? "parameter" : "local", sym);
            return 1;
        }
    for (size_t k = 0; k < sizeof stddef_names / sizeof stddef_names[0]; k++)
        if (strcmp(id, stddef_names[k]) == 0) {
            snprintf(what, size, "%s, a name of <stddef.h>, which the generated file includes", id);
            return 1;
        }
    /* A class the file declares is the program's: libbraun's names (and
     * braun.h's macros) and the implementation's are not. */
    if (declared && (strncmp(id, "braun_", 6) == 0 || strncmp(id, "BRAUN_", 6) == 0)) {
        snprintf(what, size, "libbraun's names (braun_..., BRAUN_...)");
        return 1;
    }
    if (declared && id[0] == '_') {
        snprintf(what, size, "the names reserved for the implementation (a leading '_')");
        return 1;
    }
    return 0;
}

/* A scene's classes, each once, in the order of their first element
 * (bodies, joints, effects): k 0, 1, 2 for a body, joint or effect class. */
typedef struct seen_class {
    const void *cls;
    const char *c_name, *type;
    int k;
} seen_class;

/* The class of every element has a c_name gen-c can write, and a class the
 * file declares ("&name") is the only one of that name. Each class is
 * checked once; seen (room for one per element) gets them, *nseen their
 * number, for the declarations. 0, or -1 with the reason in err. */
static int check_classes(const braun_scene_file *sf, const char *sym, seen_class *seen, int *nseen_out,
                         char *err, size_t size)
{
    const braun_scene *s = &sf->scene;
    static const char *const kinds[] = {"body", "joint", "effect"};
    const int counts[] = {s->nbodies, s->njoints, s->neffects};
    const char *const *names[] = {sf->body_names, sf->joint_names, sf->effect_names};
    char upper[BRAUN_GEN_C_SYMBOL_MAX + 1];
    upper_symbol(sym, upper);
    int nseen = 0;
    *nseen_out = 0;
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < counts[k]; i++) {
            const void *cls = NULL;
            const char *type = NULL, *c_name = NULL;
            if (k == 0 && s->bodies[i].kind)
                cls = s->bodies[i].kind, type = s->bodies[i].kind->name, c_name = s->bodies[i].kind->c_name;
            if (k == 1 && s->joints[i].type)
                cls = s->joints[i].type, type = s->joints[i].type->name, c_name = s->joints[i].type->c_name;
            if (k == 2 && s->effects[i].type)
                cls = s->effects[i].type, type = s->effects[i].type->name, c_name = s->effects[i].type->c_name;
            int known = 0;
            for (int j = 0; cls && j < nseen && !known; j++) known = seen[j].cls == cls;
            if (known) continue;
            char clash[160] = "";
            int bad = !cls || !c_name_ok(c_name) ||
                      c_name_clash(c_name, sym, upper, clash, sizeof clash);
            /* Another class declared by the same name: two declarations of
             * one object (of two types, or one object for two classes). */
            const char *other = NULL;
            for (int j = 0; !bad && c_name[0] == '&' && j < nseen; j++)
                if (strcmp(seen[j].c_name, c_name) == 0) {
                    other = seen[j].type;
                    bad = 1;
                }
            if (!bad) {
                seen[nseen].cls = cls;
                seen[nseen].c_name = c_name;
                seen[nseen].k = k;
                seen[nseen++].type = type;
                continue;
            }
            if (err && size) {
                char who[96];
                const char *name = names[k] ? names[k][i] : NULL;
                if (name) snprintf(who, sizeof who, "%s '%.60s'", kinds[k], name);
                else snprintf(who, sizeof who, "%s #%d", kinds[k], i + 1);
                if (!cls) snprintf(err, size, "%s has no class", who);
                else if (!c_name) snprintf(err, size, "%s: its class '%.60s' has no c_name", who,
                                           type ? type : "?");
                else if (!c_name_ok(c_name))
                    snprintf(err, size, "%s: the c_name of its class '%.60s' is not a C "
                                        "identifier or '&identifier'", who, type ? type : "?");
                else if (clash[0])
                    snprintf(err, size, "%s: the c_name '%s' of its class '%.60s' clashes with %s: "
                                        "give the class another c_name", who, c_name,
                             type ? type : "?", clash);
                else
                    snprintf(err, size, "%s: the c_name '%s' of its class '%.60s' is also that of "
                                        "class '%.60s': one name declares one class", who, c_name,
                             type ? type : "?", other ? other : "?");
                for (char *c = err; *c; c++)
                    if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
            }
            return -1;
        }
    *nseen_out = nseen;
    return 0;
}

/* SYMBOL_N, _M, _P, after a check that another scene's did not define
 * them: the symbols of two generated files that differ only in case (arm,
 * ARM) give one set of macros, and a program that included both read one
 * scene's sizes for the other's buffers. The same values pass (the source
 * and its header in one file). */
static void sizes(FILE *out, const braun_scene *s, const char *upper)
{
    /* No quotes in the #error (the generated file has no string literals)
     * and no line splice. */
    fprintf(out, "#if (defined(%s_N) && %s_N != %d) || (defined(%s_M) && %s_M != %d) || "
                 "(defined(%s_P) && %s_P != %d)\n"
                 "#error %s_N, %s_M or %s_P defined already with the sizes of another scene: two "
                 "generated files whose symbols differ only in case (gen-c --symbol)\n#endif\n",
            upper, upper, s->n, upper, upper, s->m, upper, upper, s->p, upper, upper, upper);
    fprintf(out, "#define %s_N %d\n#define %s_M %d\n#define %s_P %d\n", upper, s->n, upper, s->m,
            upper, s->p);
}

/* The first line of both files: where they come from, not to be edited. */
static void banner(FILE *out, const braun_scene_file *sf, const char *source)
{
    fputs("/* Generated by braun gen-c from ", out);
    comment_text(out, source ? source : "?");
    fputs(" (scene \"", out);
    comment_text(out, sf->name ? sf->name : "");
    fputs("\"): do not edit.\n * ", out);
}

/* 0 once everything written has reached the file, else BRAUN_GEN_C_WRITE:
 * flushed first, because text still in the stream's buffer (a header, a
 * small scene's whole source) has not failed yet, and ferror alone said 0
 * for a stream whose write then failed at the caller's fclose. */
static int written(FILE *out, char *err, size_t err_size)
{
    if (fflush(out) != 0 || ferror(out)) {
        if (err && err_size) snprintf(err, err_size, "write error");
        return BRAUN_GEN_C_WRITE;
    }
    return 0;
}

int braun_gen_c_write_header(FILE *out, const braun_scene_file *sf, const char *sym, const char *source,
                             char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    if (!out || !sf) {
        if (err && err_size) snprintf(err, err_size, "no output or no scene");
        return BRAUN_GEN_C_INVALID;
    }
    if (braun_gen_c_check_symbol(sym, err, err_size)) return BRAUN_GEN_C_INVALID;
    char upper[BRAUN_GEN_C_SYMBOL_MAX + 1];
    upper_symbol(sym, upper);
    const braun_scene *s = &sf->scene;
    banner(out, sf, source);
    fputs("What the generated source defines, for the program's other files. */\n", out);
    /* BRAUN_GEN_ + at most 48 + _H: within C99's 63 significant characters.
     * The symbol as given: two symbols that differ only in case (arm, ARM)
     * have guards of their own, and the second header stops at the sizes'
     * check instead of being skipped in silence. */
    fprintf(out, "#ifndef BRAUN_GEN_%s_H\n#define BRAUN_GEN_%s_H\n\n", sym, sym);
    fputs("#include \"braun.h\"\n\n", out);
    fputs("#ifdef __cplusplus\nextern \"C\" {\n#endif\n\n", out);
    /* The same tokens as the source's: a file that includes both is valid C. */
    sizes(out, s, upper);
    fputc('\n', out);
    fprintf(out, "/* The corrections the scene file asks for (braun_options.corrections). */\n");
    fprintf(out, "extern const unsigned %s_corrections;\n", sym);
    fprintf(out, "/* braun_scene_build() on the static scene, then its initial state into\n"
                 " * q0, v0 (%s_N entries each; either may be NULL). Returns the status. */\n", upper);
    fprintf(out, "int %s_build(braun_system *sys, braun_real *q0, braun_real *v0);\n", sym);
    fputs("\n#ifdef __cplusplus\n}\n#endif\n", out);
    fprintf(out, "#endif /* BRAUN_GEN_%s_H */\n", sym);
    return written(out, err, err_size);
}

int braun_gen_c_write(FILE *out, const braun_scene_file *sf, const char *sym, const char *source)
{
    return braun_gen_c_write_ex(out, sf, sym, source, NULL, 0) ? -1 : 0;
}

int braun_gen_c_write_ex(FILE *out, const braun_scene_file *sf, const char *sym,
                         const char *source, char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    if (!out || !sf) {
        if (err && err_size) snprintf(err, err_size, "no output or no scene");
        return BRAUN_GEN_C_INVALID;
    }
    const braun_scene *s = &sf->scene;
    char upper[BRAUN_GEN_C_SYMBOL_MAX + 1];
    /* Everything is checked before the first byte is written. */
    if (braun_gen_c_check_symbol(sym, err, err_size)) return BRAUN_GEN_C_INVALID;
    seen_class *seen = malloc(((size_t)s->nbodies + s->njoints + s->neffects + 1) * sizeof *seen);
    int nseen = 0;
    if (!seen) {
        if (err && err_size) snprintf(err, err_size, "out of memory");
        return BRAUN_GEN_C_WRITE;
    }
    if (check_classes(sf, sym, seen, &nseen, err, err_size)) {
        free(seen);
        return BRAUN_GEN_C_INVALID;
    }
    upper_symbol(sym, upper);

    banner(out, sf, source);
    if (sf->description && sf->description[0]) comment_text(out, sf->description);
    else fputs("(no description)", out);
    fputs("\n * The scene as static data; SYMBOL_build() calls braun_scene_build() once\n"
          " * at start-up: no parser, no allocation. Compiles in double and float. */\n", out);
    fputs("#include <stddef.h>\n\n#include \"braun_scene.h\"\n\n", out);
    fputs("/* The exact double of the scene file, rounded once to braun_real. */\n", out);
    fputs("#define R(x) ((braun_real)(x))\n", out);
    fputs("/* A value a float cannot hold (beyond FLT_MAX, or below FLT_MIN): a float\n"
          " * build stops at it rather than read Inf or 0. */\n", out);
    fputs("#ifdef BRAUN_SINGLE\n#define RD(x) value_outside_the_range_of_float_in_a_BRAUN_SINGLE_build(x)\n"
          "#else\n#define RD(x) R(x)\n#endif\n\n", out);
    sizes(out, s, upper);

    /* Classes defined by the program (not libbraun's, written "&symbol"):
     * declared here, once each, the program links their definitions. */
    {
        static const char *const class_types[] = {"braun_scene_body_class", "braun_scene_joint_class",
                                                   "braun_scene_effect_class"};
        for (int i = 0; i < nseen; i++)
            if (seen[i].c_name[0] == '&')
                fprintf(out, "extern const %s %s;\n", class_types[seen[i].k], seen[i].c_name + 1);
        free(seen);
    }

    /* Designated initialisers: robust to fields the header may add. The
     * derived fields (iq, row) are left to braun_scene_build. What only a
     * spatial scene has (z, 3-D axes and frames, inertia tensors, g and
     * f[2]) is written for spatial scenes only: a planar scene's file is
     * what it was before spatial scenes. */
    int spatial = 0;
    for (int i = 0; i < s->nbodies; i++) spatial = spatial || s->bodies[i].kind->dim == 3;
    const int vec = spatial ? 3 : 2;
    if (open_array(out, "body", sym, "bodies", s->nbodies)) {
        for (int i = 0; i < s->nbodies; i++) {
            const braun_scene_body *b = &s->bodies[i];
            fprintf(out, "    {.kind = %s", b->kind->c_name);
            fputs(", .mass = ", out);
            real(out, b->mass);
            fputs(", .inertia = ", out);
            real(out, b->inertia);
            /* q0, v0: the class's coordinates (at least 3 entries, as
             * planar scenes always had). */
            const int nq = b->kind->dof > 3 ? b->kind->dof : 3;
            fputs(",\n     .q0 = ", out);
            reals(out, b->q0, nq);
            fputs(", .v0 = ", out);
            reals(out, b->v0, nq);
            if (spatial) {
                fputs(",\n     .tensor = ", out);
                reals(out, b->tensor, 6);
            }
            item_end(out, sf->body_names, i);
        }
        fputs("};\n", out);
    }
    if (open_array(out, "point", sym, "points", s->npoints)) {
        for (int i = 0; i < s->npoints; i++) {
            const braun_scene_point *p = &s->points[i];
            fputs("    {.body = ", out);
            ref(out, p->body);
            fputs(", .x = ", out);
            real(out, p->x);
            fputs(", .y = ", out);
            real(out, p->y);
            if (spatial) {
                fputs(", .z = ", out);
                real(out, p->z);
            }
            item_end(out, NULL, i);
        }
        fputs("};\n", out);
    }
    if (open_array(out, "rod", sym, "rods", s->nrods)) {
        for (int i = 0; i < s->nrods; i++) {
            const braun_scene_rod *r = &s->rods[i];
            fprintf(out, "    {.a = %d, .b = %d, .mass = ", r->a, r->b);
            real(out, r->mass);
            fputs(", .length = ", out);
            real(out, r->length);
            item_end(out, NULL, i);
        }
        fputs("};\n", out);
    }
    /* a and b are body references (written BRAUN_SCENE_GROUND for the
     * ground) or point indices, as the class's fields say. */
    if (open_array(out, "joint", sym, "joints", s->njoints)) {
        for (int i = 0; i < s->njoints; i++) {
            const braun_scene_joint *j = &s->joints[i];
            const braun_scene_field *fl = j->type->fields;
            fprintf(out, "    {.type = %s", j->type->c_name);
            fputs(", .a = ", out);
            body_field(fl, offsetof(braun_scene_joint, a)) ? ref(out, j->a)
                                                          : (void)fprintf(out, "%d", j->a);
            fputs(", .b = ", out);
            body_field(fl, offsetof(braun_scene_joint, b)) ? ref(out, j->b)
                                                          : (void)fprintf(out, "%d", j->b);
            fputs(", .axis = ", out);
            reals(out, j->axis, vec);
            if (spatial) {
                fputs(",\n     .axis_b = ", out);
                reals(out, j->axis_b, 3);
                fputs(", .ref_a = ", out);
                reals(out, j->ref_a, 3);
                fputs(", .ref_b = ", out);
                reals(out, j->ref_b, 3);
            }
            fputs(", .value = ", out);
            real(out, j->value);
            fprintf(out, ",\n     .driven = %d, .drive = ", j->driven);
            fn(out, &j->drive);
            item_end(out, sf->joint_names, i);
        }
        fputs("};\n", out);
    }
    if (open_array(out, "effect", sym, "effects", s->neffects)) {
        for (int i = 0; i < s->neffects; i++) {
            const braun_scene_effect *e = &s->effects[i];
            const braun_scene_field *fl = e->type->fields;
            fprintf(out, "    {.type = %s", e->type->c_name);
            fputs(", .a = ", out);
            body_field(fl, offsetof(braun_scene_effect, a)) ? ref(out, e->a)
                                                           : (void)fprintf(out, "%d", e->a);
            fputs(", .b = ", out);
            body_field(fl, offsetof(braun_scene_effect, b)) ? ref(out, e->b)
                                                           : (void)fprintf(out, "%d", e->b);
            fputs(", .g = ", out);
            reals(out, e->g, vec);
            fputs(",\n     .k = ", out);
            real(out, e->k);
            fputs(", .c = ", out);
            real(out, e->c);
            fputs(", .rest = ", out);
            real(out, e->rest);
            fputs(", .tau0 = ", out);
            real(out, e->tau0);
            fputs(", .omega0 = ", out);
            real(out, e->omega0);
            fputs(",\n     .f = {", out);
            fn(out, &e->f[0]);
            fputs(", ", out);
            fn(out, &e->f[1]);
            if (spatial) {
                fputs(",\n           ", out);
                fn(out, &e->f[2]);
            }
            fputc('}', out);
            item_end(out, sf->effect_names, i);
        }
        fputs("};\n", out);
    }

    /* The coordinates' natural sizes (braun_scene.q_scale), filled by
     * braun_scene_build: the accuracy guard's scales in each coordinate's
     * unit, as the scene file's. */
    fprintf(out, "\nstatic braun_real %s_q_scale[%d];\n", sym, s->n > 0 ? s->n : 1);
    fprintf(out, "\nstatic braun_scene %s_scene = {\n", sym);
    array_field(out, sym, "bodies", s->nbodies);
    array_field(out, sym, "points", s->npoints);
    array_field(out, sym, "rods", s->nrods);
    array_field(out, sym, "joints", s->njoints);
    array_field(out, sym, "effects", s->neffects);
    fprintf(out, "    .q_scale = %s_q_scale,\n", sym);
    fputs("};\n", out);

    /* Declared before defined: a program's own declaration (or a header
     * with it) must agree, and clang's -Wmissing-variable-declarations
     * stays quiet. */
    fprintf(out, "\nextern const unsigned %s_corrections;\n", sym);
    fprintf(out, "const unsigned %s_corrections = %uu;\n", sym, sf->corrections);
    fprintf(out, "\nint %s_build(braun_system *sys, braun_real *q0, braun_real *v0);\n", sym);
    fprintf(out, "int %s_build(braun_system *sys, braun_real *q0, braun_real *v0)\n{\n", sym);
    /* Either output may be NULL: the other is still written (a scratch
     * array of N entries takes the one not asked for), and the initial
     * state's status is the function's. */
    fprintf(out, "    braun_real unused[%s_N > 0 ? %s_N : 1];\n", upper, upper);
    fprintf(out, "    int st = braun_scene_build(&%s_scene, sys, NULL);\n", sym);
    fprintf(out, "    if (st || (!q0 && !v0)) return st;\n");
    fprintf(out, "    return braun_scene_initial_state(&%s_scene, q0 ? q0 : unused, v0 ? v0 : unused);\n",
            sym);
    fputs("}\n", out);
    /* A file included rather than compiled alone leaves no R behind. */
    fputs("\n#undef R\n#undef RD\n", out);
    return written(out, err, err_size);
}
