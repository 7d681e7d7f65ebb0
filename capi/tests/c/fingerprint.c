/*
 * The determinism fingerprint (registry/src/fingerprint.rs) computed through the C
 * API: the same FNV-1a 64 hash over the same inputs, with every scalar and x8 call of the Rust
 * version replaced by a C call on 1 or 8 points and every slice call by one C call. It must
 * equal tests/golden/fingerprint.txt (capi/tests/c.rs compares). Slice outputs are written at
 * odd float offsets, so no output is 8-, 16- or 32-byte aligned.
 *
 * Then one line per function the fingerprint does not cover, "name hash", which
 * capi/tests/c.rs recomputes with the Rust crate.
 */
#include "warpcore.h"

#include <inttypes.h>
#include <math.h> /* NAN, INFINITY */
#include <stdio.h>
#include <string.h>

/* ---- hashing and inputs, as in fingerprint.rs ---- */

static uint64_t h;

static void word(uint32_t w) {
    for (int i = 0; i < 4; i++) {
        h = (h ^ ((w >> (8 * i)) & 0xff)) * UINT64_C(0x100000001b3);
    }
}

static uint32_t bits(float x) {
    uint32_t w;
    memcpy(&w, &x, 4);
    return w;
}

static float from_bits(uint32_t w) {
    float x;
    memcpy(&x, &w, 4);
    return x;
}

static void floats(const float *v, size_t n) {
    for (size_t i = 0; i < n; i++) word(bits(v[i]));
}

static void words4(const uint32_t *v) {
    for (size_t i = 0; i < 4; i++) word(v[i]);
}

/* 0, -0, 0.5, 1 - 2^-24, 1, -1, NaN, +inf, -inf, 1e-40, 0.25, 0.75 as bits (inputs). */
static const uint32_t SPECIAL_BITS[12] = {
    0x00000000u, 0x80000000u, 0x3f000000u, 0x3f7fffffu, 0x3f800000u, 0xbf800000u,
    0x7fc00000u, 0x7f800000u, 0xff800000u, 0x000116c2u, 0x3e800000u, 0x3f400000u,
};
#define S 12
#define N (1024 + S * S)

static float unit(uint32_t i) {
    uint32_t x = i * 747796405u + 2891336453u;
    x = ((x >> ((x >> 28) + 4u)) ^ x) * 277803737u;
    x ^= x >> 22;
    return (float)(x >> 8) * (1.0f / 16777216.0f);
}

/* Coordinate d of input point i of dimension D. */
static float input(size_t i, int D, int d) {
    if (i < S * S) {
        size_t k = d % 2 == 0 ? i % S : (i / S + (size_t)(d / 2)) % S;
        return from_bits(SPECIAL_BITS[k]);
    }
    return unit((uint32_t)(i * (size_t)D + (size_t)d));
}

static void inputs(float *dst, size_t first, size_t n, int D) {
    for (size_t k = 0; k < n; k++)
        for (int d = 0; d < D; d++) dst[k * D + d] = input(first + k, D, d);
}

/* ---- the two drivers of fingerprint.rs ---- */

typedef size_t (*warp_fn)(const float *, float *, size_t);

