/*
 * The C API's rules, checked from C: n = 0, null pointers, misaligned and unaligned pointers,
 * in-place and overlapping arrays, huge counts, the environment-map errors (invalid and
 * truncated storage, garbage tables), and a storage written to a file and read back at
 * another alignment. Prints "N passed, M failed"; exits nonzero on a failure.
 */
#include "warpcore.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "check.h"

#define SENTINEL 0x5au
#define BIG 1024

static unsigned char bytes[8 * BIG * 4 + 64];

/* All bytes still the sentinel? */
static int untouched(const void *p, size_t n) {
    const unsigned char *b = (const unsigned char *)p;
    for (size_t i = 0; i < n; i++)
        if (b[i] != SENTINEL) return 0;
    return 1;
}

static float in2[BIG * 2], in3[BIG * 3];

static uint32_t lcg(uint32_t *s) {
    *s = *s * 1664525u + 1013904223u;
    return *s;
}

static float rnd(uint32_t *s) { return (float)(lcg(s) >> 8) * (1.0f / 16777216.0f); }

typedef size_t (*warp_fn)(const float *, float *, size_t);
struct warp {
    const char *name;
    warp_fn f;
    int I, O;
};

static const struct warp WARPS[] = {
    {"disk_polar", wc_disk_polar, 2, 2},
    {"disk_polar_inverse", wc_disk_polar_inverse, 2, 2},
    {"disk_concentric", wc_disk_concentric, 2, 2},
    {"disk_concentric_inverse", wc_disk_concentric_inverse, 2, 2},
    {"triangle_uniform", wc_triangle_uniform, 2, 3},
    {"triangle_uniform_inverse", wc_triangle_uniform_inverse, 3, 2},
    {"triangle_sqrt_map", wc_triangle_sqrt_map, 2, 3},
    {"triangle_sqrt_map_inverse", wc_triangle_sqrt_map_inverse, 3, 2},
    {"sphere_equal_area", wc_sphere_equal_area, 2, 3},
    {"sphere_equal_area_inverse", wc_sphere_equal_area_inverse, 3, 2},
    {"sphere_equal_area_wrap", wc_sphere_equal_area_wrap, 2, 2},
    {"sphere_equirect", wc_sphere_equirect, 2, 3},
    {"sphere_equirect_inverse", wc_sphere_equirect_inverse, 3, 2},
    {"sphere_uniform", wc_sphere_uniform, 2, 3},
    {"sphere_uniform_inverse", wc_sphere_uniform_inverse, 3, 2},
    {"sphere_uniform_hemisphere", wc_sphere_uniform_hemisphere, 2, 3},
    {"sphere_uniform_hemisphere_inverse", wc_sphere_uniform_hemisphere_inverse, 3, 2},
    {"sphere_cosine_hemisphere", wc_sphere_cosine_hemisphere, 2, 3},
    {"sphere_cosine_hemisphere_inverse", wc_sphere_cosine_hemisphere_inverse, 3, 2},
    {"envmap_luminance", wc_envmap_luminance, 3, 1},
    {"sphere_equal_area_pdf_to_solid_angle", wc_sphere_equal_area_pdf_to_solid_angle, 1, 1},
    {"sphere_cosine_hemisphere_pdf", wc_sphere_cosine_hemisphere_pdf, 1, 1},
};
#define NWARPS (sizeof WARPS / sizeof WARPS[0])

/* A pointer `off` bytes into the scratch area, filled with the sentinel. Offsets that are not
   multiples of 4 make pointers no valid C float array has: the library must reject them. */
static float *scratch(size_t off) {
    memset(bytes, SENTINEL, sizeof bytes);
    return (float *)(void *)(bytes + off);
}

