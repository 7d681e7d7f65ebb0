/*
 * The sampler through the C API (capi/tests/c.rs compiles and runs this).
 *
 * 1. One line "name hash" per hash of capi/examples/sampler_hashes.rs: the same cases (every
 *    pattern, six roots, domain paths with and without splits) and the same FNV-1a 64 over the
 *    same words, computed here with C calls; the Rust test compares each with the crate's.
 * 2. The promises and rules, checked from C: draw == (draw_u32 >> 8) * 2^-24, values in
 *    [0, 1 - 2^-24], slices == scalar draws at consecutive indices (wrapping, any float
 *    offset), the index field set directly, every error return (n outside 1..=4, n = 0,
 *    count = 0, null, misaligned, overflowing counts, unknown patterns, garbage structs) with
 *    nothing written. Prints "N passed, M failed" last; exits nonzero on a failure.
 */
#include "warpcore.h"

#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "check.h"

/* ---- FNV-1a 64 over little-endian words, as sampler_hashes.rs ---- */

static uint64_t h;

static void word(uint32_t w) {
    for (int i = 0; i < 4; i++) h = (h ^ ((w >> (8 * i)) & 0xff)) * UINT64_C(0x100000001b3);
}

static uint32_t bits(float x) {
    uint32_t w;
    memcpy(&w, &x, 4);
    return w;
}

static void floats(const float *v, size_t n) {
    for (size_t i = 0; i < n; i++) word(bits(v[i]));
}

static void words(const uint32_t *v, size_t n) {
    for (size_t i = 0; i < n; i++) word(v[i]);
}

/* ---- the cases of sampler_hashes.rs ---- */

static const uint32_t ROOTS[6][5] = {
    {0, 0, 0, 0, 0},
    {5, 7, 1, 3, 0},
    {63, 64, 2, 1023, 42},
    {65535, 1, 7, 4096, 0x9e3779b9u},
    {70000, 123456, 0xffffffffu, 0xfffffff0u, 0xffffffffu},
    {0xffffffffu, 0xfffffffeu, 12345, 65536, 1},
};
#define NROOTS 6
#define SLICE 37
static const char *const PATTERNS[4] = {"pmj02bn", "sobol", "blue_pmj02bn", "blue_sobol"};

static WcSampler root(uint32_t pattern, int r) {
    const uint32_t *a = ROOTS[r];
    return wc_sampler_new(pattern, a[0], a[1], a[2], a[3], a[4]);
}

/* The domain-key paths [], [0], [7, 0xffffffff]. */
static WcSampler key_path(WcSampler s, int p) {
    if (p == 1) return wc_sampler_domain(s, 0);
    if (p == 2) return wc_sampler_domain(wc_sampler_domain(s, 7), 0xffffffffu);
    return s;
}

/* The paths with splits. */
static WcSampler split_path(WcSampler s, int p) {
    if (p == 0) return wc_sampler_split(s, 3, 4, 1);
    if (p == 1) return wc_sampler_domain(wc_sampler_split(s, 9, 0, 5), 2);
    return wc_sampler_split(wc_sampler_domain(s, 1), 0xffffffffu, 0xffffffffu, 0xfffffffeu);
}

/* The new_frame roots (samples per frame per root) and the paths below them. */
static const uint32_t FRAME_SPP[6] = {1, 4, 1, 3, 0, 4};

static WcSampler frame_root(uint32_t pattern, int r) {
    const uint32_t *a = ROOTS[r];
    return wc_sampler_new_frame(pattern, a[0], a[1], a[2], FRAME_SPP[r], a[3], a[4]);
}

static WcSampler frame_path(WcSampler s, int p) {
    if (p == 0) return wc_sampler_domain(s, 0);
    if (p == 1) return wc_sampler_split(wc_sampler_domain(s, 5), 3, 4, 1);
    return wc_sampler_domain(wc_sampler_domain(s, 6), 0);
}

static void state(WcSampler s) {
    word(s.pattern);
    word(s.pixel);
    word(s.domain);
    word(s.index);
}

/* wc_sampler_draw or wc_sampler_rnd for 1 to 4 dimensions. */
static void draws(WcSampler s, size_t (*draw)(WcSampler, size_t, float *)) {
    for (size_t n = 1; n <= 4; n++) {
        float v[4];
        CHECK(draw(s, n, v) == n);
        floats(v, n);
    }
}

