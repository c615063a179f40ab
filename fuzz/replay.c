/* Replays fuzz inputs through a target's LLVMFuzzerTestOneInput without
 * libFuzzer: every file named, and every file in every directory named
 * (the corpus, crash regressions included). Exit 0 when all ran; a crash or
 * a violated invariant aborts, as under the fuzzer. */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include <dirent.h>
#include <string.h>
#include <sys/stat.h>

/* Largest input replayed: libFuzzer's default -max_len is far below. */
#define REPLAY_MAX_BYTES (1 << 20)

static int replay_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay: cannot read %s\n", path);
        return -1;
    }
    uint8_t *buf = malloc(REPLAY_MAX_BYTES);
    const size_t n = buf ? fread(buf, 1, REPLAY_MAX_BYTES, f) : 0;
    const int bad = !buf || ferror(f);
    fclose(f);
    if (!bad) {
        /* A copy of exactly n bytes, so that reading past the input is caught
         * by the sanitizers as it would be under libFuzzer. */
        uint8_t *exact = malloc(n ? n : 1);
        if (exact) {
            memcpy(exact, buf, n);
            LLVMFuzzerTestOneInput(exact, n);
            free(exact);
        }
    }
    free(buf);
    return bad ? -1 : 0;
}

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* The files of a directory in name order, so that runs are reproducible. */
static int replay_dir(const char *dir, int *count)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "replay: cannot open %s\n", dir);
        return -1;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    int bad = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (e->d_name[0] == '.') continue;
        if (n == cap) {
            const size_t bigger = cap ? 2 * cap : 64;
            char **more = realloc(names, bigger * sizeof *names);
            if (!more) {
                bad = 1;
                break;
            }
            names = more;
            cap = bigger;
        }
        names[n] = malloc(strlen(dir) + strlen(e->d_name) + 2);
        if (!names[n]) {
            bad = 1;
            break;
        }
        sprintf(names[n], "%s/%s", dir, e->d_name);
        ++n;
    }
    closedir(d);
    qsort(names, n, sizeof *names, by_name);
    for (size_t i = 0; i < n; ++i) {
        struct stat st;
        if (!bad && stat(names[i], &st) == 0 && S_ISREG(st.st_mode)) {
            bad |= replay_file(names[i]) != 0;
            ++*count;
        }
        free(names[i]);
    }
    free(names);
    return bad ? -1 : 0;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s CORPUS_DIR_OR_FILE...\n", argv[0]);
        return 2;
    }
    LLVMFuzzerInitialize(&argc, &argv);
    int count = 0, bad = 0;
    for (int i = 1; i < argc; ++i) {
        struct stat st;
        if (stat(argv[i], &st) == 0 && S_ISDIR(st.st_mode)) {
            bad |= replay_dir(argv[i], &count) != 0;
        } else {
            bad |= replay_file(argv[i]) != 0;
            ++count;
        }
    }
    printf("%d input(s) replayed%s\n", count, bad ? ", some could not be read" : "");
    return bad;
}
