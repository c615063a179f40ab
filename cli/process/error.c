/* The tool's error messages: "jumpcyl: <msg>" on stderr, one line each. */
#include "process.h"

#include <stdarg.h>
#include <stdio.h>

/* One line, whatever the message quotes: a value with a line break or a
 * control character (from a file or an argument) is shown with '?' in its
 * place, so that the message stays one line and cannot drive the terminal. */
void cli_error(const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    for (char *c = msg; *c; ++c)
        if ((unsigned char)*c < 0x20 || *c == 0x7f) *c = '?';
    fprintf(stderr, "jumpcyl: %s\n", msg);
}
