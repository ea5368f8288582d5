/* A scene's texts (its name, description, element names) printed where
 * people and scripts read them: the terminal (progress and summary lines),
 * `braun check`'s "key: value" lines, a picture's titles. The file is not
 * trusted: a control byte is shown as \xNN and a backslash as \\, so a
 * name cannot add a line (a forged "n: 999"), move the cursor (CR) or
 * colour the terminal (ESC [31m, or the C1 CSI U+009B). The one rule for
 * every such place. */
#include <stdio.h>
#include <string.h>

#include "braun_cli.h"

const char *braun_cli_text_byte(unsigned char c, char *buf)
{
    if (c < 0x20 || c == 0x7f) snprintf(buf, 5, "\\x%02X", c);
    else if (c == '\\') buf[0] = '\\', buf[1] = '\\', buf[2] = '\0';
    else buf[0] = (char)c, buf[1] = '\0';
    return buf;
}

/* The C1 controls too (U+0080–U+009F, UTF-8 C2 80–C2 9F): U+009B is a CSI
 * to a terminal that takes 8-bit controls, as ESC [ is to every one. Shown
 * as \u00NN. */
void braun_cli_put_text(FILE *f, const char *s)
{
    char buf[8];
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++) {
        if (p[0] == 0xC2 && p[1] >= 0x80 && p[1] <= 0x9F) {
            snprintf(buf, sizeof buf, "\\u%04X", p[1]);
            fputs(buf, f);
            p++;
            continue;
        }
        fputs(braun_cli_text_byte(*p, buf), f);
    }
}

void braun_cli_mask_controls(char *s)
{
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || *s == 0x7f) *s = '?';
}

const char *braun_cli_status_name(int status, char *buf, size_t size)
{
    const char *s = braun_status_str(status);
    size_t len = strcspn(s, ":");
    if (len >= size) len = size - 1;
    memcpy(buf, s, len);
    buf[len] = '\0';
    return buf;
}
