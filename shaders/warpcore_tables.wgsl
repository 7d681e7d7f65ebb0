// warpcore_tables.wgsl: warpcore's table-driven sequences for GPUs: pmj02bn points and the
// sampling core (`Sampler<Pmj02bn>`, `Sampler<Sobol>`, `Sampler<Blue<..>>`), one point per call.
//
// Self-contained (it does not need warpcore.wgsl; the two can be concatenated in any order:
// no name is shared). Public names mirror the C ABI (`include/warpcore.h`): `wc_pmj02bn_*`,
// `wc_sampler_*`, `WcSampler`, `WC_PATTERN_*`; everything named `wcti_*` is internal.
// Integer arithmetic only until the last step, the truncating `(w >> 8) * 2^-24` conversion,
// so every function returns the crate's bits on every conforming device (checked word for word
// on Mesa lavapipe by `cargo test -p warpcore-gpu`).
//
// THE ONE BINDING. The tables live in one read-only storage buffer of u32 words, declared
// below at @group(0) @binding(0). To move it, edit those two numbers (or let your engine's
// preprocessor substitute them); nothing else in the file refers to them. The buffer holds,
// in this order (word offsets are the WC_TABLES_* constants below):
//   1. the pmj02bn tables: WC_PMJ02BN_SETS sets of WC_PMJ02BN_POINTS points, two words
//      (x, y, 0.32 fixed point) per point: exactly the bytes of src/tables/pmj02bn_<points>_<set>.bin
//      for sets 0, 1, ... one after the other (little-endian words), i.e. `warpcore::pmj02bn::raw`
//      or the C ABI's `wc_pmj02bn_raw` over every set and index;
//   2. the Sobol' generator matrices by bytes of the bit-reversed index: 1024 rows of 4 words;
//   3. the blue-noise key tiles, 64 x 64 words each, Sobol' then pmj02bn: exactly the bytes of
//      src/tables/blue_sobol_64.bin and src/tables/blue_pmj02bn_64.bin;
//   4. the blue-noise slot tiles (WC_BLUE_SLOTS tiles of 64 x 64 16-bit index offsets, two per
//      word, low half first), Sobol' then pmj02bn: exactly the bytes of
//      src/tables/blue_slots_sobol_64.bin and src/tables/blue_slots_pmj02bn_64.bin.
// `shaders/warpcore_tables.bin` is the whole buffer for the default build, and
// `warpcore_gpu::tables::table_bytes()` builds it from the crate (docs/gpu.md shows how to
// upload it from Rust, C and JS). wc_pmj02bn_sample reads part 1 only: a renderer that uses
// nothing else may upload that part alone.
//
// THE TABLE SIZE. WC_PMJ02BN_LOG2_POINTS and WC_PMJ02BN_SETS must match the crate build whose
// tables are uploaded (the defaults: 4096 points, 4 sets; `wc_pmj02bn_points()` and
// `wc_pmj02bn_sets()` tell a C program). Other builds: edit the two constants.

@group(0) @binding(0) var<storage, read> wc_tables: array<u32>;

const WC_PMJ02BN_LOG2_POINTS: u32 = 12u;
const WC_PMJ02BN_SETS: u32 = 4u;
const WC_PMJ02BN_POINTS: u32 = 1u << WC_PMJ02BN_LOG2_POINTS;
// Word offsets of the three parts, and the buffer's length in words.
const WC_TABLES_PMJ02BN: u32 = 0u;
const WC_TABLES_SOBOL: u32 = 2u * WC_PMJ02BN_SETS * WC_PMJ02BN_POINTS;
const WC_TABLES_BLUE_SOBOL: u32 = WC_TABLES_SOBOL + 4096u;
const WC_TABLES_BLUE_PMJ02BN: u32 = WC_TABLES_BLUE_SOBOL + 4096u;
const WC_TABLES_SLOTS_SOBOL: u32 = WC_TABLES_BLUE_PMJ02BN + 4096u;
const WC_TABLES_SLOTS_PMJ02BN: u32 = WC_TABLES_SLOTS_SOBOL + WC_BLUE_SLOTS * 2048u;
const WC_TABLES_WORDS: u32 = WC_TABLES_SLOTS_PMJ02BN + WC_BLUE_SLOTS * 2048u;
// Side of the blue-noise key tiles, and the spatiotemporal slots (the root's domains
// 0..WC_BLUE_SLOTS of a blue-noise sampler; their keys are `wcti_keyed`'s).
const WC_BLUE_TILE: u32 = 64u;
const WC_BLUE_SLOTS: u32 = 6u;

