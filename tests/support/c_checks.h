/* Checks for the C API's tests (tests/test_c_api.c, tests/test_c_weather.c): each failed check prints where and
 * why and counts into g_failures, which the test's main returns. Include it after the gusuku C header the test
 * exercises (gusuku_result_name and gusuku_last_error_message come from there). */
#ifndef GUSUKU_TESTS_C_CHECKS_H
#define GUSUKU_TESTS_C_CHECKS_H

#include <stdio.h>

static int g_failures = 0;

#define CHECK(condition)                                                                                          \
    do {                                                                                                          \
        if (!(condition)) {                                                                                       \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #condition);                         \
            ++g_failures;                                                                                         \
        }                                                                                                         \
    } while (0)

#define CHECK_RESULT(call, expected)                                                                              \
    do {                                                                                                          \
        gusuku_result result_ = (call);                                                                           \
        if (result_ != (expected)) {                                                                              \
            fprintf(stderr, "%s:%d: %s returned %s, expected %s (%s)\n", __FILE__, __LINE__, #call,               \
                    gusuku_result_name(result_), gusuku_result_name(expected), gusuku_last_error_message());      \
            ++g_failures;                                                                                         \
        }                                                                                                         \
    } while (0)

#endif
