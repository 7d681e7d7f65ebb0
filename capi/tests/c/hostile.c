/*
 * Hostile and careless callers of the C API, under AddressSanitizer and UBSan in CI
 * (capi/tests/c.rs; WARPCORE_CFLAGS="-fsanitize=address,undefined ...") and as a 32-bit
 * program (-m32).
 *
 * Every array lives flush against a PROT_NONE guard page (mmap + mprotect), at the end of its
 * region (an overrun by one element faults) or at its start (an underrun faults), and the
 * bytes the library must not write are filled with a sentinel and compared afterwards. Each
 * call's arguments are drawn at random (counts from 0 to SIZE_MAX, null, misaligned and
 * overlapping pointers, sizes past every limit, lying storage lengths, corrupted storage), a
 * model of the documented rules says what the call must return and whether it may touch
 * memory, and the library's answer is compared with it. A call the model says gets past the
 * checks is only made with arrays of the documented sizes (the caller's contract).
 *
 * Output: one line "row <function> <outcome> <calls>" per (function, documented outcome)
 * reached, then "<calls> hostile calls, <checks> passed, <failed> failed". capi/tests/c.rs
 * holds the table of every function x documented outcome and fails when a row is missing:
 * a new function without its rows fails the test.
 */
#define _DEFAULT_SOURCE
#include "warpcore.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

