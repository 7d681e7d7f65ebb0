// warpcore_lights.wgsl: light selection on the GPU, straight from the crate's storage words.
//
// Self-contained (no name is shared with warpcore.wgsl, warpcore_tables.wgsl or
// warpcore_envmap.wgsl). Public names mirror the C ABI (`wc_lights_*`, `WcLightChoice`);
// everything named `wcli_*` is internal.
//
// THE ONE BINDING. The tables live in one read-only storage buffer of u32 words, declared
// below at @group(0) @binding(4) (0 and 1 are the other libraries'; 2 and 3 are left for a
// caller's input and output); edit the two numbers to move it. Each function takes `base`,
// the word offset of a table's storage in that buffer, so one buffer holds several tables.
// A storage is exactly what the crate wrote (`table.storage()` in Rust): validate it on the
// CPU (`from_storage` or `from_storage_verified`) before uploading. The shader reads the
// header without checking it; whatever the words hold, the index it returns is below the
// header's light count and the probability is in [0, 1] (an out-of-range read returns a
// value or zero under WebGPU's robust buffer access).

@group(0) @binding(4) var<storage, read> wc_lights: array<u32>;

// A chosen light and the probability of choosing it (the crate's `(index, probability)`).
struct WcLightChoice {
    index: u32,
    prob: f32,
}

// ---- The alias table (`lights::AliasTable`, format version 1) ----
//
// Storage: 8 header words (tag "wcAL", version, n, checksum, reserved), then 4 words per
// light: threshold (0.32 fixed point), alias, pmf(light), pmf(alias) as f32 bits. Integer
// arithmetic only (plus the exact u * 2^31), so every conforming GPU returns the crate's bits.

// 1 - 2^-24.
const WCLI_ONE_MINUS_EPSILON: f32 = 0x1.fffffep-1f;

// Any f32 onto [0, 1 - 2^-24]: NaN, -0.0, negatives to +0.0 (`lanes::unit_interval`).
fn wcli_unit_interval(x: f32) -> f32 {
    return select(0.0f, select(WCLI_ONE_MINUS_EPSILON, x, x < WCLI_ONE_MINUS_EPSILON), 0.0f < x);
}

// The high word of the 64-bit product a * b, from 16-bit halves.
fn wcli_mul_high(a: u32, b: u32) -> u32 {
    let lo = (a & 0xffffu) * (b & 0xffffu);
    let cross1 = (a >> 16u) * (b & 0xffffu);
    let cross2 = (a & 0xffffu) * (b >> 16u);
    let carry = ((lo >> 16u) + (cross1 & 0xffffu) + (cross2 & 0xffffu)) >> 16u;
    return (a >> 16u) * (b >> 16u) + (cross1 >> 16u) + (cross2 >> 16u) + carry;
}

// A stored probability's bits, or 0 unless they are those of a number in [0, 1].
fn wcli_clean(bits: u32) -> u32 {
    return select(0u, bits, bits < 0x3f800001u);
}

// `AliasTable::sample`: light `index` with probability `prob` (= wc_lights_alias_pmf of it,
// bit for bit). The column is floor(k n / 2^32) of the 0.32 fixed-point key k = 2 floor(u 2^31),
// its own light when the low 32 bits of k n are below its threshold, else its alias.
fn wc_lights_alias_sample(base: u32, u: f32) -> WcLightChoice {
    let x = wcli_unit_interval(u);
    let key = bitcast<u32>(i32(x * 2147483648.0f)) << 1u;
    let n = wc_lights[base + 2u];
    let column = wcli_mul_high(key, n);
    let frac = key * n;
    let r = base + 8u + 4u * column;
    let threshold = wc_lights[r];
    let other = select(column, wc_lights[r + 1u], wc_lights[r + 1u] < n);
    let stay = frac < threshold;
    let bits = select(wcli_clean(wc_lights[r + 3u]), wcli_clean(wc_lights[r + 2u]), stay);
    return WcLightChoice(select(other, column, stay), bitcast<f32>(bits));
}

