// warpcore_envmap.wgsl: environment-map importance sampling on the GPU, straight from the
// crate's storage words (format version 3): `Hierarchical` and `MarginalConditional`
// `sample` and `pdf`, one point per call.
//
// Self-contained (no name is shared with warpcore.wgsl or warpcore_tables.wgsl). Public names
// mirror the C ABI: `wc_envmap_hierarchical_*`, `wc_envmap_marginal_conditional_*`,
// `WcEnvSample`; everything named `wcei_*` is internal.
//
// THE ONE BINDING. The maps live in one read-only storage buffer of u32 words, declared below
// at @group(0) @binding(1) (binding 0 is warpcore_tables.wgsl's, so the files can be used
// together); edit the two numbers to move it. Each function takes `base`, the word offset of
// a map's storage in that buffer, so one buffer can hold several maps. A map's storage is
// exactly what the crate wrote (`map.storage()` in Rust, the `uint32_t` array in C, the
// bytes of a `.wcmap` file in JS): header (16 words: tag, version, width, height, the four
// region lengths, checksum, reserved) and tables. Validate it on the CPU before uploading
// (`from_storage` or `from_storage_verified`): the shader reads the header without checking
// it (a storage read out of range returns a value or zero under WebGPU's robust buffer
// access: no crash, garbage samples).
//
// The arithmetic is the crate's, operation by operation: exact integer walks (0.30 / 0.31
// fixed point, multiply-high from 16-bit halves), the correctly rounded u32 -> f32 conversion
// `f32(x >> 8) * 256 + f32(x & 255)`, one division per axis for the position inside the
// texel, and the stored texel edges. On Mesa lavapipe the results are the crate's bits
// (`cargo test -p warpcore-gpu`); on real GPUs the division may differ by 2.5 ulp (WGSL), so
// the position inside the texel may move by a few ulps, always clamped inside its texel; the
// texel and the pdf are exact integer functions of the sample (the pdf's two products are
// correctly rounded).

@group(0) @binding(1) var<storage, read> wc_envmap: array<u32>;

// A sample: the point in [0, 1)^2 inside `texel` ([column, row]) and its density with
// respect to area on the unit square (the crate's `Sample`).
struct WcEnvSample {
    uv: vec2<f32>,
    pdf: f32,
    texel: vec2<u32>,
}

// 1 - 2^-24.
const WCEI_ONE_MINUS_EPSILON: f32 = 0x1.fffffep-1f;

// Any f32 onto [0, 1 - 2^-24]: NaN, -0.0, negatives to +0.0 (`lanes::unit_interval`).
fn wcei_unit_interval(x: f32) -> f32 {
    return select(0.0f, select(WCEI_ONE_MINUS_EPSILON, x, x < WCEI_ONE_MINUS_EPSILON), 0.0f < x);
}

// `x as i32 as f32` (exact below 2^24) and `x as i32 as u32` (0 <= x < 2^31).
fn wcei_from_uint(u: u32) -> f32 {
    return f32(bitcast<i32>(u));
}

fn wcei_to_uint(x: f32) -> u32 {
    return bitcast<u32>(i32(x));
}

// Correctly rounded u32 -> f32 for the whole range (`envmap::u32_to_f32`); the product is
// exact, so a fused multiply-add gives the same bits.
fn wcei_u32_to_f32(x: u32) -> f32 {
    return wcei_from_uint(x >> 8u) * 256.0f + wcei_from_uint(x & 255u);
}

// The high word of the 64-bit product a * b.
fn wcei_mul_high(a: u32, b: u32) -> u32 {
    let a0 = a & 0xffffu;
    let a1 = a >> 16u;
    let b0 = b & 0xffffu;
    let b1 = b >> 16u;
    let p00 = a0 * b0;
    let p01 = a0 * b1;
    let p10 = a1 * b0;
    let p11 = a1 * b1;
    let mid = (p00 >> 16u) + (p01 & 0xffffu) + (p10 & 0xffffu);
    return p11 + (p01 >> 16u) + (p10 >> 16u) + (mid >> 16u);
}

