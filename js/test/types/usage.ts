// Compiled by js/test/package.test.mjs with `tsc --noEmit --strict` against the installed
// package's types: a user's code must type-check, and misuse must not (@ts-expect-error).
import { load, MAX_COUNT, type AliasTable, type EnvMap, type LightTree, type SamplerPath, type SamplerPattern, type Warpcore } from 'warpcore';

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
const d = env.sampleDirection('equal-area', u);
const solidAnglePdf: Float32Array = env.pdfDirection('equirect', d.dir);
const fromBytes = wc.envmapFromStorage(new Uint8Array(env.storage().buffer));
fromBytes.free();
const shuffled: number = wc.pmj02bnShuffle(5, 7) + solidAnglePdf.length + d.texel.length;
env.free();
again[Symbol.dispose]();
const n: number = shuffled + MAX_COUNT + wc.pmj02bnPoints + back.length + quadrant.length + texel.length + dirs.length;
await load(new URL('file:///x.wasm'));
await load(new Uint8Array(8));

// @ts-expect-error: arrays, not numbers
wc.diskConcentric([0.5, 0.5]);
// @ts-expect-error: a count is required
wc.pmj02bnSample(0, 1);
// @ts-expect-error: channels are 1 to 4
wc.envmapEquirectToEqualArea(new Float32Array(3), 1, 1, 5, 1, 1);
// @ts-expect-error: layouts are 'equirect' and 'equal-area'
env.sampleDirection('latlong', u);
// @ts-expect-error: read-only
env.width = 3;
// @ts-expect-error: the constructor is not public
new wc.EnvMap();

const path: SamplerPath = wc.samplerPath().domain(2).split(0, 4, 1);
const point: Float32Array = wc.samplerDraw('blueSobol', Uint32Array.of(3, 4), 0, 7, 0, path, 2);
const words: Uint32Array = wc.samplerDrawU32('sobol', Uint32Array.of(3, 4), 0, 7, 0, Uint32Array.of(1, 2), 4);
const slice: Float32Array = wc.samplerDrawSlice('pmj02bn', Uint32Array.of(3, 4), 0, 0, 16, 0, path, 3, new Float32Array(48));
const pattern: SamplerPattern = 'bluePmj02bn';
wc.samplerRnd(pattern, Uint32Array.of(0, 0), 0, 0, 0, new Uint32Array(0), 1);
// @ts-expect-error: a draw has 1 to 4 dimensions
wc.samplerDraw('sobol', Uint32Array.of(3, 4), 0, 7, 0, path, 5);
// @ts-expect-error: not a pattern
wc.samplerDraw('halton', Uint32Array.of(3, 4), 0, 7, 0, path, 2);
// @ts-expect-error: a domain path is a Uint32Array or a SamplerPath
wc.samplerDraw('sobol', Uint32Array.of(3, 4), 0, 7, 0, [1, 2], 2);

const table: AliasTable = wc.lightsAlias(Float32Array.of(1, 0, 3));
const choice: { index: number; prob: number } = table.sample(0.5);
const choices: Float32Array = table.sample(u).prob;
const tableProb: number = table.pmf(choice.index);
const tree: LightTree = wc.lightsTreeFromStorage(wc.lightsTree(new Float32Array(13)).storage(), { verify: false });
const treeProb: Float32Array = tree.pmf(new Float32Array(3), new Float32Array(3), Uint32Array.of(0));
const lightsWords: Uint32Array = tree.storage();
tree.free();
// @ts-expect-error: a tree takes a point and a normal
tree.sample(0.5);
// @ts-expect-error: read-only
table.count = 3;

export { kind, ok, n, point, words, slice, choices, tableProb, treeProb, lightsWords };