static size_t failures;
#define EXPECT(cond)                                                                     \
    do {                                                                                 \
        if (!(cond)) {                                                                   \
            fprintf(stderr, "%s:%d: %s\n", __FILE__, __LINE__, #cond);                   \
            failures++;                                                                  \
        }                                                                                \
    } while (0)

/* A C call standing for a scalar, x8 or slice form: `f(in, out, n)` with I -> O floats. */
typedef size_t (*four_fn)(const float *, size_t, float *, size_t);
struct warp {
    warp_fn f;
    int I, O;
    int quadrant; /* >= 0: quadrant q of `four` (wc_disk_polar4, wc_disk_concentric4) */
    four_fn four;
};

static void call(struct warp w, const float *in, float *out, size_t n) {
    if (w.quadrant < 0) {
        EXPECT(w.f(in, out, n) == n);
        return;
    }
    for (size_t k = 0; k < n; k++) {
        float four[8];
        EXPECT(w.four(in + 2 * k, 1, four, 4) == 4);
        out[2 * k] = four[2 * w.quadrant];
        out[2 * k + 1] = four[2 * w.quadrant + 1];
    }
}

/* Up to 8 floats in or out per point (the microfacet densities take 8). */
#define MAX_DIM 8

static void warp(struct warp w) {
    float in[37 * MAX_DIM], buf[1 + 37 * MAX_DIM], one[MAX_DIM];
    float *out = buf + 1; /* odd offset */
    for (size_t i = 0; i < N; i += 37) {
        size_t n = N - i < 37 ? N - i : 37;
        inputs(in, i, n, w.I);
        call(w, in, out, n);
        word((uint32_t)n);
        for (size_t k = 0; k < n; k++) {
            call(w, in + k * w.I, one, 1);
            floats(one, w.O);
            floats(out + k * w.O, w.O);
        }
    }
    for (size_t g = 0; g + 8 <= N; g += 8) {
        float in8[8 * MAX_DIM], out8[8 * MAX_DIM];
        inputs(in8, g, 8, w.I);
        call(w, in8, out8, 8);
        for (int c = 0; c < w.O; c++)
            for (int j = 0; j < 8; j++) word(bits(out8[j * w.O + c]));
    }
}

typedef size_t (*indexed_fn)(uint32_t start, uint32_t seed, float *out, size_t n, uint32_t count);

static void indexed(indexed_fn f, int O, uint32_t count) {
    static const uint32_t seeds[4] = {0u, 1u, 0x9e3779b9u, 0xffffffffu};
    static const uint32_t starts[7] = {0u, 5u, 1023u, 4090u, 65530u, 1u << 20, 0xffffffffu - 20u};
    for (int s = 0; s < 4; s++) {
        for (int t = 0; t < 7; t++) {
            uint32_t seed = seeds[s], start = starts[t];
            float buf[1 + 37 * 4], one[4];
            float *out = buf + 1;
            EXPECT(f(start, seed, out, 37, count) == 37);
            word(37);
            for (uint32_t k = 0; k < 37; k++) {
                EXPECT(f(start + k, seed, one, 1, count) == 1);
                floats(one, O);
                floats(out + k * O, O);
            }
            float lanes[8][4];
            for (uint32_t j = 0; j < 8; j++)
                EXPECT(f(start + 3u * j, seed ^ j, lanes[j], 1, count) == 1);
            for (int c = 0; c < O; c++)
                for (int j = 0; j < 8; j++) word(bits(lanes[j][c]));
        }
    }
}

static size_t pmj(uint32_t a, uint32_t s, float *o, size_t n, uint32_t c) {
    (void)c;
    return wc_pmj02bn_sample(a, s, o, n);
}

/* The sampler of fingerprint.rs's `sampler::<P>` (`c` is the WC_PATTERN_*): a slice (n > 1) is
   the points of new(...).domain(3) from index `a`; one point is new(...).domain(3) at `a`
   split(7, 4, a & 3) (the scalar and lane forms), 4D. */
static WcSampler fp_sampler(uint32_t pattern, uint32_t index, uint32_t seed) {
    return wc_sampler_domain(wc_sampler_new(pattern, seed % 641, seed >> 20, seed ^ 5, index, seed), 3);
}

static size_t samp(uint32_t a, uint32_t s, float *o, size_t n, uint32_t c) {
    if (n == 1) return wc_sampler_draw(wc_sampler_split(fp_sampler(c, a, s), 7, 4, a & 3), 4, o) / 4;
    return wc_sampler_draw_slice(fp_sampler(c, a, s), 4, o, n);
}
/* The second part of the sampler piece: domain 3 of a new_frame root (1 spp), no split (under
   the blue-noise patterns a spatiotemporal slot), one point or a slice. */
static WcSampler fp_frame_sampler(uint32_t pattern, uint32_t index, uint32_t seed) {
    return wc_sampler_domain(wc_sampler_new_frame(pattern, seed % 641, seed >> 20, seed ^ 5, 1, index, seed), 3);
}

static size_t samp_frames(uint32_t a, uint32_t s, float *o, size_t n, uint32_t c) {
    if (n == 1) return wc_sampler_draw(fp_frame_sampler(c, a, s), 4, o) / 4;
    return wc_sampler_draw_slice(fp_frame_sampler(c, a, s), 4, o, n);
}
static size_t rnd(uint32_t a, uint32_t s, float *o, size_t n, uint32_t c) {
    (void)c;
    return wc_sequence_random(a, s, o, n);
}
static size_t strat(uint32_t a, uint32_t s, float *o, size_t n, uint32_t c) {
    return wc_sequence_stratified(a, c, s, o, n);
}
static size_t basu(uint32_t a, uint32_t s, float *o, size_t n, uint32_t c) {
    (void)c;
    return wc_triangle_basu_owen(a, s, o, n);
}
static size_t basu_permuted(uint32_t a, uint32_t s, float *o, size_t n, uint32_t c) {
    (void)c;
    return wc_triangle_basu_owen_permuted(a, s, o, n);
}

static struct warp W(warp_fn f, int I, int O) {
    struct warp w = {f, I, O, -1, 0};
    return w;
}

/* Rust's `f as i32`: saturating, NaN to 0. */
static int32_t saturating_i32(float x) {
    if (x != x) return 0;
    if (x >= 2147483648.0f) return INT32_MAX;
    if (x <= -2147483904.0f) return INT32_MIN;
    return (int32_t)x;
}

/* The 13 x 7 map of the fingerprint: zeros, a negative texel, a NaN, a 10^6 : 1 texel. */
static void envmap_weights(float *w) {
    for (uint32_t k = 0; k < 91; k++) {
        switch (k) {
        case 3: case 40: case 41: w[k] = 0.0f; break;
        case 17: w[k] = -2.0f; break;
        case 60: w[k] = from_bits(0x7fc00000u); break;
        case 77: w[k] = 1.0e6f; break;
        default: w[k] = unit(k) + 0.01f;
        }
    }
}

static void hash_sample(WcEnvSample s, float pdf_at) {
    float v[4] = {s.uv[0], s.uv[1], s.pdf, pdf_at};
    floats(v, 4);
    word(s.texel[0]);
    word(s.texel[1]);
}

static void envmap(uint32_t kind) {
    static uint32_t storage[4096];
    float weights[91];
    envmap_weights(weights);
    size_t n = wc_envmap_storage_len(kind, 13, 7);
    if (n > 4096) n = 4096;
    if (wc_envmap_build(kind, weights, 13, 7, storage, n) != WC_OK) {
        failures++;
        return;
    }
    for (int pass = 0; pass < 2; pass++) { /* scalar, then the x8 groups: the same calls */
        for (size_t i = 0; i < N; i++) {
            float u[2];
            inputs(u, i, 1, 2);
            WcEnvSample s;
            float p;
            EXPECT(wc_envmap_sample(storage, n, u, &s, 1) == 1);
            EXPECT(wc_envmap_pdf(storage, n, s.uv, &p, 1) == 1);
            hash_sample(s, p);
        }
    }
}

/* ---- spherical lights: fingerprint.rs's SPHERICAL_TRIANGLES (v0, v1, v2, p) and
   SPHERICAL_RECTANGLES (corner, ex, ey, p) ---- */

#define LIGHTS 17
static const float TRIANGLES[LIGHTS][12] = {
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.1f, 0.2f, 0.0f},
    {-1.0f, -1.0f, 0.05f, 2.0f, -1.0f, 0.05f, -1.0f, 2.0f, 0.05f, 0.0f, 0.0f, 0.0f},
    {0.3f, -2.0f, 0.5f, -0.7f, 0.4f, 1.9f, 1.5f, 0.8f, -0.3f, -0.2f, 0.1f, 0.05f},
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 1.0f, 1e-5f, 1.0f, 0.3f, 0.4f, 0.0f},
    {0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f, 3.0f, 3.0f, 1.0f, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, 1e-4f, 0.0f, 1.0f, 0.0f, 1e-4f, 1.0f, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.2f, 0.2f, 1.0f},
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 5.0f, -3.0f, 1.0f},
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.2f, 0.2f, 0.999999f},
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 3e5f, -2e5f, 1e6f},
    {-1e5f, 0.0f, 1e6f, 1e5f, -1e5f, 1e6f, 0.0f, 1e5f, 1e6f, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 1.0f, 0.0f, 1.0f},
    {0.0f, 0.0f, 1e30f, 1e30f, 0.0f, 1e30f, 0.0f, 1e30f, 1e30f, 1e29f, 2e29f, 0.0f},
    {0.0f, 0.0f, 1e-30f, 1e-30f, 0.0f, 1e-30f, 0.0f, 1e-30f, 1e-30f, 1e-31f, 2e-31f, 0.0f},
    {NAN, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.0f, INFINITY, 0.0f},
    {-3e38f, 0.0f, 1.0f, 3e38f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f},
};
static const float RECTANGLES[LIGHTS][12] = {
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.1f, 0.2f, 0.0f},
    {0.3f, -0.2f, 0.7f, 0.6f, 0.8f, 0.0f, 0.0f, 0.0f, 1.5f, 0.0f, 0.0f, 0.0f},
    {-50.0f, -50.0f, 0.01f, 100.0f, 0.0f, 0.0f, 0.0f, 100.0f, 0.0f, 0.0f, 0.0f, 0.0f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1e-6f, 0.0f, 0.0f, 0.0f, 0.0f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, 5e-5f, 0.0f, 0.0f, 0.0f, 5e-5f, 0.0f, 0.0f, 0.0f, 0.0f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 3.0f, 0.5f, 1.0f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.1f, 0.1f, 0.999999f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 2e5f, -1e5f, -1e6f},
    {-1e5f, -1e5f, 1e6f, 2e5f, 0.0f, 0.0f, 0.0f, 2e5f, 0.0f, 0.0f, 0.0f, 0.0f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.3f, 1.0f, 0.0f, 0.2f, -0.1f, 2.5f},
    {-0.5f, -0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, -0.5f, -0.5f, 1.0f},
    {-5e29f, -5e29f, 1e30f, 1e30f, 0.0f, 0.0f, 0.0f, 1e30f, 0.0f, 1e29f, 0.0f, 0.0f},
    {-5e-31f, -5e-31f, 1e-30f, 1e-30f, 0.0f, 0.0f, 0.0f, 1e-30f, 0.0f, 0.0f, 0.0f, 0.0f},
    {-0.5f, -0.5f, 1.0f, 1.0f, NAN, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f},
    {-INFINITY, 0.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f},
};