static void warps(void) {
    static float ref[BIG * 3], buf[BIG * 3 + 16];
    const size_t counts[] = {1, 7, 8, 63, 64, 65, 200, BIG};
    for (size_t w = 0; w < NWARPS; w++) {
        struct warp W = WARPS[w];
        const float *in = W.I == 2 ? in2 : in3;
        /* Reference: aligned output. */
        CHECK(W.f(in, ref, BIG) == BIG);
        /* Any count, at any float offset (4-byte aligned, otherwise unaligned): same bits. */
        for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
            for (size_t off = 0; off < 16; off += 5) {
                size_t n = counts[c];
                float *out = buf + off;
                memset(buf, 0, sizeof buf);
                CHECK(W.f(in, out, n) == n);
                CHECK(memcmp(out, ref, n * W.O * sizeof(float)) == 0);
                /* ... and nothing past the n outputs. */
                CHECK(off + n * W.O >= BIG * 3 || out[n * W.O] == 0.0f);
            }
        }
        /* Inputs at any float offset too. */
        {
            static float shifted[BIG * 3 + 8];
            memcpy(shifted + 3, in, 100 * W.I * sizeof(float));
            CHECK(W.f(shifted + 3, buf, 100) == 100);
            CHECK(memcmp(buf, ref, 100 * W.O * sizeof(float)) == 0);
        }
        /* n = 0, null pointers, misaligned pointers: 0, nothing written. */
        float *out = scratch(0);
        CHECK(W.f(in, out, 0) == 0 && untouched(out, 64));
        CHECK(W.f(NULL, out, 5) == 0 && untouched(out, 64));
        CHECK(W.f(in, NULL, 5) == 0);
        CHECK(W.f(NULL, NULL, 0) == 0);
        for (size_t off = 1; off < 4; off++) {
            out = scratch(off);
            CHECK(W.f(in, out, 5) == 0 && untouched(bytes, sizeof bytes));
            out = scratch(0);
            CHECK(W.f((const float *)(const void *)((const unsigned char *)in + off), out, 5) == 0);
            CHECK(untouched(bytes, sizeof bytes));
        }
        /* A count whose size overflows: 0, nothing written. */
        out = scratch(0);
        CHECK(W.f(in, out, SIZE_MAX) == 0 && untouched(bytes, sizeof bytes));
        /* In place works when the output is no larger than the input; other overlaps are
           refused. */
        memcpy(buf, in, BIG * W.I * sizeof(float));
        if (W.O <= W.I) {
            CHECK(W.f(buf, buf, BIG) == BIG);
            CHECK(memcmp(buf, ref, BIG * W.O * sizeof(float)) == 0);
        } else {
            CHECK(W.f(buf, buf, BIG) == 0);
            CHECK(memcmp(buf, in, BIG * W.I * sizeof(float)) == 0);
        }
        memcpy(buf, in, BIG * W.I * sizeof(float));
        CHECK(W.f(buf, buf + 1, 100) == 0);
        CHECK(W.f(buf + 1, buf, 100) == 0);
        CHECK(memcmp(buf, in, BIG * W.I * sizeof(float)) == 0);
    }
}

typedef size_t (*gen_fn)(uint32_t, uint32_t, float *, size_t);
static size_t strat64(uint32_t a, uint32_t s, float *o, size_t n) {
    return wc_sequence_stratified(a, 64, s, o, n);
}