// The header of the map at `base`: width, height and the word offsets of its four regions.
struct WceiMap {
    base: u32,
    width: u32,
    height: u32,
    // Word offsets (absolute, in wc_envmap) of the regions after the header.
    region0: u32,
    region1: u32,
    edges_x: u32,
    edges_y: u32,
}

fn wcei_map(base: u32) -> WceiMap {
    let start = base + 16u;
    let r0 = start;
    let r1 = r0 + wc_envmap[base + 4u];
    let ex = r1 + wc_envmap[base + 5u];
    let ey = ex + wc_envmap[base + 6u];
    return WceiMap(base, wc_envmap[base + 2u], wc_envmap[base + 3u], r0, r1, ex, ey);
}

// The point (k + frac) / n of texel k, clamped into [edge[k], edge[k + 1]) (`edges::point`).
fn wcei_edge_point(edges: u32, k: u32, frac: f32, n: u32) -> f32 {
    let x0 = (wcei_from_uint(k) + frac) / wcei_from_uint(n);
    let lo = bitcast<f32>(wc_envmap[edges + k]);
    let hi = bitcast<f32>(wc_envmap[edges + k + 1u] - 1u);
    let x1 = select(x0, lo, x0 < lo);
    return wcei_unit_interval(select(x1, hi, hi < x1));
}

// The texel (0..n) holding coordinate x, after the forward rule (`edges::texel`).
fn wcei_edge_texel(edges: u32, x0: f32, n: u32) -> u32 {
    let x = wcei_unit_interval(x0);
    let k0 = wcei_to_uint(x * wcei_from_uint(n));
    let last = n - 1u;
    let k = select(k0, last, last < k0);
    let lo = bitcast<f32>(wc_envmap[edges + k]);
    let next = bitcast<f32>(wc_envmap[edges + k + 1u]);
    let k1 = select(select(k, k + 1u, next <= x), k - 1u, x < lo);
    return select(k1, last, last < k1);
}

// ---------------------------------------------------------------------------------------
// Hierarchical (src/envmap/hierarchical.rs)

// ceil(log2 n) for 1 <= n <= 2^24.
fn wcei_bits(n: u32) -> u32 {
    return select(32u - countLeadingZeros(n - 1u), 0u, n <= 1u);
}

// The walk's state per axis: the key's offset `r` in the interval of `len` units, and the
// texel coordinate decided so far.
struct WceiWalk {
    r: vec2<u32>,
    len: vec2<u32>,
    texel: vec2<u32>,
}

// Shape of the padded pyramid: splits per axis of virtual level k.
fn wcei_splits(xbits: u32, ybits: u32, k: u32) -> vec2<u32> {
    let levels = max(xbits, ybits);
    let pad = ((levels + 1u) & ~1u) - levels;
    let level = k - pad;
    let sx = select(0u, 1u, level + xbits >= levels);
    let sy = select(0u, 1u, level + ybits >= levels);
    return select(vec2<u32>(sx, sy), vec2<u32>(0u), k < pad);
}

