// Compiled by js/test/package.test.mjs with `tsc --noEmit --strict` against the installed
// package's types: a user's code must type-check, and misuse must not (@ts-expect-error).
import { load, MAX_COUNT, type EnvMap, type Warpcore } from 'warpcore';

const wc: Warpcore = await load();
const u: Float32Array = wc.pmj02bnSample(0, 42, 16);
const disk: Float32Array = wc.diskPolar4(u, 64);
const dirs: Float32Array = wc.sphereEqualArea(u, new Float32Array(48));
const { u: back, quadrant }: { u: Float32Array; quadrant: Uint32Array } = wc.diskConcentric4Inverse(disk);
const env: EnvMap = wc.envmapHierarchical(new Float32Array(8).fill(1), 4, 2);
const s = env.sample(u);
const texel: Uint32Array = s.texel;
const kind: 'hierarchical' | 'marginal-conditional' = env.kind;
const ok: boolean = env instanceof wc.EnvMap;
const again = wc.envmapFromStorage(env.storage(), { verify: false });
env.free();
again[Symbol.dispose]();
const n: number = MAX_COUNT + wc.pmj02bnPoints + back.length + quadrant.length + texel.length + dirs.length;
await load(new URL('file:///x.wasm'));
await load(new Uint8Array(8));

// @ts-expect-error: arrays, not numbers
wc.diskConcentric([0.5, 0.5]);
// @ts-expect-error: a count is required
wc.pmj02bnSample(0, 1);
// @ts-expect-error: channels are 1 to 4
wc.envmapLatlongToEqualArea(new Float32Array(3), 1, 1, 5, 1, 1);
// @ts-expect-error: read-only
env.width = 3;
// @ts-expect-error: the constructor is not public
new wc.EnvMap();

export { kind, ok, n };