// The sampler patterns (the C ABI's values).
const WC_PATTERN_PMJ02BN: u32 = 0u;
const WC_PATTERN_SOBOL: u32 = 1u;
const WC_PATTERN_BLUE_PMJ02BN: u32 = 2u;
const WC_PATTERN_BLUE_SOBOL: u32 = 3u;

// ---------------------------------------------------------------------------------------
// Hashes (src/hash.rs)

// Wellons' lowbias32 (`hash::mix`); mix(0) = 0.
fn wcti_mix(x0: u32) -> u32 {
    let x1 = (x0 ^ (x0 >> 16u)) * 0x7feb352du;
    let x2 = (x1 ^ (x1 >> 15u)) * 0x846ca68bu;
    return x2 ^ (x2 >> 16u);
}

// One round of the mixer (`hash::mix1`): the sampler's domain tree.
fn wcti_mix1(x0: u32) -> u32 {
    let x1 = (x0 ^ (x0 >> 16u)) * 0x7feb352du;
    return x1 ^ (x1 >> 15u);
}

// The Laine-Karras hash with Vegdahl's constants (`hash::lk_hash`).
fn wcti_lk_hash(x0: u32, seed: u32) -> u32 {
    let x1 = x0 ^ (x0 * 0x3d20adeau);
    let x2 = x1 + seed;
    let x3 = x2 * ((seed >> 16u) | 1u);
    let x4 = x3 ^ (x3 * 0x05526c56u);
    return x4 ^ (x4 * 0x53a22864u);
}

// Nested uniform (Owen) scramble of a 0.32 fixed-point word (`hash::owen_scramble`); also
// Burley's nested index shuffle (`hash::nested_shuffle`), the same operations.
fn wcti_owen(v: u32, seed: u32) -> u32 {
    return reverseBits(wcti_lk_hash(reverseBits(v), seed));
}

fn wcti_rotr(x: u32, n: u32) -> u32 {
    return (x >> n) | (x << (32u - n));
}

// 0.32 fixed point to [0, 1 - 2^-24] by truncation (`hash::to_unit`): exact.
fn wcti_to_unit(w: u32) -> f32 {
    return f32(w >> 8u) * 0x1p-24f;
}

fn wcti_to_unit4(w: vec4<u32>) -> vec4<f32> {
    return vec4<f32>(wcti_to_unit(w.x), wcti_to_unit(w.y), wcti_to_unit(w.z), wcti_to_unit(w.w));
}

// The two words of flat table point `row` (set in the bits above log2(points)).
fn wcti_pmj02bn_row(row: u32) -> vec2<u32> {
    let r = row & (WC_PMJ02BN_SETS * WC_PMJ02BN_POINTS - 1u);
    let at = WC_TABLES_PMJ02BN + 2u * r;
    return vec2<u32>(wc_tables[at], wc_tables[at + 1u]);
}

// ---------------------------------------------------------------------------------------
// pmj02bn (src/pmj02bn.rs)

// Point `index` of the pmj02bn sequence for `seed` (`pmj02bn::sample`): a table point (set
// chosen by the seed and the block of WC_PMJ02BN_POINTS indices), Owen-scrambled, truncated
// to [0, 1 - 2^-24]. Every u32 index and seed is valid.
fn wc_pmj02bn_sample(index: u32, seed: u32) -> vec2<f32> {
    let block = index >> WC_PMJ02BN_LOG2_POINTS;
    let key = wcti_mix(seed) ^ wcti_mix(block * 0x9e3779b9u);
    let set_row = (wcti_mix(key ^ 0x1b56c4e9u) & (WC_PMJ02BN_SETS - 1u)) << WC_PMJ02BN_LOG2_POINTS;
    let kx = wcti_mix(key ^ 0x68e31da4u);
    let ky = wcti_mix(key ^ 0xb5297a4du);
    let p = wcti_pmj02bn_row(set_row | (index & (WC_PMJ02BN_POINTS - 1u)));
    return vec2<f32>(wcti_to_unit(wcti_owen(p.x, kx)), wcti_to_unit(wcti_owen(p.y, ky)));
}

