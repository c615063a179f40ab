/* The libFuzzer entry points each target defines. The same sources build
 * two ways: with clang and -fsanitize=fuzzer as fuzzers (JC_FUZZ), and with
 * any compiler and replay.c as corpus replays that ctest runs in every
 * build, the sanitizer build included. */
#ifndef JC_FUZZ_H
#define JC_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* An invariant the code under test must keep: a violation is a finding, so
 * it stops the run the way a crash does, with the reason on stderr. */
#define FUZZ_CHECK(cond)                                                                \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            fprintf(stderr, "%s:%d: invariant violated: %s\n", __FILE__, __LINE__, #cond); \
            abort();                                                                    \
        }                                                                               \
    } while (0)

#endif
