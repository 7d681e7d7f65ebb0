// warpcore.wgsl: warpcore's disk, triangle and sphere warps and its solid-angle lights for GPUs,
// one point per call.
//
// A library: no bindings, no entry points, no `enable` directives, core WebGPU only.
// Concatenate it with your own shader (or load it through your engine's include mechanism,
// see docs/gpu.md). Public names mirror the C ABI (`include/warpcore.h`): `wc_<family>_<warp>`;
// everything named `wci_*` is internal. pmj02bn and the sampling core need tables: they are in
// warpcore_tables.wgsl, which declares their one storage binding (see docs/gpu.md).
//
// Every function is transcribed operation by operation from the Rust bodies in `src/` (the
// same constants, as hex-float literals of the crate's `f32` values; the same order of
// operations; no `fma`, no `pow`, no builtin trigonometry: the crate's own polynomial kernels
// from `src/trig.rs`), with the same input clamping, so every function is total: NaN,
// infinities, negatives, values >= 1 and subnormals give the documented results of the
// crate, never NaN. On a conforming software Vulkan device (Mesa lavapipe) each function
// returns the same bits as the crate for every input (`cargo test -p warpcore-gpu` checks
// every output word); on real GPUs WGSL's accuracy rules allow small deviations, bounded in
// docs/gpu.md.
//
// Fences. Shader compilers treat WGSL float operations as inexact and may fold exact error
// compensation such as `(1 - (1 - big)) - big` to 0 (Mesa lavapipe does). Where the crate
// relies on such an exact step, the intermediate goes through `wci_fence(x, zero)`, which
// xors in a zero the compiler cannot prove to be zero (the sign bit of a value that is never
// negative at run time), so the value is opaque to the optimizer and the step is kept.

// ---------------------------------------------------------------------------------------
// Constants (the crate's f32 values, bit for bit)

// 1 - 2^-24: the top of every forward warp's input range.
const WCI_ONE_MINUS_EPSILON: f32 = 0x1.fffffep-1f;
// 1 - 2^-23: the largest radius fed into r * (cos, sin) (`trig::MAX_RADIUS`).
const WCI_MAX_RADIUS: f32 = 0x1.fffffcp-1f;
const WCI_F32_MAX: f32 = 0x1.fffffep+127f;
// 1 / pi, 1 / (2 pi), 1 / (4 pi) and 2 pi^2 rounded to f32.
const WCI_FRAC_1_PI: f32 = 0x1.45f306p-2f;
const WCI_HEMISPHERE_PDF: f32 = 0x1.45f306p-3f;
const WCI_UNIFORM_PDF: f32 = 0x1.45f306p-4f;
const WCI_TWO_PI_SQUARED: f32 = 0x1.3bd3ccp+4f;
// sin((pi/4) t) = t (S0 + S1 t^2 + S2 t^4 + S3 t^6) on [-1, 1].
const WCI_S0: f32 = 0x1.921fb4p-1f;
const WCI_S1: f32 = -0x1.4abbb8p-4f;
const WCI_S2: f32 = 0x1.465e92p-9f;
const WCI_S3: f32 = -0x1.2d9302p-15f;
// cos((pi/4) t) = 1 + C1 t^2 + C2 t^4 + C3 t^6 + C4 t^8 on [-1, 1].
const WCI_C1: f32 = -0x1.3bd3cep-2f;
const WCI_C2: f32 = 0x1.03c1dcp-6f;
const WCI_C3: f32 = -0x1.55c5ep-12f;
const WCI_C4: f32 = 0x1.d9d57ep-19f;
// atan(z) / (pi/4) = z (A0 + A1 z^2 + ... + A5 z^10) on |z| <= 1/2.
const WCI_A0: f32 = 0x1.45f306p+0f;
const WCI_A1: f32 = -0x1.b298e6p-2f;
const WCI_A2: f32 = 0x1.04abfep-2f;
const WCI_A3: f32 = -0x1.7165b4p-3f;
const WCI_A4: f32 = 0x1.0800dep-3f;
const WCI_A5: f32 = -0x1.08f39cp-4f;

// ---------------------------------------------------------------------------------------
// Lane operations (src/lanes.rs)

// `x` with its bits xor-ed with `zero`, a runtime zero: an optimization fence (see the top).
fn wci_fence(x: f32, zero: u32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) ^ zero);
}

// A zero the compiler cannot prove: the sign bit of `wci_unit_interval(x)`, never set.
fn wci_zero_of(x: f32) -> u32 {
    return bitcast<u32>(wci_unit_interval(x)) & 0x80000000u;
}

// |x| by clearing the sign bit (abs(-0.0) = +0.0, NaN stays NaN).
fn wci_abs(x: f32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) & 0x7fffffffu);
}

fn wci_sign_bit(x: f32) -> u32 {
    return bitcast<u32>(x) & 0x80000000u;
}

fn wci_flip_sign(x: f32, sign: u32) -> f32 {
    return bitcast<f32>(bitcast<u32>(x) ^ sign);
}

// NaN test on the bits (a compiler may assume `x == x`).
fn wci_is_nan(x: f32) -> bool {
    return (bitcast<u32>(x) & 0x7fffffffu) > 0x7f800000u;
}

// Any f32 onto [0, 1 - 2^-24]: NaN, -0.0, negatives and -inf to +0.0, >= 1 and +inf to the top.
fn wci_unit_interval(x: f32) -> f32 {
    return select(0.0f, select(WCI_ONE_MINUS_EPSILON, x, x < WCI_ONE_MINUS_EPSILON), 0.0f < x);
}

// Any f32 onto [-1, 1]: NaN to +0.0 (-0.0 stays -0.0), beyond the ends to the ends.
fn wci_signed_unit(x0: f32) -> f32 {
    let x = select(x0, 0.0f, wci_is_nan(x0));
    return select(select(x, 1.0f, 1.0f < x), -1.0f, x < -1.0f);
}

// x clamped to [0, 1], NaN and -0.0 to +0.0 (triangle inverses).
fn wci_unit_closed(x: f32) -> f32 {
    return select(0.0f, select(1.0f, x, x < 1.0f), 0.0f < x);
}

// A density made safe: positive values below f32::MAX pass; NaN, -0.0, negatives, f32::MAX
// and +inf (unbounded) to +0.0.
fn wci_finite_density(p: f32) -> f32 {
    return select(0.0f, p, 0.0f < p && p < WCI_F32_MAX);
}

// `u as i32 as f32` (exact below 2^24) and `x as i32 as u32` (0 <= x < 2^31).
fn wci_from_uint(u: u32) -> f32 {
    return f32(bitcast<i32>(u));
}

fn wci_to_uint(x: f32) -> u32 {
    return bitcast<u32>(i32(x));
}

// ---------------------------------------------------------------------------------------
// Kernels (src/trig.rs)

// (sin((pi/4) t), cos((pi/4) t)) for t in [-1, 1].
fn wci_sin_cos_pi4(t: f32) -> vec2<f32> {
    let s = t * t;
    let sn = t * (WCI_S0 + s * (WCI_S1 + s * (WCI_S2 + s * WCI_S3)));
    let cs = 1.0f + s * (WCI_C1 + s * (WCI_C2 + s * (WCI_C3 + s * WCI_C4)));
    return vec2<f32>(sn, cs);
}

// (sin, cos) of (pi/2) (f + q) for f in [0, 1] and any q (only q mod 4 matters).
fn wci_sin_cos_quarter_turns(f: f32, q0: u32) -> vec2<f32> {
    let h = f + f;
    let upper = 1.0f <= h;
    let t = select(h, h - 2.0f, upper);
    let q = q0 + select(0u, 1u, upper);
    let sc = wci_sin_cos_pi4(t);
    let swap = (q & 1u) == 1u;
    let sn = select(sc.x, sc.y, swap);
    let cs = select(sc.y, sc.x, swap);
    let sin_sign = (q & 2u) << 30u;
    let cos_sign = ((q + 1u) & 2u) << 30u;
    return vec2<f32>(wci_flip_sign(sn, sin_sign), wci_flip_sign(cs, cos_sign));
}

// (sin(2 pi v), cos(2 pi v)) for v in [0, 1].
fn wci_sin_cos_turns(v: f32) -> vec2<f32> {
    let v4 = v * 4.0f;
    let q = wci_to_uint(v4);
    return wci_sin_cos_quarter_turns(v4 - wci_from_uint(q), q);
}

// atan(num / den) / (pi/4) for 0 <= num <= den; den = 0 gives 0.
fn wci_atan_ratio_pi4(num: f32, den: f32) -> f32 {
    let reduce = den <= num + num;
    let n = select(num, num - den, reduce);
    let d = select(den, num + den, reduce);
    let z = n / d;
    let s = z * z;
    let p = WCI_A0 + s * (WCI_A1 + s * (WCI_A2 + s * (WCI_A3 + s * (WCI_A4 + s * WCI_A5))));
    let w = z * p;
    return select(select(w, 1.0f + w, reduce), 0.0f, den == 0.0f);
}

// atan2(y, x) / (2 pi) wrapped to [0, 1); y = -0.0 counts as y >= 0; the origin gives 0.
fn wci_atan2_turns(y: f32, x: f32) -> f32 {
    let ax = wci_abs(x);
    let ay = wci_abs(y);
    let x_major = ay <= ax;
    let w = wci_atan_ratio_pi4(select(ax, ay, x_major), select(ay, ax, x_major));
    let a0 = select(2.0f - w, w, x_major);
    let a1 = select(a0, 4.0f - a0, x < 0.0f);
    let a2 = select(a1, 8.0f - a1, y < 0.0f);
    let turns = a2 * 0.125f;
    return select(WCI_ONE_MINUS_EPSILON, turns, turns < 1.0f);
}

// ---------------------------------------------------------------------------------------
// Disk (src/disk.rs)

// The result of the quadrant inverses: the square point and the quadrant in 0..4.
struct WcQuadrantPoint {
    u: vec2<f32>,
    quadrant: u32,
}

fn wci_clamp_radius(r: f32) -> f32 {
    return select(r, WCI_MAX_RADIUS, WCI_MAX_RADIUS < r);
}

// Polar map: r = sqrt(u0), theta = 2 pi u1.
fn wc_disk_polar(u: vec2<f32>) -> vec2<f32> {
    let r = wci_clamp_radius(sqrt(wci_unit_interval(u.x)));
    let sc = wci_sin_cos_turns(wci_unit_interval(u.y));
    return vec2<f32>(r * sc.y, r * sc.x);
}

// Inverse of wc_disk_polar: (x^2 + y^2, atan2(y, x) / (2 pi)).
fn wc_disk_polar_inverse(p: vec2<f32>) -> vec2<f32> {
    let x = wci_signed_unit(p.x);
    let y = wci_signed_unit(p.y);
    return vec2<f32>(wci_unit_interval(x * x + y * y), wci_atan2_turns(y, x));
}

// The concentric map in polar form: (signed radius r, c, s) with the point (r c, r s).
fn wci_concentric_parts(u: vec2<f32>) -> vec3<f32> {
    let a = 2.0f * wci_unit_interval(u.x) - 1.0f;
    let b = 2.0f * wci_unit_interval(u.y) - 1.0f;
    let a_major = wci_abs(b) < wci_abs(a);
    let r0 = select(b, a, a_major);
    let n = select(a, b, a_major);
    let t = select(n / r0, 0.0f, r0 == 0.0f);
    let r = wci_flip_sign(wci_clamp_radius(wci_abs(r0)), wci_sign_bit(r0));
    let sc = wci_sin_cos_pi4(t);
    return vec3<f32>(r, select(sc.x, sc.y, a_major), select(sc.y, sc.x, a_major));
}

// Shirley-Chiu concentric map (textbook wedges, branch-free).
fn wc_disk_concentric(u: vec2<f32>) -> vec2<f32> {
    let rcs = wci_concentric_parts(u);
    return vec2<f32>(rcs.x * rcs.y, rcs.x * rcs.z);
}