// The prefix-preserving index permutation of `pmj02bn::shuffle` (no table): every 2D
// dimension after the first reads `wc_pmj02bn_sample(wc_pmj02bn_shuffle(i, dim_seed), seed)`.
fn wc_pmj02bn_shuffle(index: u32, seed: u32) -> u32 {
    let s = wcti_mix(seed);
    return reverseBits(wcti_lk_hash(reverseBits(index), s) ^ wcti_lk_hash(0u, s));
}

// ---------------------------------------------------------------------------------------
// The sampling core (src/sampler/)

// One sample's sampler, as the C ABI's `WcSampler`: a WC_PATTERN_* constant, the pixel
// (16 bits of x and of y), the domain path's hash and the sample index. `index` may be set
// directly (Rust's `with_index`). A `pattern` that is not a WC_PATTERN_* value is carried
// through domain and split unchanged, and its draws return 0.
struct WcSampler {
    pattern: u32,
    pixel: u32,
    domain: u32,
    index: u32,
}

fn wcti_known(pattern: u32) -> bool {
    return pattern <= WC_PATTERN_BLUE_SOBOL;
}

fn wcti_is_blue(pattern: u32) -> bool {
    return (pattern & 2u) != 0u;
}

// The root sampler of sample `index` of `pixel` in `frame`, for `seed` (`Sampler::new`).
fn wc_sampler_new(pattern: u32, pixel: vec2<u32>, frame: u32, index: u32, seed: u32) -> WcSampler {
    if (!wcti_known(pattern)) {
        return WcSampler(pattern, 0u, 0u, 0u);
    }
    let root = wcti_mix(wcti_mix(seed ^ 0x3c6ef372u) ^ (frame * 0x9e3779b9u));
    let packed = (pixel.x & 0xffffu) | (pixel.y << 16u);
    let pixel_domain = wcti_mix1(root ^ pixel.x ^ ((pixel.y << 16u) | (pixel.y >> 16u)));
    // A blue-noise root is tagged 0 in its low two bits (`blue_tagged`; 2 from new_frame).
    let domain = select(pixel_domain, root & ~3u, wcti_is_blue(pattern));
    return WcSampler(pattern, packed, domain, index);
}

// The root sampler of sample `index` (in `0..spp`) of `pixel` in `frame` of a render that
// accumulates frames: the frames continue one sequence per pixel (`Sampler::new_frame`). It is
// `wc_sampler_new` of the 64-bit sample number `frame * max(spp, 1) + index`, high word as
// `frame`, low word as `index` (the product from 16-bit halves: WGSL has no u64); under the
// blue-noise patterns its domains 0..WC_BLUE_SLOTS are spatiotemporal slots.
fn wc_sampler_new_frame(pattern: u32, pixel: vec2<u32>, frame: u32, spp: u32, index: u32, seed: u32) -> WcSampler {
    let m = max(spp, 1u);
    let a = vec2<u32>(frame & 0xffffu, frame >> 16u);
    let c = vec2<u32>(m & 0xffffu, m >> 16u);
    let p00 = a.x * c.x;
    let p01 = a.x * c.y;
    let p10 = a.y * c.x;
    let mid = (p00 >> 16u) + (p01 & 0xffffu) + (p10 & 0xffffu);
    let lo = (p00 & 0xffffu) | (mid << 16u);
    let hi = a.y * c.y + (p01 >> 16u) + (p10 >> 16u) + (mid >> 16u);
    let n = lo + index;
    let s = wc_sampler_new(pattern, pixel, hi + select(0u, 1u, n < lo), n, seed);
    // Under blue noise the root is tagged 2: its domains 0..WC_BLUE_SLOTS are the slots.
    let root = select(s.domain, (s.domain & ~3u) | 2u, wcti_known(s.pattern) && wcti_is_blue(s.pattern));
    return WcSampler(s.pattern, s.pixel, root, s.index);
}