static void generators(void) {
    const struct {
        gen_fn f;
        int O;
    } G[] = {{wc_pmj02bn_sample, 2},
             {wc_sequence_random, 2},
             {strat64, 2},
             {wc_triangle_basu_owen, 3},
             {wc_triangle_basu_owen_permuted, 3}};
    static float ref[BIG * 3], buf[BIG * 3 + 8];
    for (size_t g = 0; g < sizeof G / sizeof G[0]; g++) {
        CHECK(G[g].f(100, 7, ref, BIG) == BIG);
        /* Piecewise calls at odd offsets agree with one call (index start + i). */
        size_t done = 0;
        while (done < BIG) {
            size_t n = done % 3 == 0 ? 61 : 130;
            if (n > BIG - done) n = BIG - done;
            CHECK(G[g].f(100 + (uint32_t)done, 7, buf + 1, n) == n);
            CHECK(memcmp(buf + 1, ref + done * G[g].O, n * G[g].O * sizeof(float)) == 0);
            done += n;
        }
        /* Indices wrap after UINT32_MAX. */
        CHECK(G[g].f(UINT32_MAX - 1, 7, buf, 4) == 4);
        CHECK(G[g].f(0, 7, buf + 16, 2) == 2);
        CHECK(memcmp(buf + 2 * G[g].O, buf + 16, 2 * G[g].O * sizeof(float)) == 0);
        float *out = scratch(0);
        CHECK(G[g].f(0, 7, out, 0) == 0 && untouched(bytes, sizeof bytes));
        CHECK(G[g].f(0, 7, NULL, 9) == 0);
        CHECK(G[g].f(0, 7, scratch(2), 9) == 0 && untouched(bytes, sizeof bytes));
        CHECK(G[g].f(0, 7, scratch(0), SIZE_MAX) == 0 && untouched(bytes, sizeof bytes));
    }
    /* raw and shuffle. */
    uint32_t r[8], idx[4] = {0, 1, 2, 3}, sh[4];
    CHECK(wc_pmj02bn_raw(0, 0, r, 4) == 4);
    CHECK(wc_pmj02bn_raw(0, 0, NULL, 4) == 0);
    CHECK(wc_pmj02bn_raw(0, 0, (uint32_t *)(void *)(bytes + 1), 4) == 0);
    CHECK(wc_pmj02bn_shuffle(idx, 3, sh, 4) == 4);
    CHECK(wc_pmj02bn_shuffle(idx, 3, idx, 4) == 4 && memcmp(idx, sh, sizeof sh) == 0);
    CHECK(wc_pmj02bn_shuffle(NULL, 3, sh, 4) == 0);
    CHECK(wc_pmj02bn_points() >= 1024 && wc_pmj02bn_sets() >= 1);
    /* Points are in [0, 1). */
    static float p[BIG * 2];
    CHECK(wc_pmj02bn_sample(0, 0, p, BIG) == BIG);
    int inside = 1;
    for (size_t i = 0; i < 2 * BIG; i++) inside &= p[i] >= 0.0f && p[i] < 1.0f;
    CHECK(inside);
}