// Inverse of wc_disk_concentric.
fn wc_disk_concentric_inverse(p: vec2<f32>) -> vec2<f32> {
    let x = wci_signed_unit(p.x);
    let y = wci_signed_unit(p.y);
    let ax = wci_abs(x);
    let ay = wci_abs(y);
    let x_major = ay < ax;
    let r = sqrt(x * x + y * y);
    let w = wci_atan_ratio_pi4(select(ax, ay, x_major), select(ay, ax, x_major));
    let rw = r * w;
    let a = wci_flip_sign(select(rw, r, x_major), wci_sign_bit(x));
    let b = wci_flip_sign(select(r, rw, x_major), wci_sign_bit(y));
    return vec2<f32>(
        wci_unit_interval(a * 0.5f + 0.5f),
        wci_unit_interval(b * 0.5f + 0.5f),
    );
}

// Polar4 (Christensen 2018): r = sqrt(u0), theta = (pi/2) u1 + (pi/2) quadrant (mod 4).
fn wc_disk_polar4(u: vec2<f32>, quadrant: u32) -> vec2<f32> {
    let r = wci_clamp_radius(sqrt(wci_unit_interval(u.x)));
    let sc = wci_sin_cos_quarter_turns(wci_unit_interval(u.y), quadrant);
    return vec2<f32>(r * sc.y, r * sc.x);
}

// Inverse of wc_disk_polar4: the point and its quadrant.
fn wc_disk_polar4_inverse(p: vec2<f32>) -> WcQuadrantPoint {
    let ut = wc_disk_polar_inverse(p);
    let v = ut.y * 4.0f;
    let q = wci_to_uint(v);
    return WcQuadrantPoint(vec2<f32>(ut.x, v - wci_from_uint(q)), q);
}

// (x, y) turned by quadrant % 4 quarter turns, exactly.
fn wci_quarter_turns(x0: f32, y0: f32, quadrant: u32) -> vec2<f32> {
    let odd = (quadrant & 1u) == 1u;
    let x = select(x0, y0, odd);
    let y = select(y0, x0, odd);
    let neg_x = ((quadrant ^ (quadrant >> 1u)) & 1u) << 31u;
    let neg_y = ((quadrant >> 1u) & 1u) << 31u;
    return vec2<f32>(wci_flip_sign(x, neg_x), wci_flip_sign(y, neg_y));
}

// Concentric4 (Christensen 2018): Shirley-Chiu on the quarter disk, turned by quadrant % 4.
fn wc_disk_concentric4(u: vec2<f32>, quadrant: u32) -> vec2<f32> {
    let a = wci_unit_interval(u.x);
    let b = wci_unit_interval(u.y);
    let a_major = b < a;
    let r0 = select(b, a, a_major);
    let t = select(select(a, b, a_major) / r0, 0.0f, r0 == 0.0f);
    let r = wci_clamp_radius(r0);
    let sc = wci_sin_cos_pi4(t);
    let x = r * select(sc.x, sc.y, a_major);
    let y = r * select(sc.y, sc.x, a_major);
    return wci_quarter_turns(x, y, quadrant);
}

// Inverse of wc_disk_concentric4: the point and its quadrant.
fn wc_disk_concentric4_inverse(p: vec2<f32>) -> WcQuadrantPoint {
    let x0 = wci_signed_unit(p.x);
    let y0 = wci_signed_unit(p.y);
    let q = select(
        select(
            select(0u, 3u, (y0 < 0.0f) & (0.0f <= x0)),
            2u,
            (y0 <= 0.0f) & (x0 < 0.0f),
        ),
        1u,
        (0.0f < y0) & (x0 <= 0.0f),
    );
    let turned = wci_quarter_turns(x0, y0, q * 3u);
    let x = wci_abs(turned.x);
    let y = wci_abs(turned.y);
    let x_major = y < x;
    let r = sqrt(x * x + y * y);
    let w = wci_atan_ratio_pi4(select(x, y, x_major), select(y, x, x_major));
    let rw = r * w;
    return WcQuadrantPoint(
        vec2<f32>(
            wci_unit_interval(select(rw, r, x_major)),
            wci_unit_interval(select(r, rw, x_major)),
        ),
        q,
    );
}

// ---------------------------------------------------------------------------------------
// Triangle (src/triangle.rs, src/triangle/base4.rs); barycentrics (b0, b1, b2)

// Heitz's low-distortion map; b2 = 1 - b0 - b1 rounded once (fenced compensation).
fn wc_triangle_uniform(u: vec2<f32>) -> vec3<f32> {
    let u0 = wci_unit_interval(u.x);
    let u1 = wci_unit_interval(u.y);
    let zero = wci_sign_bit(u0); // u0 >= +0.0: a zero the compiler cannot see
    let upper = u0 < u1;
    let big = select(u0, u1, upper);
    let small = select(u1, u0, upper);
    let half = small * 0.5f;
    let rest = big - half;
    let e = (big - wci_fence(rest, zero)) - half;
    let t = 1.0f - big;
    let c = (1.0f - wci_fence(t, zero)) - big;
    let b2 = t + (c + e);
    return vec3<f32>(select(rest, half, upper), select(half, rest, upper), b2);
}

// Inverse of wc_triangle_uniform (reads b0 and b1).
fn wc_triangle_uniform_inverse(b: vec3<f32>) -> vec2<f32> {
    let b0 = wci_unit_closed(b.x);
    let b1 = wci_unit_closed(b.y);
    let upper = b0 < b1;
    let sum = b0 + b1;
    return vec2<f32>(
        wci_unit_interval(select(sum, b0 * 2.0f, upper)),
        wci_unit_interval(select(b1 * 2.0f, sum, upper)),
    );
}

// The classic square-root map: b0 = 1 - sqrt(u0), b1 = u1 sqrt(u0).
fn wc_triangle_sqrt_map(u: vec2<f32>) -> vec3<f32> {
    let u0 = wci_unit_interval(u.x);
    let b0 = 1.0f - sqrt(u0);
    // s = 1 - b0 exactly: fenced, or the compiler may fold it to sqrt(u0).
    let s = 1.0f - wci_fence(b0, wci_sign_bit(u0));
    let b1 = wci_unit_interval(u.y) * s;
    return vec3<f32>(b0, b1, s - b1);
}

// Inverse of wc_triangle_sqrt_map (reads b0 and b1).
fn wc_triangle_sqrt_map_inverse(b: vec3<f32>) -> vec2<f32> {
    let s = 1.0f - wci_unit_closed(b.x);
    let b1 = wci_unit_closed(b.y);
    let u1 = select(b1 / s, 0.0f, s == 0.0f);
    return vec2<f32>(wci_unit_interval(s * s), wci_unit_interval(u1));
}

fn wci_delta_swap(x: u32, mask: u32, shift: u32) -> u32 {
    let t = (x ^ (x >> shift)) & mask;
    return x ^ t ^ (t << shift);
}

fn wci_unzip(x0: u32) -> u32 {
    let x1 = wci_delta_swap(x0, 0x22222222u, 1u);
    let x2 = wci_delta_swap(x1, 0x0c0c0c0cu, 2u);
    let x3 = wci_delta_swap(x2, 0x00f000f0u, 4u);
    return wci_delta_swap(x3, 0x0000ff00u, 8u);
}

fn wci_mix(x0: u32) -> u32 {
    let x1 = (x0 ^ (x0 >> 16u)) * 0x21f0aaadu;
    let x2 = (x1 ^ (x1 >> 15u)) * 0xd35a2d97u;
    return x2 ^ (x2 >> 15u);
}

fn wci_rotate_digits(x: u32, m: u32) -> u32 {
    let lo = x & 0x55555555u;
    let hi = (x >> 1u) & 0x55555555u;
    let once = hi | ((lo ^ hi) << 1u);
    let twice = (lo ^ hi) | (lo << 1u);
    return select(select(x, twice, m == 2u), once, m == 1u);
}

// Nested (Owen) scramble of the base-4 digits of index; seed 0 is the identity.
fn wci_nested_scramble(index: u32, seed: u32) -> u32 {
    let k1 = wci_mix(seed);
    let k2 = wci_mix(seed ^ 0x5bd1e995u);
    let k3 = wci_mix(seed ^ 0x2545f491u);
    let m = ((k3 >> 8u) * 3u) >> 24u;
    let x0 = wci_rotate_digits(index, m);
    let x1 = x0 ^ (x0 * 0x9e3779b8u);
    let x2 = x1 + k1;
    let x3 = x2 * (k2 | 1u);
    let x4 = x3 ^ (x3 * 0x6a09e666u);
    let x5 = x4 ^ (x4 * 0xbb67ae84u);
    return select(x5, index, seed == 0u);
}

// The index's 16 digits in the "fields" layout (bit 15 - j: low bit of digit j; 31 - j: high).
fn wci_fields(index: u32) -> u32 {
    let x = wci_unzip(reverseBits(index));
    return (x >> 16u) | (x << 16u);
}

// The Basu-Owen walk over all 16 digits at once: the centroid on the 2^-24 grid.
fn wci_walk(fields: u32) -> vec3<f32> {
    let bits = ~fields;
    let dy = bits & 0xffffu;
    let dx = bits >> 16u;
    let zero = dx & dy;
    let n0 = zero >> 1u;
    let n1 = n0 ^ (n0 >> 1u);
    let n2 = n1 ^ (n1 >> 2u);
    let n3 = n2 ^ (n2 >> 4u);
    let neg = n3 ^ (n3 >> 8u);
    let cx = dx - ((dx & neg) << 1u);
    let cy = dy - ((dy & neg) << 1u);
    let odd = (neg ^ zero) & 1u;
    let centre = 85u - odd * 170u;
    let qx = (cx << 8u) + centre;
    let qy = (cy << 8u) + centre;
    let qz = 16777216u - qx - qy;
    let scale = 0x1p-24f;
    return vec3<f32>(wci_from_uint(qx) * scale, wci_from_uint(qy) * scale, wci_from_uint(qz) * scale);
}

// Basu-Owen point `index`, nested-scrambled by `seed` (0: the plain construction).
fn wc_triangle_basu_owen(index: u32, seed: u32) -> vec3<f32> {
    return wci_walk(wci_fields(wci_nested_scramble(index, seed)));
}

// One digit permutation per level, as masks over the fields layout (LevelKeys).
struct WciLevelKeys {
    a: u32,
    b: u32,
    k: u32,
}

fn wci_level_keys(seed: u32) -> WciLevelKeys {
    let k = wci_mix(seed ^ 0x68e31da4u);
    let s = wci_mix(seed ^ 0xb5b84f2bu) & 0xffffu;
    let w0 = wci_mix(seed ^ 0x3c6ef372u);
    let w1 = wci_mix(seed ^ 0xa54ff53au);
    var ge1 = 0u;
    var ge2 = 0u;
    var power = 1u; // 3^step
    for (var step = 0u; step < 8u; step++) {
        let t0 = w0 * power;
        let bit0 = 1u << (15u - step);
        ge1 = ge1 | select(bit0, 0u, t0 < 0x55555556u);
        ge2 = ge2 | select(bit0, 0u, t0 < 0xaaaaaaabu);
        let t1 = w1 * power;
        let bit1 = 1u << (7u - step);
        ge1 = ge1 | select(bit1, 0u, t1 < 0x55555556u);
        ge2 = ge2 | select(bit1, 0u, t1 < 0xaaaaaaabu);
        power = power * 3u;
    }
    let l00 = ~(ge1 & ~ge2) & 0xffffu;
    let l01 = ge1;
    let l10 = ge1;
    let l11 = ~ge2 & 0xffffu;
    let n00 = (l00 & ~s) | (l10 & s);
    let n01 = (l01 & ~s) | (l11 & s);
    let n10 = (l10 & ~s) | (l00 & s);
    let n11 = (l11 & ~s) | (l01 & s);
    let zero = seed == 0u;
    return WciLevelKeys(
        select(n00 | (n11 << 16u), 0xffffffffu, zero),
        select(n01 | (n10 << 16u), 0u, zero),
        select(k, 0u, zero),
    );
}

// Basu-Owen point `index` with one digit permutation per level drawn from `seed`.
fn wc_triangle_basu_owen_permuted(index: u32, seed: u32) -> vec3<f32> {
    let keys = wci_level_keys(seed);
    let f = wci_fields(index);
    let swapped = (f >> 16u) | (f << 16u);
    return wci_walk((f & keys.a) ^ (swapped & keys.b) ^ keys.k);
}

// ---------------------------------------------------------------------------------------
// Sphere (src/sphere/); directions (x, y, z), the square's centre maps to +z

