/*
 * A tiny test runner in the style of Box2D's tests: a test is a function
 * `static int test_x(void)` that returns 0 on success; ENSURE* print what
 * failed and return 1 from the test. RUN_TEST counts, TEST_MAIN_END prints
 * "N passed, N failed" and gives the process its exit status.
 */
#ifndef JC_TEST_H
#define JC_TEST_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int jc_test_passed_count, jc_test_failed_count;

#define ENSURE(cond)                                                                    \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            fprintf(stderr, "%s:%d: ENSURE(%s) failed\n", __FILE__, __LINE__, #cond);   \
            return 1;                                                                   \
        }                                                                               \
    } while (0)

/* Like ENSURE, with a printf-style explanation (the values that matter). */
#define ENSURE_MSG(cond, ...)                                                           \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            fprintf(stderr, "%s:%d: ENSURE(%s) failed: ", __FILE__, __LINE__, #cond);   \
            fprintf(stderr, __VA_ARGS__);                                               \
            fputc('\n', stderr);                                                        \
            return 1;                                                                   \
        }                                                                               \
    } while (0)

/* |a - b| <= abs_tol; NaN never passes. */
#define ENSURE_NEAR(a, b, abs_tol)                                                      \
    do {                                                                                \
        const double ens_a_ = (a), ens_b_ = (b), ens_t_ = (abs_tol);                    \
        if (!(fabs(ens_a_ - ens_b_) <= ens_t_)) {                                       \
            fprintf(stderr,                                                             \
                    "%s:%d: ENSURE_NEAR(%s, %s) failed: %.17g vs %.17g, |diff| %.3g > " \
                    "tol %.3g\n",                                                       \
                    __FILE__, __LINE__, #a, #b, ens_a_, ens_b_, fabs(ens_a_ - ens_b_),  \
                    ens_t_);                                                            \
            return 1;                                                                   \
        }                                                                               \
    } while (0)

/* |a - b| <= rel_tol * max(|a|, |b|); NaN never passes. */
#define ENSURE_REL(a, b, rel_tol)                                                       \
    do {                                                                                \
        const double ens_a_ = (a), ens_b_ = (b), ens_t_ = (rel_tol);                    \
        const double ens_s_ = fmax(fabs(ens_a_), fabs(ens_b_));                         \
        if (!(fabs(ens_a_ - ens_b_) <= ens_t_ * ens_s_)) {                              \
            fprintf(stderr,                                                             \
                    "%s:%d: ENSURE_REL(%s, %s) failed: %.17g vs %.17g, rel diff %.3g > " \
                    "tol %.3g\n",                                                       \
                    __FILE__, __LINE__, #a, #b, ens_a_, ens_b_,                         \
                    ens_s_ > 0 ? fabs(ens_a_ - ens_b_) / ens_s_ : 0.0, ens_t_);         \
            return 1;                                                                   \
        }                                                                               \
    } while (0)

/* A library call that must succeed; prints its message otherwise. */
#define ENSURE_OK(call, err)                                                            \
    do {                                                                                \
        const int ens_st_ = (call);                                                     \
        if (ens_st_ != 0) {                                                             \
            fprintf(stderr, "%s:%d: %s returned %d: %s\n", __FILE__, __LINE__, #call,   \
                    ens_st_, (err));                                                    \
            return 1;                                                                   \
        }                                                                               \
    } while (0)

#define RUN_TEST(fn)                                                                    \
    do {                                                                                \
        if ((fn)() == 0) {                                                              \
            ++jc_test_passed_count;                                                     \
            printf("passed: %s\n", #fn);                                                \
        } else {                                                                        \
            ++jc_test_failed_count;                                                     \
            printf("FAILED: %s\n", #fn);                                                \
        }                                                                               \
        fflush(stdout);                                                                 \
    } while (0)

/* The last statement of main(). */
#define TEST_MAIN_END()                                                                 \
    do {                                                                                \
        printf("%d passed, %d failed\n", jc_test_passed_count, jc_test_failed_count);   \
        return jc_test_failed_count != 0;                                               \
    } while (0)

#endif