static void disk_extras(void) {
    float pts[6] = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f}, out[32], one[8];
    /* n is capped at 4 n_points; sample i uses point i / 4, quadrant i % 4. */
    CHECK(wc_disk_polar4(pts, 3, out, 100) == 12);
    CHECK(wc_disk_polar4(pts, 3, out, 5) == 5);
    CHECK(wc_disk_polar4(pts + 2, 1, one, 4) == 4);
    CHECK(wc_disk_polar4(pts, 3, out, 12) == 12 && memcmp(out + 8, one, sizeof one) == 0);
    CHECK(wc_disk_polar4(pts, 0, out, 4) == 0);
    CHECK(wc_disk_polar4(NULL, 3, out, 4) == 0);
    CHECK(wc_disk_polar4(pts, 3, NULL, 4) == 0);
    CHECK(wc_disk_polar4(pts, 3, (float *)pts, 4) == 0); /* overlap */
    /* polar4_inverse recovers the point and the quadrant. */
    uint32_t q[12];
    float u[24];
    CHECK(wc_disk_polar4_inverse(out, u, q, 12) == 12);
    int ok = 1;
    for (int i = 0; i < 12; i++) {
        ok &= q[i] == (uint32_t)(i % 4);
        ok &= u[2 * i] - pts[2 * (i / 4)] < 1e-6f && pts[2 * (i / 4)] - u[2 * i] < 1e-6f;
    }
    CHECK(ok);
    CHECK(wc_disk_polar4_inverse(out, u, NULL, 12) == 0);
    CHECK(wc_disk_polar4_inverse(out, u, (uint32_t *)(void *)u, 12) == 0);
    float copy[24];
    memcpy(copy, out, sizeof copy);
    CHECK(wc_disk_polar4_inverse(copy, copy, q, 12) == 12 && memcmp(copy, u, sizeof copy) == 0);
    /* concentric4: the same counts and rules; its inverse recovers the point and quadrant. */
    CHECK(wc_disk_concentric4(pts, 3, out, 100) == 12);
    CHECK(wc_disk_concentric4(pts + 2, 1, one, 4) == 4);
    CHECK(wc_disk_concentric4(pts, 3, out, 12) == 12 && memcmp(out + 8, one, sizeof one) == 0);
    CHECK(wc_disk_concentric4(pts, 0, out, 4) == 0 && wc_disk_concentric4(NULL, 3, out, 4) == 0);
    CHECK(wc_disk_concentric4(pts, 3, (float *)pts, 4) == 0);
    CHECK(wc_disk_concentric4_inverse(out, u, q, 12) == 12);
    ok = 1;
    for (int i = 0; i < 12; i++) {
        ok &= q[i] == (uint32_t)(i % 4);
        for (int c = 0; c < 2; c++) {
            float e = u[2 * i + c] - pts[2 * (i / 4) + c];
            ok &= e < 1e-6f && e > -1e-6f;
        }
    }
    CHECK(ok);
    CHECK(wc_disk_concentric4_inverse(out, u, NULL, 12) == 0);
    /* wrap_texel. */
    int32_t t[4] = {-1, 5, 40, -70};
    uint32_t wt[4];
    CHECK(wc_sphere_equal_area_wrap_texel(t, 32, wt, 2) == 2 && wt[0] < 32 && wt[1] < 32);
    CHECK(wc_sphere_equal_area_wrap_texel(t, 0, wt, 2) == 0);
    /* Two-input conversions. */
    float pdf[2] = {1.0f, 2.0f}, d[6] = {1, 0, 0, 0, 0, 1}, v[2] = {0.5f, 0.0f}, o[2];
    CHECK(wc_sphere_equirect_pdf_to_solid_angle(pdf, d, o, 2) == 2 && o[0] > 0 && o[1] == 0);
    CHECK(wc_sphere_equirect_pdf_to_solid_angle(pdf, d, d, 2) == 0);
    CHECK(wc_sphere_equirect_pdf_to_solid_angle(pdf, NULL, o, 2) == 0);
    CHECK(wc_envmap_equirect_pdf_to_solid_angle(pdf, v, o, 2) == 2 && o[0] > 0 && o[1] == 0);
    CHECK(wc_envmap_equirect_pdf_to_solid_angle(pdf, v, v, 2) == 0);
    CHECK(wc_envmap_equirect_pdf_to_solid_angle(pdf, v, o, 0) == 0);
}

/* ---- environment maps ---- */

#define W 37
#define H 19
static float weights[W * H];
static uint32_t storage[64 * 1024], other[64 * 1024], loaded[64 * 1024 + 16];
static float us[BIG * 2];
static WcEnvSample ref[BIG], got[BIG];

static int in_map(const WcEnvSample *s, size_t n) {
    for (size_t i = 0; i < n; i++) {
        if (s[i].texel[0] >= W || s[i].texel[1] >= H) return 0;
        if (!(s[i].uv[0] >= 0.0f && s[i].uv[0] < 1.0f && s[i].uv[1] >= 0.0f && s[i].uv[1] < 1.0f))
            return 0;
        if (!(s[i].pdf >= 0.0f && s[i].pdf <= 3.4e38f)) return 0;
    }
    return 1;
}