// One level (`Walk::level`); `texel_bits` >= 0x80000000 means "sample" (compare keys),
// otherwise the pdf lookup follows bit `shift` of the padded texel `pdf_texel`.
fn wcei_level(w: ptr<function, WceiWalk>, shift: u32, s: vec2<u32>, px: u32, py0: u32, py1: u32,
              pdf: bool, pdf_texel: vec2<u32>) -> u32 {
    let my0 = wcei_mul_high((*w).len.y + (*w).len.y, py0);
    let my1 = wcei_mul_high((*w).len.y + (*w).len.y, py1);
    let mx = wcei_mul_high((*w).len.x + (*w).len.x, px);
    let gox = select((*w).r.x < mx, ((pdf_texel.x >> shift) & 1u) == 0u, pdf);
    (*w).len.x = select((*w).len.x - mx, mx, gox);
    (*w).r.x = select((*w).r.x - mx, (*w).r.x, gox);
    let bx = select(s.x, 0u, gox);
    (*w).texel.x = ((*w).texel.x << 1u) | bx;
    let my = select(my1, my0, gox);
    let goy = select((*w).r.y < my, ((pdf_texel.y >> shift) & 1u) == 0u, pdf);
    (*w).len.y = select((*w).len.y - my, my, goy);
    (*w).r.y = select((*w).r.y - my, (*w).r.y, goy);
    let by = select(s.y, 0u, goy);
    (*w).texel.y = ((*w).texel.y << 1u) | by;
    return bx | (by << s.x);
}

fn wcei_descend(m: WceiMap, key: vec2<u32>, pdf: bool, pdf_texel: vec2<u32>) -> WceiWalk {
    let xbits = wcei_bits(m.width);
    let ybits = wcei_bits(m.height);
    let levels = max(xbits, ybits);
    let vl = (levels + 1u) & ~1u;
    var w = WceiWalk(key, vec2<u32>(0x40000000u), vec2<u32>(0u));
    var index = 0u;
    var offset = 0u;
    var count = 1u;
    for (var b = 0u; b < vl / 2u; b++) {
        let k = 2u * b;
        let s0 = wcei_splits(xbits, ybits, k);
        let s1 = wcei_splits(xbits, ybits, k + 1u);
        let b0 = s0.x + s0.y;
        let b1 = s1.x + s1.y;
        let at = m.region1 + ((offset + index) << 4u);
        let c = wcei_level(&w, vl - 1u - k, s0, wc_envmap[at], wc_envmap[at + 1u], wc_envmap[at + 2u], pdf, pdf_texel);
        let at2 = at + 3u + 3u * c;
        let g = wcei_level(&w, vl - 2u - k, s1, wc_envmap[at2], wc_envmap[at2 + 1u], wc_envmap[at2 + 2u], pdf, pdf_texel);
        index = (((index << b0) | c) << b1) | g;
        offset += count;
        count = count << (b0 + b1);
    }
    return w;
}

// The pdf scale of a w x h map: w h 2^-60 (`pdf_scale`, rounded once: w and h are exact).
fn wcei_density(len: vec2<u32>, w: u32, h: u32, scale: f32) -> f32 {
    let dx = wcei_u32_to_f32(len.x);
    let dy = wcei_u32_to_f32(len.y);
    return dy * dx * (wcei_from_uint(w) * wcei_from_uint(h) * scale);
}

fn wcei_hierarchical_offsets(m: WceiMap) -> vec2<u32> {
    let xbits = wcei_bits(m.width);
    let ybits = wcei_bits(m.height);
    return vec2<u32>(((1u << xbits) - m.width) / 2u, ((1u << ybits) - m.height) / 2u);
}

// `Hierarchical::sample` of the map whose storage starts at word `base` of wc_envmap.
fn wc_envmap_hierarchical_sample(base: u32, u: vec2<f32>) -> WcEnvSample {
    let m = wcei_map(base);
    let key = vec2<u32>(wcei_to_uint(wcei_unit_interval(u.x) * 0x1p30f),
                        wcei_to_uint(wcei_unit_interval(u.y) * 0x1p30f));
    let w = wcei_descend(m, key, false, vec2<u32>(0u));
    let off = wcei_hierarchical_offsets(m);
    let tx0 = w.texel.x - off.x;
    let ty0 = w.texel.y - off.y;
    let tx = select(tx0, m.width - 1u, m.width - 1u < tx0);
    let ty = select(ty0, m.height - 1u, m.height - 1u < ty0);
    let fx = wcei_unit_interval(wcei_u32_to_f32(w.r.x) / wcei_u32_to_f32(w.len.x));
    let fy = wcei_unit_interval(wcei_u32_to_f32(w.r.y) / wcei_u32_to_f32(w.len.y));
    let uv = vec2<f32>(wcei_edge_point(m.edges_x, tx, fx, m.width),
                       wcei_edge_point(m.edges_y, ty, fy, m.height));
    return WcEnvSample(uv, wcei_density(w.len, m.width, m.height, 0x1p-60f), vec2<u32>(tx, ty));
}