// Clarberg's equal-area octahedral map.
fn wc_sphere_equal_area(u: vec2<f32>) -> vec3<f32> {
    let a = 2.0f * wci_unit_interval(u.x) - 1.0f;
    let b = 2.0f * wci_unit_interval(u.y) - 1.0f;
    let ua = wci_abs(a);
    let ub = wci_abs(b);
    let lower = 1.0f < ua + ub;
    let p = select(ua, 1.0f - ub, lower);
    let q = select(ub, 1.0f - ua, lower);
    let r = p + q;
    let q_major = p < q;
    let m = select(q, p, q_major);
    let t = select((m + m) / r, 0.0f, r == 0.0f);
    let sc = wci_sin_cos_pi4(t);
    let cos_phi = select(sc.y, sc.x, q_major);
    let sin_phi = select(sc.x, sc.y, q_major);
    let r2 = r * r;
    let z = wci_flip_sign(1.0f - r2, select(0u, 0x80000000u, lower));
    let rho = sqrt(r2 * (2.0f - r2));
    return vec3<f32>(
        wci_flip_sign(rho * cos_phi, wci_sign_bit(a)),
        wci_flip_sign(rho * sin_phi, wci_sign_bit(b)),
        z,
    );
}

// Inverse of wc_sphere_equal_area; only the direction of d matters (zero vector: +z).
fn wc_sphere_equal_area_inverse(d: vec3<f32>) -> vec2<f32> {
    let x = wci_signed_unit(d.x);
    let y = wci_signed_unit(d.y);
    let z = wci_signed_unit(d.z);
    let rho2 = x * x + y * y;
    let n = rho2 + z * z;
    let ax = wci_abs(x);
    let ay = wci_abs(y);
    let az = wci_abs(z);
    let len = sqrt(n);
    let den = n + len * az;
    let r2 = rho2 / select(den, 1.0f, den == 0.0f);
    let r = sqrt(select(r2, 1.0f, 1.0f < r2));
    let x_major = ay <= ax;
    let w = wci_atan_ratio_pi4(select(ax, ay, x_major), select(ay, ax, x_major));
    let minor = r * w * 0.5f;
    let major = r - minor;
    let p = select(minor, major, x_major);
    let q = select(major, minor, x_major);
    let lower = wci_sign_bit(z) == 0x80000000u;
    let ua = select(p, 1.0f - q, lower);
    let ub = select(q, 1.0f - p, lower);
    let a = wci_flip_sign(ua, wci_sign_bit(x));
    let b = wci_flip_sign(ub, wci_sign_bit(y));
    return vec2<f32>(
        wci_unit_interval(a * 0.5f + 0.5f),
        wci_unit_interval(b * 0.5f + 0.5f),
    );
}

// A density over the equal-area square as a density over solid angle: pdf / (4 pi).
fn wc_sphere_equal_area_pdf_to_solid_angle(pdf: f32) -> f32 {
    return wci_finite_density(wci_finite_density(pdf) * WCI_UNIFORM_PDF);
}

// floor(x) for |x| <= 2^22 with correctly rounded adds (x + 1.5 * 2^23 - 1.5 * 2^23).
fn wci_floor_small(x: f32, zero: u32) -> f32 {
    let k = wci_fence(x + 12582912.0f, zero) - 12582912.0f;
    return select(k, k - 1.0f, x < k);
}

// x modulo 2 into [0, 2]; |x| >= 2^23, infinities and NaN become 0.
fn wci_reduce_mod_2(x0: f32, zero: u32) -> f32 {
    let x = select(0.0f, x0, wci_abs(x0) < 8388608.0f);
    let k = wci_floor_small(x * 0.5f, zero);
    let r = x - (k + k);
    return select(r, r + 2.0f, r < 0.0f);
}

// Folds a point outside the equal-area square onto its neighbour on the sphere.
fn wc_sphere_equal_area_wrap(u: vec2<f32>) -> vec2<f32> {
    let zero = wci_zero_of(u.x);
    let f0 = wci_reduce_mod_2(u.x, zero);
    let f1 = wci_reduce_mod_2(u.y, zero);
    let hi0 = 1.0f < f0;
    let hi1 = 1.0f < f1;
    let both = hi0 & hi1;
    let w0 = select(select(select(f0, 1.0f - f0, hi1), 2.0f - f0, hi0), f0 - 1.0f, both);
    let w1 = select(select(select(f1, 1.0f - f1, hi0), 2.0f - f1, hi1), f1 - 1.0f, both);
    return vec2<f32>(w0, w1);
}

// Uniform sphere (Archimedes' hat-box): z = 1 - 2 u0, phi = 2 pi u1.
fn wc_sphere_uniform(u: vec2<f32>) -> vec3<f32> {
    let u0 = wci_unit_interval(u.x);
    let z = 1.0f - (u0 + u0);
    let s = sqrt(u0 * (1.0f - u0));
    let r = s + s;
    let sc = wci_sin_cos_turns(wci_unit_interval(u.y));
    return vec3<f32>(r * sc.y, r * sc.x, z);
}

// Inverse of wc_sphere_uniform; only the direction of d matters (zero vector: +z).
fn wc_sphere_uniform_inverse(d: vec3<f32>) -> vec2<f32> {
    let x = wci_signed_unit(d.x);
    let y = wci_signed_unit(d.y);
    let z = wci_signed_unit(d.z);
    let rho2 = x * x + y * y;
    let n = rho2 + z * z;
    let len = sqrt(n);
    let north = 0.0f < z;
    let num = select(len - z, rho2, north);
    // Fenced (n >= +0.0 has no sign bit): otherwise lavapipe folds the doubling below into
    // the product (s * (2 len)), which rounds differently when den is subnormal.
    let den = wci_fence(select(1.0f, len + z, north) * len, wci_sign_bit(n));
    let u0 = num / (den + den);
    return vec2<f32>(wci_unit_interval(u0), wci_atan2_turns(y, x));
}

// Uniform hemisphere: the concentric disk lifted by Lambert's equal-area projection.
fn wc_sphere_uniform_hemisphere(u: vec2<f32>) -> vec3<f32> {
    let rcs = wci_concentric_parts(u);
    let r = rcs.x;
    let r2 = r * r;
    let z = 1.0f - r2;
    // 1 + z, not 2 - r2: fenced against constant reassociation (the sign of r2 is never set).
    let rho = wci_flip_sign(sqrt(r2 * (1.0f + wci_fence(z, wci_sign_bit(r2)))), wci_sign_bit(r));
    return vec3<f32>(rho * rcs.y, rho * rcs.z, z);
}

// Cosine-weighted hemisphere (Malley): the concentric disk point lifted to the hemisphere.
fn wc_sphere_cosine_hemisphere(u: vec2<f32>) -> vec3<f32> {
    let rcs = wci_concentric_parts(u);
    let r = rcs.x;
    let ar = wci_abs(r);
    return vec3<f32>(r * rcs.y, r * rcs.z, sqrt((1.0f - ar) * (1.0f + ar)));
}

// (x, y) / sqrt(den) (0 where den = 0) through the concentric inverse.
fn wci_to_disk(x: f32, y: f32, den: f32) -> vec2<f32> {
    let degenerate = den == 0.0f;
    let scale0 = 1.0f / select(sqrt(den), 1.0f, degenerate);
    let scale = select(scale0, 0.0f, degenerate);
    return wc_disk_concentric_inverse(vec2<f32>(x * scale, y * scale));
}

// Inverse of wc_sphere_uniform_hemisphere (below the horizon: the mirror image).
fn wc_sphere_uniform_hemisphere_inverse(d: vec3<f32>) -> vec2<f32> {
    let x = wci_signed_unit(d.x);
    let y = wci_signed_unit(d.y);
    let z = wci_signed_unit(d.z);
    let n = (x * x + y * y) + z * z;
    let den = n + sqrt(n) * wci_abs(z);
    return wci_to_disk(x, y, den);
}

// Inverse of wc_sphere_cosine_hemisphere (below the horizon: the mirror image).
fn wc_sphere_cosine_hemisphere_inverse(d: vec3<f32>) -> vec2<f32> {
    let x = wci_signed_unit(d.x);
    let y = wci_signed_unit(d.y);
    let z = wci_signed_unit(d.z);
    let n = (x * x + y * y) + z * z;
    return wci_to_disk(x, y, n);
}

// The cosine-weighted density cos(theta) / pi (0 below the horizon and for NaN; a cosine
// above 1 counts as 1).
fn wc_sphere_cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    return wci_finite_density(select(cos_theta, 1.0f, 1.0f < cos_theta) * WCI_FRAC_1_PI);
}

// Lat-long: phi = 2 pi u0, theta = pi u1, d = (sin theta cos phi, sin theta sin phi, cos theta).
fn wc_sphere_equirect(u: vec2<f32>) -> vec3<f32> {
    let p = wci_sin_cos_turns(wci_unit_interval(u.x));
    // u1 / 2 rounded, then times 4 in the kernel: fenced, or the two constants fold into
    // u1 * 2 (which differs for the smallest subnormals). u1 >= +0.0 has no sign bit.
    let v1 = wci_unit_interval(u.y);
    let t = wci_sin_cos_turns(wci_fence(v1 * 0.5f, wci_sign_bit(v1)));
    return vec3<f32>(t.x * p.y, t.x * p.x, t.y);
}

// Inverse of wc_sphere_equirect; only the direction of d matters.
fn wc_sphere_equirect_inverse(d: vec3<f32>) -> vec2<f32> {
    let x = wci_signed_unit(d.x);
    let y = wci_signed_unit(d.y);
    let z = wci_signed_unit(d.z);
    let rho2 = x * x + y * y;
    let phi = wci_atan2_turns(y, x);
    let theta = wci_atan2_turns(sqrt(rho2), z);
    return vec2<f32>(phi, wci_unit_interval(theta + theta));
}

// A density over the lat-long square as a density over solid angle at direction d:
// pdf / (2 pi^2 sin theta); 0 on the axis.
fn wc_sphere_equirect_pdf_to_solid_angle(pdf: f32, d: vec3<f32>) -> f32 {
    let x = wci_signed_unit(d.x);
    let y = wci_signed_unit(d.y);
    let z = wci_signed_unit(d.z);
    let rho2 = x * x + y * y;
    let n = rho2 + z * z;
    let rho = sqrt(rho2);
    let on_axis = rho == 0.0f;
    let den = select(rho * WCI_TWO_PI_SQUARED, 1.0f, on_axis);
    let q = (wci_finite_density(pdf) * sqrt(n)) / den;
    return wci_finite_density(select(q, 0.0f, on_axis));
}

// ---------------------------------------------------------------------------------------
// Solid-angle lights (src/spherical/): Arvo's spherical triangle (1995), Urena, Fajardo and
// King's spherical rectangle (2013), Van Oosterom-Strackee solid angles, and the
// cosine-aware variants (Hart et al. 2020). Densities are with respect to solid angle at `p`;
// below 1e-8 sr the maps sample by area (see the crate's `spherical` module docs).

// 1 / (4 pi), 4 pi, and 1e-8 sr in turns of 4 pi (`AREA_FALLBACK_SR`), rounded to f32.
const WCI_INV_4PI: f32 = 0x1.45f306p-4f;
const WCI_FOUR_PI: f32 = 0x1.921fb6p+3f;
const WCI_FALLBACK_TURNS: f32 = 0x1.b57b56p-31f;
// 1e-2 sr and 2 sr in turns of 4 pi: the rectangle's closed-form window (`NEWTON_FROM_TURNS`).
const WCI_NEWTON_FROM_TURNS: f32 = 0x1.a13714p-11f;
const WCI_NEWTON_UP_TO_TURNS: f32 = 0x1.45f306p-3f;

