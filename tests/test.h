/*
 * A tiny test runner in the style of Box2D's tests: a test is a function
 * `static int test_x(void)` that returns 0 on success; ENSURE* print what
 * failed and return 1 from the test. RUN_TEST counts and prints each test's
 * time, TEST_MAIN_END prints "N passed, N failed" and gives the process its
 * exit status.
 */
#ifndef JC_TEST_H
#define JC_TEST_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int jc_test_passed_count, jc_test_failed_count;

/* Every ENSURE* failure: "file:line: ", a head, the printf-style rest and a
 * newline on stderr; then the test returns 1. */
#define ENSURE_FAIL_(head, ...)                                                         \
    do {                                                                                \
        fprintf(stderr, "%s:%d: %s", __FILE__, __LINE__, head);                         \
        fprintf(stderr, __VA_ARGS__);                                                   \
        fputc('\n', stderr);                                                            \
        return 1;                                                                       \
    } while (0)

#define ENSURE(cond)                                                                    \
    do {                                                                                \
        if (!(cond)) ENSURE_FAIL_("ENSURE(" #cond ") failed", "%s", "");                \
    } while (0)

/* Like ENSURE, with a printf-style explanation (the values that matter). */
#define ENSURE_MSG(cond, ...)                                                           \
    do {                                                                                \
        if (!(cond)) ENSURE_FAIL_("ENSURE(" #cond ") failed: ", __VA_ARGS__);           \
    } while (0)

/* |a - b| <= abs_tol; NaN never passes. */
#define ENSURE_NEAR(a, b, abs_tol)                                                      \
    do {                                                                                \
        const double ens_a_ = (a), ens_b_ = (b), ens_t_ = (abs_tol);                    \
        if (!(fabs(ens_a_ - ens_b_) <= ens_t_))                                         \
            ENSURE_FAIL_("ENSURE_NEAR(" #a ", " #b ") failed: ",                        \
                         "%.17g vs %.17g, |diff| %.3g > tol %.3g", ens_a_, ens_b_,      \
                         fabs(ens_a_ - ens_b_), ens_t_);                                \
    } while (0)

/* |a - b| <= rel_tol * max(|a|, |b|); NaN never passes. */
#define ENSURE_REL(a, b, rel_tol)                                                       \
    do {                                                                                \
        const double ens_a_ = (a), ens_b_ = (b), ens_t_ = (rel_tol);                    \
        const double ens_s_ = fmax(fabs(ens_a_), fabs(ens_b_));                         \
        if (!(fabs(ens_a_ - ens_b_) <= ens_t_ * ens_s_))                                \
            ENSURE_FAIL_("ENSURE_REL(" #a ", " #b ") failed: ",                         \
                         "%.17g vs %.17g, rel diff %.3g > tol %.3g", ens_a_, ens_b_,    \
                         ens_s_ > 0 ? fabs(ens_a_ - ens_b_) / ens_s_ : 0.0, ens_t_);    \
    } while (0)

/* A library call that must succeed; prints its message otherwise. */
#define ENSURE_OK(call, err)                                                            \
    do {                                                                                \
        const int ens_st_ = (call);                                                     \
        if (ens_st_ != 0) ENSURE_FAIL_(#call, " returned %d: %s", ens_st_, (err));      \
    } while (0)

/* Deterministic pseudo-random numbers (xorshift64*), uniform in [lo, hi),
 * from the caller's state: each test seeds its own (a fixed, portable stream). */
static inline double test_uniform(uint64_t *state, double lo, double hi)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    const uint64_t x = *state * 2685821657736338717ull;
    return lo + (hi - lo) * (double)(x >> 11) * (1.0 / 9007199254740992.0);
}

/* Which tests of an executable run (tests/CMakeLists.txt splits a long
 * executable into several ctest tests this way): JC_TESTS, names of test
 * functions separated by spaces or commas, runs only those; JC_TESTS_SKIP
 * runs all but those. A name in either that the executable does not have
 * fails the run, so that a renamed test cannot drop out unseen. */
static int jc_test_named_seen_count;

/* Whether name is a word of the list (spaces or commas between words). */
static inline int jc_test_listed(const char *list, const char *name)
{
    const size_t n = strlen(name);
    for (const char *p = list; p && *p;) {
        p += strspn(p, " ,");
        const size_t len = strcspn(p, " ,");
        if (len == n && strncmp(p, name, n) == 0) return 1;
        p += len;
    }
    return 0;
}

/* The number of words of a list. */
static inline int jc_test_list_count(const char *list)
{
    int count = 0;
    for (const char *p = list; p && *p;) {
        p += strspn(p, " ,");
        const size_t len = strcspn(p, " ,");
        count += len > 0;
        p += len;
    }
    return count;
}

/* Whether the test named name runs; counts the names listed that were seen. */
static inline int jc_test_selected(const char *name)
{
    const char *only = getenv("JC_TESTS"), *skip = getenv("JC_TESTS_SKIP");
    const int in_only = jc_test_listed(only, name), in_skip = jc_test_listed(skip, name);
    jc_test_named_seen_count += in_only + in_skip;
    if (in_skip) return 0;
    return !only || !*only || in_only;
}

/* Seconds on a steady enough clock (C11 timespec_get), for the time each test takes. */
static inline double jc_test_now_s(void)
{
    struct timespec t;
    if (timespec_get(&t, TIME_UTC) != TIME_UTC) return 0.0;
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

#define RUN_TEST(fn)                                                                    \
    do {                                                                                \
        if (!jc_test_selected(#fn)) break;                                              \
        const double run_test_t0_ = jc_test_now_s();                                    \
        if ((fn)() == 0) {                                                              \
            ++jc_test_passed_count;                                                     \
            printf("passed: %s (%.2f s)\n", #fn, jc_test_now_s() - run_test_t0_);       \
        } else {                                                                        \
            ++jc_test_failed_count;                                                     \
            printf("FAILED: %s (%.2f s)\n", #fn, jc_test_now_s() - run_test_t0_);       \
        }                                                                               \
        fflush(stdout);                                                                 \
    } while (0)

/* The last statement of main(). */
#define TEST_MAIN_END()                                                                 \
    do {                                                                                \
        const int tme_named_ = jc_test_list_count(getenv("JC_TESTS")) +                 \
                               jc_test_list_count(getenv("JC_TESTS_SKIP"));             \
        if (jc_test_named_seen_count != tme_named_) {                                   \
            ++jc_test_failed_count;                                                     \
            printf("FAILED: JC_TESTS '%s' or JC_TESTS_SKIP '%s' names a test this "     \
                   "executable does not have\n", getenv("JC_TESTS") ? getenv("JC_TESTS") : "", \
                   getenv("JC_TESTS_SKIP") ? getenv("JC_TESTS_SKIP") : "");             \
        }                                                                               \
        if (jc_test_passed_count + jc_test_failed_count == 0) {                         \
            ++jc_test_failed_count;                                                     \
            printf("FAILED: no test ran\n");                                            \
        }                                                                               \
        printf("%d passed, %d failed\n", jc_test_passed_count, jc_test_failed_count);   \
        return jc_test_failed_count != 0;                                               \
    } while (0)

#endif
