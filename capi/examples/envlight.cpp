// Direct lighting of a diffuse ground plane from a disk light and an environment map, through
// warpcore's C API, written as a PFM image.
//
//   envlight [map.pfm] [out.pfm] [size] [spp]
//
// Scene: the plane z = 0 (albedo 0.8) seen from above over [-1.5, 1.5]^2, one shading point
// per pixel; a disk light (radius 0.5, at height 2, facing down) and a lat-long environment
// map (row 0 around +z); a sphere hovering over the plane casts shadows from both.
//
// Disk light: pmj02bn points, four disk samples per point with polar4 (spp / 4 points per
// pixel). Environment: hierarchical importance sampling of the map's luminance times the rows'
// solid angle, from tables built once, saved to a file and loaded back (as an asset pipeline
// would), checked with wc_envmap_from_storage_verified. Each pixel uses its own pmj02bn seed.
//
// Self-check (exit status 1 on failure): the light the environment reflects off an unoccluded
// plane, estimated with importance sampling, agrees with the exact sum over the map's texels.
#include "warpcore.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Vec3 {
    float x, y, z;
};

Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

struct Image {
    uint32_t width = 0, height = 0;
    std::vector<float> rgb;  // row 0 at the top (+z for a lat-long map)
};

// A PFM ("PF", little-endian) image; PFM stores rows bottom to top.
bool read_pfm(const std::string &path, Image &img) {
    FILE *f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    char magic[3] = {};
    float scale = 0;
    bool ok = std::fscanf(f, "%2s %u %u %f", magic, &img.width, &img.height, &scale) == 4 &&
              std::strcmp(magic, "PF") == 0 && scale < 0 && std::fgetc(f) != EOF;
    if (ok) {
        std::vector<float> bottom_up(size_t(img.width) * img.height * 3);
        ok = std::fread(bottom_up.data(), 4, bottom_up.size(), f) == bottom_up.size();
        img.rgb.resize(bottom_up.size());
        size_t row = size_t(img.width) * 3;
        for (uint32_t r = 0; ok && r < img.height; r++)
            std::memcpy(&img.rgb[r * row], &bottom_up[(img.height - 1 - r) * row], row * 4);
    }
    std::fclose(f);
    return ok;
}

bool write_pfm(const std::string &path, const Image &img) {
    FILE *f = std::fopen(path.c_str(), "wb");
    if (!f) return false;
    std::fprintf(f, "PF\n%u %u\n-1.0\n", img.width, img.height);
    size_t row = size_t(img.width) * 3;
    bool ok = true;
    for (uint32_t r = img.height; ok && r-- > 0;)
        ok = std::fwrite(&img.rgb[r * row], 4, row, f) == row;
    return std::fclose(f) == 0 && ok;
}

// Does the segment from p along unit w, up to distance t_max, hit the occluding sphere?
const Vec3 kSphere = {0.35f, 0.0f, 0.6f};
const float kSphereRadius = 0.35f;
bool occluded(Vec3 p, Vec3 w, float t_max) {
    Vec3 o = p - kSphere;
    float b = dot(o, w), c = dot(o, o) - kSphereRadius * kSphereRadius;
    float disc = b * b - c;
    if (disc < 0) return false;
    float t = -b - std::sqrt(disc);
    return t > 1e-4f && t < t_max;
}

const float kPi = 3.14159265358979f;
const float kAlbedo = 0.8f;
const Vec3 kLightCentre = {-0.3f, 0.2f, 2.0f};
const float kLightRadius = 0.5f, kLightRadiance = 6.0f;

// Environment tables, loaded from a file.
struct Env {
    Image map;
    std::vector<uint32_t> storage;
};

Vec3 env_radiance(const Env &env, uint32_t column, uint32_t row) {
    const float *c = &env.map.rgb[(size_t(row) * env.map.width + column) * 3];
    return {c[0], c[1], c[2]};
}