fn wci_dot3(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

fn wci_cross3(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

fn wci_norm3(a: vec3<f32>) -> f32 {
    return sqrt(wci_dot3(a, a));
}

// x clamped to [0, hi]; NaN and -0.0 to +0.0.
fn wci_clamp0(x: f32, hi: f32) -> f32 {
    return select(0.0f, select(hi, x, x < hi), 0.0f < x);
}

// 0 < x < +inf (false for NaN).
fn wci_positive_finite(x: f32) -> bool {
    return 0.0f < x && x <= WCI_F32_MAX;
}

// Every component finite, on the bits (the crate's `x * 0 == 0` test, which a compiler may fold).
fn wci_finite3(a: vec3<f32>) -> bool {
    let e = vec3<u32>(0x7f800000u);
    return all((bitcast<vec3<u32>>(a) & e) != e);
}

fn wci_max_abs3(m: f32, a: vec3<f32>) -> f32 {
    let x = wci_abs(a.x);
    let m0 = select(m, x, m < x);
    let y = wci_abs(a.y);
    let m1 = select(m0, y, m0 < y);
    let z = wci_abs(a.z);
    return select(m1, z, m1 < z);
}

// The power of two 2^k with 2^k max|x| in [1, 2), or 0 where max|x| is 0, subnormal,
// >= 2^127 or NaN-only (`vec::pow2_scale`).
fn wci_pow2_scale_of(m: f32) -> f32 {
    let e = bitcast<u32>(m) >> 23u;
    let ok = 0u < e && e < 254u;
    return bitcast<f32>(select(0u, (254u - e) << 23u, ok));
}

// Components below 2^-126 (the smallest normal) in magnitude made 0 (`vec::flush_subnormal`).
fn wci_flush3(a: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        select(a.x, 0.0f, wci_abs(a.x) < 0x1p-126f),
        select(a.y, 0.0f, wci_abs(a.y) < 0x1p-126f),
        select(a.z, 0.0f, wci_abs(a.z) < 0x1p-126f),
    );
}

// The power of two lifting the largest of |a|, |b|, |c| into [1, 2) where it is a normal
// number below 1, else 1 (`vec::pow2_lift`).
fn wci_pow2_lift(a: f32, b: f32, c: f32) -> f32 {
    let m = wci_max_abs3(0.0f, vec3<f32>(a, b, c));
    let e = bitcast<u32>(m) >> 23u;
    return select(1.0f, bitcast<f32>((254u - e) << 23u), 0u < e && e < 127u);
}

// `x` made opaque to the optimizer (a fence with a zero derived from x itself).
fn wci_opaque(x: f32) -> f32 {
    return wci_fence(x, wci_zero_of(x));
}

// The chord y^ - x^ from the edge e = y - x (`vec::chord`).
fn wci_chord(x: vec3<f32>, y: vec3<f32>, e: vec3<f32>, lx: f32, ly: f32) -> vec3<f32> {
    let k = wci_dot3(e, x + y) / ((lx + ly) * lx);
    return (e - x * k) * (1.0f / ly);
}

// Van Oosterom-Strackee: the solid angle of (a0, a1, a2) in turns of 4 pi.
fn wci_half_angle_turns(a0: vec3<f32>, a1: vec3<f32>, a2: vec3<f32>, len: vec3<f32>, abs_det: f32) -> f32 {
    // Fenced: a compiler may factor `l0 l1 l2 + (a0.a1) l2` into `(l0 l1 + a0.a1) l2`.
    let lll = wci_fence(len.x * len.y * len.z, wci_zero_of(len.x));
    let den = lll + wci_dot3(a0, a1) * len.z + wci_dot3(a0, a2) * len.y + wci_dot3(a1, a2) * len.x;
    return wci_atan2_turns(abs_det, den);
}

// The triangle seen from p, scaled by an exact power of two (`spherical::triangle::Tri`).
struct WciTri {
    a0: vec3<f32>,
    a1: vec3<f32>,
    a2: vec3<f32>,
    e1: vec3<f32>,
    e2: vec3<f32>,
    f2: vec3<f32>,
    len: vec3<f32>,
    det: f32,
    turns: f32,
    ok: bool,
}

fn wci_tri_setup(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, p: vec3<f32>) -> WciTri {
    let ar0 = wci_flush3(v0 - p);
    let ar1 = wci_flush3(v1 - p);
    let ar2 = wci_flush3(v2 - p);
    let er1 = wci_flush3(v1 - v0);
    let er2 = wci_flush3(v2 - v0);
    let fr2 = wci_flush3(v2 - v1);
    let finite = wci_finite3(ar0) && wci_finite3(ar1) && wci_finite3(ar2) && wci_finite3(er1)
        && wci_finite3(er2) && wci_finite3(fr2);
    let k = wci_pow2_scale_of(wci_max_abs3(wci_max_abs3(wci_max_abs3(0.0f, ar0), ar1), ar2));
    let scaled = bitcast<u32>(k) != 0u;
    var t: WciTri;
    t.a0 = ar0 * k;
    t.a1 = ar1 * k;
    t.a2 = ar2 * k;
    t.e1 = er1 * k;
    t.e2 = er2 * k;
    t.f2 = fr2 * k;
    t.len = vec3<f32>(wci_norm3(t.a0), wci_norm3(t.a1), wci_norm3(t.a2));
    t.ok = finite && scaled && 0.0f < t.len.x && 0.0f < t.len.y && 0.0f < t.len.z;
    let det = wci_dot3(t.a0, wci_cross3(t.e1, t.e2));
    let turns = wci_half_angle_turns(t.a0, t.a1, t.a2, t.len, wci_abs(det));
    // Edge-on below the area-sampling threshold: solid angle and density 0 (`FLAT_DET`).
    let flat = turns < WCI_FALLBACK_TURNS && wci_abs(det) < 0x1p-120f;
    t.det = select(det, 0.0f, flat);
    t.turns = select(0.0f, turns, t.ok && !flat);
    return t;
}

// The solid angle of triangle (v0, v1, v2) at p, in [0, 2 pi].
fn wc_spherical_triangle_solid_angle(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, p: vec3<f32>) -> f32 {
    return wci_tri_setup(v0, v1, v2, p).turns * WCI_FOUR_PI;
}

// Everything Arvo's map computes from the light and p alone (`triangle::Prepared`).
struct WciTriPrepared {
    t: WciTri,
    d: vec3<f32>,
    d2: f32,
    dl: f32,
    dab: vec3<f32>,
    one_ab: f32,
    s: f32,
    tt: f32,
    b: vec3<f32>,
    n: vec3<f32>,
    c1: vec3<f32>,
    c2: vec3<f32>,
    det_la: f32,
    arvo: bool,
    area_ok: bool,
}

fn wci_tri_prepare(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, p: vec3<f32>) -> WciTriPrepared {
    var r: WciTriPrepared;
    let t = wci_tri_setup(v0, v1, v2, p);
    r.t = t;
    let la = t.len.x;
    let lb = t.len.y;
    let lc = t.len.z;
    let ia = 1.0f / la;
    let ib = 1.0f / lb;
    let ic = 1.0f / lc;
    r.d = wci_chord(t.a0, t.a2, t.e2, la, lc);
    r.dab = wci_chord(t.a0, t.a1, t.e1, la, lb);
    r.d2 = wci_dot3(r.d, r.d);
    r.one_ab = 2.0f - wci_dot3(r.dab, r.dab) * 0.5f;
    r.s = wci_dot3(r.dab, r.d) - r.d2;
    r.tt = wci_abs(t.det) * ia * ib * ic;
    r.dl = sqrt(r.d2);
    r.b = t.a0 * ia + r.dab;
    r.n = wci_cross3(t.e1, t.e2);
    r.c1 = wci_cross3(t.e2, t.a0);
    r.c2 = wci_cross3(t.a0, t.e1);
    r.det_la = t.det * ia;
    r.area_ok = t.ok && 0.0f < wci_abs(t.det);
    r.arvo = r.area_ok && WCI_FALLBACK_TURNS <= t.turns;
    return r;
}

// max(0, x) after flipping x's sign by `sign` (the barycentric numerators).
fn wci_pos_signed(x0: f32, sign: u32) -> f32 {
    let x = wci_flip_sign(x0, sign);
    return select(0.0f, x, 0.0f < x);
}

fn wci_tri_sample(pr: WciTriPrepared, u: vec2<f32>) -> vec4<f32> {
    let u0 = wci_unit_interval(u.x);
    let u1 = wci_unit_interval(u.y);
    let t = pr.t;
    let la = t.len.x;
    let va = t.a0;
    // Step 1: the point on the chord a^ c^ with area(a, b, x^) = u0 omega (closed form).
    let sc = wci_sin_cos_turns(u0 * t.turns);
    let pp = pr.tt * sc.y - pr.s * sc.x;
    let q = pr.one_ab * sc.x;
    let tau = wci_clamp0(q * (pp + pp - q * pr.d2) / ((pp - q * pr.dl) * (pp + q * pr.dl)), 1.0f);
    let e = pr.d * (tau * la);
    let xv = va + e;
    let lx = wci_norm3(xv);
    let ox = wci_chord(va, xv, e, la, lx);
    // Step 2: along the arc from b^ to x^, by chord lengths.
    let g = ox - pr.dab;
    let g2 = wci_dot3(g, g);
    let b = pr.b;
    let wv = g + b * (g2 * 0.5f);
    let wl2 = wci_dot3(wv, wv);
    let l2 = u1 * g2;
    // sin(chord l) / |wv| = sqrt(u1 (1 - l2 / 4) (g2 / |wv|^2)): one root.
    let sw0 = sqrt(u1 * wci_clamp0(1.0f - l2 * 0.25f, 1.0f) * (g2 / wl2));
    let sw = select(0.0f, sw0, 0.0f < wl2);
    let op = pr.dab + (b * (-(l2 * 0.5f)) + wv * sw);
    // Barycentrics of the ray's hit, from a^ and the edges.
    let lam1 = wci_dot3(op, pr.c1);
    let lam2 = wci_dot3(op, pr.c2);
    let sum = pr.det_la + wci_dot3(op, pr.n);
    let lam0 = sum - lam1 - lam2;
    let sign = wci_sign_bit(sum);
    let p0 = wci_pos_signed(lam0, sign);
    let p1 = wci_pos_signed(lam1, sign);
    let p2 = wci_pos_signed(lam2, sign);
    // Numerators summing below 2^-64 lifted by an exact 2^64 (a no-op elsewhere).
    let tot0 = p0 + p1 + p2;
    let lift = select(1.0f, 0x1p64f, tot0 < 0x1p-64f);
    let tot = tot0 * lift;
    let arvo = pr.arvo && wci_positive_finite(tot);
    let inv = 1.0f / tot;
    let bary = vec3<f32>(wci_clamp0((p0 * lift) * inv, 1.0f), wci_clamp0((p1 * lift) * inv, 1.0f),
        wci_clamp0((p2 * lift) * inv, 1.0f));
    // Area sampling: density 2 |q|^3 / |det|.
    let fb = wc_triangle_uniform(vec2<f32>(u0, u1));
    let qv = va + (t.e1 * fb.y + t.e2 * fb.z);
    // Fenced: lavapipe changes the cube of a square root here (apparently folding
    // sqrt(x) * sqrt(x) to x).
    let ql = wci_opaque(wci_norm3(qv));
    let adet = wci_abs(t.det);
    // Below 2^-40, |q|^3 would lose bits to underflow: the same quotient in another order.
    let area0 = select((ql * ql * ql + ql * ql * ql) / adet, ql * ((ql + ql) * (ql / adet)), ql < 0x1p-40f);
    let area_pdf = select(0.0f, select(WCI_F32_MAX, area0, area0 < WCI_F32_MAX), pr.area_ok);
    let pdf = select(area_pdf, WCI_INV_4PI / t.turns, pr.arvo);
    return vec4<f32>(select(fb, bary, arvo), pdf);
}

// Uniform in solid angle over the spherical triangle that (v0, v1, v2) subtends at p:
// (b0, b1, b2, density w.r.t. solid angle).
fn wc_spherical_triangle(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, p: vec3<f32>, u: vec2<f32>) -> vec4<f32> {
    return wci_tri_sample(wci_tri_prepare(v0, v1, v2, p), u);
}

// Inverse of wc_spherical_triangle: the u that maps to barycentrics b.
fn wc_spherical_triangle_inverse(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, p: vec3<f32>, bary: vec3<f32>) -> vec2<f32> {
    let t = wci_tri_setup(v0, v1, v2, p);
    let bc = vec3<f32>(wci_clamp0(bary.x, 1.0f), wci_clamp0(bary.y, 1.0f), wci_clamp0(bary.z, 1.0f));
    let sb = bc.x + bc.y + bc.z;
    let has = 0.0f < sb;
    let inv = 1.0f / sb;
    let third = 0x1.555556p-2f;
    let b = vec3<f32>(select(third, bc.x * inv, has), select(third, bc.y * inv, has), select(third, bc.z * inv, has));
    let la = t.len.x;
    let lb = t.len.y;
    let va = t.a0;
    let vb = t.a1;
    let s02 = b.x + b.z;
    let mu = select(0.0f, b.z / s02, 0.0f < s02);
    let cm = va + t.e2 * mu;
    let lcm = wci_norm3(cm);
    let sub_turns = wci_half_angle_turns(va, vb, cm, vec3<f32>(la, lb, lcm), mu * wci_abs(t.det));
    let u0 = sub_turns / t.turns;
    let ep = t.f2 * b.z - t.e1 * b.x;
    let pv = vb + ep;
    let lp = wci_norm3(pv);
    let cp = wci_chord(vb, pv, ep, lb, lp);
    let cc = wci_chord(vb, cm, t.e2 * mu - t.e1, lb, lcm);
    let cc2 = wci_dot3(cc, cc);
    let u1 = select(0.0f, wci_dot3(cp, cp) / cc2, 0.0f < cc2);
    let arvo = t.ok && 0.0f < wci_abs(t.det) && WCI_FALLBACK_TURNS <= t.turns;
    let fb = wc_triangle_uniform_inverse(b);
    return select(fb, vec2<f32>(wci_unit_interval(u0), wci_unit_interval(u1)), arvo);
}

// The rectangle in its own frame seen from p (`spherical::rectangle::Rect`).
struct WciRect {
    x0: f32,
    w: f32,
    y0: f32,
    h: f32,
    z: f32,
    turns: f32,
    iw: f32,
    ih: f32,
    // |(x, y, z)| at (x0, y0), (x1, y0), (x1, y1), (x0, y1), with z before the edge-on rule.
    radii: vec4<f32>,
    ok: bool,
    c: vec3<f32>,
    ex: vec3<f32>,
    eyp: vec3<f32>,
}

// Solid angle (turns of 4 pi) of [x0, x0 + dx] x [y0, y0 + dy] at height z.
fn wci_quad_turns(x0: f32, dx: f32, y0: f32, dy: f32, z: f32) -> f32 {
    return wci_quad_turns_r(x0, dx, y0, dy, z, wci_corner_radii(x0, dx, y0, dy, z * z));
}

// |(x, y, z)| at the corners (x0, y0), (x1, y0), (x1, y1), (x0, y1) (`corner_radii`).
fn wci_corner_radii(x0: f32, dx: f32, y0: f32, dy: f32, z2: f32) -> vec4<f32> {
    let x1 = x0 + dx;
    let y1 = y0 + dy;
    return vec4<f32>(sqrt(x0 * x0 + y0 * y0 + z2), sqrt(x1 * x1 + y0 * y0 + z2),
        sqrt(x1 * x1 + y1 * y1 + z2), sqrt(x0 * x0 + y1 * y1 + z2));
}

// The squared distance to the nearer of two parallel sides, 0 between them (`quad_turns_r`).
fn wci_near2(a0: f32, b0: f32, inside: bool) -> f32 {
    let a = wci_abs(a0);
    let b = wci_abs(b0);
    let m = select(b, a, a < b);
    return select(m * m, 0.0f, inside);
}

// wci_quad_turns given the corner radii (`quad_turns_r`): a long light seen from beside its
// middle (-x0 x1 > 32 (y_near^2 + z^2), or the same in y) is cut at p's foot into pieces on
// one side of it, whose solid angles are added; elsewhere the one pair of triangles.
fn wci_quad_turns_r(x0: f32, dx: f32, y0: f32, dy: f32, z: f32, radii: vec4<f32>) -> f32 {
    let whole = wci_vos_quad_turns(x0, dx, y0, dy, z, radii);
    let x1 = x0 + dx;
    let y1 = y0 + dy;
    let z2 = z * z;
    let sx = x0 < 0.0f && 0.0f < x1;
    let sy = y0 < 0.0f && 0.0f < y1;
    let cut_x = sx && 32.0f * (wci_near2(y0, y1, sy) + z2) < -(x0 * x1);
    let cut_y = sy && 32.0f * (wci_near2(x0, x1, sx) + z2) < -(y0 * y1);
    // Not where z^2 is below the smallest normal f32 (the pieces' corner at the foot).
    let cut = (cut_x || cut_y) && 0x1p-126f <= z2;
    if (!cut) {
        return whole;
    }
    let wa = select(dx, -x0, cut_x);
    let ha = select(dy, -y0, cut_y);
    // The pieces' turns are >= 0: adding the ones not cut as 0 (as the crate does) is a no-op.
    var split = wci_vos_quad_turns(x0, wa, y0, ha, z, wci_corner_radii(x0, wa, y0, ha, z2));
    if (cut_x) {
        split = split + wci_vos_quad_turns(0.0f, x1, y0, ha, z, wci_corner_radii(0.0f, x1, y0, ha, z2));
    }
    if (cut_y) {
        split = split + wci_vos_quad_turns(x0, wa, 0.0f, y1, z, wci_corner_radii(x0, wa, 0.0f, y1, z2));
    }
    if (cut_x && cut_y) {
        split = split + wci_vos_quad_turns(0.0f, x1, 0.0f, y1, z, wci_corner_radii(0.0f, x1, 0.0f, y1, z2));
    }
    // Four pieces can round past half a turn (p a hair above the light, inside it): held at
    // 1/2 (2 pi), as the crate does.
    return wci_clamp0(split, 0.5f);
}

// The solid angle (turns of 4 pi) as the two triangles (00, 10, 11) and (00, 11, 01), given
// the corner radii (`vos_quad_turns`).
fn wci_vos_quad_turns(x0: f32, dx: f32, y0: f32, dy: f32, z: f32, radii: vec4<f32>) -> f32 {
    let x1 = x0 + dx;
    let y1 = y0 + dy;
    let z2 = z * z;
    let r00 = radii.x;
    let r10 = radii.y;
    let r11 = radii.z;
    let r01 = radii.w;
    let d00_10 = x0 * x1 + y0 * y0 + z2;
    let d00_11 = x0 * x1 + y0 * y1 + z2;
    let d10_11 = x1 * x1 + y0 * y1 + z2;
    let d00_01 = x0 * x0 + y0 * y1 + z2;
    let d11_01 = x1 * x0 + y1 * y1 + z2;
    // Fenced against factoring out r11 and r01 (see wci_half_angle_turns).
    let zero = wci_zero_of(r00);
    let den1 = wci_fence(r00 * r10 * r11, zero) + d00_10 * r11 + d00_11 * r10 + d10_11 * r00;
    let den2 = wci_fence(r00 * r11 * r01, zero) + d00_11 * r01 + d00_01 * r11 + d11_01 * r00;
    let n0 = z * dx * dy;
    // Both factors of the degree-6 product lifted by one exact power of two (`quad_turns`).
    let s = wci_pow2_lift(den1, den2, n0);
    let d1 = den1 * s;
    let d2 = den2 * s;
    let n = n0 * s;
    let y = n * (d1 + d2);
    return wci_atan2_turns(select(0.0f, y, 0.0f < y), d1 * d2 - n * n);
}

fn wci_rect_setup(corner: vec3<f32>, ex0: vec3<f32>, ey0: vec3<f32>, p: vec3<f32>) -> WciRect {
    let c0 = wci_flush3(corner - p);
    let ex1 = wci_flush3(ex0);
    let ey1 = wci_flush3(ey0);
    let finite = wci_finite3(c0) && wci_finite3(ex1) && wci_finite3(ey1);
    let k = wci_pow2_scale_of(wci_max_abs3(wci_max_abs3(wci_max_abs3(0.0f, c0), ex1), ey1));
    let scaled = bitcast<u32>(k) != 0u;
    var r: WciRect;
    r.c = c0 * k;
    r.ex = ex1 * k;
    let ey = ey1 * k;
    r.w = wci_norm3(r.ex);
    r.iw = 1.0f / r.w;
    let xh = r.ex * r.iw;
    r.eyp = ey - xh * wci_dot3(ey, xh);
    r.h = wci_norm3(r.eyp);
    r.ih = 1.0f / r.h;
    let yh = r.eyp * r.ih;
    let nh = wci_cross3(xh, yh);
    r.x0 = wci_dot3(r.c, xh);
    r.y0 = wci_dot3(r.c, yh);
    let z = wci_abs(wci_dot3(r.c, nh));
    r.ok = finite && scaled && 0.0f < r.w && 0.0f < r.h;
    r.radii = wci_corner_radii(r.x0, r.w, r.y0, r.h, z * z);
    let turns = wci_quad_turns_r(r.x0, r.w, r.y0, r.h, z, r.radii);
    // Edge-on below the area-sampling threshold: solid angle and density 0 (`FLAT_ZWH`).
    let flat = turns < WCI_FALLBACK_TURNS && z * r.w * r.h < 0x1p-116f;
    r.z = select(z, 0.0f, flat);
    r.turns = select(0.0f, turns, r.ok && !flat);
    return r;
}

// The solid angle of the rectangle corner + s ex + t ey at p, in [0, 2 pi].
fn wc_spherical_rectangle_solid_angle(corner: vec3<f32>, ex: vec3<f32>, ey: vec3<f32>, p: vec3<f32>) -> f32 {
    return wci_rect_setup(corner, ex, ey, p).turns * WCI_FOUR_PI;
}

// b / sqrt(d2 + b^2) - a / sqrt(d2 + a^2) with b = a + ba, without cancellation.
fn wci_h_diff(a: f32, ba: f32, d2: f32) -> f32 {
    let b = a + ba;
    let ra = sqrt(d2 + a * a);
    let rb = sqrt(d2 + b * b);
    let same = 0.0f < a * b;
    let num = select(b * ra - a * rb, d2 * ba * (b + a) / (b * ra + a * rb), same);
    return num / (ra * rb);
}

// (1 - y / r, 1 + y / r) from small = 1 - |y| / r and big = 1 + |y| / r (`minus_plus`).
fn wci_minus_plus(y: f32, small: f32, big: f32) -> vec2<f32> {
    let pos = 0.0f < y;
    return vec2<f32>(select(big, small, pos), select(small, big, pos));
}

// Everything Urena's map computes from the light and p alone (`rectangle::Prepared`).
struct WciRectPrepared {
    r: WciRect,
    y1: f32,
    z2: f32,
    left: f32,
    right: f32,
    b01: f32,
    exact: bool,
    closed: bool,
    area_ok: bool,
}

// The half-infinite strip beyond one side of the light in turns of 4 pi (`half_strip`): the
// factors r - x as they are (na, nb), or beyond p's foot from the far forms (fa, fb).
fn wci_half_strip(zh: f32, yy: f32, far: bool, fa: f32, fb: f32, na: f32, nb: f32) -> f32 {
    return wci_atan2_turns(zh, select(na, fa, far) * select(nb, fb, far) + yy);
}

fn wci_rect_prepare(corner: vec3<f32>, ex: vec3<f32>, ey: vec3<f32>, p: vec3<f32>) -> WciRectPrepared {
    var pr: WciRectPrepared;
    let r = wci_rect_setup(corner, ex, ey, p);
    pr.r = r;
    let x0 = r.x0;
    let y0 = r.y0;
    let z = r.z;
    let y1 = y0 + r.h;
    let z2 = z * z;
    pr.y1 = y1;
    pr.z2 = z2;
    let r00 = r.radii.x;
    let r10 = r.radii.y;
    let r11 = r.radii.z;
    let r01 = r.radii.w;
    let x1 = x0 + r.w;
    let zh = z * r.h;
    let yy = y0 * y1 + z2;
    let qa = y0 * y0 + z2;
    let qb = y1 * y1 + z2;
    // At most one side is beyond p's foot: one pair of divisions serves it.
    let far_l = 0.0f < x0;
    let far_r = x1 < 0.0f;
    let xf = select(-x1, x0, far_l);
    let fa = qa / (select(r10, r00, far_l) + xf);
    let fb = qb / (select(r11, r01, far_l) + xf);
    pr.left = wci_half_strip(zh, yy, far_l, fa, fb, r00 - x0, r01 - x0);
    pr.right = wci_half_strip(zh, yy, far_r, fa, fb, r10 + x1, r11 + x1);
    pr.b01 = z2 / (sqrt(qa) * sqrt(qb));
    pr.area_ok = r.ok && 0.0f < z;
    pr.exact = pr.area_ok && WCI_FALLBACK_TURNS <= r.turns;
    // The closed-form start is the point from 1e-2 to 2 sr within kappa 16, aspect 16 (`closed`).
    let m0 = select(r00, r10, r00 < r10);
    let m1 = select(r11, r01, r11 < r01);
    let far = select(m0, m1, m0 < m1);
    pr.closed = WCI_NEWTON_FROM_TURNS <= r.turns && r.turns <= WCI_NEWTON_UP_TO_TURNS
        && far <= z * 16.0f && r.w <= r.h * 16.0f && r.h <= r.w * 16.0f;
    return pr;
}

// One Newton step on quad_turns(x0, dx, ..) = goal, the step res / slope as one quotient.
fn wci_rect_newton(r: WciRect, y1: f32, z2: f32, goal: f32, dx: f32) -> f32 {
    let y0 = r.y0;
    let x = r.x0 + dx;
    let ra = sqrt(x * x + y0 * y0 + z2);
    let rb = sqrt(x * x + y1 * y1 + z2);
    let res = wci_quad_turns_r(r.x0, dx, y0, r.h, r.z, vec4<f32>(r.radii.x, ra, rb, r.radii.w)) - goal;
    let d2 = x * x + z2;
    let same = 0.0f < y0 * y1;
    let d = select(d2, wci_abs(y1 * ra + y0 * rb), same);
    let num = res * (WCI_FOUR_PI * wci_opaque(ra * rb)) * d;
    let den = r.z * select(y1 * ra - y0 * rb, r.h * wci_abs(y0 + y1), same);
    let step = select(0.0f, num / den, wci_positive_finite(den));
    return wci_clamp0(dx - step, r.w);
}

fn wci_rect_sample(pr: WciRectPrepared, u: vec2<f32>) -> vec3<f32> {
    let u0 = wci_unit_interval(u.x);
    let u1 = wci_unit_interval(u.y);
    let r = pr.r;
    let x0 = r.x0;
    let w = r.w;
    let y0 = r.y0;
    let h = r.h;
    let z = r.z;
    let y1 = pr.y1;
    let z2 = pr.z2;
    let goal = u0 * r.turns;
    let tl = pr.left + goal;
    let tr = pr.right + (r.turns - goal);
    let a = wci_sin_cos_turns(wci_clamp0(tl, 0.5f));
    let bb = wci_sin_cos_turns(wci_clamp0(tr, 0.5f));
    let sg = a.x * bb.y - a.y * bb.x;
    let k = (a.x + a.x) * bb.x;
    let xu = z * sg / sqrt(k * (k + pr.b01 + pr.b01));
    let dx0 = wci_clamp0(xu - x0, w);
    var dx = dx0;
    if (!pr.closed) {
        dx = wci_rect_newton(r, y1, z2, goal, dx0);
    }
    // The height: uniform in y / sqrt(d^2 + y^2) between its values at y0 and y1.
    let x = x0 + dx;
    let d2 = x * x + z2;
    let r0 = sqrt(d2 + y0 * y0);
    let r1 = sqrt(d2 + y1 * y1);
    let ir = 1.0f / (r0 * r1);
    let i0 = r1 * ir;
    let i1 = r0 * ir;
    let h0 = y0 * i0;
    let h1 = y1 * i1;
    let big0 = 1.0f + wci_abs(h0);
    let big1 = 1.0f + wci_abs(h1);
    let rb = 1.0f / (big0 * big1);
    let small0 = d2 * i0 * i0 * (big1 * rb);
    let small1 = d2 * i1 * i1 * (big0 * rb);
    let mp0 = wci_minus_plus(y0, small0, big0);
    let mp1 = wci_minus_plus(y1, small1, big1);
    let v1 = 1.0f - u1;
    let same = 0.0f < y0 * y1;
    let hd = select(h1 - h0, d2 * h * (y1 + y0) * (i0 * i1) / (y1 * r0 + y0 * r1), same);
    let dh = u1 * hd;
    let hv = h0 + dh;
    let om = v1 * mp0.x + u1 * mp1.x;
    let op = v1 * mp0.y + u1 * mp1.y;
    let dd = sqrt(d2);
    let c0 = dd * i0;
    let cv = sqrt(om * op);
    let dy = dd * dh * (1.0f + c0 * cv + h0 * hv) / ((c0 + cv) * cv * c0);
    let s = wci_clamp0(dx * r.iw, 1.0f);
    let t = wci_clamp0(dy * r.ih, 1.0f);
    // Area sampling: density |q|^3 / (z w h).
    let qx = x0 + u0 * w;
    let qy = y0 + u1 * h;
    let ql = wci_opaque(sqrt(qx * qx + qy * qy + z2)); // fenced as in wci_tri_sample
    let zwh = z * w * h;
    let area0 = select(ql * ql * ql / zwh, ql * (ql * (ql / zwh)), ql < 0x1p-40f);
    let area_pdf = select(0.0f, select(WCI_F32_MAX, area0, area0 < WCI_F32_MAX), pr.area_ok);
    let pdf = select(area_pdf, WCI_INV_4PI / r.turns, pr.exact);
    return vec3<f32>(select(u0, s, pr.exact), select(u1, t, pr.exact), pdf);
}

// Uniform in solid angle over the spherical rectangle that corner + s ex + t ey (ex
// orthogonal to ey) subtends at p: (s, t, density w.r.t. solid angle).
fn wc_spherical_rectangle(corner: vec3<f32>, ex: vec3<f32>, ey: vec3<f32>, p: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
    return wci_rect_sample(wci_rect_prepare(corner, ex, ey, p), u);
}

// Inverse of wc_spherical_rectangle: the u that maps to (s, t).
fn wc_spherical_rectangle_inverse(corner: vec3<f32>, ex: vec3<f32>, ey: vec3<f32>, p: vec3<f32>, st: vec2<f32>) -> vec2<f32> {
    let r = wci_rect_setup(corner, ex, ey, p);
    let s = wci_clamp0(st.x, 1.0f);
    let t = wci_clamp0(st.y, 1.0f);
    let dx = s * r.w;
    let u0 = wci_quad_turns(r.x0, dx, r.y0, r.h, r.z) / r.turns;
    let x = r.x0 + dx;
    let d2 = x * x + r.z * r.z;
    let full = wci_h_diff(r.y0, r.h, d2);
    let part = wci_h_diff(r.y0, t * r.h, d2);
    let u1 = select(0.0f, part / full, 0.0f < full);
    let exact = r.ok && 0.0f < r.z && WCI_FALLBACK_TURNS <= r.turns;
    return vec2<f32>(
        select(wci_unit_interval(s), wci_unit_interval(u0), exact),
        select(wci_unit_interval(t), wci_unit_interval(u1), exact),
    );
}

// Inverse CDF of the density 2 ((1 - x) a + x b) / (a + b) on [0, 1], clamped to [0, 1 - 2^-24].
fn wci_sample_linear(u: f32, a: f32, b: f32) -> f32 {
    let x = u * (a + b) / (a + sqrt((1.0f - u) * (a * a) + u * (b * b)));
    return select(0.0f, select(WCI_ONE_MINUS_EPSILON, x, x < WCI_ONE_MINUS_EPSILON), 0.0f < x);
}

// 4 ((1-x)(1-y) w00 + x(1-y) w10 + (1-x) y w01 + x y w11) for weights summing to 1.
fn wci_lerp_pdf(x: f32, y: f32, w: vec4<f32>) -> f32 {
    let x1 = 1.0f - x;
    let y1 = 1.0f - y;
    return 4.0f * (x1 * y1 * w.x + x * y1 * w.y + x1 * y * w.z + x * y * w.w);
}

// The bilinear warp of Hart et al. 2020 (`spherical::bilinear`): (x, y, density).
fn wci_bilinear(u: vec2<f32>, w0: vec4<f32>) -> vec3<f32> {
    let u0 = wci_unit_interval(u.x);
    let u1 = wci_unit_interval(u.y);
    let wp = vec4<f32>(select(0.0f, w0.x, 0.0f < w0.x), select(0.0f, w0.y, 0.0f < w0.y),
        select(0.0f, w0.z, 0.0f < w0.z), select(0.0f, w0.w, 0.0f < w0.w));
    let sum = wp.x + wp.y + wp.z + wp.w;
    // A sum below the smallest normal counts as zero (flush-proof: `cosine::normalise`).
    let ok = 0x1p-126f <= sum && sum <= WCI_F32_MAX;
    let inv = select(0.0f, 1.0f / sum, ok);
    // A second, fenced copy of inv: a compiler may factor w0 inv + w1 inv into (w0 + w1) inv
    // (lavapipe does).
    let inv2 = wci_opaque(inv);
    let w = vec4<f32>(wp.x * inv, wp.y * inv2, wp.z * inv, wp.w * inv2);
    let y = wci_sample_linear(u1, w.x + w.y, w.z + w.w);
    let y1 = 1.0f - y;
    let x = wci_sample_linear(u0, y1 * w.x + y * w.z, y1 * w.y + y * w.w);
    let pdf = wci_lerp_pdf(x, y, w);
    return vec3<f32>(select(u0, x, ok), select(u1, y, ok), select(1.0f, pdf, ok));
}

// max(0, n . d / |d|) with n scaled by a power of two; 0 for zero or non-finite n or d.
fn wci_clamped_cosine(n: vec3<f32>, ok: bool, d: vec3<f32>) -> f32 {
    let c = wci_dot3(n, d) / wci_norm3(d);
    return select(0.0f, c, ok && 0.0f < c);
}

// The solid-angle density times the bilinear factor, kept finite.
fn wci_product(pdf: f32, factor: f32) -> f32 {
    let d = pdf * factor;
    return select(WCI_F32_MAX, d, d < WCI_F32_MAX);
}

// Cosine-aware wc_spherical_triangle: u warped by the bilinear fit of the receiver's
// clamped cosine (normal n) at v1, v1, v0, v2, then Arvo's map; (b0, b1, b2, density).
fn wc_spherical_triangle_cosine(v0: vec3<f32>, v1: vec3<f32>, v2: vec3<f32>, p: vec3<f32>, n: vec3<f32>, u: vec2<f32>) -> vec4<f32> {
    let pr = wci_tri_prepare(v0, v1, v2, p);
    let k = wci_pow2_scale_of(wci_max_abs3(0.0f, n));
    let ok = bitcast<u32>(k) != 0u;
    let ns = n * k;
    let c0 = wci_clamped_cosine(ns, ok, pr.t.a0);
    let c1 = wci_clamped_cosine(ns, ok, pr.t.a1);
    let c2 = wci_clamped_cosine(ns, ok, pr.t.a2);
    let warped = wci_bilinear(u, vec4<f32>(c1, c1, c0, c2));
    let r = wci_tri_sample(pr, warped.xy);
    return vec4<f32>(r.xyz, wci_product(r.w, warped.z));
}

// Cosine-aware wc_spherical_rectangle: weights at corner, + ex, + ey, + ex + ey; (s, t, density).
fn wc_spherical_rectangle_cosine(corner: vec3<f32>, ex: vec3<f32>, ey: vec3<f32>, p: vec3<f32>, n: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
    let pr = wci_rect_prepare(corner, ex, ey, p);
    let k = wci_pow2_scale_of(wci_max_abs3(0.0f, n));
    let ok = bitcast<u32>(k) != 0u;
    let ns = n * k;
    let c = pr.r.c;
    let c10 = c + pr.r.ex;
    let w = vec4<f32>(
        wci_clamped_cosine(ns, ok, c),
        wci_clamped_cosine(ns, ok, c10),
        wci_clamped_cosine(ns, ok, c + pr.r.eyp),
        wci_clamped_cosine(ns, ok, c10 + pr.r.eyp),
    );
    let warped = wci_bilinear(u, w);
    let r = wci_rect_sample(pr, warped.xy);
    return vec3<f32>(r.xy, wci_product(r.z, warped.z));
}

// ---------------------------------------------------------------------------------------
// Sphere lights by cone (src/spherical/cone.rs)

const WCI_TWO_PI: f32 = 0x1.921fb6p+2f;

// The cone a sphere subtends at p (`cone::Cone`): axis n, tangents t, b (Duff et al. 2017),
// 1 - cos theta_max (2 inside; 0 where not ok).
struct WciCone {
    n: vec3<f32>,
    t: vec3<f32>,
    b: vec3<f32>,
    omc: f32,
    ok: bool,
}

fn wci_cone_setup(centre: vec3<f32>, radius: f32, p: vec3<f32>) -> WciCone {
    let d0 = wci_flush3(centre - p);
    let rv = wci_flush3(vec3<f32>(wci_abs(radius), 0.0f, 0.0f));
    let finite = wci_finite3(d0) && wci_finite3(rv);
    let kd = wci_pow2_scale_of(wci_max_abs3(0.0f, d0));
    let dn = d0 * kd;
    let inv = 1.0f / wci_norm3(dn);
    let k = wci_pow2_scale_of(wci_max_abs3(wci_max_abs3(0.0f, d0), rv));
    let scaled = bitcast<u32>(k) != 0u;
    let d = d0 * k;
    let r = rv.x * k;
    let dist = wci_norm3(d);
    let has_axis = finite && bitcast<u32>(kd) != 0u;
    let outside = has_axis && r <= dist;
    let dist_s = select(1.0f, dist, outside);
    let s = r / dist_s;
    let cos = select(0.0f, sqrt((dist_s - r) * (dist_s + r)) / dist_s, outside);
    let omc = select(2.0f, s * s / (1.0f + cos), outside);
    var c: WciCone;
    c.ok = finite && scaled && !(outside && s < 0x1p-60f);
    c.n = vec3<f32>(
        select(0.0f, dn.x * inv, has_axis),
        select(0.0f, dn.y * inv, has_axis),
        select(1.0f, dn.z * inv, has_axis),
    );
    let sign = wci_flip_sign(1.0f, wci_sign_bit(c.n.z));
    let a = -1.0f / (sign + c.n.z);
    let bxy = c.n.x * c.n.y * a;
    c.t = vec3<f32>(1.0f + ((sign * c.n.x) * c.n.x) * a, sign * bxy, -(sign * c.n.x));
    c.b = vec3<f32>(bxy, sign + (c.n.y * c.n.y) * a, -c.n.y);
    c.omc = select(0.0f, omc, c.ok);
    return c;
}

// Uniform in the cone the sphere (centre, radius) subtends at p: (direction, density).
fn wc_spherical_cone(centre: vec3<f32>, radius: f32, p: vec3<f32>, u: vec2<f32>) -> vec4<f32> {
    let c = wci_cone_setup(centre, radius, p);
    let rcs = wci_concentric_parts(u);
    let x = rcs.x * rcs.x * c.omc;
    let cos = 1.0f - x;
    let sin = wci_flip_sign(sqrt(x * (2.0f - x)), wci_sign_bit(rcs.x));
    let st = sin * rcs.y;
    let sb = sin * rcs.z;
    let pdf = select(0.0f, WCI_HEMISPHERE_PDF / c.omc, c.ok);
    return vec4<f32>(
        c.t.x * st + c.b.x * sb + c.n.x * cos,
        c.t.y * st + c.b.y * sb + c.n.y * cos,
        c.t.z * st + c.b.z * sb + c.n.z * cos,
        pdf,
    );
}

// Inverse of wc_spherical_cone: the u whose direction is dir (any length).
fn wc_spherical_cone_inverse(centre: vec3<f32>, radius: f32, p: vec3<f32>, dir: vec3<f32>) -> vec2<f32> {
    let c = wci_cone_setup(centre, radius, p);
    let w0 = wci_flush3(dir);
    let k = wci_pow2_scale_of(wci_max_abs3(0.0f, w0));
    let valid = wci_finite3(w0) && bitcast<u32>(k) != 0u;
    let w1 = w0 * k;
    let l = wci_norm3(w1);
    let inv = select(0.0f, 1.0f / l, valid);
    let w = w1 * inv;
    let xt = wci_dot3(w, c.t);
    let yb = wci_dot3(w, c.b);
    let zc = select(1.0f, wci_dot3(w, c.n), valid);
    let sin2 = xt * xt + yb * yb;
    let x = select(1.0f - zc, sin2 / (1.0f + zc), 0.0f < zc);
    let omc = select(1.0f, c.omc, c.ok);
    let within = x <= omc;
    let den = select(sin2, omc * (2.0f - x), within);
    let has = 0.0f < den;
    let kd = select(0.0f, 1.0f / sqrt(select(1.0f, den, has)), has);
    let rim = !has && 1.0f < x;
    let disk = vec2<f32>(
        select(0.0f, select(xt * kd, 1.0f, rim), valid),
        select(0.0f, yb * kd, valid),
    );
    let uv = wc_disk_concentric_inverse(disk);
    return vec2<f32>(select(0.5f, uv.x, c.ok), select(0.5f, uv.y, c.ok));
}

// The solid angle of the sphere (centre, radius) at p: [0, 2 pi] outside, 4 pi inside.
fn wc_spherical_cone_solid_angle(centre: vec3<f32>, radius: f32, p: vec3<f32>) -> f32 {
    return wci_cone_setup(centre, radius, p).omc * WCI_TWO_PI;
}

// GGX microfacet reflection (src/microfacet): D, Smith G1 and height-correlated G2, visible
// normals by spherical caps (Dupuy and Benyoub 2023), reflection and bounded reflection (Eto
// and Tokuyoshi 2023) with their exact densities. alpha = r^2 of a perceptual roughness r.

// 1e-4 (`microfacet::ALPHA_MIN`), 1 / (2 pi), and the bounded cap test's slack 1 - 2^-16.
const WCI_ALPHA_MIN: f32 = 0x1.a36e2ep-14f;
const WCI_HALF_FRAC_1_PI: f32 = 0x1.45f306p-3f;
const WCI_CAP_SLACK: f32 = 0x1.fffep-1f;
// 4 (1/8)^2: the plain half vector is used where alpha_min^2 |h|^2 >= 4 (1/8)^2 |wi|^2.
const WCI_PLAIN_BOUND: f32 = 0x1p-4f;

// The reflection's result: the direction and its density per steradian.
struct WcDirectionPdf {
    wi: vec3<f32>,
    pdf: f32,
}

// The roughness clamped to [1e-4, 1] (NaN to 1e-4) and its reciprocals (`Rough`).
struct WciRough {
    a: vec2<f32>,
    inv: vec2<f32>,
}

fn wci_rough(alpha: vec2<f32>) -> WciRough {
    let ax = select(WCI_ALPHA_MIN, select(1.0f, alpha.x, alpha.x < 1.0f), WCI_ALPHA_MIN < alpha.x);
    let ay = select(WCI_ALPHA_MIN, select(1.0f, alpha.y, alpha.y < 1.0f), WCI_ALPHA_MIN < alpha.y);
    return WciRough(vec2<f32>(ax, ay), vec2<f32>(1.0f / ax, 1.0f / ay));
}

fn wci_stretch(r: WciRough, w: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(r.a.x * w.x, r.a.y * w.y, w.z);
}

fn wci_unstretch(r: WciRough, m: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(m.x * r.inv.x, m.y * r.inv.y, m.z);
}

// v scaled by the power of two putting its largest component in [1, 2), or the zero vector
// where that does not exist or v is not finite (w: 1 for valid).
fn wci_scaled(v: vec3<f32>) -> vec4<f32> {
    let k = wci_pow2_scale_of(wci_max_abs3(0.0f, v));
    let ok = bitcast<u32>(k) != 0u && wci_finite3(v);
    let s = v * k;
    return vec4<f32>(select(vec3<f32>(0.0f), s, ok), select(0.0f, 1.0f, ok));
}

// The outgoing direction scaled by a power of two, mirrored into z >= 0, +z when not a
// direction (`outgoing_scaled`).
fn wci_outgoing_scaled(wo: vec3<f32>) -> vec3<f32> {
    let s = wci_scaled(vec3<f32>(wo.x, wo.y, wci_abs(wo.z)));
    return vec3<f32>(s.x, s.y, select(1.0f, s.z, s.w == 1.0f));
}

// The outgoing direction as every function reads it (`Outgoing`): s scaled, inv = 1 / |s|,
// the unit w = s inv.
struct WciOutgoing {
    s: vec3<f32>,
    inv: f32,
    w: vec3<f32>,
}

fn wci_outgoing(wo: vec3<f32>) -> WciOutgoing {
    let s = wci_outgoing_scaled(wo);
    let inv = 1.0f / wci_norm3(s);
    return WciOutgoing(s, inv, s * inv);
}

// Double-f32 error-free transformations (src/microfacet/exact.rs: Veltkamp's split, Knuth's
// two-sum, Dekker's product), pairs (hi, lo). Every step is fenced with the runtime zero z:
// the shader compiler would otherwise fold c - (c - x) to x or (a - (s - bb)) to 0.
fn wci_split(x: f32, z: u32) -> vec2<f32> {
    let c = wci_fence(4097.0f * x, z);
    let hi = wci_fence(c - wci_fence(c - x, z), z);
    return vec2<f32>(hi, wci_fence(x - hi, z));
}

fn wci_two_sum(a: f32, b: f32, z: u32) -> vec2<f32> {
    let s = wci_fence(a + b, z);
    let bb = wci_fence(s - a, z);
    return vec2<f32>(s, wci_fence(a - wci_fence(s - bb, z), z) + wci_fence(b - bb, z));
}

fn wci_two_prod(a: f32, b: f32, z: u32) -> vec2<f32> {
    let p = wci_fence(a * b, z);
    let x = wci_split(a, z);
    let y = wci_split(b, z);
    let e0 = wci_fence(wci_fence(x.x * y.x, z) - p, z);
    let e1 = wci_fence(e0 + wci_fence(x.x * y.y, z), z);
    let e2 = wci_fence(e1 + wci_fence(x.y * y.x, z), z);
    return vec2<f32>(p, e2 + wci_fence(x.y * y.y, z));
}

fn wci_two_square(a: f32, z: u32) -> vec2<f32> {
    let p = wci_fence(a * a, z);
    let x = wci_split(a, z);
    let t = wci_fence(x.x * x.y, z);
    let e0 = wci_fence(wci_fence(x.x * x.x, z) - p, z);
    let e1 = wci_fence(e0 + wci_fence(t + t, z), z);
    return vec2<f32>(p, e1 + wci_fence(x.y * x.y, z));
}

// The sum of three exact products (p, e) as (hi, lo) (`dot2`, `norm2`).
fn wci_sum3_2(p0: vec2<f32>, p1: vec2<f32>, p2: vec2<f32>, z: u32) -> vec2<f32> {
    let s0 = wci_two_sum(p0.x, p1.x, z);
    let s1 = wci_two_sum(s0.x, p2.x, z);
    let e = wci_fence(wci_fence(p0.y + p1.y, z) + p2.y, z);
    return vec2<f32>(s1.x, wci_fence(s0.y + s1.y, z) + e);
}

// v with its components below 2^-40 made 0 (`coarse`): no partial product is subnormal.
fn wci_coarse(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        select(v.x, 0.0f, wci_abs(v.x) < 0x1p-40f),
        select(v.y, 0.0f, wci_abs(v.y) < 0x1p-40f),
        select(v.z, 0.0f, wci_abs(v.z) < 0x1p-40f),
    );
}

