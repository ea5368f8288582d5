/* A scene's texts (its name, description, element names) printed where
 * people and scripts read them: the terminal (progress and summary lines),
 * `braun check`'s "key: value" lines, a picture's titles. The file is not
 * trusted: a control byte is shown as \xNN and a backslash as \\, so a
 * name cannot add a line (a forged "n: 999"), move the cursor (CR) or
 * colour the terminal (ESC [31m). The one rule for every such place. */
#include <stdio.h>

#include "braun_cli.h"

const char *braun_cli_text_byte(unsigned char c, char *buf)
{
    if (c < 0x20 || c == 0x7f) snprintf(buf, 5, "\\x%02X", c);
    else if (c == '\\') buf[0] = '\\', buf[1] = '\\', buf[2] = '\0';
    else buf[0] = (char)c, buf[1] = '\0';
    return buf;
}

void braun_cli_put_text(FILE *f, const char *s)
{
    char buf[5];
    for (const unsigned char *p = (const unsigned char *)(s ? s : ""); *p; p++)
        fputs(braun_cli_text_byte(*p, buf), f);
}
