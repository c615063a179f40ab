/* Fuzz target: output file names, through the functions that stand between
 * a user's name and the programs that must never read it as code: the safe
 * name a kept script writes to (cli_safe_name), gnuplot quoting (fig_quote),
 * shell quoting for printed commands and script comments (cli_shell_word),
 * and the path helpers. No program is run per input.
 *
 * Invariants: a safe name is non-empty, starts with a letter or digit and
 * holds only letters, digits, '.', '_', '+', '-', and is its own safe
 * name; a gnuplot-quoted name is one line and reads back to the name (line
 * breaks as spaces); a shell word has no control character and reads back
 * to the name (control characters as '?'); an absolute path starts with '/'. */
#include "fuzz.h"

#include "figures.h"

#include <string.h>

#define MAX_NAME 4095

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

static int plain(unsigned char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

static void check_safe_name(const char *name)
{
    char safe[256], again[256];
    cli_safe_name(name, safe, sizeof safe);
    FUZZ_CHECK(safe[0] != '\0' && plain((unsigned char)safe[0]));
    for (const char *p = safe; *p; ++p)
        FUZZ_CHECK(plain((unsigned char)*p) || *p == '.' || *p == '_' || *p == '+' || *p == '-');
    cli_safe_name(safe, again, sizeof again);
    FUZZ_CHECK(strcmp(safe, again) == 0);
}

/* What a quoting function writes for name, in memory (free it). */
static char *quoted(void (*quote)(FILE *, const char *), const char *name, size_t *len)
{
    char *buf = NULL;
    FILE *m = open_memstream(&buf, len);
    FUZZ_CHECK(m != NULL);
    quote(m, name);
    fclose(m);
    FUZZ_CHECK(buf != NULL);
    return buf;
}

/* 'text' with '' for a quote: what gnuplot reads in single quotes. */
static void check_gnuplot_quote(const char *name)
{
    size_t len = 0;
    char *buf = quoted(fig_quote, name, &len);
    FUZZ_CHECK(len >= 2 && buf[0] == '\'' && buf[len - 1] == '\'');
    size_t k = 0;
    for (size_t i = 1; i + 1 < len; ++i, ++k) {
        FUZZ_CHECK(buf[i] != '\n');
        if (buf[i] == '\'') {
            FUZZ_CHECK(i + 2 < len && buf[i + 1] == '\''); /* a lone quote would end the string */
            ++i;
        }
        const char want = name[k] == '\n' ? ' ' : name[k];
        FUZZ_CHECK(name[k] != '\0' && buf[i] == want);
    }
    FUZZ_CHECK(name[k] == '\0');
    free(buf);
}

/* A word of the shell: bare, or '...' pieces joined by \' . */
static void check_shell_word(const char *name)
{
    size_t len = 0;
    char *buf = quoted(cli_shell_word, name, &len);
    char *read = malloc(len + 1);
    FUZZ_CHECK(read != NULL);
    size_t n = 0;
    int in_quotes = 0;
    for (size_t i = 0; i < len; ++i) {
        const unsigned char c = (unsigned char)buf[i];
        FUZZ_CHECK(c >= 0x20 && c != 0x7f);
        if (!in_quotes && c == '\\') {
            FUZZ_CHECK(i + 1 < len && buf[i + 1] == '\'');
            read[n++] = buf[++i];
        } else if (c == '\'') {
            in_quotes = !in_quotes;
        } else {
            /* Outside quotes only characters the shell takes literally. */
            FUZZ_CHECK(in_quotes || strchr(" \t\"$`\\|&;<>()*?[]#~{}!", c) == NULL);
            read[n++] = (char)c;
        }
    }
    FUZZ_CHECK(!in_quotes);
    read[n] = '\0';
    size_t k = 0;
    for (; name[k]; ++k) {
        const unsigned char c = (unsigned char)name[k];
        FUZZ_CHECK(read[k] == (c < 0x20 || c == 0x7f ? '?' : (char)c));
    }
    FUZZ_CHECK(read[k] == '\0');
    free(read);
    free(buf);
}

static void check_paths(const char *name)
{
    char dir[CLI_PATH_MAX], stem[CLI_PATH_MAX], abs_path[2 * CLI_PATH_MAX];
    if (cli_path_split(name, dir, sizeof dir, stem, sizeof stem) == 0) FUZZ_CHECK(dir[0] != '\0');
    (void)cli_path_ext(name);
    if (name[0] && cli_path_absolute(name, abs_path, sizeof abs_path) == 0) FUZZ_CHECK(abs_path[0] == '/');
    fig_Format f;
    if (fig_format_from_path(name, &f) == 0) FUZZ_CHECK(f == FIG_PNG || f == FIG_SVG || f == FIG_PDF);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char name[MAX_NAME + 1];
    const size_t n = size < MAX_NAME ? size : MAX_NAME;
    memcpy(name, data, n);
    name[n] = '\0'; /* a name ends at its first NUL, as in argv */
    check_safe_name(name);
    check_gnuplot_quote(name);
    check_shell_word(name);
    check_paths(name);
    return 0;
}