fn wci_dot2(a0: vec3<f32>, b0: vec3<f32>, z: u32) -> vec2<f32> {
    let a = wci_coarse(a0);
    let b = wci_coarse(b0);
    return wci_sum3_2(wci_two_prod(a.x, b.x, z), wci_two_prod(a.y, b.y, z), wci_two_prod(a.z, b.z, z), z);
}

fn wci_norm2(a: vec3<f32>, z: u32) -> vec2<f32> {
    return wci_sum3_2(wci_two_square(a.x, z), wci_two_square(a.y, z), wci_two_square(a.z, z), z);
}

// One component of the half direction: a + rho b rounded once from double-f32.
fn wci_half_component(a: f32, b: f32, rho: vec2<f32>, z: u32) -> f32 {
    let pe = wci_two_prod(b, rho.x, z);
    let st = wci_two_sum(a, pe.x, z);
    let lo = wci_fence(wci_fence(st.y + pe.y, z) + wci_fence(b * rho.y, z), z);
    return st.x + lo;
}

// The direction of a / |a| + b / |b| as a + (|a| / |b|) b (`half_direction`).
fn wci_half_direction(a0: vec3<f32>, b0: vec3<f32>, z: u32) -> vec3<f32> {
    let a = wci_coarse(a0);
    let b = wci_coarse(b0);
    let a2 = wci_norm2(a, z);
    let b2 = wci_norm2(b, z);
    let inv = 1.0f / b2.x;
    let r = wci_fence(a2.x * inv, z);
    let pe = wci_two_prod(r, b2.x, z);
    let r0 = wci_fence(wci_fence(wci_fence(a2.x - pe.x, z) - pe.y, z) + a2.y, z);
    let rl = wci_fence(r0 - wci_fence(r * b2.y, z), z) * inv;
    let rho = wci_fence(sqrt(r), z);
    let qe = wci_two_square(rho, z);
    let rhol = wci_fence(wci_fence(wci_fence(r - qe.x, z) - qe.y, z) + rl, z) / (rho + rho);
    let rr = vec2<f32>(rho, rhol);
    return vec3<f32>(
        wci_half_component(a.x, b.x, rr, z),
        wci_half_component(a.y, b.y, rr, z),
        wci_half_component(a.z, b.z, rr, z),
    );
}

