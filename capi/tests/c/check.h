/*
 * The checks of the C test programs rules.c and sampler.c: CHECK(cond) counts a pass, or a
 * failure with the condition printed to stderr; the program prints "N passed, M failed" last
 * (capi/tests/c.rs reads that line). Include after <stdio.h>.
 */
#ifndef WARPCORE_TEST_CHECK_H
#define WARPCORE_TEST_CHECK_H

static int passed, failed;
#define CHECK(cond)                                                                      \
    do {                                                                                 \
        if (cond) {                                                                      \
            passed++;                                                                    \
        } else {                                                                         \
            failed++;                                                                    \
            fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond);     \
        }                                                                                \
    } while (0)

#endif
