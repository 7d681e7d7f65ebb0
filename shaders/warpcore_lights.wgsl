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