// D(m) of a scaled m, and |unstretch(m)|^2.
fn wci_ggx_d(r: WciRough, m: vec3<f32>) -> vec2<f32> {
    let um = wci_unstretch(r, m);
    let q = wci_dot3(um, um);
    let rr = wci_dot3(m, m) / q;
    // Fenced: the shader compiler would reorder the products with the constant.
    let z = wci_zero_of(m.z);
    let c = wci_fence(wci_fence(r.inv.x * r.inv.y, z) * WCI_FRAC_1_PI, z);
    let d = wci_fence(rr * rr, z) * c;
    return vec2<f32>(select(0.0f, d, 0.0f < m.z && 0.0f < q), q);
}

// The bounded sampler's k and 1 - k over their common denominator d: (k d, d, (1 - k) d).
fn wci_shrink_parts(r: WciRough, w: vec3<f32>) -> vec3<f32> {
    let a = select(r.a.y, r.a.x, r.a.x < r.a.y);
    let a2 = a * a;
    let s = 1.0f + sqrt(w.x * w.x + w.y * w.y);
    let s2 = s * s;
    let z2 = w.z * w.z;
    return vec3<f32>((1.0f - a2) * s2, s2 + a2 * z2, a2 * (s2 + z2));
}

// The bounded sampler's (k, 1 - k) for a unit w.
fn wci_shrink(r: WciRough, w: vec3<f32>) -> vec2<f32> {
    let kp = wci_shrink_parts(r, w);
    let inv = 1.0f / kp.y;
    return vec2<f32>(kp.x * inv, kp.z * inv);
}