// Reflected radiance at plane point p from the environment, n samples (uniforms u), with or
// without the occluder.
Vec3 env_light(const Env &env, Vec3 p, const float *u, size_t n, std::vector<WcEnvSample> &s,
               std::vector<float> &dirs, std::vector<float> &pdf_sa, bool shadows = true) {
    const size_t len = env.storage.size();
    if (wc_envmap_sample(env.storage.data(), len, u, s.data(), n) != n) std::abort();
    std::vector<float> uv(2 * n), pdf(n), v(n);
    for (size_t i = 0; i < n; i++) {
        uv[2 * i] = s[i].uv[0];
        uv[2 * i + 1] = s[i].uv[1];
        pdf[i] = s[i].pdf;
        v[i] = s[i].uv[1];
    }
    wc_sphere_equirect(uv.data(), dirs.data(), n);
    wc_envmap_equirect_pdf_to_solid_angle(pdf.data(), v.data(), pdf_sa.data(), n);
    Vec3 sum = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        Vec3 w = {dirs[3 * i], dirs[3 * i + 1], dirs[3 * i + 2]};
        if (w.z <= 0 || pdf_sa[i] <= 0 || (shadows && occluded(p, w, 1e30f))) continue;
        Vec3 L = env_radiance(env, s[i].texel[0], s[i].texel[1]);
        float f = kAlbedo / kPi * w.z / pdf_sa[i];
        sum = {sum.x + L.x * f, sum.y + L.y * f, sum.z + L.z * f};
    }
    return {sum.x / n, sum.y / n, sum.z / n};
}

// Reflected radiance at p from the disk light: n polar4 samples from n / 4 points.
float disk_light(Vec3 p, const float *points, size_t n, std::vector<float> &disk) {
    if (wc_disk_polar4(points, n / 4, disk.data(), n) != n) std::abort();
    const float area = kPi * kLightRadius * kLightRadius;
    float sum = 0;
    for (size_t i = 0; i < n; i++) {
        Vec3 q = {kLightCentre.x + kLightRadius * disk[2 * i],
                  kLightCentre.y + kLightRadius * disk[2 * i + 1], kLightCentre.z};
        Vec3 d = q - p;
        float dist2 = dot(d, d), dist = std::sqrt(dist2);
        Vec3 w = {d.x / dist, d.y / dist, d.z / dist};
        if (occluded(p, w, dist)) continue;
        // cos at the plane (normal +z) and at the light (normal -z) are both w.z.
        sum += kLightRadiance * kAlbedo / kPi * w.z * w.z / dist2 * area;
    }
    return sum / n;
}

}  // namespace