static void draws_u32(WcSampler s) {
    for (size_t n = 1; n <= 4; n++) {
        uint32_t v[4];
        CHECK(wc_sampler_draw_u32(s, n, v) == n);
        words(v, n);
    }
}

static void slices(WcSampler s) {
    for (size_t n = 1; n <= 4; n++) {
        float v[4 * SLICE];
        CHECK(wc_sampler_draw_slice(s, n, v, SLICE) == SLICE);
        floats(v, n * SLICE);
    }
}

static void hashes(void) {
    static const char *const WHAT[5] = {"state", "draw", "draw_u32", "rnd", "slice"};
    for (uint32_t pattern = 0; pattern < 4; pattern++) {
        for (int what = 0; what < 5; what++) {
            h = UINT64_C(0xcbf29ce484222325);
            for (int r = 0; r < NROOTS; r++) {
                for (int p = 0; p < 3; p++) {
                    WcSampler s = key_path(root(pattern, r), p);
                    switch (what) {
                    case 0: state(s); break;
                    case 1: draws(s, wc_sampler_draw); break;
                    case 2: draws_u32(s); break;
                    case 3: draws(s, wc_sampler_rnd); break;
                    default: slices(s); break;
                    }
                }
            }
            printf("sampler_%s_%s %016" PRIx64 "\n", PATTERNS[pattern], WHAT[what], h);
        }
        for (int st = 0; st < 2; st++) {
            h = UINT64_C(0xcbf29ce484222325);
            for (int r = 0; r < NROOTS; r++) {
                for (int p = 0; p < 3; p++) {
                    WcSampler s = split_path(root(pattern, r), p);
                    if (st) {
                        state(s);
                        continue;
                    }
                    draws(s, wc_sampler_draw);
                    draws_u32(s);
                    draws(s, wc_sampler_rnd);
                    slices(s);
                }
            }
            printf("sampler_%s_split%s %016" PRIx64 "\n", PATTERNS[pattern], st ? "_state" : "", h);
        }
        h = UINT64_C(0xcbf29ce484222325);
        for (int r = 0; r < NROOTS; r++) {
            for (int p = 0; p < 3; p++) {
                WcSampler s = frame_path(frame_root(pattern, r), p);
                draws(s, wc_sampler_draw);
                draws_u32(s);
                draws(s, wc_sampler_rnd);
                slices(s);
            }
        }
        printf("sampler_%s_frames %016" PRIx64 "\n", PATTERNS[pattern], h);
    }
}

/* ---- promises ---- */

static int same_bits(const float *a, const float *b, size_t n) {
    return memcmp(a, b, n * sizeof(float)) == 0;
}

static int in_range(const float *v, size_t n) {
    for (size_t i = 0; i < n; i++)
        if (!(v[i] >= 0.0f && v[i] <= 1.0f - 1.0f / 16777216.0f)) return 0;
    return 1;
}

/* Every sampler of a pattern's paths: the draw/draw_u32 identity, ranges, and slices (at
   float offsets 0..3 of a buffer, starting at an index near the wrap) against scalar draws. */