// `Hierarchical::pdf`: the density of the texel holding `uv` (after the forward rule).
fn wc_envmap_hierarchical_pdf(base: u32, uv: vec2<f32>) -> f32 {
    let m = wcei_map(base);
    let off = wcei_hierarchical_offsets(m);
    let t = vec2<u32>(wcei_edge_texel(m.edges_x, uv.x, m.width) + off.x,
                      wcei_edge_texel(m.edges_y, uv.y, m.height) + off.y);
    let w = wcei_descend(m, vec2<u32>(0u), true, t);
    return wcei_density(w.len, m.width, m.height, 0x1p-60f);
}

// ---------------------------------------------------------------------------------------
// Marginal-conditional (src/envmap/marginal.rs)

// The largest k < n with table[base + k] <= key (`marginal::search`).
fn wcei_search(base: u32, n: u32, key: u32) -> u32 {
    var lo = 0u;
    var len = n;
    while (len > 1u) {
        let half = len / 2u;
        let mid = lo + half;
        lo = select(mid, lo, key < wc_envmap[base + mid]);
        len -= half;
    }
    return lo;
}

// `MarginalConditional::sample` of the map whose storage starts at word `base` of wc_envmap.
fn wc_envmap_marginal_conditional_sample(base: u32, u: vec2<f32>) -> WcEnvSample {
    let m = wcei_map(base);
    let key_x = wcei_to_uint(wcei_unit_interval(u.x) * 0x1p31f);
    let key_y = wcei_to_uint(wcei_unit_interval(u.y) * 0x1p31f);
    let row = wcei_search(m.region0, m.height, key_y);
    let r0 = wc_envmap[m.region0 + row];
    let r1 = wc_envmap[m.region0 + row + 1u];
    let cdf = m.region1 + row * (m.width + 1u);
    let column = wcei_search(cdf, m.width, key_x);
    let c0 = wc_envmap[cdf + column];
    let c1 = wc_envmap[cdf + column + 1u];
    let fy = wcei_unit_interval(wcei_u32_to_f32(key_y - r0) / wcei_u32_to_f32(r1 - r0));
    let fx = wcei_unit_interval(wcei_u32_to_f32(key_x - c0) / wcei_u32_to_f32(c1 - c0));
    let uv = vec2<f32>(wcei_edge_point(m.edges_x, column, fx, m.width),
                       wcei_edge_point(m.edges_y, row, fy, m.height));
    let pdf = wcei_density(vec2<u32>(c1 - c0, r1 - r0), m.width, m.height, 0x1p-62f);
    return WcEnvSample(uv, pdf, vec2<u32>(column, row));
}

// `MarginalConditional::pdf`: the density of the texel holding `uv`.
fn wc_envmap_marginal_conditional_pdf(base: u32, uv: vec2<f32>) -> f32 {
    let m = wcei_map(base);
    let column = wcei_edge_texel(m.edges_x, uv.x, m.width);
    let row = wcei_edge_texel(m.edges_y, uv.y, m.height);
    let r0 = wc_envmap[m.region0 + row];
    let r1 = wc_envmap[m.region0 + row + 1u];
    let cdf = m.region1 + row * (m.width + 1u);
    let c0 = wc_envmap[cdf + column];
    let c1 = wc_envmap[cdf + column + 1u];
    return wcei_density(vec2<u32>(c1 - c0, r1 - r0), m.width, m.height, 0x1p-62f);
}