int main(int argc, char **argv) {
    std::string map_path = argc > 1 ? argv[1] : "tests/data/envmaps/park.pfm";
    std::string out_path = argc > 2 ? argv[2] : "envlight.pfm";
    const uint32_t size = argc > 3 ? uint32_t(std::atoi(argv[3])) : 256;
    const size_t spp = argc > 4 ? size_t(std::atoi(argv[4])) & ~size_t(3) : 64;
    if (size == 0 || spp == 0) return 2;

    // 1. Asset pipeline: weights = luminance x row solid angle, tables built and saved.
    Env env;
    if (!read_pfm(map_path, env.map)) {
        std::fprintf(stderr, "cannot read %s\n", map_path.c_str());
        return 2;
    }
    const uint32_t w = env.map.width, h = env.map.height;
    std::vector<float> weights(size_t(w) * h);
    wc_envmap_luminance(env.map.rgb.data(), weights.data(), weights.size());
    if (wc_envmap_equirect_solid_angle_weights(weights.data(), w, h) != WC_OK) return 2;
    std::vector<uint32_t> built(wc_envmap_storage_len(WC_ENVMAP_KIND_HIERARCHICAL, w, h));
    int32_t err = wc_envmap_build(WC_ENVMAP_KIND_HIERARCHICAL, weights.data(), w, h, built.data(),
                                  built.size());
    if (err != WC_OK) {
        std::fprintf(stderr, "build failed: %d\n", int(err));
        return 1;
    }
    const std::string table_path = out_path + ".table";
    FILE *f = std::fopen(table_path.c_str(), "wb");
    if (!f || std::fwrite(built.data(), 4, built.size(), f) != built.size()) return 2;
    std::fclose(f);

    // 2. Renderer: load the tables (no weights needed) and check them once.
    f = std::fopen(table_path.c_str(), "rb");
    if (!f) return 2;
    std::fseek(f, 0, SEEK_END);
    env.storage.resize(size_t(std::ftell(f)) / 4);
    std::fseek(f, 0, SEEK_SET);
    size_t got = std::fread(env.storage.data(), 4, env.storage.size(), f);
    std::fclose(f);
    std::remove(table_path.c_str());
    err = wc_envmap_from_storage_verified(env.storage.data(), got);
    if (got != built.size() || err != WC_OK) {
        std::fprintf(stderr, "loaded tables rejected: %d\n", int(err));
        return 1;
    }

    // 3. Render.
    Image out;
    out.width = out.height = size;
    out.rgb.assign(size_t(size) * size * 3, 0.0f);
    std::vector<float> points(spp / 4 * 2), u(spp * 2), disk(spp * 2), dirs(spp * 3), pdf_sa(spp);
    std::vector<WcEnvSample> samples(spp);
    for (uint32_t y = 0; y < size; y++) {
        for (uint32_t x = 0; x < size; x++) {
            Vec3 p = {-1.5f + 3.0f * (x + 0.5f) / size, 1.5f - 3.0f * (y + 0.5f) / size, 0.0f};
            uint32_t seed = y * size + x;
            wc_pmj02bn_sample(0, seed, points.data(), spp / 4);
            wc_pmj02bn_sample(0, seed ^ 0x9e3779b9u, u.data(), spp);
            float d = disk_light(p, points.data(), spp, disk);
            Vec3 e = env_light(env, p, u.data(), spp, samples, dirs, pdf_sa);
            float *px = &out.rgb[(size_t(y) * size + x) * 3];
            px[0] = d + e.x;
            px[1] = d + e.y;
            px[2] = d + e.z;
        }
    }
    if (!write_pfm(out_path, out)) return 2;

    // 4. Self-check without the occluder: importance sampling against the exact reflected
    // radiance of the piecewise-constant map, sum over texels of L * cos-weighted solid angle
    // (row r spans theta in [pi r / h, pi (r + 1) / h]; the integral of cos over it is
    // (2 pi / w) (sin^2 theta1 - sin^2 theta0) / 2), times albedo / pi. Texels of negative
    // luminance (compression artifacts; park.pfm's sum to -2.4% here) weigh 0 in the sampler
    // by design, so the sum leaves them out too.
    const size_t n_is = 1 << 14;
    std::vector<float> uu(2 * n_is), dir_is(3 * n_is), pp(n_is);
    std::vector<WcEnvSample> ss(n_is);
    wc_pmj02bn_sample(0, 7, uu.data(), n_is);
    Vec3 is = env_light(env, {0, 0, 0}, uu.data(), n_is, ss, dir_is, pp, false);
    double exact = 0;
    for (uint32_t r = 0; r < h; r++) {
        double t0 = kPi * double(r) / h, t1 = std::min(kPi * double(r + 1) / h, kPi / 2.0);
        if (t0 >= kPi / 2.0) break;
        double band = (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) / 2.0;
        for (uint32_t c = 0; c < w; c++) {
            Vec3 L = env_radiance(env, c, r);
            double lum = 0.2126 * L.x + 0.7152 * L.y + 0.0722 * L.z;
            exact += std::max(0.0, lum) * (2.0 * kPi / w) * band;
        }
    }
    exact *= kAlbedo / kPi;
    double estimate = 0.2126 * is.x + 0.7152 * is.y + 0.0722 * is.z;
    double rel = std::fabs(estimate - exact) / exact;
    std::printf("wrote %s (%ux%u, %zu spp per light); reflected environment luminance: %.6g "
                "(%zu importance samples) vs %.6g (exact), relative difference %.2g\n",
                out_path.c_str(), size, size, spp, estimate, n_is, exact, rel);
    return rel < 0.01 ? 0 : 1;
}