static void promises(void) {
    static float buf[4 * 80 + 4];
    for (uint32_t pattern = 0; pattern < 4; pattern++) {
        for (int r = 0; r < NROOTS; r++) {
            for (int p = 0; p < 6; p++) {
                WcSampler s = p < 3 ? key_path(root(pattern, r), p) : split_path(root(pattern, r), p - 3);
                for (size_t n = 1; n <= 4; n++) {
                    float f[4], g[4];
                    uint32_t w[4];
                    int ok = 1;
                    CHECK(wc_sampler_draw(s, n, f) == n && wc_sampler_draw_u32(s, n, w) == n);
                    for (size_t d = 0; d < n; d++)
                        ok &= bits(f[d]) == bits((float)(w[d] >> 8) * (1.0f / 16777216.0f));
                    CHECK(ok);
                    CHECK(in_range(f, n));
                    CHECK(wc_sampler_rnd(s, n, g) == n && in_range(g, n));
                    /* Pure: the same call gives the same bits. */
                    CHECK(wc_sampler_draw(s, n, g) == n && same_bits(f, g, n));
                }
                /* Slices: index fields 0, 1000 and UINT32_MAX - 40 (the slice wraps). */
                const uint32_t starts[3] = {0, 1000, 0xffffffffu - 40};
                for (int k = 0; k < 3; k++) {
                    WcSampler t = s;
                    t.index = starts[k];
                    for (size_t n = 1; n <= 4; n++) {
                        size_t off = (n + (size_t)k) % 4, count = 80 - (size_t)k;
                        float *out = buf + off;
                        int ok = 1;
                        CHECK(wc_sampler_draw_slice(t, n, out, count) == count);
                        for (size_t i = 0; i < count; i++) {
                            WcSampler u = t;
                            float v[4];
                            u.index = starts[k] + (uint32_t)i;
                            ok &= wc_sampler_draw(u, n, v) == n && same_bits(v, out + i * n, n);
                        }
                        CHECK(ok);
                        CHECK(in_range(out, n * count));
                    }
                }
            }
        }
    }
}

/* ---- error returns: nothing written ---- */

#define SENTINEL 0x5au
static unsigned char area[4 * 64 + 16];

static float *scratch(size_t off) {
    memset(area, SENTINEL, sizeof area);
    return (float *)(void *)(area + off);
}

static int untouched(void) {
    for (size_t i = 0; i < sizeof area; i++)
        if (area[i] != SENTINEL) return 0;
    return 1;
}

static int same_sampler(WcSampler a, WcSampler b) {
    return a.pattern == b.pattern && a.pixel == b.pixel && a.domain == b.domain && a.index == b.index;
}

/* Every draw of `s` refuses to write, whatever the count and pointer. */
static void refuses(WcSampler s) {
    for (size_t n = 0; n <= 5; n++) {
        CHECK(wc_sampler_draw(s, n, scratch(0)) == 0 && untouched());
        CHECK(wc_sampler_draw_u32(s, n, (uint32_t *)(void *)scratch(0)) == 0 && untouched());
        CHECK(wc_sampler_rnd(s, n, scratch(0)) == 0 && untouched());
        CHECK(wc_sampler_draw_slice(s, n, scratch(0), 16) == 0 && untouched());
    }
}