/* `kind`, its format tag as bytes, and the other kind. */
static void envmap(uint32_t kind, const char *tag, uint32_t other_kind) {
    size_t need = wc_envmap_storage_len(kind, W, H);
    CHECK(need > WC_ENVMAP_HEADER_WORDS && need < 64 * 1024);
    CHECK(wc_envmap_storage_len(kind, 0, 5) == 0 && wc_envmap_storage_len(kind, 5, 0) == 0);
    CHECK(wc_envmap_storage_len(kind, 1u << 24, 1u << 24) == SIZE_MAX && wc_envmap_storage_len(kind, (1u << 24) + 1, 1) == SIZE_MAX);
    CHECK(wc_envmap_storage_len(2, W, H) == SIZE_MAX && wc_envmap_storage_len(UINT32_MAX, 0, 5) == SIZE_MAX);

    /* Build errors; nothing written on argument errors. */
    memset(storage, SENTINEL, sizeof storage);
    CHECK(wc_envmap_build(2, weights, W, H, storage, need) == WC_ERR_INVALID_ARGUMENT); /* unknown kind */
    CHECK(wc_envmap_build_compensated(UINT32_MAX, weights, 0, H, WC_ENVMAP_COMPENSATION_NONE, 1.0f, storage,
                                      need) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_build_compensated(kind, weights, 0, H, 3, 1.0f, storage, need) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_build(kind, weights, 0, H, storage, need) == WC_ERR_ZERO_SIZE);
    CHECK(wc_envmap_build(kind, weights, (1u << 24) + 1, 1, storage, need) == WC_ERR_TOO_LARGE);
    CHECK(wc_envmap_build(kind, weights, W, H, storage, need - 1) == WC_ERR_STORAGE_TOO_SMALL);
    CHECK(wc_envmap_build(kind, NULL, W, H, storage, need) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_build(kind, weights, W, H, NULL, need) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_build(kind, weights, W, H, (uint32_t *)(void *)(bytes + 2), need) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_build(kind, (const float *)(const void *)storage, W, H, storage, need) == WC_ERR_INVALID_ARGUMENT);
    CHECK(untouched(storage, sizeof storage));
    weights[100] = INFINITY;
    CHECK(wc_envmap_build(kind, weights, W, H, storage, need) == WC_ERR_INFINITE_WEIGHT);
    weights[100] = 0.5f;

    /* Build; only `need` words are written. */
    memset(storage, SENTINEL, sizeof storage);
    CHECK(wc_envmap_build(kind, weights, W, H, storage, sizeof storage / 4) == WC_OK);
    CHECK(untouched(storage + need, (sizeof storage / 4 - need) * 4));
    CHECK(memcmp(storage, tag, 4) == 0); /* the format tag, as bytes */
    CHECK(wc_envmap_from_storage(storage, need) == WC_OK && wc_envmap_from_storage_verified(storage, need) == WC_OK);
    CHECK(wc_envmap_sample(storage, need, us, ref, BIG) == BIG && in_map(ref, BIG));
    {
        float p[BIG], uv[BIG * 2];
        for (size_t i = 0; i < BIG; i++) {
            uv[2 * i] = ref[i].uv[0];
            uv[2 * i + 1] = ref[i].uv[1];
        }
        CHECK(wc_envmap_pdf(storage, need, uv, p, BIG) == BIG);
        int same = 1;
        for (size_t i = 0; i < BIG; i++) same &= memcmp(&p[i], &ref[i].pdf, 4) == 0;
        CHECK(same);
        size_t zero_weight = 0;
        for (size_t i = 0; i < BIG; i++) zero_weight += !(weights[ref[i].texel[1] * W + ref[i].texel[0]] > 0.0f);
        CHECK(zero_weight == 0);
    }
    /* Output at odd offsets, in pieces: the same samples. */
    {
        static WcEnvSample buf[BIG + 3];
        CHECK(wc_envmap_sample(storage, need, us, buf + 1, 500) == 500);
        CHECK(wc_envmap_sample(storage, need, us + 1000, buf + 501, BIG - 500) == BIG - 500);
        CHECK(memcmp(buf + 1, ref, sizeof ref) == 0);
    }

    /* The pointer rules. */
    memset(got, SENTINEL, sizeof got);
    CHECK(wc_envmap_sample(storage, need, us, got, 0) == 0);
    CHECK(wc_envmap_sample(NULL, need, us, got, 4) == 0);
    CHECK(wc_envmap_sample(storage, need, NULL, got, 4) == 0);
    CHECK(wc_envmap_sample(storage, need, us, NULL, 4) == 0);
    CHECK(wc_envmap_sample(storage, need, us, (WcEnvSample *)(void *)storage, 4) == 0); /* overlap */
    CHECK(wc_envmap_sample(storage, need, (const float *)(const void *)got, got, 4) == 0);
    CHECK(wc_envmap_pdf(storage, need, us, (float *)(void *)(storage + 8), 4) == 0);
    CHECK(untouched(got, sizeof got));
    CHECK(wc_envmap_from_storage(NULL, need) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_from_storage((const uint32_t *)(const void *)(bytes + 1), need) == WC_ERR_INVALID_ARGUMENT);

    /* Invalid and truncated storage: an error, and sampling returns 0 writing nothing. */
    for (size_t n = 0; n < need; n += (n < 12 ? 1 : need / 7)) {
        CHECK(wc_envmap_from_storage(storage, n) == WC_ERR_STORAGE_TOO_SMALL);
        CHECK(wc_envmap_from_storage_verified(storage, n) == WC_ERR_STORAGE_TOO_SMALL);
        CHECK(wc_envmap_sample(storage, n, us, got, 4) == 0 && untouched(got, sizeof got));
    }
    CHECK(wc_envmap_from_storage(storage, need - 1) == WC_ERR_STORAGE_TOO_SMALL);
    CHECK(wc_envmap_from_storage(storage, need + 1) == WC_OK); /* longer is fine */
    size_t other_need = wc_envmap_storage_len(other_kind, W, H);
    CHECK(wc_envmap_build(other_kind, weights, W, H, other, other_need) == WC_OK);
    /* The other distribution's storage: read as that one (its tag), not as this one. */
    CHECK(wc_envmap_from_storage(other, other_need) == WC_OK && wc_envmap_from_storage_verified(other, other_need) == WC_OK);
    CHECK(wc_envmap_sample(other, other_need, us, got, BIG) == BIG && in_map(got, BIG));
    CHECK(memcmp(got, ref, sizeof ref) != 0);
    memset(got, SENTINEL, sizeof got);
    /* A tag of neither (one changed byte; a byte-swapped copy): the wrong format. */
    memcpy(loaded, storage, need * 4);
    loaded[0] ^= 0x20u;
    CHECK(wc_envmap_from_storage(loaded, need) == WC_ERR_WRONG_FORMAT);
    CHECK(wc_envmap_from_storage_verified(loaded, need) == WC_ERR_WRONG_FORMAT);
    CHECK(wc_envmap_sample(loaded, need, us, got, 4) == 0 && untouched(got, sizeof got));
    loaded[0] = storage[0] >> 24 | (storage[0] >> 8 & 0xff00u) | (storage[0] << 8 & 0xff0000u) | storage[0] << 24;
    CHECK(wc_envmap_from_storage(loaded, need) == WC_ERR_WRONG_FORMAT);
    memcpy(loaded, storage, need * 4);
    loaded[1] = WC_ENVMAP_FORMAT_VERSION + 1;
    CHECK(wc_envmap_from_storage(loaded, need) == WC_ERR_UNSUPPORTED_VERSION);
    loaded[1] = 1; /* version 1 (corner-padded pyramids): refused, never misread */
    CHECK(wc_envmap_from_storage(loaded, need) == WC_ERR_UNSUPPORTED_VERSION);
    CHECK(wc_envmap_from_storage_verified(loaded, need) == WC_ERR_UNSUPPORTED_VERSION);
    memcpy(loaded, storage, need * 4);
    loaded[2] = 0;
    CHECK(wc_envmap_from_storage(loaded, need) == WC_ERR_CORRUPT);
    memcpy(loaded, storage, need * 4);
    loaded[5] += 1;
    CHECK(wc_envmap_from_storage(loaded, need) == WC_ERR_CORRUPT);
    CHECK(wc_envmap_sample(loaded, need, us, got, 4) == 0 && untouched(got, sizeof got));
    /* A corrupt table word: the O(1) check passes, the one-pass check does not, and sampling
       stays in the map. */
    memcpy(loaded, storage, need * 4);
    loaded[need - 10] ^= 0x40000000u; /* an edge */
    CHECK(wc_envmap_from_storage(loaded, need) == WC_OK && wc_envmap_from_storage_verified(loaded, need) == WC_ERR_CORRUPT);
    CHECK(wc_envmap_sample(loaded, need, us, got, BIG) == BIG && in_map(got, BIG));
    /* Garbage tables behind a valid header: samples stay in the map. */
    for (uint32_t seed = 1; seed < 40; seed++) {
        uint32_t s = seed;
        memcpy(loaded, storage, need * 4);
        for (size_t i = WC_ENVMAP_HEADER_WORDS; i < need; i++) {
            uint32_t r = lcg(&s);
            loaded[i] = seed % 3 == 0 ? r : seed % 3 == 1 ? (r & 1u ? 0xffffffffu : 0u) : loaded[i] ^ (r & 0x80000401u);
        }
        CHECK(wc_envmap_from_storage(loaded, need) == WC_OK);
        CHECK(wc_envmap_sample(loaded, need, us, got, BIG) == BIG && in_map(got, BIG));
        float p[16];
        CHECK(wc_envmap_pdf(loaded, need, us, p, 16) == 16);
        int finite = 1;
        for (int i = 0; i < 16; i++) finite &= p[i] >= 0.0f && p[i] <= 3.4e38f;
        CHECK(finite);
    }

    /* The same map built at another address: the same bytes (format version 3). */
    memset(loaded, SENTINEL, sizeof loaded);
    CHECK(wc_envmap_build(kind, weights, W, H, loaded + 3, need) == WC_OK);
    CHECK(memcmp(loaded + 3, storage, need * 4) == 0);
    /* Every single-bit flip of the header and of the first 200 table words is caught by the
       verifying loader (the content checksum). */
    {
        int caught = 1;
        for (size_t i = 0; i < WC_ENVMAP_HEADER_WORDS + 200 && i < need; i++) {
            for (int b = 0; b < 32; b++) {
                memcpy(loaded, storage, need * 4);
                loaded[i] ^= 1u << b;
                caught &= wc_envmap_from_storage_verified(loaded, need) != WC_OK;
            }
        }
        CHECK(caught);
    }
    /* Directions and densities per steradian in one call, both layouts. */
    for (uint32_t layout = 0; layout < 2; layout++) {
        static WcEnvDirection d[BIG];
        static float dirs[BIG * 3], p[BIG * 3];
        CHECK(wc_envmap_sample_direction(storage, need, layout, us, d, BIG) == BIG);
        size_t close = 0;
        for (size_t i = 0; i < BIG; i++) {
            CHECK(memcmp(d[i].uv, ref[i].uv, 8) == 0 && d[i].texel[0] == ref[i].texel[0] &&
                  d[i].texel[1] == ref[i].texel[1]);
            for (int c = 0; c < 3; c++) dirs[3 * i + c] = d[i].dir[c];
        }
        CHECK(wc_envmap_pdf_direction(storage, need, layout, dirs, p, BIG) == BIG);
        for (size_t i = 0; i < BIG; i++) close += fabsf(p[i] - d[i].pdf) <= 1e-4f * d[i].pdf;
        CHECK(close * 1000 >= BIG * 999);
        /* In place: density i overwrites float i after direction i / 3 was read. */
        memcpy(p, dirs, sizeof dirs);
        CHECK(wc_envmap_pdf_direction(storage, need, layout, p, p, BIG) == BIG);
        {
            float q[BIG];
            CHECK(wc_envmap_pdf_direction(storage, need, layout, dirs, q, BIG) == BIG);
            CHECK(memcmp(p, q, sizeof q) == 0);
        }
        /* The rules: unknown layout, null, overlap, n = 0. */
        memset(got, SENTINEL, sizeof got);
        CHECK(wc_envmap_sample_direction(storage, need, 2, us, (WcEnvDirection *)(void *)got, 4) == 0);
        CHECK(wc_envmap_sample_direction(storage, need, layout, NULL, (WcEnvDirection *)(void *)got, 4) == 0);
        CHECK(wc_envmap_sample_direction(storage, need, layout, us, (WcEnvDirection *)(void *)got, 0) == 0);
        CHECK(wc_envmap_pdf_direction(storage, need, 7, dirs, (float *)(void *)got, 4) == 0);
        CHECK(untouched(got, sizeof got));
    }

    /* Written to a file and read back at every word alignment: the same samples. */
    {
        FILE *f = fopen("envmap.bin", "wb");
        CHECK(f != NULL);
        if (!f) return;
        CHECK(fwrite(storage, 4, need, f) == need);
        fclose(f);
        for (size_t off = 0; off < 16; off += 3) {
            memset(loaded, 0, sizeof loaded);
            f = fopen("envmap.bin", "rb");
            CHECK(f != NULL);
            if (!f) return;
            CHECK(fread(loaded + off, 4, need + 1, f) == need);
            fclose(f);
            CHECK(wc_envmap_from_storage_verified(loaded + off, need) == WC_OK);
            CHECK(wc_envmap_sample(loaded + off, need, us, got, BIG) == BIG);
            CHECK(memcmp(got, ref, sizeof ref) == 0);
        }
        remove("envmap.bin");
    }
}