// `AliasTable::pmf`: the probability that wc_lights_alias_sample returns `index` (0 for
// index >= n).
fn wc_lights_alias_pmf(base: u32, index: u32) -> f32 {
    let n = wc_lights[base + 2u];
    let bits = wcli_clean(wc_lights[base + 8u + 4u * index + 2u]);
    return select(0.0f, bitcast<f32>(bits), index < n);
}

// ---- The light tree (`lights::LightTree`, format version 2) ----
//
// Storage: 16 header words (tag "wcLT", version, n, m, levels, 0, 0, 0, checksum, 0 ...),
// then n / 3 + 14 quads of 48 words (the four children of an inner node, field-major: word k
// of child c at 4 k + c; a node, f32 words: bounding-sphere centre and radius, power, unit
// axis, cos theta_o, sin theta_o, cos theta_e, then a word with the leaf flag, the two-sided
// flag and an index), then
// one bit trail per light. The walk is src/lights/tree.rs's, operation by operation (the
// same IEEE operations in the same order: +, -, *, /, sqrt, compares and selects only), so
// a GPU that rounds them as IEEE 754 says returns the crate's bits (proved on lavapipe).

const WCLI_TREE_HEADER: u32 = 16u;
const WCLI_TREE_QUAD_WORDS: u32 = 48u;
// The node word holding the flags and the index.
const WCLI_TREE_INFO: u32 = 11u;
const WCLI_TREE_LEAF: u32 = 0x80000000u;
const WCLI_TREE_TWO_SIDED: u32 = 0x40000000u;
const WCLI_TREE_INDEX_MASK: u32 = 0x3fffffffu;
const WCLI_TREE_MAX_LEVELS: u32 = 16u;
// Importances are clamped to 2^125, so a quad's sum of four stays finite.
const WCLI_TREE_BIG: f32 = 0x1p125f;
// Unscaled importances are used where phi / max(d^2, r^2) lies in [2^-100, 2^100)
// (`tree::RANGE`).
const WCLI_TREE_RANGE: f32 = 0x1p100f;
const WCLI_F32_MAX: f32 = 0x1.fffffep127f;
const WCLI_F32_MIN_POSITIVE: f32 = 0x1p-126f;

// The shading point as the walk sees it (`tree::Point`): p (zeros unless finite), the unit
// normal (zeros for a medium), whether there is a normal, whether p is finite.
struct WcliPoint {
    p: vec3<f32>,
    n: vec3<f32>,
    has_n: bool,
    valid: bool,
}

// `x` if 0 < x, else 0 (NaN too).
fn wcli_pos(x: f32) -> f32 {
    return select(0.0f, x, 0.0f < x);
}

// x.x * x.x + x.y * x.y + x.z * x.z, in that order.
fn wcli_len2(v: vec3<f32>) -> f32 {
    return v.x * v.x + v.y * v.y + v.z * v.z;
}

// 2^k with 2^k m in [1, 2) for a normal m below 2^127 (`tree::pow2_down`): [2, 4) above,
// 2^126 for a smaller m, 2^-126 for inf or NaN; always a normal number.
fn wcli_pow2_down(m: f32) -> f32 {
    let e = clamp((bitcast<u32>(m) >> 23u) & 0xffu, 1u, 253u);
    return bitcast<f32>((254u - e) << 23u);
}

// m raised to x where m < x <= f32::MAX (`tree::raise`: NaN and infinities never win).
fn wcli_raise(m: f32, x: f32) -> f32 {
    return select(m, x, m < x && x <= WCLI_F32_MAX);
}

fn wcli_finite3(v: vec3<f32>) -> bool {
    return abs(v.x) <= WCLI_F32_MAX && abs(v.y) <= WCLI_F32_MAX && abs(v.z) <= WCLI_F32_MAX;
}