// An independent child pattern for `key`, same index (`Sampler::domain`).
fn wc_sampler_domain(s: WcSampler, key: u32) -> WcSampler {
    if (!wcti_known(s.pattern)) {
        return s;
    }
    let h = wcti_mix1(s.domain + key * 0xc2b2ae35u);
    // Blue noise: the root's children 0..WC_BLUE_SLOTS are its slots (tag 1, the slot in bits
    // 2..4), every other domain is tagged 0 (`blue::tag_child`).
    let slot = (h & ~0x1fu) | 1u | (key << 2u);
    let is_slot = (s.domain & 3u) == 2u && key < WC_BLUE_SLOTS;
    let blue = select(h & ~3u, slot, is_slot);
    return WcSampler(s.pattern, s.pixel, select(h, blue, wcti_is_blue(s.pattern)), s.index);
}

// Sub-sample `sub` of `size` per sample: child index `index * size + sub` (wrapping) in a
// child domain for `key` (`Sampler::split`); size 0 acts as 1.
fn wc_sampler_split(s: WcSampler, key: u32, size: u32, sub: u32) -> WcSampler {
    if (!wcti_known(s.pattern)) {
        return s;
    }
    let h = wcti_mix((s.domain ^ 0x27d4eb2fu) + key * 0xc2b2ae35u);
    let domain = select(h, h & ~3u, wcti_is_blue(s.pattern));
    return WcSampler(s.pattern, s.pixel, domain, s.index * max(size, 1u) + sub);
}

// The blue-noise tile position of the pixel in this domain (src/sampler/blue.rs).
fn wcti_blue_position(pixel: u32, domain: u32) -> u32 {
    let m = WC_BLUE_TILE - 1u;
    let x0 = pixel & m;
    let y0 = (pixel >> 16u) & m;
    let t = ((domain >> 29u) & 1u) == 1u;
    let x1 = select(x0, y0, t);
    let y1 = select(y0, x0, t);
    let fx = 0u - ((domain >> 30u) & 1u);
    let fy = 0u - (domain >> 31u);
    let x = (x1 ^ (fx & m)) + (domain >> 6u);
    let y = (y1 ^ (fy & m)) + (domain >> 12u);
    return (y & m) * WC_BLUE_TILE + (x & m);
}

// The key and the index of the base pattern's draw: the domain hash and the index; under blue
// noise the pixel's tile key and the index, or in a slot the slot's key and the index XOR the
// pixel's offset (`blue::keyed`).
fn wcti_keyed(s: WcSampler) -> vec2<u32> {
    if (!wcti_is_blue(s.pattern)) {
        return vec2<u32>(s.domain, s.index);
    }
    let sobol = (s.pattern & 1u) == 1u;
    let at = wcti_blue_position(s.pixel, s.domain);
    let slot = (s.domain >> 2u) & 7u;
    if ((s.domain & 3u) == 1u && slot < WC_BLUE_SLOTS) {
        let base = select(WC_TABLES_SLOTS_PMJ02BN, WC_TABLES_SLOTS_SOBOL, sobol);
        let i = slot * 4096u + at;
        let offset = (wc_tables[base + (i >> 1u)] >> (16u * (i & 1u))) & 0xffffu;
        var keys = array<u32, 6>(0x8a2f0c4bu, 0x3d6e91a7u, 0xc51b7e23u, 0x6f94d2c9u, 0x1be74a35u, 0xe403b86du);
        return vec2<u32>(keys[slot], s.index ^ offset);
    }
    let tile = select(WC_TABLES_BLUE_PMJ02BN, WC_TABLES_BLUE_SOBOL, sobol);
    return vec2<u32>(wc_tables[tile + at], s.index);
}

// Owen-scrambled Sobol' dimensions 0..3 of point `index` keyed by `seed` (src/sampler/sobol.rs).
fn wcti_sobol(index: u32, seed: u32) -> vec4<u32> {
    let r = wcti_lk_hash(reverseBits(index), seed);
    var dims = vec4<u32>(0u);
    for (var b = 0u; b < 4u; b++) {
        let row = WC_TABLES_SOBOL + 4u * (256u * b + ((r >> (8u * b)) & 0xffu));
        dims = dims ^ vec4<u32>(wc_tables[row], wc_tables[row + 1u], wc_tables[row + 2u], wc_tables[row + 3u]);
    }
    return vec4<u32>(
        reverseBits(wcti_lk_hash(dims.x, wcti_rotr(seed, 6u))),
        reverseBits(wcti_lk_hash(dims.y, wcti_rotr(seed, 13u))),
        reverseBits(wcti_lk_hash(dims.z, wcti_rotr(seed, 19u))),
        reverseBits(wcti_lk_hash(dims.w, wcti_rotr(seed, 26u))));
}