static unsigned long passed, failed, calls;
#define CHECK(cond)                                                                      \
    do {                                                                                 \
        if (cond) {                                                                      \
            passed++;                                                                    \
        } else {                                                                         \
            if (failed++ < 50)                                                           \
                fprintf(stderr, "%s:%d: CHECK(%s) failed (case %s)\n", __FILE__, __LINE__, \
                        #cond, current);                                                 \
        }                                                                                \
    } while (0)

static const char *current = "";

/* ---- rows: function x outcome ---- */

#define MAX_ROWS 1024
static struct row {
    const char *fn, *outcome;
    unsigned long calls;
} rows[MAX_ROWS];
static int nrows;

static void reach(const char *fn, const char *outcome) {
    calls++;
    for (int i = 0; i < nrows; i++) {
        if (strcmp(rows[i].fn, fn) == 0 && strcmp(rows[i].outcome, outcome) == 0) {
            rows[i].calls++;
            return;
        }
    }
    if (nrows == MAX_ROWS) {
        fprintf(stderr, "too many rows\n");
        exit(2);
    }
    rows[nrows].fn = fn;
    rows[nrows].outcome = outcome;
    rows[nrows].calls = 1;
    nrows++;
}

/* ---- random numbers ---- */

static uint32_t seed = 0x9e3779b9u;
static uint32_t rnd(void) {
    seed ^= seed << 13;
    seed ^= seed >> 17;
    seed ^= seed << 5;
    return seed;
}
static size_t below(size_t n) { return n ? (size_t)rnd() % n : 0; }
static float rnd_float(void) {
    static const float specials[] = {0.0f, -0.0f, 1.0f, 0.5f, 0.99999994f, -1.0f, 2.0f, 1e-40f};
    uint32_t r = rnd();
    if (r % 16 == 0) return specials[(r >> 4) % 8];
    if (r % 16 == 1) return (r & 32) ? INFINITY : -INFINITY;
    if (r % 16 == 2) return NAN;
    return (float)(rnd() >> 8) * (1.0f / 16777216.0f) * 1.4f - 0.2f;
}

/* ---- guarded memory ---- */

#define REGIONS 6
#define REGION_BYTES ((size_t)1 << 20)
#define SENTINEL 0xa5
static unsigned char *region[REGIONS];

static void guard_pages(void) {
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    for (int k = 0; k < REGIONS; k++) {
        unsigned char *base = mmap(NULL, REGION_BYTES + 2 * page, PROT_READ | PROT_WRITE,
                                   MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (base == MAP_FAILED || mprotect(base, page, PROT_NONE) != 0 ||
            mprotect(base + page + REGION_BYTES, page, PROT_NONE) != 0) {
            perror("mmap");
            exit(2);
        }
        region[k] = base + page;
        memset(region[k], SENTINEL, REGION_BYTES);
    }
}

/* The ranges handed out since the last reset (with a margin), to restore the sentinel. */
#define MAX_USED 32
static struct {
    unsigned char *lo, *hi;
} used[MAX_USED];
static int nused;

/* An array of `bytes` in region k: flush against the guard page after it (`end`), or the one
   before it; `skew` bytes further (misaligned pointers), kept inside the region. */
static void *place(int k, size_t bytes, int end, size_t skew) {
    if (bytes + skew > REGION_BYTES) bytes = REGION_BYTES - skew;
    unsigned char *p = end ? region[k] + REGION_BYTES - bytes - skew : region[k] + skew;
    if (nused < MAX_USED) {
        unsigned char *lo = p - 64 < region[k] ? region[k] : p - 64;
        unsigned char *hi = p + bytes + 64 > region[k] + REGION_BYTES ? region[k] + REGION_BYTES : p + bytes + 64;
        used[nused].lo = lo;
        used[nused].hi = hi;
        nused++;
    }
    return p;
}

static int is_sentinel(const void *p, size_t n) {
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        if (b[i] != SENTINEL) return 0;
    return 1;
}

/* The ranges a case used back to the sentinel. */
static void reset(void) {
    for (int i = 0; i < nused; i++) memset(used[i].lo, SENTINEL, (size_t)(used[i].hi - used[i].lo));
    nused = 0;
}

/* The ranges a case used still hold the sentinel. */
static int untouched_all(void) {
    for (int i = 0; i < nused; i++)
        if (!is_sentinel(used[i].lo, (size_t)(used[i].hi - used[i].lo))) return 0;
    return 1;
}

/* Fills `n` floats (or words) with data whose bytes are never all the sentinel. */
static void fill_floats(float *p, size_t n) {
    for (size_t i = 0; i < n; i++) p[i] = rnd_float();
}

/* ---- sizes ---- */

/* Byte size of `n` elements of `elem` bytes fits PTRDIFF_MAX (overflow-safe). */
static int fits(size_t n, size_t elem) { return n <= (size_t)PTRDIFF_MAX / elem; }
static int fits_u32(uint64_t n) { return n <= UINT32_MAX; } /* (a function: no -Wtype-limits on 32-bit) */
static int fits64(uint64_t n, size_t elem) { return n <= (uint64_t)((size_t)PTRDIFF_MAX / elem); }

/* Bytes from `p` to the end of its guarded region (0 outside every region). */
static size_t avail(const void *p) {
    for (int k = 0; k < REGIONS; k++) {
        uintptr_t lo = (uintptr_t)region[k], x = (uintptr_t)p;
        if (x >= lo && x < lo + REGION_BYTES) return lo + REGION_BYTES - x;
    }
    return 0;
}

/* Snapshots of memory a call must not change. */
static unsigned char snap_bytes[4][1 << 16];
static const void *snap_at[4];
static size_t snap_len[4];
static void snapshot(int i, const void *p, size_t bytes) {
    size_t a = p ? avail(p) : 0;
    if (bytes > a) bytes = a;
    if (bytes > sizeof snap_bytes[i]) bytes = sizeof snap_bytes[i];
    snap_at[i] = p;
    snap_len[i] = bytes;
    if (bytes) memcpy(snap_bytes[i], p, bytes);
}
static int unchanged(void) {
    int same = 1;
    for (int i = 0; i < 4; i++) {
        if (snap_len[i]) same &= memcmp(snap_bytes[i], snap_at[i], snap_len[i]) == 0;
        snap_len[i] = 0;
    }
    return same;
}

/* A count: usually small, sometimes 0, sometimes one whose byte size overflows for
   elements of `elem` bytes. */
static size_t hostile_count(size_t elem, size_t small) {
    uint32_t r = rnd() % 16;
    if (r == 0) return 0;
    if (r == 1) {
        const size_t huge[] = {SIZE_MAX, SIZE_MAX - 1, SIZE_MAX / 2 + 1, SIZE_MAX / 3 + 1,
                               SIZE_MAX / 4 + 1, (size_t)PTRDIFF_MAX / 4 + 1,
                               (size_t)PTRDIFF_MAX / 8 + 1, (size_t)PTRDIFF_MAX / 12 + 1};
        size_t n = huge[rnd() % 8];
        return fits(n, elem) ? SIZE_MAX : n;
    }
    return 1 + below(small);
}

/* A storage length for a build needing `need` words: none, one short, SIZE_MAX, a few words
   more, or exactly `need`. */
static size_t hostile_len(size_t need) {
    switch (rnd() % 6) {
    case 0: return 0;
    case 1: return need - 1;
    case 2: return SIZE_MAX;
    case 3: return need + below(9);
    default: return need;
    }
}

static int overlaps(const void *a, size_t an, const void *b, size_t bn) {
    uintptr_t x = (uintptr_t)a, y = (uintptr_t)b;
    return an && bn && x < y + bn && y < x + an;
}

static int aligned(const void *p) { return ((uintptr_t)p & 3u) == 0; }

/* ---- one-to-one maps: f(in, out, n) ---- */

typedef size_t (*map_fn)(const float *, float *, size_t);
struct map {
    const char *name;
    map_fn f;
    size_t I, O; /* 4-byte values per element */
    int refuses; /* always returns 0 (wrap_texel with size 0) */
};

static size_t shuffle7(const float *in, float *out, size_t n) {
    return wc_pmj02bn_shuffle((const uint32_t *)(const void *)in, 7, (uint32_t *)(void *)out, n);
}
static size_t wrap_texel32(const float *in, float *out, size_t n) {
    return wc_sphere_equal_area_wrap_texel((const int32_t *)(const void *)in, 32,
                                           (uint32_t *)(void *)out, n);
}
static size_t wrap_texel0(const float *in, float *out, size_t n) {
    return wc_sphere_equal_area_wrap_texel((const int32_t *)(const void *)in, 0,
                                           (uint32_t *)(void *)out, n);
}

/* Lights by solid angle: one fixed light per wrapper (the light's own pointer rules are
   exercised by one_light below). */
static const float TRI_LIGHT[12] = {0, 0, 1, 1, 0, 1, 0, 1, 1, 0.1f, 0.2f, 0};
static const float RECT_LIGHT[12] = {-0.5f, -0.5f, 1, 1, 0, 0, 0, 1, 0, 0.1f, 0.2f, 0};
static size_t sph_tri(const float *in, float *out, size_t n) {
    return wc_spherical_triangle(TRI_LIGHT, in, out, n);
}
static size_t sph_tri_inv(const float *in, float *out, size_t n) {
    return wc_spherical_triangle_inverse(TRI_LIGHT, in, out, n);
}
static size_t sph_rect(const float *in, float *out, size_t n) {
    return wc_spherical_rectangle(RECT_LIGHT, in, out, n);
}
static size_t sph_rect_inv(const float *in, float *out, size_t n) {
    return wc_spherical_rectangle_inverse(RECT_LIGHT, in, out, n);
}
static const float TRI_LIGHT_N[15] = {0, 0, 1, 1, 0, 1, 0, 1, 1, 0.1f, 0.2f, 0, 0.3f, 0, 1};
static const float RECT_LIGHT_N[15] = {-0.5f, -0.5f, 1, 1, 0, 0, 0, 1, 0, 0.1f, 0.2f, 0, 0, -0.4f, 1};
static size_t sph_tri_cos(const float *in, float *out, size_t n) {
    return wc_spherical_triangle_cosine(TRI_LIGHT_N, in, out, n);
}
static size_t sph_rect_cos(const float *in, float *out, size_t n) {
    return wc_spherical_rectangle_cosine(RECT_LIGHT_N, in, out, n);
}
static const float SPHERE_LIGHT[7] = {0.2f, -0.1f, 3.0f, 1.0f, 0.1f, 0.2f, 0};
static size_t sph_cone(const float *in, float *out, size_t n) {
    return wc_spherical_cone(SPHERE_LIGHT, in, out, n);
}
static size_t sph_cone_inv(const float *in, float *out, size_t n) {
    return wc_spherical_cone_inverse(SPHERE_LIGHT, in, out, n);
}

static const struct map MAPS[] = {
    {"wc_disk_polar", wc_disk_polar, 2, 2, 0},
    {"wc_disk_polar_inverse", wc_disk_polar_inverse, 2, 2, 0},
    {"wc_disk_concentric", wc_disk_concentric, 2, 2, 0},
    {"wc_disk_concentric_inverse", wc_disk_concentric_inverse, 2, 2, 0},
    {"wc_triangle_uniform", wc_triangle_uniform, 2, 3, 0},
    {"wc_triangle_uniform_inverse", wc_triangle_uniform_inverse, 3, 2, 0},
    {"wc_triangle_sqrt_map", wc_triangle_sqrt_map, 2, 3, 0},
    {"wc_triangle_sqrt_map_inverse", wc_triangle_sqrt_map_inverse, 3, 2, 0},
    {"wc_sphere_equal_area", wc_sphere_equal_area, 2, 3, 0},
    {"wc_sphere_equal_area_inverse", wc_sphere_equal_area_inverse, 3, 2, 0},
    {"wc_sphere_equal_area_wrap", wc_sphere_equal_area_wrap, 2, 2, 0},
    {"wc_sphere_equirect", wc_sphere_equirect, 2, 3, 0},
    {"wc_sphere_equirect_inverse", wc_sphere_equirect_inverse, 3, 2, 0},
    {"wc_sphere_uniform", wc_sphere_uniform, 2, 3, 0},
    {"wc_sphere_uniform_inverse", wc_sphere_uniform_inverse, 3, 2, 0},
    {"wc_sphere_uniform_hemisphere", wc_sphere_uniform_hemisphere, 2, 3, 0},
    {"wc_sphere_uniform_hemisphere_inverse", wc_sphere_uniform_hemisphere_inverse, 3, 2, 0},
    {"wc_sphere_cosine_hemisphere", wc_sphere_cosine_hemisphere, 2, 3, 0},
    {"wc_sphere_cosine_hemisphere_inverse", wc_sphere_cosine_hemisphere_inverse, 3, 2, 0},
    {"wc_sphere_equal_area_pdf_to_solid_angle", wc_sphere_equal_area_pdf_to_solid_angle, 1, 1, 0},
    {"wc_sphere_cosine_hemisphere_pdf", wc_sphere_cosine_hemisphere_pdf, 1, 1, 0},
    {"wc_microfacet_ggx_d", wc_microfacet_ggx_d, 5, 1, 0},
    {"wc_microfacet_ggx_g1", wc_microfacet_ggx_g1, 5, 1, 0},
    {"wc_microfacet_ggx_g2", wc_microfacet_ggx_g2, 8, 1, 0},
    {"wc_microfacet_ggx_visible_normal", wc_microfacet_ggx_visible_normal, 7, 3, 0},
    {"wc_microfacet_ggx_visible_normal_pdf", wc_microfacet_ggx_visible_normal_pdf, 8, 1, 0},
    {"wc_microfacet_ggx_reflect", wc_microfacet_ggx_reflect, 7, 4, 0},
    {"wc_microfacet_ggx_reflect_pdf", wc_microfacet_ggx_reflect_pdf, 8, 1, 0},
    {"wc_microfacet_ggx_reflect_bounded", wc_microfacet_ggx_reflect_bounded, 7, 4, 0},
    {"wc_microfacet_ggx_reflect_bounded_pdf", wc_microfacet_ggx_reflect_bounded_pdf, 8, 1, 0},
    {"wc_envmap_luminance", wc_envmap_luminance, 3, 1, 0},
    {"wc_pmj02bn_shuffle", shuffle7, 1, 1, 0},
    {"wc_sphere_equal_area_wrap_texel", wrap_texel32, 2, 2, 0},
    {"wc_sphere_equal_area_wrap_texel", wrap_texel0, 2, 2, 1},
    {"wc_spherical_triangle", sph_tri, 2, 4, 0},
    {"wc_spherical_triangle_inverse", sph_tri_inv, 3, 2, 0},
    {"wc_spherical_rectangle", sph_rect, 2, 3, 0},
    {"wc_spherical_rectangle_inverse", sph_rect_inv, 2, 2, 0},
    {"wc_spherical_triangle_cosine", sph_tri_cos, 2, 4, 0},
    {"wc_spherical_rectangle_cosine", sph_rect_cos, 2, 3, 0},
    {"wc_spherical_cone", sph_cone, 2, 4, 0},
    {"wc_spherical_cone_inverse", sph_cone_inv, 3, 2, 0},
};
#define NMAPS (sizeof MAPS / sizeof MAPS[0])

static float ref_in[4096 * 3], ref_out[4096 * 3];

/* Pointer plans shared by the array functions. */
enum plan { SEPARATE, NULL_IN, NULL_OUT, SKEW_IN, SKEW_OUT, OVERLAP, IN_PLACE, PLANS };

static void one_map(const struct map *M) {
    size_t n = hostile_count(4 * (M->I > M->O ? M->I : M->O), 300);
    enum plan plan = (enum plan)(rnd() % PLANS);
    int end = rnd() & 1;
    size_t small = n <= 4096 ? n : 0; /* elements actually placed */
    float *in = place(0, small * M->I * 4, end, 0);
    float *out = place(1, small * M->O * 4, !end, 0);
    switch (plan) {
    case NULL_IN: in = NULL; break;
    case NULL_OUT: out = NULL; break;
    case SKEW_IN: in = place(0, small * M->I * 4, end, 1 + below(3)); break;
    case SKEW_OUT: out = place(1, small * M->O * 4, !end, 1 + below(3)); break;
    case OVERLAP: {
        /* The output anywhere from ending one float before the input to starting at its end. */
        float *base = place(2, (2 * (small * M->O + 1) + small * M->I) * 4, 1, 0);
        in = base + small * M->O + 1;
        out = base + below(small * (M->I + M->O) + 2);
        break;
    }
    case IN_PLACE: {
        size_t bytes = small * (M->I > M->O ? M->I : M->O) * 4;
        in = out = place(2, bytes, end, 0);
        break;
    }
    default: break;
    }
    if (in && small && aligned(in)) fill_floats(in, small * M->I);
    /* The model. */
    const char *outcome;
    size_t want = 0;
    if (M->refuses) outcome = "0:size=0";
    else if (n == 0) outcome = "0:n=0";
    else if (!in || !out) outcome = "0:null";
    else if (!aligned(in) || !aligned(out)) outcome = "0:misaligned";
    else if (!fits(n, 4 * M->I) || !fits(n, 4 * M->O)) outcome = "0:size";
    else if (overlaps(in, n * M->I * 4, out, n * M->O * 4) && !(in == out && M->O <= M->I))
        outcome = "0:overlap";
    else {
        outcome = in == out ? "in-place" : "n";
        want = n;
    }
    if (want) {
        memcpy(ref_in, in, n * M->I * 4);
        M->f(ref_in, ref_out, n);
    }
    /* What must not change: everything, on a refused call; the input, unless in place. */
    if (!want) snapshot(0, out, small * M->O * 4 + 64);
    if (!want || in != out) snapshot(1, in, small * M->I * 4);
    size_t got = M->f(in, out, n);
    reach(M->name, outcome);
    current = M->name;
    CHECK(got == want);
    if (want) CHECK(memcmp(out, ref_out, n * M->O * 4) == 0);
    CHECK(unchanged());
    reset();
}

/* The light pointer of the spherical functions: 12 floats (15 for the cosine-aware ones, 7
   for the spheres)
   flush against a guard page (a read past them faults), null or misaligned (0, nothing
   written); a valid call's result equals the same call with a copy of the light. */
static void one_light(int which) {
    static const char *names[11] = {"wc_spherical_triangle", "wc_spherical_triangle_inverse",
                                    "wc_spherical_rectangle", "wc_spherical_rectangle_inverse",
                                    "wc_spherical_triangle_solid_angle",
                                    "wc_spherical_rectangle_solid_angle",
                                    "wc_spherical_triangle_cosine",
                                    "wc_spherical_rectangle_cosine", "wc_spherical_cone",
                                    "wc_spherical_cone_inverse",
                                    "wc_spherical_cone_solid_angle"};
    size_t len = which >= 8 ? 7 : which >= 6 ? 15 : 12;
    int end = rnd() & 1;
    float *light = place(0, len * 4, end, 0);
    uint32_t r = rnd() % 4;
    if (r == 0) light = NULL;
    if (r == 1) light = place(0, len * 4, end, 1 + below(3));
    if (light && aligned(light)) fill_floats(light, len);
    float copy[15] = {0};
    if (light && aligned(light)) memcpy(copy, light, len * 4);
    size_t n = 1 + below(20);
    float *u = place(1, n * 3 * 4, end, 0), *out = place(3, n * 4 * 4, !end, 0);
    fill_floats(u, n * 3);
    int ok = light && aligned(light);
    int array = which < 4 || (which >= 6 && which < 10);
    const char *outcome = !light ? "0:null" : !aligned(light) ? "0:misaligned" : array ? "n" : "omega";
    static float ref[4 * 20];
    snapshot(0, out, n * 4 * 4 + 64);
    if (light) snapshot(2, light, len * 4);
    size_t got = 0, want = ok ? n : 0;
    float om = 0, want_om = 0;
    switch (which) {
    case 0: if (ok) wc_spherical_triangle(copy, u, ref, n); got = wc_spherical_triangle(light, u, out, n); break;
    case 1: if (ok) wc_spherical_triangle_inverse(copy, u, ref, n); got = wc_spherical_triangle_inverse(light, u, out, n); break;
    case 2: if (ok) wc_spherical_rectangle(copy, u, ref, n); got = wc_spherical_rectangle(light, u, out, n); break;
    case 3: if (ok) wc_spherical_rectangle_inverse(copy, u, ref, n); got = wc_spherical_rectangle_inverse(light, u, out, n); break;
    case 4: if (ok) want_om = wc_spherical_triangle_solid_angle(copy); om = wc_spherical_triangle_solid_angle(light); break;
    case 5: if (ok) want_om = wc_spherical_rectangle_solid_angle(copy); om = wc_spherical_rectangle_solid_angle(light); break;
    case 6: if (ok) wc_spherical_triangle_cosine(copy, u, ref, n); got = wc_spherical_triangle_cosine(light, u, out, n); break;
    case 7: if (ok) wc_spherical_rectangle_cosine(copy, u, ref, n); got = wc_spherical_rectangle_cosine(light, u, out, n); break;
    case 8: if (ok) wc_spherical_cone(copy, u, ref, n); got = wc_spherical_cone(light, u, out, n); break;
    case 9: if (ok) wc_spherical_cone_inverse(copy, u, ref, n); got = wc_spherical_cone_inverse(light, u, out, n); break;
    default: if (ok) want_om = wc_spherical_cone_solid_angle(copy); om = wc_spherical_cone_solid_angle(light); break;
    }
    reach(names[which], outcome);
    current = names[which];
    if (array) {
        static const size_t O[10] = {4, 2, 3, 2, 0, 0, 4, 3, 4, 2};
        CHECK(got == want);
        if (want) {
            CHECK(memcmp(out, ref, n * O[which] * 4) == 0);
            snap_len[0] = 0; /* written, as it should be */
        }
    } else {
        CHECK(memcmp(&om, &want_om, sizeof om) == 0);
        CHECK(om >= 0.0f && om <= (which == 10 ? 12.566371f : 6.2831855f));
    }
    CHECK(unchanged());
    reset();
}

/* ---- generators: f(a, b, out, n) ---- */

typedef size_t (*gen_fn)(uint32_t, uint32_t, float *, size_t);
struct gen {
    const char *name;
    gen_fn f;
    size_t O;
};
static size_t stratified(uint32_t a, uint32_t s, float *o, size_t n) {
    return wc_sequence_stratified(a, s % 5000, s, o, n);
}
static size_t raw(uint32_t a, uint32_t s, float *o, size_t n) {
    return wc_pmj02bn_raw(s, a, (uint32_t *)(void *)o, n);
}
static const struct gen GENS[] = {
    {"wc_pmj02bn_sample", wc_pmj02bn_sample, 2},
    {"wc_pmj02bn_raw", raw, 2},
    {"wc_sequence_random", wc_sequence_random, 2},
    {"wc_sequence_stratified", stratified, 2},
    {"wc_triangle_basu_owen", wc_triangle_basu_owen, 3},
    {"wc_triangle_basu_owen_permuted", wc_triangle_basu_owen_permuted, 3},
};
#define NGENS (sizeof GENS / sizeof GENS[0])

static void one_gen(const struct gen *G) {
    size_t n = hostile_count(4 * G->O, 300);
    uint32_t a = rnd(), b = rnd();
    size_t small = n <= 4096 ? n : 0;
    int end = rnd() & 1;
    float *out = place(0, small * G->O * 4, end, 0);
    uint32_t r = rnd() % 4;
    if (r == 0) out = NULL;
    if (r == 1) out = place(0, small * G->O * 4, end, 1 + below(3));
    const char *outcome;
    size_t want = 0;
    if (n == 0) outcome = "0:n=0";
    else if (!out) outcome = "0:null";
    else if (!aligned(out)) outcome = "0:misaligned";
    else if (!fits(n, 4 * G->O)) outcome = "0:size";
    else {
        outcome = "n";
        want = n;
        G->f(a, b, ref_out, n);
    }
    size_t got = G->f(a, b, out, n);
    reach(G->name, outcome);
    current = G->name;
    CHECK(got == want);
    if (want) CHECK(memcmp(out, ref_out, n * G->O * 4) == 0);
    CHECK(untouched_all() == !want);
    reset();
}

/* ---- two inputs: f(a, b, out, n), a: n floats, b: D n floats ---- */

typedef size_t (*pair_fn)(const float *, const float *, float *, size_t);
struct pair {
    const char *name;
    pair_fn f;
    size_t D;
};
static const struct pair PAIRS[] = {
    {"wc_sphere_equirect_pdf_to_solid_angle", wc_sphere_equirect_pdf_to_solid_angle, 3},
    {"wc_envmap_equirect_pdf_to_solid_angle", wc_envmap_equirect_pdf_to_solid_angle, 1},
};

static void one_pair(const struct pair *P) {
    size_t n = hostile_count(4 * P->D, 300);
    size_t small = n <= 4096 ? n : 0;
    int end = rnd() & 1;
    float *a = place(0, small * 4, end, 0), *b = place(1, small * P->D * 4, !end, 0),
          *out = place(3, small * 4, end, 0);
    uint32_t r = rnd() % 10;
    float *base = place(2, small * (P->D + 4) * 4 + 64, 1, 0);
    switch (r) {
    case 0: a = NULL; break;
    case 1: b = NULL; break;
    case 2: out = NULL; break;
    case 3: a = place(0, small * 4, end, 1 + below(3)); break;
    case 4: out = place(3, small * 4, end, 1 + below(3)); break;
    case 5: out = a; break;                                                   /* in place */
    case 6: b = base; out = base + below(small * P->D + 1); break;            /* out in b */
    case 7: a = base + 2; out = base + below(small + 4); break;               /* near a */
    case 8: a = base; b = base + below(small + 1); break;                     /* a and b */
    default: break;
    }
    if (a && aligned(a) && small) fill_floats(a, small);
    if (b && aligned(b) && small && b != a) fill_floats(b, small * P->D);
    const char *outcome;
    size_t want = 0;
    if (n == 0) outcome = "0:n=0";
    else if (!a || !b || !out) outcome = "0:null";
    else if (!aligned(a) || !aligned(b) || !aligned(out)) outcome = "0:misaligned";
    else if (!fits(n, 4 * P->D)) outcome = "0:size";
    else if (overlaps(out, n * 4, b, n * P->D * 4) || (overlaps(out, n * 4, a, n * 4) && out != a))
        outcome = "0:overlap";
    else {
        outcome = out == a ? "in-place" : "n";
        want = n;
        static float ra[4096], rb[4096 * 3];
        memcpy(ra, a, n * 4);
        memcpy(rb, b, n * P->D * 4);
        P->f(ra, rb, ref_out, n);
    }
    if (!want) snapshot(0, out, small * 4);
    if (!want || out != a) snapshot(1, a, small * 4);
    snapshot(2, b, small * P->D * 4);
    size_t got = P->f(a, b, out, n);
    reach(P->name, outcome);
    current = P->name;
    CHECK(got == want);
    if (want) CHECK(memcmp(out, ref_out, n * 4) == 0);
    CHECK(unchanged());
    reset();
}

/* ---- four disk samples per point: f(points, n_points, out, n) ---- */

typedef size_t (*four_fn)(const float *, size_t, float *, size_t);
static const struct {
    const char *name;
    four_fn f;
} FOURS[] = {{"wc_disk_polar4", wc_disk_polar4}, {"wc_disk_concentric4", wc_disk_concentric4}};

static void one_four(int which) {
    four_fn f = FOURS[which].f;
    size_t np = below(80), n = hostile_count(8, 400);
    if (rnd() % 16 == 0) { /* counts whose byte sizes overflow, with a lying n_points */
        np = rnd() % 2 ? SIZE_MAX : SIZE_MAX / 4 + 1;
        n = rnd() % 2 ? SIZE_MAX : (size_t)PTRDIFF_MAX / 8 + 1;
    }
    size_t m = np > SIZE_MAX / 4 ? n : (n < 4 * np ? n : 4 * np);
    size_t used = (m + 3) / 4, small = m <= 4096 ? m : 0, placed = np < 4096 ? np : 0;
    int end = rnd() & 1;
    float *pts = place(0, placed * 8, end, 0), *out = place(1, small * 8, !end, 0);
    uint32_t r = rnd() % 7;
    if (r == 0) pts = NULL;
    if (r == 1) out = NULL;
    if (r == 2) pts = place(0, placed * 8, end, 1 + below(3));
    if (r == 3) out = place(1, small * 8, !end, 1 + below(3));
    if (r == 4 && placed) { /* out overlapping the used points, or just past them */
        pts = place(2, placed * 8 + small * 8 + 16, 0, 0);
        out = pts + below(2 * used + 2);
    }
    if (pts && aligned(pts)) fill_floats(pts, placed * 2);
    const char *outcome;
    size_t want = 0;
    if (m == 0) outcome = "0:n=0";
    else if (!pts || !out) outcome = "0:null";
    else if (!aligned(pts) || !aligned(out)) outcome = "0:misaligned";
    else if (!fits(m, 8)) outcome = "0:size";
    else if (overlaps(pts, used * 8, out, m * 8)) outcome = "0:overlap";
    else {
        outcome = m < n ? "capped" : "n";
        want = m;
        static float rp[4096];
        memcpy(rp, pts, np * 8);
        f(rp, np, ref_out, n);
    }
    if (!want) snapshot(0, out, small * 8 + 64);
    snapshot(1, pts, (want ? used : placed) * 8); /* outputs may follow the used points */
    size_t got = f(pts, np, out, n);
    reach(FOURS[which].name, outcome);
    current = FOURS[which].name;
    CHECK(got == want);
    if (want) CHECK(memcmp(out, ref_out, m * 8) == 0);
    CHECK(unchanged());
    reset();
}

/* ---- inverses with quadrants: f(p, out, quadrant, n) ---- */

typedef size_t (*quad_fn)(const float *, float *, uint32_t *, size_t);
static const struct {
    const char *name;
    quad_fn f;
} QUADS[] = {{"wc_disk_polar4_inverse", wc_disk_polar4_inverse},
             {"wc_disk_concentric4_inverse", wc_disk_concentric4_inverse}};

static void one_quad(int which) {
    quad_fn f = QUADS[which].f;
    size_t n = hostile_count(8, 300);
    size_t small = n <= 4096 ? n : 0;
    int end = rnd() & 1;
    float *p = place(0, small * 8, end, 0), *out = place(1, small * 8, !end, 0);
    uint32_t *q = place(3, small * 4, end, 0);
    float *base = place(2, small * 24 + 64, 1, 0);
    switch (rnd() % 10) {
    case 0: p = NULL; break;
    case 1: out = NULL; break;
    case 2: q = NULL; break;
    case 3: p = place(0, small * 8, end, 1 + below(3)); break;
    case 4: q = place(3, small * 4, end, 1 + below(3)); break;
    case 5: out = p; break;
    case 6: p = base; out = base + below(4 * small + 2); break;
    case 7: p = base; q = (uint32_t *)(void *)(base + below(3 * small + 2)); break;
    case 8: out = base; q = (uint32_t *)(void *)(base + below(3 * small + 2)); break;
    default: break;
    }
    if (p && aligned(p) && small) fill_floats(p, small * 2);
    const char *outcome;
    size_t want = 0;
    if (n == 0) outcome = "0:n=0";
    else if (!p || !out || !q) outcome = "0:null";
    else if (!aligned(p) || !aligned(out) || !aligned(q)) outcome = "0:misaligned";
    else if (!fits(n, 8)) outcome = "0:size";
    else if (overlaps(q, n * 4, p, n * 8) || overlaps(q, n * 4, out, n * 8) ||
             (overlaps(p, n * 8, out, n * 8) && p != out))
        outcome = "0:overlap";
    else {
        outcome = p == out ? "in-place" : "n";
        want = n;
        static float rp[8192];
        memcpy(rp, p, n * 8);
        f(rp, ref_out, (uint32_t *)(void *)ref_in, n);
    }
    if (!want) {
        snapshot(0, out, small * 8);
        snapshot(1, q, small * 4);
        snapshot(2, p, small * 8);
    }
    size_t got = f(p, out, q, n);
    reach(QUADS[which].name, outcome);
    current = QUADS[which].name;
    CHECK(got == want);
    if (want) {
        CHECK(memcmp(out, ref_out, n * 8) == 0);
        CHECK(memcmp(q, ref_in, n * 4) == 0);
    }
    CHECK(unchanged());
    reset();
}

/* ---- environment maps ---- */

/* The two distributions: their `kind` and format tag (storage word 0). */
struct dist {
    uint32_t kind, tag;
};
static const struct dist DISTS[2] = {
    {WC_ENVMAP_KIND_HIERARCHICAL, 0x49486377u},
    {WC_ENVMAP_KIND_MARGINAL_CONDITIONAL, 0x434d6377u},
};

/* A `kind`: usually `D`'s, sometimes one that names no distribution. */
static uint32_t hostile_kind(const struct dist *D) {
    uint32_t r = rnd() % 8;
    if (r == 0) return 2 + rnd() % 1000;
    if (r == 1) return UINT32_MAX - rnd() % 4;
    return D->kind;
}

static int known_kind(uint32_t kind) {
    return kind == WC_ENVMAP_KIND_HIERARCHICAL || kind == WC_ENVMAP_KIND_MARGINAL_CONDITIONAL;
}

#define MAX_SIDE ((uint32_t)1 << 24)

/* A side: small, zero, or past a limit. */
static uint32_t hostile_side(void) {
    static const uint32_t big[] = {MAX_SIDE,  MAX_SIDE + 1, UINT32_MAX, 65536, 65537,
                                   40000,     1u << 20,     1u << 31,   46341, 100000};
    uint32_t r = rnd() % 16;
    if (r == 0) return 0;
    if (r <= 3) return big[rnd() % 10];
    return 1 + (uint32_t)below(40);
}

static void one_storage_len(const struct dist *D) {
    uint32_t w = hostile_side(), h = hostile_side(), kind = hostile_kind(D);
    size_t got = wc_envmap_storage_len(kind, w, h);
    const char *name = "wc_envmap_storage_len";
    current = name;
    if (!known_kind(kind)) {
        reach(name, "SIZE_MAX");
        CHECK(got == SIZE_MAX);
    } else if (w == 0 || h == 0) {
        reach(name, "0:zero-side");
        CHECK(got == 0);
    } else if (w > MAX_SIDE || h > MAX_SIDE) {
        reach(name, "SIZE_MAX");
        CHECK(got == SIZE_MAX);
    } else if (got == SIZE_MAX) {
        /* Tables above 2^32 words (hierarchical pads to powers of two: up to 4x). */
        reach(name, "SIZE_MAX");
        CHECK((uint64_t)w * h > UINT32_MAX / 8);
    } else {
        reach(name, "words");
        CHECK((uint64_t)got >= 8 + (uint64_t)w * h && fits_u32(got));
    }
}

/* A small built storage of each kind for the checks and samplers (words at the start of
   `built[k]`, `built_len[k]` of them). */
static uint32_t built[2][8192];
static size_t built_len[2];
#define BW 13
#define BH 7

/* The arrays of a build: weights (`placed_w` bytes) and storage (`placed_s`), flush against
   guard pages; then, in half the calls, one hostile change: a null or misaligned pointer,
   or the weights overlapping the storage or ending just before it. */
static void hostile_build_arrays(size_t placed_w, size_t placed_s, float **weights, uint32_t **storage) {
    int end = rnd() & 1;
    *weights = place(0, placed_w, end, 0);
    *storage = place(1, placed_s, !end, 0);
    switch (rnd() % 8) {
    case 0: *weights = NULL; break;
    case 1: *storage = NULL; break;
    case 2: *weights = place(0, placed_w, end, 1 + below(3)); break;
    case 3: *storage = place(1, placed_s, !end, 1 + below(3)); break;
    case 4: {
        float *base = place(2, 2 * placed_w + placed_s, 1, 0);
        *storage = (uint32_t *)(void *)(base + placed_w / 4);
        *weights = base + below(placed_w / 4 + placed_s / 4);
        break;
    }
    default: break;
    }
}

static void one_build(const struct dist *D) {
    uint32_t w = hostile_side(), h = hostile_side(), kind = hostile_kind(D);
    size_t need = wc_envmap_storage_len(kind, w, h);
    size_t len = hostile_len(need);
    uint64_t texels = (uint64_t)w * h;
    int small = w && h && texels <= 4096 && need <= 60000; /* arrays can be placed */
    size_t placed_w = small ? (size_t)texels * 4 : 64, placed_s = small ? need * 4 : 64;
    int slack = small && len > need && len - need <= 8; /* words the call must not write */
    if (slack) placed_s = len * 4;
    float *weights;
    uint32_t *storage;
    hostile_build_arrays(placed_w, placed_s, &weights, &storage);
    int inf_at = -1;
    if (weights && aligned(weights) && small) {
        fill_floats(weights, (size_t)texels);
        for (size_t i = 0; i < texels; i++)
            if (weights[i] == INFINITY) weights[i] = 1.0f;
        if (rnd() % 4 == 0) {
            inf_at = (int)below((size_t)texels);
            weights[inf_at] = INFINITY;
        }
    }
    /* Half the calls go to the compensated build, with any compensation (known or not) and
       any fraction. */
    int compensated = rnd() & 1;
    uint32_t comps[] = {WC_ENVMAP_COMPENSATION_NONE, WC_ENVMAP_COMPENSATION_UNIFORM,
                        WC_ENVMAP_COMPENSATION_EQUIRECT, 3, UINT32_MAX};
    uint32_t comp = comps[rnd() % 5];
    float fraction;
    fill_floats(&fraction, 1);
    const char *name = compensated ? "wc_envmap_build_compensated" : "wc_envmap_build";
    /* The model, in the documented order. */
    int32_t want;
    int access = 0;
    if (!known_kind(kind) || (compensated && comp > WC_ENVMAP_COMPENSATION_EQUIRECT))
        want = WC_ERR_INVALID_ARGUMENT;
    else if (w == 0 || h == 0) want = WC_ERR_ZERO_SIZE;
    else if (need == SIZE_MAX || !fits64(texels, 4) || !fits(need, 4))
        want = WC_ERR_TOO_LARGE;
    else if (len < need) want = WC_ERR_STORAGE_TOO_SMALL;
    else if (!weights || !storage || !aligned(weights) || !aligned(storage))
        want = WC_ERR_INVALID_ARGUMENT;
    else if (overlaps(weights, (size_t)texels * 4, storage, need * 4)) want = WC_ERR_INVALID_ARGUMENT;
    else {
        access = 1;
        want = inf_at >= 0 ? WC_ERR_INFINITE_WEIGHT : WC_OK;
    }
    if (access && !small) return; /* would need arrays this test does not place */
    snapshot(0, weights, placed_w);
    if (!access) snapshot(1, storage, placed_s);
    /* Exactly `need` words written: the words after them keep what they held (the sentinel,
       or the weights of case 4, which may start there). */
    else if (slack) snapshot(1, storage + need, (len - need) * 4);
    int32_t got = compensated ? wc_envmap_build_compensated(kind, weights, w, h, comp, fraction, storage, len)
                              : wc_envmap_build(kind, weights, w, h, storage, len);
    const char *names[] = {"WC_OK", "WC_ERR_ZERO_SIZE", "WC_ERR_TOO_LARGE", "WC_ERR_LENGTH_MISMATCH",
                           "WC_ERR_STORAGE_TOO_SMALL", "WC_ERR_INFINITE_WEIGHT", "WC_ERR_WRONG_FORMAT",
                           "WC_ERR_UNSUPPORTED_VERSION", "WC_ERR_CORRUPT", "WC_ERR_INVALID_ARGUMENT"};
    reach(name, names[-want]);
    current = name;
    CHECK(got == want);
    CHECK(unchanged()); /* the weights always; the storage when refused, its slack if not */
    if (access) {
        if (want == WC_OK)
            CHECK(wc_envmap_from_storage(storage, need) == WC_OK &&
                  wc_envmap_from_storage_verified(storage, need) == WC_OK);
    }
    reset();
}

/* A storage to check: built, then damaged in one of many ways; `want` is the documented
   code. */
static void one_check(const struct dist *D, const struct dist *other, int verify) {
    int k = (int)(D - DISTS);
    size_t need = built_len[k];
    int end = rnd() & 1;
    size_t len = need;
    uint32_t *s = place(0, need * 4, end, 0);
    memcpy(s, built[k], need * 4);
    int32_t want = WC_OK;
    switch (rnd() % 14) {
    case 0: s = NULL; want = WC_ERR_INVALID_ARGUMENT; break;
    case 1: s = NULL; len = 0; want = WC_ERR_STORAGE_TOO_SMALL; break;
    case 2: /* misaligned: refused, unless there is nothing to read */
        s = place(0, need * 4, end, 1 + below(3));
        len = rnd() % 4 ? need : 0;
        want = len ? WC_ERR_INVALID_ARGUMENT : WC_ERR_STORAGE_TOO_SMALL;
        break;
    case 3: len = (size_t)PTRDIFF_MAX / 4 + 1 + below(3); want = WC_ERR_INVALID_ARGUMENT; break;
    case 4: len = SIZE_MAX; want = WC_ERR_INVALID_ARGUMENT; break;
    case 5: /* shorter than the header, flush against the guard */
        len = below(WC_ENVMAP_HEADER_WORDS);
        s = place(0, len * 4, 1, 0);
        memcpy(s, built[k], len * 4);
        want = WC_ERR_STORAGE_TOO_SMALL;
        break;
    case 6: /* shorter than the header says */
        len = WC_ENVMAP_HEADER_WORDS + below(need - WC_ENVMAP_HEADER_WORDS);
        s = place(0, len * 4, 1, 0);
        memcpy(s, built[k], len * 4);
        want = WC_ERR_STORAGE_TOO_SMALL;
        break;
    case 7: /* the other distribution's storage: read by its own tag */
        len = built_len[other - DISTS];
        s = place(0, len * 4, end, 0);
        memcpy(s, built[other - DISTS], len * 4);
        want = WC_OK;
        break;
    case 8: /* a tag of neither */
        do s[0] = rnd() | 1u;
        while (s[0] == D->tag || s[0] == other->tag);
        want = WC_ERR_WRONG_FORMAT;
        break;
    case 9: { /* any other version: 0, 1 (the corner-padded format), later ones */
        uint32_t v = rnd() % 100;
        s[1] = v == WC_ENVMAP_FORMAT_VERSION ? 1 : v;
        want = WC_ERR_UNSUPPORTED_VERSION;
        break;
    }
    case 10: s[2 + rnd() % 2] = rnd() % 2 ? 0 : MAX_SIDE + 1 + rnd() % 1000; want = WC_ERR_CORRUPT; break;
    case 11: { /* a region length, or a reserved header word (words 9..15, always 0) */
        uint32_t k = rnd() % 3 ? 4 + rnd() % 4 : 9 + rnd() % 7;
        s[k] += 1 + rnd() % 1000;
        want = WC_ERR_CORRUPT;
        break;
    }
    case 12: /* longer than needed: fine */
        len = need + 1 + below(30);
        s = place(0, len * 4, end, 0);
        memcpy(s, built[k], need * 4);
        want = WC_OK;
        break;
    default: /* one bit of a table word or of the checksum (header word 8): the O(1) check
                cannot see it; verify always does (the content checksum) */
        s[rnd() % 4 ? WC_ENVMAP_HEADER_WORDS + below(need - WC_ENVMAP_HEADER_WORDS) : 8] ^=
            1u << (rnd() % 32);
        want = verify ? WC_ERR_CORRUPT : WC_OK;
        break;
    }
    snapshot(0, s, len < need + 64 ? len * 4 : need * 4);
    int32_t got = verify ? wc_envmap_from_storage_verified(s, len) : wc_envmap_from_storage(s, len);
    const char *name = verify ? "wc_envmap_from_storage_verified" : "wc_envmap_from_storage";
    const char *names[] = {"WC_OK", "WC_ERR_ZERO_SIZE", "WC_ERR_TOO_LARGE", "WC_ERR_LENGTH_MISMATCH",
                           "WC_ERR_STORAGE_TOO_SMALL", "WC_ERR_INFINITE_WEIGHT", "WC_ERR_WRONG_FORMAT",
                           "WC_ERR_UNSUPPORTED_VERSION", "WC_ERR_CORRUPT", "WC_ERR_INVALID_ARGUMENT"};
    current = name;
    if (want == 1) {
        CHECK(got == WC_OK || got == WC_ERR_CORRUPT);
        if (got == WC_OK || got == WC_ERR_CORRUPT) reach(name, names[-got]);
        else reach(name, "unexpected");
    } else {
        CHECK(got == want);
        reach(name, names[-want]);
    }
    /* Reads only. */
    CHECK(unchanged());
    reset();
}

/* The arrays of a batch call that reads a storage: a copy `*s` of `need` words of `src`
   (`header` of them the header), the input `*in` and the output `*out` (`in_bytes` and
   `out_bytes`), flush against guard pages; then, in most calls, one hostile change: a null
   or misaligned pointer, `out == in` (in place), overlapping arrays, `out` over the
   storage, a truncated length, a flipped header bit, a garbage word after the first 8. */
static void hostile_arrays(const uint32_t *src, size_t need, size_t header, size_t in_bytes, size_t out_bytes,
                           uint32_t **s, size_t *len, void **in, void **out) {
    int end = rnd() & 1;
    *s = place(0, need * 4, end, 0);
    memcpy(*s, src, need * 4);
    *len = need;
    *in = place(1, in_bytes, !end, 0);
    *out = place(3, out_bytes, end, 0);
    float *base = place(2, in_bytes + out_bytes + need * 4 + 64, 1, 0);
    switch (rnd() % 14) {
    case 0: *s = NULL; break;
    case 1: *in = NULL; break;
    case 2: *out = NULL; break;
    case 3: *s = place(0, need * 4, end, 1 + below(3)); break;
    case 4: *in = place(1, in_bytes, !end, 1 + below(3)); break;
    case 5: *out = place(3, out_bytes, end, 1 + below(3)); break;
    case 6: *out = *in; break; /* in place: allowed for some functions only */
    case 7: *in = base; *out = base + below(in_bytes / 4 + 2); break;
    case 8: /* out over the storage */
        *s = (uint32_t *)(void *)base;
        memcpy(*s, src, need * 4);
        *out = base + below(need + 1);
        break;
    case 9: *len = below(need); break;                                  /* truncated */
    case 10: (*s)[below(header)] ^= 1u << (rnd() % 32); break;          /* bad header (usually) */
    case 11: (*s)[8 + below(need - 8)] = rnd(); break; /* a garbage checksum, reserved or table word */
    default: break;
    }
}

static WcEnvSample ref_samples[4096];
static WcEnvDirection ref_dirs[4096];

/* mode 0: sample, 1: pdf, 2: sample_direction, 3: pdf_direction. */
static void one_sample(const struct dist *D, int mode) {
    int k = (int)(D - DISTS);
    size_t need = built_len[k];
    int pdf = mode == 1 || mode == 3, direction = mode >= 2;
    size_t in_floats = mode == 3 ? 3 : 2, in_elem = in_floats * 4;
    size_t elem = pdf ? 4 : mode == 2 ? sizeof(WcEnvDirection) : sizeof(WcEnvSample);
    uint32_t layout = rnd() % 8 == 0 ? 2 + rnd() % 1000 : rnd() % 2;
    size_t n = hostile_count(elem > in_elem ? elem : in_elem, 300);
    size_t small = n <= 4096 ? n : 0;
    uint32_t *s;
    size_t len;
    void *in, *out;
    hostile_arrays(built[k], need, WC_ENVMAP_HEADER_WORDS, small * in_elem, small * elem, &s, &len, &in, &out);
    float *u = in;
    if (u && aligned(u) && small) fill_floats(u, small * in_floats);
    int storage_ok = s && aligned(s) && wc_envmap_from_storage(s, len) == WC_OK;
    const char *outcome;
    size_t want = 0;
    if (n == 0) outcome = "0:n=0";
    else if (!s || !u || !out) outcome = "0:null";
    else if (!aligned(s) || !aligned(u) || !aligned(out)) outcome = "0:misaligned";
    else if (!fits(n, in_elem) || !fits(n, elem)) outcome = "0:size";
    else if ((overlaps(u, n * in_elem, out, n * elem) && !(pdf && (void *)u == out)) ||
             overlaps(s, len * 4, out, n * elem))
        outcome = "0:overlap";
    else if (direction && layout > WC_ENVMAP_LAYOUT_EQUAL_AREA) outcome = "0:unknown-layout";
    else if (!storage_ok) outcome = "0:invalid-storage";
    else {
        outcome = (void *)u == out ? "in-place" : "n";
        want = n;
        static float ru[3 * 4096];
        static uint32_t rs[8192];
        memcpy(ru, u, n * in_elem);
        memcpy(rs, s, len * 4);
        switch (mode) {
        case 0: wc_envmap_sample(rs, len, ru, ref_samples, n); break;
        case 1: wc_envmap_pdf(rs, len, ru, ref_out, n); break;
        case 2: wc_envmap_sample_direction(rs, len, layout, ru, ref_dirs, n); break;
        default: wc_envmap_pdf_direction(rs, len, layout, ru, ref_out, n); break;
        }
    }
    if (!want) snapshot(0, out, small * elem);
    if (!want || (void *)u != out) snapshot(1, u, small * in_elem);
    snapshot(2, s, len < need ? len * 4 : need * 4);
    size_t got;
    const char *name;
    switch (mode) {
    case 0: got = wc_envmap_sample(s, len, u, out, n); name = "wc_envmap_sample"; break;
    case 1: got = wc_envmap_pdf(s, len, u, out, n); name = "wc_envmap_pdf"; break;
    case 2: got = wc_envmap_sample_direction(s, len, layout, u, out, n); name = "wc_envmap_sample_direction"; break;
    default: got = wc_envmap_pdf_direction(s, len, layout, u, out, n); name = "wc_envmap_pdf_direction"; break;
    }
    reach(name, outcome);
    current = name;
    CHECK(got == want);
    if (want) {
        const void *ref = pdf ? (const void *)ref_out
                              : mode == 2 ? (const void *)ref_dirs : (const void *)ref_samples;
        CHECK(memcmp(out, ref, n * elem) == 0);
        if (pdf) {
            const float *o = out;
            int ok = 1;
            for (size_t i = 0; i < n; i++) ok &= o[i] >= 0.0f && o[i] <= 3.4e38f;
            CHECK(ok);
        } else if (mode == 2) {
            const WcEnvDirection *o = out;
            int inside = 1;
            for (size_t i = 0; i < n; i++) {
                float r2 = o[i].dir[0] * o[i].dir[0] + o[i].dir[1] * o[i].dir[1] +
                           o[i].dir[2] * o[i].dir[2];
                inside &= o[i].texel[0] < BW && o[i].texel[1] < BH && o[i].uv[0] >= 0.0f &&
                          o[i].uv[0] < 1.0f && o[i].uv[1] >= 0.0f && o[i].uv[1] < 1.0f &&
                          o[i].pdf >= 0.0f && o[i].pdf <= 3.4e38f && r2 > 0.999f && r2 < 1.001f;
            }
            CHECK(inside);
        } else {
            const WcEnvSample *o = out;
            int inside = 1;
            for (size_t i = 0; i < n; i++)
                inside &= o[i].texel[0] < BW && o[i].texel[1] < BH && o[i].uv[0] >= 0.0f &&
                          o[i].uv[0] < 1.0f && o[i].uv[1] >= 0.0f && o[i].uv[1] < 1.0f &&
                          o[i].pdf >= 0.0f && o[i].pdf <= 3.4e38f;
            CHECK(inside);
        }
    }
    CHECK(unchanged());
    reset();
}

static void one_weights(void) {
    uint32_t w = hostile_side(), h = hostile_side();
    if (rnd() % 16 == 0) w = h = UINT32_MAX - (uint32_t)below(3); /* no such array */
    uint64_t texels = (uint64_t)w * h;
    int small = w && h && texels <= 8192;
    int end = rnd() & 1;
    float *p = place(0, small ? (size_t)texels * 4 : 64, end, 0);
    uint32_t r = rnd() % 5;
    if (r == 0) p = NULL;
    if (r == 1) p = place(0, small ? (size_t)texels * 4 : 64, end, 1 + below(3));
    int32_t want;
    int access = 0;
    if (w == 0 || h == 0) want = WC_ERR_ZERO_SIZE;
    else if (!fits64(texels, 4)) want = WC_ERR_TOO_LARGE;
    else if (!p || !aligned(p)) want = WC_ERR_INVALID_ARGUMENT;
    else {
        want = WC_OK;
        access = 1;
    }
    if (access && !small) return;
    static float copy[8192];
    if (access) {
        fill_floats(p, (size_t)texels);
        memcpy(copy, p, (size_t)texels * 4);
        wc_envmap_equirect_solid_angle_weights(copy, w, h);
    }
    const char *fname = "wc_envmap_equirect_solid_angle_weights";
    int32_t got = wc_envmap_equirect_solid_angle_weights(p, w, h);
    const char *names[] = {"WC_OK", "WC_ERR_ZERO_SIZE", "WC_ERR_TOO_LARGE", "", "", "", "", "", "", "WC_ERR_INVALID_ARGUMENT"};
    reach(fname, names[-want]);
    current = fname;
    CHECK(got == want);
    if (access) CHECK(memcmp(p, copy, (size_t)texels * 4) == 0);
    else CHECK(untouched_all());
    reset();
}

static void one_equal_area(void) {
    uint32_t sw = hostile_side(), sh = hostile_side(), size = hostile_side();
    uint32_t c = rnd() % 8 == 0 ? rnd() % 7 : 1 + rnd() % 4;
    uint32_t ss = rnd() % 8 == 0 ? (rnd() % 2 ? 65 + rnd() % 100 : 0) : 1 + rnd() % 3;
    if (rnd() % 8 == 0) size = MAX_SIDE + 1; /* the old out-of-bounds write */
    if (size > 24 && size <= MAX_SIDE && rnd() % 2) size = 1 + rnd() % 24;
    uint64_t src_n = (uint64_t)sw * sh * c, dst_n = (uint64_t)size * size * c;
    int small = src_n && dst_n && src_n <= 8192 && dst_n <= 8192;
    /* src below dst in one region, dst flush against the guard page: zeroing or writing
       past a 1-texel dst faults. */
    size_t dst_bytes = small ? (size_t)dst_n * 4 : 4 * (c ? c : 1);
    float *dst = place(1, dst_bytes, 1, 0);
    float *src = place(0, small ? (size_t)src_n * 4 : 64, rnd() & 1, 0);
    switch (rnd() % 8) {
    case 0: src = NULL; break;
    case 1: dst = NULL; break;
    case 2: src = place(0, small ? (size_t)src_n * 4 : 64, 0, 1 + below(3)); break;
    case 3: dst = place(1, dst_bytes, 1, 1 + below(3)); break;
    case 4: /* overlapping */
        src = place(2, (small ? (size_t)(src_n + dst_n) * 4 : 128) + 64, 0, 0);
        dst = src + below(small ? (size_t)src_n + 1 : 16);
        break;
    default: break;
    }
    int32_t want;
    int access = 0;
    if (!sw || !sh || !size || !ss) want = WC_ERR_ZERO_SIZE;
    else if (c < 1 || c > 4) want = WC_ERR_INVALID_ARGUMENT;
    else if (sw > MAX_SIDE || sh > MAX_SIDE || size > MAX_SIDE || ss > 64) want = WC_ERR_TOO_LARGE;
    else if (!fits64(src_n, 4) || !fits64(dst_n, 4))
        want = WC_ERR_TOO_LARGE;
    else if (!src || !dst || !aligned(src) || !aligned(dst)) want = WC_ERR_INVALID_ARGUMENT;
    else if (overlaps(src, (size_t)src_n * 4, dst, (size_t)dst_n * 4)) want = WC_ERR_INVALID_ARGUMENT;
    else {
        want = WC_OK;
        access = 1;
    }
    if (access && !small) return;
    static float rs[8192], rd[8192];
    if (src && aligned(src) && small) fill_floats(src, (size_t)src_n);
    if (access) {
        memcpy(rs, src, (size_t)src_n * 4);
        wc_envmap_equirect_to_equal_area(rs, sw, sh, c, rd, size, ss);
    }
    if (!access) snapshot(0, dst, dst_bytes);
    snapshot(1, src, small ? (size_t)src_n * 4 : 64);
    const char *fname = "wc_envmap_equirect_to_equal_area";
    int32_t got = wc_envmap_equirect_to_equal_area(src, sw, sh, c, dst, size, ss);
    const char *names[] = {"WC_OK", "WC_ERR_ZERO_SIZE", "WC_ERR_TOO_LARGE", "", "", "", "", "", "", "WC_ERR_INVALID_ARGUMENT"};
    reach(fname, names[-want]);
    current = fname;
    CHECK(got == want);
    if (access) CHECK(memcmp(dst, rd, (size_t)dst_n * 4) == 0);
    CHECK(unchanged());
    reset();
}

/* wc_error_string: a static, non-empty string for any code; the named codes get their own. */
static void one_error_string(void) {
    int32_t code = rnd() % 2 ? -(int32_t)(rnd() % 16) : (int32_t)rnd();
    const char *a = wc_error_string(code), *b = wc_error_string(code);
    const char *unknown = wc_error_string(INT32_MIN);
    reach("wc_error_string", "string");
    current = "wc_error_string";
    CHECK(a != NULL && a[0] != 0 && a == b);
    if ((code <= 0 && code >= WC_ERR_OTHER) || (code <= WC_ERR_EMPTY && code >= WC_ERR_ALL_ZERO))
        CHECK(strcmp(a, unknown) != 0);
    else CHECK(strcmp(a, unknown) == 0);
}

/* ---- the sampler: WcSampler values, draws of n (1 to 4) dimensions, slices ---- */

static int blue; /* the blue-noise patterns are patterns of this build */

/* Is `pattern` a pattern of this build (the documented model)? */
static int known(uint32_t pattern) {
    return pattern == WC_PATTERN_PMJ02BN || pattern == WC_PATTERN_SOBOL ||
           (blue && (pattern == WC_PATTERN_BLUE_PMJ02BN || pattern == WC_PATTERN_BLUE_SOBOL));
}

/* A pattern: usually one of the four constants, sometimes garbage. */
static uint32_t hostile_pattern(void) {
    uint32_t r = rnd() % 8;
    if (r < 6) return r % 4;
    return r == 6 ? 4 + rnd() % 8 : rnd();
}

/* A sampler struct with any bits: a root, a child, or garbage fields. */
static WcSampler hostile_sampler(void) {
    uint32_t p = hostile_pattern();
    WcSampler s = wc_sampler_new(p, rnd() % 4 ? rnd() % 256 : rnd(), rnd() % 4 ? rnd() % 256 : rnd(),
                                 rnd(), rnd() % 4 ? rnd() % 64 : rnd(), rnd());
    switch (rnd() % 4) {
    case 0: s = wc_sampler_domain(s, rnd()); break;
    case 1: s = wc_sampler_split(s, rnd(), rnd() % 16, rnd() % 16); break;
    case 2: s.pixel = rnd(); s.domain = rnd(); s.index = rnd() % 2 ? rnd() : UINT32_MAX - rnd() % 8; break;
    default: break;
    }
    s.pattern = p;
    return s;
}

/* A dimension count: usually 1 to 4, sometimes 0, just past 4, or huge. */
static size_t hostile_dims(void) {
    uint32_t r = rnd() % 8;
    if (r == 0) return 0;
    if (r == 1) {
        const size_t bad[] = {5, 6, 8, 255, SIZE_MAX, SIZE_MAX - 3, (size_t)PTRDIFF_MAX + 1, 1u << 31};
        return bad[rnd() % 8];
    }
    return 1 + below(4);
}

/* The ranges a case used hold the sentinel, except `bytes` at `p`. */
static int untouched_except(const void *p, size_t bytes) {
    const unsigned char *lo = p, *hi = lo + bytes;
    for (int i = 0; i < nused; i++)
        for (const unsigned char *b = used[i].lo; b < used[i].hi; b++)
            if ((b < lo || b >= hi) && *b != SENTINEL) return 0;
    return 1;
}

static int same_sampler(WcSampler a, WcSampler b) {
    return a.pattern == b.pattern && a.pixel == b.pixel && a.domain == b.domain && a.index == b.index;
}

/* A value of wc_sampler_draw or wc_sampler_rnd: in [0, 1 - 2^-24], a multiple of 2^-24. */
static int unit24(float v) {
    return v >= 0.0f && v <= 1.0f - 1.0f / 16777216.0f && v * 16777216.0f == floorf(v * 16777216.0f);
}

static void one_sampler_value(void) {
    uint32_t p = hostile_pattern(), k = rnd(), size = rnd() % 4 ? rnd() % 9 : rnd(), sub = rnd() % 4 ? rnd() % 9 : rnd();
    uint32_t r = rnd() % 4;
    current = "wc_sampler_pattern_supported";
    CHECK(wc_sampler_pattern_supported(p) == (uint32_t)known(p));
    reach("wc_sampler_pattern_supported", known(p) ? "1" : "0");

    uint32_t x = r ? rnd() % 256 : rnd(), y = r ? rnd() % 256 : rnd(), frame = rnd(), index = rnd() % 2 ? rnd() % 64 : rnd(),
             sd = rnd();
    /* new_frame is new of the 64-bit sample number frame * max(spp, 1) + index, high word
       as frame (worked here in C's own 64-bit arithmetic); under the blue-noise patterns its
       domain word carries the tag 2 in its low two bits (src/sampler/blue.rs: a root whose
       domains 0..6 are slots), new's the tag 0. */
    uint32_t spp = rnd() % 2 ? rnd() % 9 : rnd();
    uint64_t n = (uint64_t)frame * (spp ? spp : 1u) + index;
    current = "wc_sampler_new_frame";
    WcSampler want = wc_sampler_new(p, x, y, (uint32_t)(n >> 32), (uint32_t)n, sd);
    if (known(p) && (p & 2u)) want.domain = (want.domain & ~3u) | 2u;
    CHECK(same_sampler(wc_sampler_new_frame(p, x, y, frame, spp, index, sd), want));
    reach("wc_sampler_new_frame", known(p) ? "sampler" : "unknown-pattern");
    WcSampler s = wc_sampler_new(p, x, y, frame, index, sd);
    current = "wc_sampler_new";
    float v[4];
    if (known(p)) {
        reach("wc_sampler_new", "sampler");
        CHECK(s.pattern == p && s.index == index);
        CHECK(same_sampler(s, wc_sampler_new(p, x, y, frame, index, sd)));
        CHECK(wc_sampler_draw(s, 2, v) == 2 && unit24(v[0]) && unit24(v[1]));
    } else {
        reach("wc_sampler_new", "unknown-pattern");
        WcSampler z = {p, 0, 0, 0};
        CHECK(same_sampler(s, z));
    }

    /* Children of any struct: garbage fields are safe. */
    if (rnd() % 2) {
        s.pixel = rnd();
        s.domain = rnd();
        s.index = rnd();
    }
    WcSampler d = wc_sampler_domain(s, k), d2 = wc_sampler_domain(s, k ^ (1u + rnd() % 0xffffffu));
    current = "wc_sampler_domain";
    if (known(p)) {
        reach("wc_sampler_domain", "sampler");
        CHECK(d.pattern == p && d.pixel == s.pixel && d.index == s.index);
        CHECK(same_sampler(d, wc_sampler_domain(s, k)));
        CHECK(d.domain != d2.domain); /* different keys, different children */
    } else {
        reach("wc_sampler_domain", "unknown-pattern");
        CHECK(same_sampler(d, s) && same_sampler(d2, s));
    }
    WcSampler c = wc_sampler_split(s, k, size, sub);
    current = "wc_sampler_split";
    if (known(p)) {
        reach("wc_sampler_split", "sampler");
        CHECK(c.pattern == p && c.pixel == s.pixel && c.index == s.index * (size ? size : 1u) + sub);
        CHECK(same_sampler(c, wc_sampler_split(s, k, size, sub)));
        CHECK(size > 1 || same_sampler(c, wc_sampler_split(s, k, 1u - size, sub))); /* 0 acts as 1 */
    } else {
        reach("wc_sampler_split", "unknown-pattern");
        CHECK(same_sampler(c, s));
    }
}

/* A sampler's output of `bytes` bytes, flush against a guard page: one call in six null,
   one in six misaligned. */
static float *hostile_out(size_t bytes) {
    int end = rnd() & 1;
    float *out = place(0, bytes, end, 0);
    uint32_t r = rnd() % 6;
    if (r == 0) return NULL;
    if (r == 1) return place(0, bytes, end, 1 + below(3));
    return out;
}

/* wc_sampler_draw (0), wc_sampler_draw_u32 (1), wc_sampler_rnd (2). */
static void one_sampler_draw(int which) {
    static const char *names[] = {"wc_sampler_draw", "wc_sampler_draw_u32", "wc_sampler_rnd"};
    WcSampler s = hostile_sampler();
    size_t n = hostile_dims();
    size_t small = n >= 1 && n <= 4 ? n : 4; /* elements placed */
    float *out = hostile_out(small * 4);
    const char *outcome;
    size_t want = 0;
    if (n < 1 || n > 4) outcome = "0:n-range";
    else if (!known(s.pattern)) outcome = "0:unknown-pattern";
    else if (!out) outcome = "0:null";
    else if (!aligned(out)) outcome = "0:misaligned";
    else {
        outcome = "n";
        want = n;
    }
    size_t got = which == 0 ? wc_sampler_draw(s, n, out)
               : which == 1 ? wc_sampler_draw_u32(s, n, (uint32_t *)(void *)out)
                            : wc_sampler_rnd(s, n, out);
    reach(names[which], outcome);
    current = names[which];
    CHECK(got == want);
    if (want) {
        /* Exactly n values written, each documented. */
        CHECK(untouched_except(out, n * 4));
        float f[4];
        uint32_t w[4];
        int ok = 1;
        if (which == 2) {
            CHECK(wc_sampler_rnd(s, n, f) == n && memcmp(f, out, n * 4) == 0);
            for (size_t i = 0; i < n; i++) ok &= unit24(out[i]);
        } else {
            CHECK(wc_sampler_draw(s, n, f) == n && wc_sampler_draw_u32(s, n, w) == n);
            CHECK(memcmp(which == 0 ? (const void *)f : (const void *)w, out, n * 4) == 0);
            for (size_t i = 0; i < n; i++)
                ok &= unit24(f[i]) && f[i] == (float)(w[i] >> 8) * (1.0f / 16777216.0f) && f[i] < 1.0f;
        }
        CHECK(ok);
    } else {
        CHECK(untouched_all());
    }
    reset();
}

static float slice_ref[4 * 300];

static void one_sampler_slice(void) {
    WcSampler s = hostile_sampler();
    size_t n_dims = hostile_dims();
    int dims_ok = n_dims >= 1 && n_dims <= 4;
    size_t count = hostile_count(4 * (dims_ok ? n_dims : 1), 300);
    size_t placed = dims_ok && count <= 300 ? count * n_dims : 16; /* floats */
    float *out = hostile_out(placed * 4);
    const char *outcome;
    size_t want = 0;
    if (count == 0) outcome = "0:count=0";
    else if (!dims_ok) outcome = "0:n_dims-range";
    else if (!known(s.pattern)) outcome = "0:unknown-pattern";
    else if (!out) outcome = "0:null";
    else if (!aligned(out)) outcome = "0:misaligned";
    else if (!fits(count, 4 * n_dims)) outcome = "0:size";
    else {
        outcome = "count";
        want = count;
    }
    if (want && count > 300) return; /* would need arrays this test does not place */
    size_t got = wc_sampler_draw_slice(s, n_dims, out, count);
    reach("wc_sampler_draw_slice", outcome);
    current = "wc_sampler_draw_slice";
    CHECK(got == want);
    if (want) {
        /* Exactly count * n_dims floats: the scalar draws at s.index, s.index + 1, ... */
        CHECK(untouched_except(out, count * n_dims * 4));
        int ok = 1;
        for (size_t i = 0; i < count; i++) {
            WcSampler t = s;
            t.index = s.index + (uint32_t)i; /* wrapping */
            ok &= wc_sampler_draw(t, n_dims, slice_ref + i * n_dims) == n_dims;
        }
        for (size_t i = 0; i < count * n_dims; i++) ok &= unit24(out[i]);
        CHECK(ok && memcmp(out, slice_ref, count * n_dims * 4) == 0);
    } else {
        CHECK(untouched_all());
    }
    reset();
}


/* ---- the light tree ---- */

#define TREE_LIGHTS 40
static uint32_t tree_built[4096];
static size_t tree_len;

static void tree_light(WcLightBounds *l, int i) {
    float x = (float)(i % 7), y = (float)(i % 5), z = (float)(i % 3);
    WcLightBounds v = {{x, y, z}, {x + 0.5f, y + 0.25f, z}, 1.0f + (float)(i % 4),
                       {0.0f, (float)(i % 2) - 0.5f, 1.0f}, i % 2 ? 1.0f : -1.0f, 0.0f,
                       (uint32_t)(i % 3 == 0)};
    *l = v;
}

static const char *TREE_CODES[] = {"WC_OK", "", "WC_ERR_TOO_LARGE", "", "WC_ERR_STORAGE_TOO_SMALL", "",
                                   "WC_ERR_WRONG_FORMAT", "WC_ERR_UNSUPPORTED_VERSION", "WC_ERR_CORRUPT",
                                   "WC_ERR_INVALID_ARGUMENT", "", "WC_ERR_EMPTY", "WC_ERR_INVALID_WEIGHT",
                                   "WC_ERR_INVALID_BOUNDS", "WC_ERR_ALL_ZERO"};

static void one_tree_storage_len(void) {
    static const size_t odd[] = {SIZE_MAX, ((size_t)1 << 24) + 1, (size_t)1 << 24, 0};
    size_t n = rnd() % 4 == 0 ? odd[rnd() % 4] : below(1000);
    size_t got = wc_lights_tree_storage_len(n);
    current = "wc_lights_tree_storage_len";
    if (n > ((size_t)1 << 24)) {
        reach(current, "SIZE_MAX");
        CHECK(got == SIZE_MAX);
    } else {
        reach(current, "words");
        CHECK(got == 16 + 48 * (n / 3 + 14) + n);
    }
}

static void one_tree_build(void) {
    static const size_t huge[] = {SIZE_MAX, ((size_t)1 << 24) + 1, (size_t)PTRDIFF_MAX / 8 + 1};
    size_t n = rnd() % 8 == 0 ? 0 : rnd() % 8 == 1 ? huge[rnd() % 3] : 1 + below(TREE_LIGHTS);
    int small = n >= 1 && n <= TREE_LIGHTS;
    size_t need = wc_lights_tree_storage_len(n), len = hostile_len(need);
    size_t lb = small ? n * sizeof(WcLightBounds) : 64, sb = small ? need * 4 : 64;
    int end = rnd() & 1;
    WcLightBounds *lights = place(0, lb, end, 0);
    uint32_t *storage = place(1, small && len > need && len - need <= 8 ? len * 4 : sb, !end, 0);
    switch (rnd() % 8) {
    case 0: lights = NULL; break;
    case 1: storage = NULL; break;
    case 2: lights = (WcLightBounds *)(void *)((unsigned char *)place(0, lb + 4, end, 0) + 1 + below(3)); break;
    case 3: storage = (uint32_t *)(void *)((unsigned char *)place(1, sb + 4, !end, 0) + 1 + below(3)); break;
    case 4: { /* the lights overlapping the storage */
        unsigned char *base = place(2, 2 * lb + sb, 1, 0);
        storage = (uint32_t *)(void *)(base + (lb & ~(size_t)3));
        lights = (WcLightBounds *)(void *)(base + 4 * below((lb + sb) / 4));
        break;
    }
    default: break;
    }
    int bad = -1; /* 0: NaN power, 1: min > max, 2: all zero */
    if (lights && aligned(lights) && small) {
        for (size_t i = 0; i < n; i++) tree_light(&lights[i], (int)i);
        if (rnd() % 3 == 0) {
            bad = (int)(rnd() % 3);
            size_t at = below(n);
            if (bad == 0) lights[at].power = rnd() & 1 ? NAN : -1.0f;
            if (bad == 1) lights[at].min[rnd() % 3] = 100.0f;
            if (bad == 2)
                for (size_t i = 0; i < n; i++) lights[i].power = 0.0f;
        }
    }
    int32_t want;
    int access = 0;
    if (n == 0) want = WC_ERR_EMPTY;
    else if (need == SIZE_MAX || !fits(n, sizeof(WcLightBounds)) || !fits(need, 4)) want = WC_ERR_TOO_LARGE;
    else if (len < need) want = WC_ERR_STORAGE_TOO_SMALL;
    else if (!lights || !storage || !aligned(lights) || !aligned(storage)) want = WC_ERR_INVALID_ARGUMENT;
    else if (overlaps(lights, n * sizeof(WcLightBounds), storage, need * 4)) want = WC_ERR_INVALID_ARGUMENT;
    else {
        access = 1;
        want = bad == 0 ? WC_ERR_INVALID_WEIGHT : bad == 1 ? WC_ERR_INVALID_BOUNDS : bad == 2 ? WC_ERR_ALL_ZERO : WC_OK;
    }
    if (access && !small) return;
    snapshot(0, lights, lb);
    if (!access) snapshot(1, storage, sb);
    else if (len > need && len - need <= 8) snapshot(1, storage + need, (len - need) * 4);
    int32_t got = wc_lights_tree_build(lights, n, storage, len);
    current = "wc_lights_tree_build";
    reach(current, TREE_CODES[-want]);
    CHECK(got == want);
    CHECK(unchanged());
    if (want == WC_OK)
        CHECK(wc_lights_tree_from_storage(storage, need) == WC_OK &&
              wc_lights_tree_from_storage_verified(storage, need) == WC_OK);
    reset();
}

static void one_tree_check(int verify) {
    size_t need = tree_len, len = need;
    int end = rnd() & 1;
    uint32_t *s = place(0, need * 4, end, 0);
    memcpy(s, tree_built, need * 4);
    int32_t want = WC_OK;
    switch (rnd() % 13) {
    case 0: s = NULL; want = WC_ERR_INVALID_ARGUMENT; break;
    case 1: s = NULL; len = 0; want = WC_ERR_STORAGE_TOO_SMALL; break;
    case 2:
        s = (uint32_t *)(void *)((unsigned char *)place(0, need * 4 + 4, end, 0) + 1 + below(3));
        want = WC_ERR_INVALID_ARGUMENT;
        break;
    case 3: len = (size_t)PTRDIFF_MAX / 4 + 1 + below(3); want = WC_ERR_INVALID_ARGUMENT; break;
    case 4: /* shorter than the header, or than the header says, flush against the guard */
        len = below(need);
        s = place(0, len * 4, 1, 0);
        memcpy(s, tree_built, len * 4);
        want = WC_ERR_STORAGE_TOO_SMALL;
        break;
    case 5: s[0] ^= 1u << (rnd() % 32); want = WC_ERR_WRONG_FORMAT; break;
    case 6: /* version 1 (8-word nodes) or a later one */
        s[1] = rnd() % 2 ? 1 : 3 + rnd() % 100;
        want = WC_ERR_UNSUPPORTED_VERSION;
        break;
    case 7: { /* n, m, levels or a reserved header word */
        static const uint32_t words[] = {2, 3, 4, 5, 6, 7, 9, 15};
        uint32_t k = words[rnd() % 8];
        s[k] = k == 2 || k == 3 ? 0 : s[k] + 1 + rnd() % 1000;
        want = WC_ERR_CORRUPT;
        break;
    }
    case 8: /* longer than needed: fine */
        len = need + 1 + below(30);
        s = place(0, len * 4, end, 0);
        memcpy(s, tree_built, need * 4);
        break;
    default: /* one bit of a body word or of the checksum: verify catches it */
        s[rnd() % 4 ? 16 + below(need - 16) : 8] ^= 1u << (rnd() % 32);
        want = verify ? WC_ERR_CORRUPT : WC_OK;
        break;
    }
    snapshot(0, s, len < need + 64 ? len * 4 : need * 4);
    int32_t got = verify ? wc_lights_tree_from_storage_verified(s, len) : wc_lights_tree_from_storage(s, len);
    current = verify ? "wc_lights_tree_from_storage_verified" : "wc_lights_tree_from_storage";
    reach(current, TREE_CODES[-want]);
    CHECK(got == want);
    CHECK(unchanged());
    reset();
}

/* mode 0: sample (outputs index, prob), 1: pmf (inputs index, output out). */
static void one_tree_sample(int mode) {
    size_t need = tree_len, len = need;
    size_t n = hostile_count(12, 300);
    size_t small = n <= 300 ? n : 0;
    int end = rnd() & 1;
    uint32_t *s = place(0, need * 4, end, 0);
    memcpy(s, tree_built, need * 4);
    float *p = place(1, small * 12, !end, 0);
    float *nrm = place(2, small * 12, end, 0);
    void *a = place(3, small * 4, !end, 0); /* sample: u; pmf: index */
    void *b = place(4, small * 4, end, 0);  /* sample: index; pmf: out */
    void *c = place(5, small * 4, !end, 0); /* sample: prob */
    switch (rnd() % 14) {
    case 0: s = NULL; break;
    case 1: p = NULL; break;
    case 2: nrm = NULL; break;
    case 3: a = NULL; break;
    case 4: b = NULL; break;
    case 5: c = mode == 0 ? NULL : c; break;
    case 6: p = (float *)(void *)((unsigned char *)place(1, small * 12 + 4, !end, 0) + 1 + below(3)); break;
    case 7: b = (unsigned char *)place(4, small * 4 + 4, end, 0) + 1 + below(3); break;
    case 8: { /* an output over p, or just after it */
        unsigned char *base = place(1, small * 16 + 16, end, 0);
        p = (float *)(void *)base;
        b = base + 4 * below(3 * small + 1);
        break;
    }
    case 9: if (mode == 0) c = b; else b = a; break; /* outputs over each other / over index */
    case 10: b = (unsigned char *)s + 4 * below(need); break; /* an output over the storage */
    case 11: len = below(need); break;
    case 12: s[below(16)] ^= 1u << (rnd() % 32); break;
    default: break;
    }
    if (p && aligned(p) && small) fill_floats(p, 3 * small);
    if (nrm && aligned(nrm) && small) fill_floats(nrm, 3 * small);
    if (a && aligned(a) && small) {
        if (mode == 0) fill_floats(a, small);
        else for (size_t i = 0; i < small; i++) ((uint32_t *)a)[i] = rnd() % (TREE_LIGHTS + 3);
    }
    int storage_ok = s && aligned(s) && wc_lights_tree_from_storage(s, len) == WC_OK;
    size_t outs = mode == 0 ? 2 : 1;
    void *out[2] = {b, c};
    int any_null = !s || !p || !nrm || !a || !b || (mode == 0 && !c);
    int any_mis = !aligned(s) || !aligned(p) || !aligned(nrm) || !aligned(a) || !aligned(b) || (mode == 0 && !aligned(c));
    int ov = 0;
    for (size_t k = 0; k < outs; k++) {
        ov |= overlaps(out[k], n * 4, p, n * 12) || overlaps(out[k], n * 4, nrm, n * 12) ||
              overlaps(out[k], n * 4, a, n * 4) || overlaps(out[k], n * 4, s, len * 4);
    }
    if (mode == 0) ov |= overlaps(b, n * 4, c, n * 4);
    const char *outcome;
    size_t want = 0;
    if (n == 0) outcome = "0:n=0";
    else if (any_null) outcome = "0:null";
    else if (any_mis) outcome = "0:misaligned";
    else if (!fits(n, 12)) outcome = "0:size";
    else if (ov) outcome = "0:overlap";
    else if (!storage_ok) outcome = "0:invalid-storage";
    else {
        outcome = "n";
        want = n;
    }
    if (want && !small) return;
    if (!want) {
        snapshot(0, b, small * 4);
        if (mode == 0) snapshot(1, c, small * 4);
    }
    snapshot(2, p, small * 12);
    snapshot(3, s, len < need ? len * 4 : need * 4);
    size_t got = mode == 0 ? wc_lights_tree_sample(s, len, p, nrm, a, b, c, n)
                           : wc_lights_tree_pmf(s, len, p, nrm, a, b, n);
    current = mode == 0 ? "wc_lights_tree_sample" : "wc_lights_tree_pmf";
    reach(current, outcome);
    CHECK(got == want);
    if (want) {
        int ok = 1;
        for (size_t i = 0; i < n; i++) {
            float q = mode == 0 ? ((float *)c)[i] : ((float *)b)[i];
            ok &= q >= 0.0f && q <= 1.0f;
            if (mode == 0) {
                uint32_t idx = ((uint32_t *)b)[i];
                ok &= q > 0.0f ? idx < TREE_LIGHTS : idx == UINT32_MAX;
                if (q > 0.0f) {
                    float back;
                    ok &= wc_lights_tree_pmf(s, len, p + 3 * i, nrm + 3 * i, &idx, &back, 1) == 1 &&
                          memcmp(&back, &q, 4) == 0;
                }
            }
        }
        CHECK(ok);
    }
    CHECK(unchanged());
    reset();
}

/* Calls with no arguments to get wrong. */
static void constants(void) {
    current = "constants";
    CHECK(wc_pmj02bn_points() >= 1024 && (wc_pmj02bn_points() & (wc_pmj02bn_points() - 1)) == 0);
    reach("wc_pmj02bn_points", "value");
    CHECK(wc_pmj02bn_sets() == 1 || wc_pmj02bn_sets() == 4);
    reach("wc_pmj02bn_sets", "value");
}

/* ---- light selection: the alias table ---- */

#define NL 37
static uint32_t lights_built[8 + 4 * NL];
static size_t lights_len;
static const char *LIGHT_CODES[] = {"WC_OK", "WC_ERR_ZERO_SIZE", "WC_ERR_TOO_LARGE", "", "WC_ERR_STORAGE_TOO_SMALL",
                                    "", "WC_ERR_WRONG_FORMAT", "WC_ERR_UNSUPPORTED_VERSION", "WC_ERR_CORRUPT",
                                    "WC_ERR_INVALID_ARGUMENT", "", "WC_ERR_EMPTY", "WC_ERR_INVALID_WEIGHT",
                                    "", "WC_ERR_ALL_ZERO"};

static void one_lights_len(void) {
    size_t n = rnd() % 4 ? below(100) : (rnd() % 2 ? ((size_t)1 << 26) + below(3) : SIZE_MAX - below(3));
    size_t got = wc_lights_alias_storage_len(n);
    const char *name = "wc_lights_alias_storage_len";
    current = name;
    if (n > ((size_t)1 << 26)) {
        reach(name, "SIZE_MAX");
        CHECK(got == SIZE_MAX);
    } else {
        reach(name, "words");
        CHECK(got == 8 + 4 * n);
    }
}

static void one_lights_build(void) {
    size_t n = rnd() % 8 ? below(60) : (rnd() % 2 ? ((size_t)1 << 26) + 1 : (size_t)PTRDIFF_MAX);
    size_t need = wc_lights_alias_storage_len(n);
    size_t len;
    switch (rnd() % 5) {
    case 0: len = need - 1; break;
    case 1: len = need + below(5); break;
    default: len = need; break;
    }
    int small = n <= 60;
    size_t placed_w = small && n ? n * 4 : 64, placed_s = small ? need * 4 + 20 : 64;
    float *weights;
    uint32_t *storage;
    hostile_build_arrays(placed_w, placed_s, &weights, &storage);
    int bad = -1, zero = 1;
    if (weights && aligned(weights) && small) {
        for (size_t i = 0; i < n; i++) weights[i] = rnd() % 3 ? (float)(rnd() % 1000) * 0.01f : 0.0f;
        if (rnd() % 4 == 0) {
            for (size_t i = 0; i < n; i++) weights[i] = 0.0f;
        }
        if (n && rnd() % 4 == 0) {
            const float bads[] = {NAN, INFINITY, -INFINITY, -1.0f, -1e-30f};
            bad = (int)below(n);
            weights[bad] = bads[rnd() % 5];
        }
        for (size_t i = 0; i < n; i++) zero &= weights[i] == 0.0f;
    }
    int32_t want;
    int access = 0;
    if (n == 0) want = WC_ERR_EMPTY;
    else if (need == SIZE_MAX || !fits(n, 4) || !fits(need, 4)) want = WC_ERR_TOO_LARGE;
    else if (len < need) want = WC_ERR_STORAGE_TOO_SMALL;
    else if (!weights || !storage || !aligned(weights) || !aligned(storage)) want = WC_ERR_INVALID_ARGUMENT;
    else if (overlaps(weights, n * 4, storage, need * 4)) want = WC_ERR_INVALID_ARGUMENT;
    else {
        access = 1;
        want = bad >= 0 ? WC_ERR_INVALID_WEIGHT : zero ? WC_ERR_ALL_ZERO : WC_OK;
    }
    if (access && !small) return;
    snapshot(0, weights, placed_w);
    if (!access) snapshot(1, storage, placed_s);
    else if (len > need) snapshot(1, storage + need, (len - need) * 4);
    int32_t got = wc_lights_alias_build(weights, n, storage, len);
    const char *name = "wc_lights_alias_build";
    reach(name, LIGHT_CODES[-want]);
    current = name;
    CHECK(got == want);
    CHECK(unchanged());
    if (want == WC_OK)
        CHECK(wc_lights_alias_from_storage(storage, need) == WC_OK &&
              wc_lights_alias_from_storage_verified(storage, need) == WC_OK);
    reset();
}

static void one_lights_check(int verify) {
    size_t need = lights_len, len = need;
    int end = rnd() & 1;
    uint32_t *s = place(0, need * 4, end, 0);
    memcpy(s, lights_built, need * 4);
    int32_t want = WC_OK;
    switch (rnd() % 11) {
    case 0: s = NULL; want = WC_ERR_INVALID_ARGUMENT; break;
    case 1: s = place(0, need * 4, end, 1 + below(3)); want = WC_ERR_INVALID_ARGUMENT; break;
    case 2: len = SIZE_MAX; want = WC_ERR_INVALID_ARGUMENT; break;
    case 3: len = below(8); s = place(0, len * 4, 1, 0); memcpy(s, lights_built, len * 4);
        want = WC_ERR_STORAGE_TOO_SMALL; break;
    case 4: len = 8 + below(need - 8); s = place(0, len * 4, 1, 0); memcpy(s, lights_built, len * 4);
        want = WC_ERR_STORAGE_TOO_SMALL; break;
    case 5: s[0] ^= 1u << (rnd() % 32); want = WC_ERR_WRONG_FORMAT; break;
    case 6: s[1] = 2 + rnd() % 100; want = WC_ERR_UNSUPPORTED_VERSION; break;
    case 7: if (rnd() % 2) s[2] = rnd() % 2 ? 0 : (1u << 26) + 1 + rnd() % 100;
        else s[4 + rnd() % 4] = 1 + rnd() % 1000;
        want = WC_ERR_CORRUPT; break;
    case 8: /* one bit of a column or of the checksum: only verify sees it */
        s[rnd() % 4 ? 8 + below(need - 8) : 3] ^= 1u << (rnd() % 32);
        want = verify ? WC_ERR_CORRUPT : WC_OK;
        break;
    default: break;
    }
    snapshot(0, s, len < need + 64 ? len * 4 : need * 4);
    int32_t got = verify ? wc_lights_alias_from_storage_verified(s, len) : wc_lights_alias_from_storage(s, len);
    const char *name = verify ? "wc_lights_alias_from_storage_verified" : "wc_lights_alias_from_storage";
    reach(name, LIGHT_CODES[-want]);
    current = name;
    CHECK(got == want);
    CHECK(unchanged());
    reset();
}

/* mode 0: sample (float u -> WcLightChoice), 1: pmf (uint32 index -> float, in place allowed). */
static void one_lights_sample(int mode) {
    size_t need = lights_len;
    size_t elem = mode ? 4 : sizeof(WcLightChoice), in_elem = 4;
    size_t n = hostile_count(elem, 300);
    size_t small = n <= 4096 ? n : 0;
    uint32_t *s;
    size_t len;
    void *in, *out;
    hostile_arrays(lights_built, need, 8, small * in_elem, small * elem, &s, &len, &in, &out);
    if (in && aligned(in) && small) {
        if (mode) {
            uint32_t *idx = in;
            for (size_t i = 0; i < small; i++) idx[i] = rnd() % 4 ? rnd() % (NL + 3) : rnd();
        } else {
            fill_floats(in, small);
        }
    }
    int storage_ok = s && aligned(s) && wc_lights_alias_from_storage(s, len) == WC_OK;
    const char *outcome;
    size_t want = 0;
    static WcLightChoice ref_choices[4096];
    if (n == 0) outcome = "0:n=0";
    else if (!s || !in || !out) outcome = "0:null";
    else if (!aligned(s) || !aligned(in) || !aligned(out)) outcome = "0:misaligned";
    else if (!fits(n, in_elem) || !fits(n, elem)) outcome = "0:size";
    else if ((overlaps(in, n * in_elem, out, n * elem) && !(mode && in == out)) || overlaps(s, len * 4, out, n * elem))
        outcome = "0:overlap";
    else if (!storage_ok) outcome = "0:invalid-storage";
    else {
        outcome = in == out ? "in-place" : "n";
        want = n;
        static uint32_t rin[4096], rs[8 + 4 * NL];
        memcpy(rin, in, n * 4);
        memcpy(rs, s, need * 4);
        if (mode) wc_lights_alias_pmf(rs, len, rin, ref_out, n);
        else wc_lights_alias_sample(rs, len, (const float *)(void *)rin, ref_choices, n);
    }
    if (!want) snapshot(0, out, small * elem);
    if (!want || in != out) snapshot(1, in, small * in_elem);
    snapshot(2, s, len < need ? len * 4 : need * 4);
    const char *name = mode ? "wc_lights_alias_pmf" : "wc_lights_alias_sample";
    size_t got = mode ? wc_lights_alias_pmf(s, len, in, out, n) : wc_lights_alias_sample(s, len, in, out, n);
    reach(name, outcome);
    current = name;
    CHECK(got == want);
    if (want) {
        CHECK(memcmp(out, mode ? (const void *)ref_out : (const void *)ref_choices, n * elem) == 0);
        int ok = 1;
        for (size_t i = 0; i < n; i++) {
            if (mode) {
                float p = ((const float *)out)[i];
                ok &= p >= 0.0f && p <= 1.0f;
            } else {
                WcLightChoice c = ((const WcLightChoice *)out)[i];
                ok &= c.index < NL && c.prob >= 0.0f && c.prob <= 1.0f;
            }
        }
        CHECK(ok);
    }
    CHECK(unchanged());
    reset();
}

int main(int argc, char **argv) {
    unsigned long rounds = argc > 1 ? strtoul(argv[1], NULL, 10) : 400;
    guard_pages();
    /* The storages the checks and samplers damage. */
    for (int k = 0; k < 2; k++) {
        float w[BW * BH];
        for (int i = 0; i < BW * BH; i++) w[i] = i % 5 == 0 ? 0.0f : (float)(i % 7) + 0.5f;
        built_len[k] = wc_envmap_storage_len(DISTS[k].kind, BW, BH);
        if (built_len[k] > 8192 || wc_envmap_build(DISTS[k].kind, w, BW, BH, built[k], built_len[k]) != WC_OK) {
            fprintf(stderr, "cannot build the reference storage\n");
            return 2;
        }
    }
    {
        float w[NL];
        for (int i = 0; i < NL; i++) w[i] = i % 4 == 1 ? 0.0f : (float)(i % 9) + 0.25f;
        lights_len = wc_lights_alias_storage_len(NL);
        if (wc_lights_alias_build(w, NL, lights_built, lights_len) != WC_OK) {
            fprintf(stderr, "cannot build the reference alias table\n");
            return 2;
        }
    }
    for (int i = 0; i < TREE_LIGHTS; i++) {
        static WcLightBounds tl[TREE_LIGHTS];
        tree_light(&tl[i], i);
        if (i == TREE_LIGHTS - 1) {
            tree_len = wc_lights_tree_storage_len(TREE_LIGHTS);
            if (tree_len > 4096 || wc_lights_tree_build(tl, TREE_LIGHTS, tree_built, tree_len) != WC_OK) {
                fprintf(stderr, "cannot build the reference light tree\n");
                return 2;
            }
        }
    }
    constants();
    /* The blue-noise patterns are both of this build, or neither (the `blue-noise` feature). */
    blue = wc_sampler_pattern_supported(WC_PATTERN_BLUE_PMJ02BN) != 0;
    current = "constants";
    CHECK(wc_sampler_pattern_supported(WC_PATTERN_BLUE_SOBOL) == (uint32_t)blue);
    for (unsigned long r = 0; r < rounds; r++) {
        for (size_t i = 0; i < NMAPS; i++) one_map(&MAPS[i]);
        for (size_t i = 0; i < NGENS; i++) one_gen(&GENS[i]);
        for (int i = 0; i < 2; i++) {
            one_pair(&PAIRS[i]);
            one_four(i);
            one_quad(i);
            one_storage_len(&DISTS[i]);
            one_build(&DISTS[i]);
            one_check(&DISTS[i], &DISTS[1 - i], 0);
            one_check(&DISTS[i], &DISTS[1 - i], 1);
            for (int mode = 0; mode < 4; mode++) one_sample(&DISTS[i], mode);
        }
        one_weights();
        one_equal_area();
        one_error_string();
        one_sampler_value();
        for (int i = 0; i < 3; i++) one_sampler_draw(i);
        one_sampler_slice();
        for (int i = 0; i < 11; i++) one_light(i);
        one_lights_len();
        one_lights_build();
        one_lights_check(0);
        one_lights_check(1);
        one_lights_sample(0);
        one_lights_sample(1);
        one_tree_storage_len();
        one_tree_build();
        one_tree_check(0);
        one_tree_check(1);
        one_tree_sample(0);
        one_tree_sample(1);
    }
    for (int i = 0; i < nrows; i++) printf("row %s %s %lu\n", rows[i].fn, rows[i].outcome, rows[i].calls);
    printf("%lu hostile calls, %lu passed, %lu failed\n", calls, passed, failed);
    return failed == 0 ? 0 : 1;
}