fn wcli_point(p: vec3<f32>, n: vec3<f32>) -> WcliPoint {
    let valid = wcli_finite3(p);
    let q = vec3<f32>(select(0.0f, p.x, valid), select(0.0f, p.y, valid), select(0.0f, p.z, valid));
    // The normal scaled by a power of two before its length is taken.
    let m = wcli_raise(wcli_raise(wcli_raise(0.0f, abs(n.x)), abs(n.y)), abs(n.z));
    let has_n = wcli_finite3(n) && WCLI_F32_MIN_POSITIVE <= m;
    let nk = n * wcli_pow2_down(m);
    let len2 = nk.x * nk.x + nk.y * nk.y + nk.z * nk.z;
    let inv = select(0.0f, 1.0f / sqrt(len2), has_n);
    let u = vec3<f32>(select(0.0f, nk.x * inv, has_n), select(0.0f, nk.y * inv, has_n), select(0.0f, nk.z * inv, has_n));
    return WcliPoint(q, u, has_n, valid);
}

// Word k of child c of quad `quad` (zeros past the storage's quads, as the crate's gather).
fn wcli_tree_word(base: u32, quads: u32, quad: u32, k: u32, c: u32) -> u32 {
    let at = base + WCLI_TREE_HEADER + WCLI_TREE_QUAD_WORDS * quad + 4u * k + c;
    return select(0u, wc_lights[at], quad < quads);
}

// How far child c of a quad reaches at the point and how much it emits (`tree::extent`):
// the largest of |p - c|'s coordinates and the radius, and the power (0 and 0 for a child
// of no positive power).
fn wcli_tree_extent(pt: WcliPoint, base: u32, quads: u32, quad: u32, c: u32) -> vec2<f32> {
    let phi = wcli_raise(0.0f, bitcast<f32>(wcli_tree_word(base, quads, quad, 4u, c)));
    var len = wcli_raise(0.0f, bitcast<f32>(wcli_tree_word(base, quads, quad, 3u, c)));
    len = wcli_raise(len, abs(pt.p.x - bitcast<f32>(wcli_tree_word(base, quads, quad, 0u, c))));
    len = wcli_raise(len, abs(pt.p.y - bitcast<f32>(wcli_tree_word(base, quads, quad, 1u, c))));
    len = wcli_raise(len, abs(pt.p.z - bitcast<f32>(wcli_tree_word(base, quads, quad, 2u, c))));
    return vec2<f32>(select(0.0f, len, 0.0f < phi), phi);
}

