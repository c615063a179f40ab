/* Bad values of one field of a validated struct, each checked as a case of
 * its own: one line lists a field and every value it must refuse.
 *
 * The including file defines bad_case (with the members what, key and
 * value) and check_bad(const bad_case *), which asserts that the case is
 * refused with a message naming key and showing value (NULL: not checked).
 * BAD_VALUES(start, field, key, {v, "shown"}, ...) checks, for each value,
 * the case `start` with `field` set to v. The fields are doubles: an int or
 * enum field is set by hand (-Wconversion). */
#ifndef JC_TESTS_BAD_VALUES_H
#define JC_TESTS_BAD_VALUES_H

#include <stdio.h>

typedef struct {
    double v;
    const char *shown; /* how the message must show v (NULL: not checked) */
} bad_value;

#define BAD_VALUES(start, field, key_text, ...)                                          \
    do {                                                                                  \
        const bad_value bad_values_[] = {__VA_ARGS__};                                    \
        for (size_t i_ = 0; i_ < sizeof bad_values_ / sizeof bad_values_[0]; ++i_) {      \
            char label_[128];                                                             \
            snprintf(label_, sizeof label_, "%s = %g", #field, bad_values_[i_].v);        \
            bad_case c_ = start;                                                          \
            c_.what = label_;                                                             \
            c_.key = key_text;                                                            \
            c_.value = bad_values_[i_].shown;                                             \
            c_.field = bad_values_[i_].v;                                                 \
            if (check_bad(&c_)) return 1;                                                 \
        }                                                                                 \
    } while (0)

#endif