// The block key of a pmj02bn draw (`pmj02bn_block_keys`).
fn wcti_pmj02bn_block(index: u32, seed: u32) -> u32 {
    return wcti_mix(seed ^ ((index >> WC_PMJ02BN_LOG2_POINTS) * 0x5851f42du));
}

// Pair `p` (0 or 1) of a pmj02bn draw, unscrambled: its own index shuffle and table set.
fn wcti_pmj02bn_pair(index: u32, seed: u32, k: u32, p: u32) -> vec2<u32> {
    let shuffle = select(seed, wcti_rotr(seed, 16u), p == 1u);
    let mult = select(0x4c957f2du, 0xd1b54a35u, p == 1u);
    let set_row = (((k * mult) >> 30u) & (WC_PMJ02BN_SETS - 1u)) << WC_PMJ02BN_LOG2_POINTS;
    let i = wcti_owen(index, shuffle) & (WC_PMJ02BN_POINTS - 1u);
    return wcti_pmj02bn_row(set_row | i);
}

// The stratified point, dimensions 0..3 (0..1 when `four` is false, the rest then 0), as
// 0.32 fixed point; zeros for an unknown pattern.
fn wcti_bits(s: WcSampler, four: bool) -> vec4<u32> {
    if (!wcti_known(s.pattern)) {
        return vec4<u32>(0u);
    }
    let keyed = wcti_keyed(s);
    let seed = keyed.x;
    let index = keyed.y;
    if ((s.pattern & 1u) == 1u) {
        return wcti_sobol(index, seed);
    }
    let k = wcti_pmj02bn_block(index, seed);
    let a = wcti_pmj02bn_pair(index, seed, k, 0u);
    let x0 = wcti_owen(a.x, k);
    let y0 = wcti_owen(a.y, wcti_rotr(k, 8u));
    if (!four) {
        return vec4<u32>(x0, y0, 0u, 0u);
    }
    let b = wcti_pmj02bn_pair(index, seed, k, 1u);
    return vec4<u32>(x0, y0, wcti_owen(b.x, wcti_rotr(k, 16u)), wcti_owen(b.y, wcti_rotr(k, 24u)));
}

// `draw::<2>()`: two stratified dimensions in [0, 1 - 2^-24].
fn wc_sampler_draw2(s: WcSampler) -> vec2<f32> {
    return wcti_to_unit4(wcti_bits(s, false)).xy;
}

// `draw::<4>()` (its first one or three components are `draw::<1>()` and `draw::<3>()`).
fn wc_sampler_draw4(s: WcSampler) -> vec4<f32> {
    return wcti_to_unit4(wcti_bits(s, true));
}

// `draw_u32::<4>()`: the point of wc_sampler_draw4 as 0.32 fixed point.
fn wc_sampler_draw4_u32(s: WcSampler) -> vec4<u32> {
    return wcti_bits(s, true);
}

// `rnd::<4>()`: cheap unstratified values in [0, 1 - 2^-24] (roulette); its prefixes are
// `rnd::<1..3>()`. Needs no table. Zeros for an unknown pattern.
fn wc_sampler_rnd4(s: WcSampler) -> vec4<f32> {
    if (!wcti_known(s.pattern)) {
        return vec4<f32>(0.0);
    }
    let blue_d = s.domain ^ wcti_mix(s.pixel ^ 0x85ebca6bu);
    let d = select(s.domain, blue_d, wcti_is_blue(s.pattern));
    let h = wcti_mix(d ^ wcti_mix(s.index ^ 0x165667b1u));
    // h + (k + 1) * 0x9e3779b9 (mod 2^32) for k = 0..3.
    return wcti_to_unit4(vec4<u32>(
        wcti_mix(h + 0x9e3779b9u),
        wcti_mix(h + 0x3c6ef372u),
        wcti_mix(h + 0xdaa66d2bu),
        wcti_mix(h + 0x78dde6e4u)));
}