// The importance of child c of a quad at the point (`tree::importance`): finite, in
// [0, 2^125], whatever the words hold. Cosines and sines carry the distance d (the stored
// axis is taken as unit): three square roots side by side, one division at the end.
// Lengths are multiplied by `ls` and the power by `ps`: 1 and 1, or the quad's exact
// power-of-two scales (`tree::with_scales`). Returns the importance and 1 where nothing that
// decides it came near overflow or underflow (`in_range`), else 0.
fn wcli_tree_importance(pt: WcliPoint, ls: f32, ps: f32, base: u32, quads: u32, quad: u32, c: u32) -> vec2<f32> {
    let d = vec3<f32>(
        (pt.p.x - bitcast<f32>(wcli_tree_word(base, quads, quad, 0u, c))) * ls,
        (pt.p.y - bitcast<f32>(wcli_tree_word(base, quads, quad, 1u, c))) * ls,
        (pt.p.z - bitcast<f32>(wcli_tree_word(base, quads, quad, 2u, c))) * ls,
    );
    let d2 = wcli_len2(d);
    let r = bitcast<f32>(wcli_tree_word(base, quads, quad, 3u, c)) * ls;
    let r2 = r * r;
    let phi = bitcast<f32>(wcli_tree_word(base, quads, quad, 4u, c)) * ps;
    let outside = r2 < d2;
    // d cos(theta_w) (folded for two-sided nodes) and d sin(theta_w).
    let v = vec3<f32>(
        bitcast<f32>(wcli_tree_word(base, quads, quad, 5u, c)),
        bitcast<f32>(wcli_tree_word(base, quads, quad, 6u, c)),
        bitcast<f32>(wcli_tree_word(base, quads, quad, 7u, c)),
    );
    let a0 = v.x * d.x + v.y * d.y + v.z * d.z;
    let info = wcli_tree_word(base, quads, quad, WCLI_TREE_INFO, c);
    let two_sided = (info & WCLI_TREE_TWO_SIDED) != 0u;
    let a = select(a0, abs(a0), two_sided);
    let sw = sqrt(wcli_pos(d2 - a * a));
    let dist = sqrt(d2);
    let cos_o = bitcast<f32>(wcli_tree_word(base, quads, quad, 8u, c));
    let sin_o = bitcast<f32>(wcli_tree_word(base, quads, quad, 9u, c));
    let cos_e = bitcast<f32>(wcli_tree_word(base, quads, quad, 10u, c));
    // d cos(theta_x), d sin(theta_x).
    let within = cos_o * dist < a;
    let cx = select(a * cos_o + sw * sin_o, dist, within);
    let sx = select(sw * cos_o - a * sin_o, 0.0f, within);
    // d cos(theta_b).
    let cb = sqrt(wcli_pos(d2 - r2));
    let ci = abs(d.x * pt.n.x + d.y * pt.n.y + d.z * pt.n.z);
    let si = sqrt(wcli_pos(d2 - ci * ci));
    let cp = select(cx * cb + sx * r, d2, cb < cx);
    let cpi = select(ci * cb + si * r, d2, cb < ci);
    let dc0 = select(r2, d2, outside);
    let dc = select(WCLI_F32_MIN_POSITIVE, dc0, WCLI_F32_MIN_POSITIVE < dc0);
    let inv = 1.0f / dc;
    let cos_p = select(1.0f, cp * inv, outside);
    let cos_pi = select(1.0f, cpi * inv, outside && pt.has_n);
    let q = phi * inv;
    let imp0 = q * cos_pi * cos_p;
    let alive = cos_e <= cos_p && pt.valid;
    let imp = select(0.0f, imp0, alive);
    let in_range = (q < WCLI_TREE_RANGE && 1.0f / WCLI_TREE_RANGE <= q) || !(0.0f < phi);
    let clamped = select(0.0f, select(WCLI_TREE_BIG, imp, imp < WCLI_TREE_BIG), WCLI_F32_MIN_POSITIVE <= imp);
    return vec2<f32>(clamped, select(0.0f, 1.0f, in_range));
}