static void errors(void) {
    WcSampler good = wc_sampler_domain(wc_sampler_new(WC_PATTERN_SOBOL, 3, 4, 0, 9, 0), 1);
    size_t n;
    /* The patterns of this build (every one: the default features). */
    CHECK(wc_sampler_pattern_supported(WC_PATTERN_PMJ02BN) == 1);
    CHECK(wc_sampler_pattern_supported(WC_PATTERN_SOBOL) == 1);
    CHECK(wc_sampler_pattern_supported(WC_PATTERN_BLUE_PMJ02BN) == 1);
    CHECK(wc_sampler_pattern_supported(WC_PATTERN_BLUE_SOBOL) == 1);
    CHECK(wc_sampler_pattern_supported(4) == 0);
    CHECK(wc_sampler_pattern_supported(0xffffffffu) == 0);

    /* Dimension counts outside 1..=4, including ones that would overflow a byte size. */
    const size_t bad_n[] = {0, 5, 8, 64, SIZE_MAX / 4 + 1, SIZE_MAX};
    for (size_t k = 0; k < sizeof bad_n / sizeof bad_n[0]; k++) {
        n = bad_n[k];
        CHECK(wc_sampler_draw(good, n, scratch(0)) == 0 && untouched());
        CHECK(wc_sampler_draw_u32(good, n, (uint32_t *)(void *)scratch(0)) == 0 && untouched());
        CHECK(wc_sampler_rnd(good, n, scratch(0)) == 0 && untouched());
        CHECK(wc_sampler_draw_slice(good, n, scratch(0), 3) == 0 && untouched());
    }
    /* Null and misaligned outputs. */
    for (n = 1; n <= 4; n++) {
        CHECK(wc_sampler_draw(good, n, NULL) == 0);
        CHECK(wc_sampler_draw_u32(good, n, NULL) == 0);
        CHECK(wc_sampler_rnd(good, n, NULL) == 0);
        CHECK(wc_sampler_draw_slice(good, n, NULL, 5) == 0);
        for (size_t off = 1; off < 4; off++) {
            CHECK(wc_sampler_draw(good, n, scratch(off)) == 0 && untouched());
            CHECK(wc_sampler_draw_u32(good, n, (uint32_t *)(void *)scratch(off)) == 0 && untouched());
            CHECK(wc_sampler_rnd(good, n, scratch(off)) == 0 && untouched());
            CHECK(wc_sampler_draw_slice(good, n, scratch(off), 5) == 0 && untouched());
        }
        /* Slices: count 0, and counts whose byte size overflows. */
        CHECK(wc_sampler_draw_slice(good, n, scratch(0), 0) == 0 && untouched());
        CHECK(wc_sampler_draw_slice(good, n, NULL, 0) == 0);
        CHECK(wc_sampler_draw_slice(good, n, scratch(0), SIZE_MAX) == 0 && untouched());
        CHECK(wc_sampler_draw_slice(good, n, scratch(0), SIZE_MAX / n) == 0 && untouched());
        /* The valid calls write exactly n (or count * n) values. */
        float *out = scratch(4);
        CHECK(wc_sampler_draw(good, n, out) == n);
        CHECK(area[4 + 4 * n] == SENTINEL && area[3] == SENTINEL);
        out = scratch(4);
        CHECK(wc_sampler_draw_slice(good, n, out, 7) == 7);
        CHECK(area[4 + 4 * 7 * n] == SENTINEL && area[3] == SENTINEL);
    }

    /* Unknown patterns: new gives {pattern, 0, 0, 0}; domain and split return the sampler
       unchanged; every draw refuses. Also blue-noise-sized garbage in every other field. */
    const uint32_t unknown[] = {4, 5, 255, 0x80000000u, 0xffffffffu};
    for (size_t k = 0; k < sizeof unknown / sizeof unknown[0]; k++) {
        WcSampler s = wc_sampler_new(unknown[k], 1, 2, 3, 4, 5);
        WcSampler zero = {0, 0, 0, 0};
        zero.pattern = unknown[k];
        CHECK(same_sampler(s, zero));
        WcSampler garbage = {0, 0xdeadbeefu, 0x12345678u, 0xffffffffu};
        garbage.pattern = unknown[k];
        CHECK(same_sampler(wc_sampler_domain(garbage, 7), garbage));
        CHECK(same_sampler(wc_sampler_split(garbage, 7, 4, 3), garbage));
        CHECK(same_sampler(wc_sampler_split(wc_sampler_domain(s, 1), 2, 0, 9), s));
        refuses(s);
        refuses(garbage);
        refuses(wc_sampler_domain(garbage, 3));
    }

    /* Garbage in the other fields of a known pattern is some sampler: it draws, in range. */
    uint32_t x = 12345;
    for (int i = 0; i < 400; i++) {
        WcSampler s;
        x = x * 1664525u + 1013904223u;
        s.pattern = x % 4;
        x = x * 1664525u + 1013904223u;
        s.pixel = x;
        x = x * 1664525u + 1013904223u;
        s.domain = x;
        x = x * 1664525u + 1013904223u;
        s.index = x;
        s = wc_sampler_split(s, x, x >> 3, x >> 7);
        float v[4 * 9];
        CHECK(wc_sampler_draw(s, 4, v) == 4 && in_range(v, 4));
        CHECK(wc_sampler_rnd(s, 4, v) == 4 && in_range(v, 4));
        CHECK(wc_sampler_draw_slice(s, 4, v, 9) == 9 && in_range(v, 36));
    }

    /* Setting the index field is Rust's with_index: the same point as a fresh root. */
    {
        WcSampler a = wc_sampler_domain(wc_sampler_new(WC_PATTERN_BLUE_SOBOL, 9, 9, 2, 0, 7), 4);
        WcSampler b = wc_sampler_domain(wc_sampler_new(WC_PATTERN_BLUE_SOBOL, 9, 9, 2, 77, 7), 4);
        a.index = 77;
        CHECK(same_sampler(a, b));
    }
}

int main(void) {
    hashes();
    promises();
    errors();
    printf("%d passed, %d failed\n", passed, failed);
    return failed != 0;
}