typedef size_t (*light_fn)(const float *light, const float *in, float *out, size_t n);

/* fingerprint.rs's SPHERICAL_CONES: centre, [radius, 0, 0], -, p (the C functions take the
   7 floats centre, radius, p). */
static const float CONES[LIGHTS][12] = {
    {0.0f, 0.0f, 3.0f, 1.0f, 0, 0, 0, 0, 0, 0.1f, 0.2f, 0.0f},
    {1.0f, -2.0f, 5.0f, 3e-3f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {0.3f, 0.4f, 2.0f, 3.6e-5f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, 0.999f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 2.0f, 2.0f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {0.1f, 0.2f, 0.3f, 2.0f, 0, 0, 0, 0, 0, -0.5f, 0.4f, 0.0f},
    {5.0f, 5.0f, 5.0f, 1.0f, 0, 0, 0, 0, 0, 5.0f, 5.0f, 5.0f},
    {0.0f, 3.0f, 4.0f, 0.0f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {-1.0f, 0.5f, -2.0f, -0.5f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {0.0f, 3.0f, 4.0f, 5e-25f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {3e5f, -2e5f, 1e6f, 10.0f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {1e30f, 2e30f, -1e30f, 5e29f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {1e-30f, 2e-30f, -1e-30f, 5e-31f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, 1e30f, 0, 0, 0, 0, 0, 1e29f, -3e29f, 0.0f},
    {0.0f, 0.0f, 0.0f, 0.0f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {NAN, 0.0f, 1.0f, 0.5f, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
    {0.0f, 0.0f, 1.0f, INFINITY, 0, 0, 0, 0, 0, 0.0f, 0.0f, 0.0f},
};
/* A 12-float cone light as the 7 floats the C functions take. */
static void sphere7(const float *l, float *s) {
    for (int k = 0; k < 4; k++) s[k] = l[k];
    for (int k = 0; k < 3; k++) s[4 + k] = l[9 + k];
}
static size_t cone12(const float *l, const float *in, float *out, size_t n) {
    float s[7];
    sphere7(l, s);
    return wc_spherical_cone(s, in, out, n);
}
static size_t cone_inverse12(const float *l, const float *in, float *out, size_t n) {
    float s[7];
    sphere7(l, s);
    return wc_spherical_cone_inverse(s, in, out, n);
}
static float cone_solid_angle12(const float *l) {
    float s[7];
    sphere7(l, s);
    return wc_spherical_cone_solid_angle(s);
}



/* fingerprint.rs's `lights`: for each light l, the slice over all inputs in chunks of 37 and
   one call per input; then the lane forms as single calls, input i with light (l + i) % 17. */
static void lights(const float (*ls)[12], light_fn f, int I, int O) {
    for (size_t l = 0; l < LIGHTS; l++) {
        float in[37 * 3], buf[1 + 37 * 4], one[4];
        float *out = buf + 1; /* odd offset */
        for (size_t i = 0; i < N; i += 37) {
            size_t n = N - i < 37 ? N - i : 37;
            inputs(in, i, n, I);
            EXPECT(f(ls[l], in, out, n) == n);
            word((uint32_t)n);
            for (size_t k = 0; k < n; k++) {
                EXPECT(f(ls[l], in + k * I, one, 1) == 1);
                floats(one, O);
                floats(out + k * O, O);
            }
        }
        for (size_t g = 0; g + 8 <= N; g += 8) {
            float u[3], out8[8 * 4];
            for (size_t j = 0; j < 8; j++) {
                inputs(u, g + j, 1, I);
                EXPECT(f(ls[(l + g + j) % LIGHTS], u, out8 + j * O, 1) == 1);
            }
            for (int c = 0; c < O; c++)
                for (int j = 0; j < 8; j++) word(bits(out8[j * O + c]));
        }
    }
}

/* fingerprint.rs's `solid_angles`: every light, then lane j of group g holding light
   (g + j) % 17, for 16 lanes and g < 17. */
static void solid_angles(const float (*ls)[12], float (*f)(const float *)) {
    for (size_t l = 0; l < LIGHTS; l++) word(bits(f(ls[l])));
    for (size_t g = 0; g < LIGHTS; g++)
        for (size_t j = 0; j < 16; j++) word(bits(f(ls[(g + j) % LIGHTS])));
}

static uint64_t fingerprint(void) {
    h = UINT64_C(0xcbf29ce484222325);
    /* disk */
    warp(W(wc_disk_polar, 2, 2));
    warp(W(wc_disk_concentric, 2, 2));
    warp(W(wc_disk_polar_inverse, 2, 2));
    warp(W(wc_disk_concentric_inverse, 2, 2));
    for (int q = 0; q < 4; q++) {
        struct warp w = {0, 2, 2, q, wc_disk_polar4};
        warp(w);
    }
    for (int q = 0; q < 4; q++) {
        struct warp w = {0, 2, 2, q, wc_disk_concentric4};
        warp(w);
    }
    for (size_t i = 0; i < N; i++) {
        float p[2], u[2];
        uint32_t q;
        inputs(p, i, 1, 2);
        EXPECT(wc_disk_concentric4_inverse(p, u, &q, 1) == 1);
        floats(u, 2);
        word(q);
    }
    {
        float pts[9 * 2], out[35 * 2];
        inputs(pts, 0, 9, 2);
        word((uint32_t)wc_disk_polar4(pts, 9, out, 35));
        floats(out, 35 * 2);
        word((uint32_t)wc_disk_concentric4(pts, 9, out, 35));
        floats(out, 35 * 2);
    }
    /* pmj02bn */
    indexed(pmj, 2, 0);
    {
        static const uint32_t raw[4][2] = {{0, 0}, {1, 1}, {3, 4095}, {7, 1u << 30}};
        for (int k = 0; k < 4; k++) {
            uint32_t w[2];
            EXPECT(wc_pmj02bn_raw(raw[k][0], raw[k][1], w, 1) == 1);
            word(w[0]);
            word(w[1]);
        }
    }
    /* sampler: every pattern, then draw_u32 and rnd of 64 split states, then a new_frame slot */
    for (uint32_t p = 0; p < 4; p++) {
        indexed(samp, 4, p);
        for (uint32_t k = 0; k < 64; k++) {
            uint32_t index = k * 0x9e3779b9u, w[4];
            float r[4];
            WcSampler s = wc_sampler_split(fp_sampler(p, index, k), 7, 4, index & 3);
            EXPECT(wc_sampler_draw_u32(s, 4, w) == 4 && wc_sampler_rnd(s, 4, r) == 4);
            words4(w);
            floats(r, 4);
        }
        indexed(samp_frames, 4, p);
    }
    /* sequence */
    indexed(rnd, 2, 0);
    {
        static const uint32_t counts[4] = {1, 16, 17, 1024};
        for (int k = 0; k < 4; k++) indexed(strat, 2, counts[k]);
    }
    /* triangle */
    warp(W(wc_triangle_uniform, 2, 3));
    warp(W(wc_triangle_uniform_inverse, 3, 2));
    warp(W(wc_triangle_sqrt_map, 2, 3));
    warp(W(wc_triangle_sqrt_map_inverse, 3, 2));
    indexed(basu, 3, 0);
    indexed(basu_permuted, 3, 0);
    /* sphere */
    warp(W(wc_sphere_equal_area, 2, 3));
    warp(W(wc_sphere_equal_area_inverse, 3, 2));
    warp(W(wc_sphere_equal_area_wrap, 2, 2));
    warp(W(wc_sphere_equirect, 2, 3));
    warp(W(wc_sphere_equirect_inverse, 3, 2));
    warp(W(wc_sphere_uniform, 2, 3));
    warp(W(wc_sphere_uniform_inverse, 3, 2));
    warp(W(wc_sphere_uniform_hemisphere, 2, 3));
    warp(W(wc_sphere_uniform_hemisphere_inverse, 3, 2));
    warp(W(wc_sphere_cosine_hemisphere, 2, 3));
    warp(W(wc_sphere_cosine_hemisphere_inverse, 3, 2));
    for (size_t i = 0; i < N; i++) {
        float d[3], p, t[2], v[3];
        inputs(d, i, 1, 3);
        inputs(&p, i, 1, 1);
        EXPECT(wc_sphere_equirect_pdf_to_solid_angle(&p, d, &v[0], 1) == 1);
        EXPECT(wc_sphere_equal_area_pdf_to_solid_angle(&p, &v[1], 1) == 1);
        EXPECT(wc_sphere_cosine_hemisphere_pdf(&p, &v[2], 1) == 1);
        floats(v, 3);
        inputs(t, i, 1, 2);
        int32_t texel[2];
        uint32_t wrapped[2];
        for (int c = 0; c < 2; c++)
            texel[c] = (int32_t)((uint32_t)saturating_i32(t[c] * 64.0f) - 16u);
        EXPECT(wc_sphere_equal_area_wrap_texel(texel, 32, wrapped, 1) == 1);
        word(wrapped[0]);
        word(wrapped[1]);
    }
    /* envmap */
    envmap(WC_ENVMAP_KIND_MARGINAL_CONDITIONAL);
    envmap(WC_ENVMAP_KIND_HIERARCHICAL);
    /* spherical */
    lights(TRIANGLES, wc_spherical_triangle, 2, 4);
    lights(TRIANGLES, wc_spherical_triangle_inverse, 3, 2);
    solid_angles(TRIANGLES, wc_spherical_triangle_solid_angle);
    lights(RECTANGLES, wc_spherical_rectangle, 2, 3);
    lights(RECTANGLES, wc_spherical_rectangle_inverse, 2, 2);
    solid_angles(RECTANGLES, wc_spherical_rectangle_solid_angle);
    return h;
}

/* ---- functions the fingerprint does not cover: one hash each, named by the registry entry
   whose piece computes the same (registry/src/fingerprint.rs) ---- */

static void line(const char *name) { printf("%s %016" PRIx64 "\n", name, h); }

static void extras(void) {
    static float in[N * 3], out[N * 3];
    static uint32_t idx[N], wout[N];

    h = UINT64_C(0xcbf29ce484222325);
    inputs(in, 0, N, 2);
    EXPECT(wc_disk_polar4_inverse(in, out, wout, N) == N);
    for (size_t i = 0; i < N; i++) {
        floats(out + 2 * i, 2);
        word(wout[i]);
    }
    line("disk::polar4_inverse");

    h = UINT64_C(0xcbf29ce484222325);
    for (size_t i = 0; i < N; i++) idx[i] = (uint32_t)i * 2654435761u;
    EXPECT(wc_pmj02bn_shuffle(idx, 0xabcdu, wout, N) == N);
    for (size_t i = 0; i < N; i++) word(wout[i]);
    word((uint32_t)wc_pmj02bn_points());
    word((uint32_t)wc_pmj02bn_sets());
    line("pmj02bn::shuffle");

    h = UINT64_C(0xcbf29ce484222325);
    lights(CONES, cone12, 2, 4);
    line("spherical::cone");
    h = UINT64_C(0xcbf29ce484222325);
    lights(CONES, cone_inverse12, 3, 2);
    line("spherical::cone_inverse");
    h = UINT64_C(0xcbf29ce484222325);
    solid_angles(CONES, cone_solid_angle12);
    line("spherical::cone_solid_angle");

    h = UINT64_C(0xcbf29ce484222325);
    inputs(in, 0, N, 3);
    EXPECT(wc_envmap_luminance(in, out, N) == N);
    floats(out, N);
    line("envmap::image::luminance");

    h = UINT64_C(0xcbf29ce484222325);
    {
        float pdf[N], v[N];
        for (size_t i = 0; i < N; i++) {
            pdf[i] = input(i, 2, 0);
            v[i] = input(i, 2, 1);
        }
        EXPECT(wc_envmap_equirect_pdf_to_solid_angle(pdf, v, out, N) == N);
        floats(out, N);
    }
    line("envmap::image::equirect_pdf_to_solid_angle");

    h = UINT64_C(0xcbf29ce484222325);
    {
        float w[91];
        envmap_weights(w);
        EXPECT(wc_envmap_equirect_solid_angle_weights(w, 13, 7) == WC_OK);
        floats(w, 91);
        /* A 13 x 7 RGB image resampled to 8 x 8 equal-area texels, 3 x 3 supersampling. */
        float rgb[91 * 3], dst[64 * 3];
        inputs(rgb, 200, 91, 3);
        EXPECT(wc_envmap_equirect_to_equal_area(rgb, 13, 7, 3, dst, 8, 3) == WC_OK);
        floats(dst, 64 * 3);
    }
    line("envmap::image::equirect_solid_angle_weights");

    /* The marginal-conditional storage words (the hierarchical ones depend on the buffer's
       address modulo 64, by design), then the storage lengths. */
    h = UINT64_C(0xcbf29ce484222325);
    {
        float w[91];
        static uint32_t storage[4096];
        envmap_weights(w);
        size_t n = wc_envmap_storage_len(WC_ENVMAP_KIND_MARGINAL_CONDITIONAL, 13, 7);
        EXPECT(wc_envmap_build(WC_ENVMAP_KIND_MARGINAL_CONDITIONAL, w, 13, 7, storage, n) == WC_OK);
        EXPECT(wc_envmap_from_storage_verified(storage, n) == WC_OK);
        for (size_t i = 0; i < n; i++) word(storage[i]);
    }
    line("envmap::MarginalConditional::new");

    h = UINT64_C(0xcbf29ce484222325);
    word((uint32_t)wc_envmap_storage_len(WC_ENVMAP_KIND_MARGINAL_CONDITIONAL, 13, 7));
    word((uint32_t)wc_envmap_storage_len(WC_ENVMAP_KIND_HIERARCHICAL, 13, 7));
    word((uint32_t)wc_envmap_storage_len(WC_ENVMAP_KIND_HIERARCHICAL, 4096, 2048));
    line("envmap::MarginalConditional::storage_len");

    /* microfacet: each function's map piece (slice in chunks of 37 against one-point calls,
       then groups of 8), as registry/src/fingerprint.rs `map` hashes its entry. */
    static const struct {
        const char *name;
        warp_fn f;
        int I, O;
    } MICROFACET[] = {
        {"microfacet::ggx_d", wc_microfacet_ggx_d, 5, 1},
        {"microfacet::ggx_g1", wc_microfacet_ggx_g1, 5, 1},
        {"microfacet::ggx_g2", wc_microfacet_ggx_g2, 8, 1},
        {"microfacet::ggx_visible_normal", wc_microfacet_ggx_visible_normal, 7, 3},
        {"microfacet::ggx_visible_normal_pdf", wc_microfacet_ggx_visible_normal_pdf, 8, 1},
        {"microfacet::ggx_reflect", wc_microfacet_ggx_reflect, 7, 4},
        {"microfacet::ggx_reflect_pdf", wc_microfacet_ggx_reflect_pdf, 8, 1},
        {"microfacet::ggx_reflect_bounded", wc_microfacet_ggx_reflect_bounded, 7, 4},
        {"microfacet::ggx_reflect_bounded_pdf", wc_microfacet_ggx_reflect_bounded_pdf, 8, 1},
    };
    for (size_t k = 0; k < sizeof MICROFACET / sizeof MICROFACET[0]; k++) {
        h = UINT64_C(0xcbf29ce484222325);
        warp(W(MICROFACET[k].f, MICROFACET[k].I, MICROFACET[k].O));
        line(MICROFACET[k].name);
    }
}

int main(void) {
    printf("fingerprint %016" PRIx64 "\n", fingerprint());
    extras();
    printf("%zu failed\n", failures);
    return failures == 0 ? 0 : 1;
}