// The visible normal by a spherical cap (`cap_normal`): xyz the normal, w = |stretch(w)|.
// `bounded` selects the cap z >= -k i.z (kp from wci_shrink_parts), built multiplied by d.
fn wci_cap_normal(r: WciRough, w: vec3<f32>, u: vec2<f32>, kp: vec3<f32>, bounded: bool) -> vec4<f32> {
    let ws = wci_stretch(r, w);
    let l = wci_norm3(ws);
    let ld = select(l, l * kp.y, bounded);
    let bl = select(ws.z, kp.x * ws.z, bounded);
    let wd = select(ws, ws * kp.y, bounded);
    let rim = kp.z * ws.z;
    let p = ld + bl;
    // ld >= bl in IEEE arithmetic (a correctly rounded |ws| is at least ws.z); a GPU's sqrt
    // (within its WGSL tolerance) can return l an ulp below ws.z, and a negative q would take
    // the square root below of a negative number (NaN on the NVIDIA H200). No bits change
    // where sqrt is correctly rounded.
    let q0 = ld - bl;
    let q = select(q0, 0.0f, q0 < 0.0f);
    let u0 = wci_unit_interval(u.x);
    let u1 = wci_unit_interval(u.y);
    let vp = (1.0f - u1) * p;
    let sn = sqrt(u1 * p * (vp + q));
    let sc = wci_sin_cos_turns(u0);
    let hz = select(vp, vp + rim, bounded);
    // (ax cos, ay sin) fenced: the compiler would reassociate sin (ax cos) as (sin ax) cos.
    let z = wci_zero_of(u.y);
    let m = vec3<f32>(
        sn * wci_fence(r.a.x * sc.y, z) + r.a.x * wd.x,
        sn * wci_fence(r.a.y * sc.x, z) + r.a.y * wd.y,
        hz,
    );
    let n = wci_norm3(m);
    return vec4<f32>(m.x / n, m.y / n, m.z / n, l);
}