// The walk (`tree::walk`): from quad 0, `levels` steps, each picking child c with
// probability I_c / S by two binary choices, by `u` (t = u S against the cumulative bounds,
// then u = (t - start) / I_c) or by the bits of `trail`.
fn wcli_tree_walk(base: u32, pt: WcliPoint, u0: f32, trail: u32, by_u: bool) -> WcLightChoice {
    let len = wc_lights[base + 2u];
    let levels = min(wc_lights[base + 4u], WCLI_TREE_MAX_LEVELS);
    let quads = len / 3u + 14u;
    var u = u0;
    var quad = 0u;
    var prob = 1.0f;
    var index = 0xffffffffu;
    var done = false;
    var dead = !pt.valid;
    for (var level = 0u; level < levels; level++) {
        var f0 = wcli_tree_importance(pt, 1.0f, 1.0f, base, quads, quad, 0u);
        var f1 = wcli_tree_importance(pt, 1.0f, 1.0f, base, quads, quad, 1u);
        var f2 = wcli_tree_importance(pt, 1.0f, 1.0f, base, quads, quad, 2u);
        var f3 = wcli_tree_importance(pt, 1.0f, 1.0f, base, quads, quad, 3u);
        if f0.y * f1.y * f2.y * f3.y == 0.0f {
            // A child out of range: the quad again at its scales, from its children's
            // largest extent and power.
            var len = 0.0f;
            var power = 0.0f;
            for (var c = 0u; c < 4u; c++) {
                let e = wcli_tree_extent(pt, base, quads, quad, c);
                len = wcli_raise(len, e.x);
                power = wcli_raise(power, e.y);
            }
            let ls = wcli_pow2_down(len);
            let ps = wcli_pow2_down(power);
            f0 = wcli_tree_importance(pt, ls, ps, base, quads, quad, 0u);
            f1 = wcli_tree_importance(pt, ls, ps, base, quads, quad, 1u);
            f2 = wcli_tree_importance(pt, ls, ps, base, quads, quad, 2u);
            f3 = wcli_tree_importance(pt, ls, ps, base, quads, quad, 3u);
        }
        let i0 = f0.x;
        let i1 = f1.x;
        let i2 = f2.x;
        let i3 = f3.x;
        let s01 = i0 + i1;
        let s23 = i2 + i3;
        let sum = s01 + s23;
        var high = ((trail >> (2u * level)) & 1u) != 0u;
        var second = ((trail >> (2u * level + 1u)) & 1u) != 0u;
        if by_u {
            // A side of weight 0 is never taken (`ByU`'s infinite bound).
            let s012 = s01 + i2;
            let t = u * sum;
            high = !(t < s01) && 0.0f < s23;
            second = select(!(t < i0) && 0.0f < i1, !(t < s012) && 0.0f < i3, high);
            let start = select(select(0.0f, i0, second), select(s01, s012, second), high);
            let chosen_u = select(select(i0, i1, second), select(i2, i3, second), high);
            let v = (t - start) / chosen_u;
            u = select(0.0f, select(WCLI_ONE_MINUS_EPSILON, v, v < WCLI_ONE_MINUS_EPSILON), 0.0f < v);
        }
        let chosen = select(select(i0, i1, second), select(i2, i3, second), high);
        let live = 0.0f < sum;
        let was_going = !(done || dead);
        dead = dead || (was_going && !live);
        let going = was_going && live;
        let p_child = select(0.0f, chosen / sum, live);
        prob = select(prob, prob * p_child, going);
        let child = select(0u, 2u, high) + select(0u, 1u, second);
        let info = wcli_tree_word(base, quads, quad, WCLI_TREE_INFO, child);
        let next = info & WCLI_TREE_INDEX_MASK;
        let leaf = (info & WCLI_TREE_LEAF) != 0u;
        let reached = going && leaf;
        index = select(index, next, reached);
        done = done || reached;
        quad = select(quad, next, going && !leaf);
    }
    // A leaf naming a light past the end, a walk cut short, a dead end or a probability
    // below 2^-126: no light.
    let ok = done && !dead && index < len && WCLI_F32_MIN_POSITIVE <= prob;
    return WcLightChoice(select(0xffffffffu, index, ok), select(0.0f, prob, ok));
}

// `LightTree::sample`: a light for the shading point `p` with normal `n` (zeros: a point in
// a medium; need not be unit) from `u` (any value: NaN, negatives as 0, >= 1 as 1 - 2^-24);
// `prob` = wc_lights_tree_pmf of it, bit for bit; index 0xffffffff and prob 0 where no light
// contributes.
fn wc_lights_tree_sample(base: u32, p: vec3<f32>, n: vec3<f32>, u: f32) -> WcLightChoice {
    return wcli_tree_walk(base, wcli_point(p, n), wcli_unit_interval(u), 0u, true);
}

// `LightTree::pmf`: the probability that wc_lights_tree_sample at (p, n) returns `index`
// (0 past the end, for a light of power 0 or of importance 0 at p), along its bit trail.
fn wc_lights_tree_pmf(base: u32, p: vec3<f32>, n: vec3<f32>, index: u32) -> f32 {
    let len = wc_lights[base + 2u];
    let quads = len / 3u + 14u;
    let at = base + WCLI_TREE_HEADER + WCLI_TREE_QUAD_WORDS * quads + index;
    let trail = select(0u, wc_lights[at], index < len);
    let r = wcli_tree_walk(base, wcli_point(p, n), 0.0f, trail, false);
    return select(0.0f, r.prob, r.index == index);
}