static void error_strings(void) {
    const char *unknown = wc_error_string(12345);
    CHECK(unknown != NULL && unknown[0] != 0 && wc_error_string(INT32_MIN) == unknown);
    for (int32_t c = WC_OK; c >= WC_ERR_OTHER; c--) {
        const char *e = wc_error_string(c);
        CHECK(e != NULL && e[0] != 0 && e != unknown && e == wc_error_string(c));
        for (int32_t d = c + 1; d <= WC_OK; d++) CHECK(strcmp(e, wc_error_string(d)) != 0);
    }
    CHECK(strstr(wc_error_string(WC_ERR_CORRUPT), "checksum") != NULL);
    CHECK(strstr(wc_error_string(WC_ERR_UNSUPPORTED_VERSION), "rebuild") != NULL);
}

static void images(void) {
    float w[6] = {1, 1, 1, 1, 1, 1};
    CHECK(wc_envmap_equirect_solid_angle_weights(w, 3, 2) == WC_OK && w[0] > 0.0f && w[0] < 1.0f);
    CHECK(wc_envmap_equirect_solid_angle_weights(w, 0, 2) == WC_ERR_ZERO_SIZE);
    CHECK(wc_envmap_equirect_solid_angle_weights(NULL, 3, 2) == WC_ERR_INVALID_ARGUMENT);
    float src[4 * 2 * 3], dst[4 * 4 * 3];
    for (int i = 0; i < 24; i++) src[i] = 1.0f;
    CHECK(wc_envmap_equirect_to_equal_area(src, 4, 2, 3, dst, 4, 2) == WC_OK);
    CHECK(dst[0] > 0.99f && dst[0] < 1.01f);
    CHECK(wc_envmap_equirect_to_equal_area(src, 4, 2, 5, dst, 4, 2) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_equirect_to_equal_area(src, 4, 2, 3, dst, 0, 2) == WC_ERR_ZERO_SIZE);
    CHECK(wc_envmap_equirect_to_equal_area(src, 4, 2, 3, src, 2, 1) == WC_ERR_INVALID_ARGUMENT);
    CHECK(wc_envmap_equirect_to_equal_area(NULL, 4, 2, 3, dst, 4, 2) == WC_ERR_INVALID_ARGUMENT);
}

int main(void) {
    uint32_t s = 12345;
    for (size_t i = 0; i < BIG * 2; i++) in2[i] = rnd(&s) * 1.2f - 0.1f; /* some out of range */
    for (size_t i = 0; i < BIG * 3; i++) in3[i] = rnd(&s) * 2.4f - 1.2f;
    in2[0] = NAN;
    in3[4] = -INFINITY;
    for (size_t i = 0; i < W * H; i++) weights[i] = i % 7 == 0 ? 0.0f : rnd(&s) * (i == 300 ? 1e5f : 1.0f);
    weights[11] = -3.0f;
    for (size_t i = 0; i < BIG * 2; i++) us[i] = rnd(&s);

    warps();
    generators();
    disk_extras();
    envmap(WC_ENVMAP_KIND_HIERARCHICAL, "wcHI", WC_ENVMAP_KIND_MARGINAL_CONDITIONAL);
    envmap(WC_ENVMAP_KIND_MARGINAL_CONDITIONAL, "wcMC", WC_ENVMAP_KIND_HIERARCHICAL);
    images();
    error_strings();
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