// The reflection density at the half vector h0 (any length), den = k w.z + t, omk = 1 - k.
fn wci_density_at(r: WciRough, w: vec3<f32>, h0: vec3<f32>, den: f32, omk: f32, valid: bool, bounded: bool) -> f32 {
    let h = h0 * wci_pow2_lift(h0.x, h0.y, h0.z);
    let hh = wci_dot3(h, h);
    let uh = wci_unstretch(r, h);
    let q = wci_dot3(uh, uh);
    let lhs = 2.0f * wci_dot3(w, h) * h.z;
    let z = wci_zero_of(w.z);
    let rhs = wci_fence(w.z * omk * q, z) * WCI_CAP_SLACK;
    let inside = !bounded || rhs <= lhs;
    let c = wci_fence(wci_fence(r.inv.x * r.inv.y, z) * WCI_HALF_FRAC_1_PI, z);
    let pdf = wci_fence(hh * hh, z) * c / (q * q * den);
    return select(0.0f, pdf, valid && inside && 0.0f < h.z && 0.0f < q);
}

// The reflection density at wi for the outgoing o with t = |stretch(o.w)|: the half vector
// |wi| w + wi where alpha_min wo.h >= 1/8, else in double-f32 (wci_half_direction).
fn wci_reflect_density(r: WciRough, o: WciOutgoing, t: f32, wi0: vec3<f32>, bounded: bool) -> f32 {
    let w = o.w;
    let s = wci_scaled(wi0);
    let valid = s.w == 1.0f;
    let wi = vec3<f32>(s.x, s.y, select(1.0f, s.z, valid));
    let km = wci_shrink(r, w);
    let den = select(w.z + t, km.x * w.z + t, bounded);
    let omk = select(0.0f, km.y, bounded);
    let l = wci_norm3(wi);
    let plain = vec3<f32>(w.x * l + wi.x, w.y * l + wi.y, w.z * l + wi.z);
    let amin = select(r.a.y, r.a.x, r.a.x < r.a.y);
    let z = wci_zero_of(w.z);
    let bound = wci_fence(WCI_PLAIN_BOUND * l, z) * l;
    let use_plain = bound <= amin * amin * wci_dot3(plain, plain);
    let p = wci_density_at(r, w, plain, den, omk, valid, bounded);
    let e = wci_density_at(r, w, wci_half_direction(o.s, wi, z), den, omk, valid, bounded);
    return select(e, p, use_plain);
}

fn wci_reflect_sample(wo: vec3<f32>, alpha: vec2<f32>, u: vec2<f32>, bounded: bool) -> WcDirectionPdf {
    let r = wci_rough(alpha);
    let o = wci_outgoing(wo);
    let w = o.w;
    let mt = wci_cap_normal(r, w, u, wci_shrink_parts(r, w), bounded);
    let m = mt.xyz;
    let wm = wci_dot3(w, m);
    let t2 = wm + wm;
    let wi = vec3<f32>(t2 * m.x - w.x, t2 * m.y - w.y, t2 * m.z - w.z);
    return WcDirectionPdf(wi, wci_reflect_density(r, o, mt.w, wi, bounded));
}

fn wci_reflect_pdf(wo: vec3<f32>, wi: vec3<f32>, alpha: vec2<f32>, bounded: bool) -> f32 {
    let r = wci_rough(alpha);
    let o = wci_outgoing(wo);
    return wci_reflect_density(r, o, wci_norm3(wci_stretch(r, o.w)), wi, bounded);
}

// |stretch(w)| / |w.z| of the scale-free w (inf at w.z = 0; 1 for an invalid w).
fn wci_lambda_term(r: WciRough, w: vec3<f32>) -> f32 {
    let s = wci_scaled(vec3<f32>(w.x, w.y, wci_abs(w.z)));
    return select(1.0f, wci_norm3(wci_stretch(r, s.xyz)) / s.z, s.w == 1.0f);
}

// D(m) per steradian of m (0 for m.z <= 0 or an invalid m).
fn wc_microfacet_ggx_d(m: vec3<f32>, alpha: vec2<f32>) -> f32 {
    let s = wci_scaled(m);
    return select(0.0f, wci_ggx_d(wci_rough(alpha), s.xyz).x, s.w == 1.0f);
}

// Smith masking G1(w) = 2 |wz| / (|wz| + |(ax wx, ay wy, wz)|).
fn wc_microfacet_ggx_g1(w: vec3<f32>, alpha: vec2<f32>) -> f32 {
    return 2.0f / (1.0f + wci_lambda_term(wci_rough(alpha), w));
}

// Height-correlated Smith G2(wo, wi).
fn wc_microfacet_ggx_g2(wo: vec3<f32>, wi: vec3<f32>, alpha: vec2<f32>) -> f32 {
    let r = wci_rough(alpha);
    return 2.0f / (wci_lambda_term(r, wo) + wci_lambda_term(r, wi));
}

// A GGX normal visible from wo (spherical caps).
fn wc_microfacet_ggx_visible_normal(wo: vec3<f32>, alpha: vec2<f32>, u: vec2<f32>) -> vec3<f32> {
    return wci_cap_normal(wci_rough(alpha), wci_outgoing_scaled(wo), u, vec3<f32>(0.0f), false).xyz;
}

// The density of wc_microfacet_ggx_visible_normal per steradian of m.
fn wc_microfacet_ggx_visible_normal_pdf(wo: vec3<f32>, m0: vec3<f32>, alpha: vec2<f32>) -> f32 {
    let r = wci_rough(alpha);
    let o = wci_outgoing(wo);
    let w = o.w;
    let s = wci_scaled(m0);
    let m = s.xyz;
    let d = wci_ggx_d(r, m).x;
    // w.m = (s . m) / |s| with the dot product in double-f32.
    let wm2 = wci_dot2(o.s, m, wci_zero_of(w.z));
    let wm = (wm2.x + wm2.y) * o.inv;
    let den = (w.z + wci_norm3(wci_stretch(r, w))) * wci_norm3(m);
    // No subnormal operand or result: wo.m and a density below 2^-126 count as 0.
    let p = (wm + wm) * (d / den);
    return select(0.0f, p, s.w == 1.0f && 0x1p-126f <= wm && 0x1p-126f <= p);
}

// Reflection by visible normals: wi and its density (that of wc_microfacet_ggx_reflect_pdf at wi).
fn wc_microfacet_ggx_reflect(wo: vec3<f32>, alpha: vec2<f32>, u: vec2<f32>) -> WcDirectionPdf {
    return wci_reflect_sample(wo, alpha, u, false);
}

fn wc_microfacet_ggx_reflect_pdf(wo: vec3<f32>, wi: vec3<f32>, alpha: vec2<f32>) -> f32 {
    return wci_reflect_pdf(wo, wi, alpha, false);
}

// Bounded reflection (Eto and Tokuyoshi 2023) with its exact density.
fn wc_microfacet_ggx_reflect_bounded(wo: vec3<f32>, alpha: vec2<f32>, u: vec2<f32>) -> WcDirectionPdf {
    return wci_reflect_sample(wo, alpha, u, true);
}

fn wc_microfacet_ggx_reflect_bounded_pdf(wo: vec3<f32>, wi: vec3<f32>, alpha: vec2<f32>) -> f32 {
    return wci_reflect_pdf(wo, wi, alpha, true);
}
