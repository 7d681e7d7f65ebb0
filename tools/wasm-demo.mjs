// Loads the wasm32-unknown-unknown build of examples/wasm-demo and checks the promises it
// carries: no imports (so no reachable panic path and no host dependency), the golden
// determinism fingerprint, and correct results from JavaScript.
// Usage: node tools/wasm-demo.mjs path/to/warpcore_demo.wasm
import { readFileSync } from 'node:fs';
import assert from 'node:assert/strict';

const wasmPath = process.argv[2];
const module = new WebAssembly.Module(readFileSync(wasmPath));
assert.deepEqual(WebAssembly.Module.imports(module), [],
  'the module must have no imports (an env.warpcore_panic_path_reached import means a reachable panic)');
const { exports: wc } = new WebAssembly.Instance(module, {});

const golden = readFileSync(new URL('../tests/golden/fingerprint.txt', import.meta.url), 'utf8').trim();
const fp = BigInt.asUintN(64, wc.fingerprint()).toString(16).padStart(16, '0');
assert.equal(fp, golden, 'determinism fingerprint differs from the golden value');
const fp16 = BigInt.asUintN(64, wc.fingerprint_x16()).toString(16).padStart(16, '0');
assert.equal(fp16, golden, 'the _x16 forms give other bits than the golden value');

// The concentric map against the textbook formula in f64.
function concentric(u0, u1) {
  const a = 2 * u0 - 1, b = 2 * u1 - 1;
  if (a === 0 && b === 0) return [0, 0];
  const [r, phi] = Math.abs(a) > Math.abs(b) ? [a, Math.PI / 4 * (b / a)] : [b, Math.PI / 2 - Math.PI / 4 * (a / b)];
  return [r * Math.cos(phi), r * Math.sin(phi)];
}
let worst = 0;
for (let i = 0; i < 64; i++) {
  for (let j = 0; j < 64; j++) {
    const u0 = Math.fround((i + 0.37) / 64), u1 = Math.fround((j + 0.61) / 64);
    const want = concentric(u0, u1);
    for (const k of [0, 1]) {
      worst = Math.max(worst, Math.abs(wc.disk_concentric(u0, u1, k) - want[k]));
    }
    const p = [wc.disk_polar4(u0, u1, 2, 0), wc.disk_polar4(u0, u1, 2, 1)];
    assert.ok(p[0] <= 0 && p[1] <= 0 && p[0] * p[0] + p[1] * p[1] <= 1, 'polar4 quadrant 2');
  }
}
assert.ok(worst <= 2.5e-7, `concentric from JS: max error ${worst}`);
assert.ok(Number.isFinite(wc.disk_concentric(NaN, Infinity, 0)));
console.log(`wasm demo: no imports, fingerprint ${fp} (x8 and x16), concentric max error ${worst.toExponential(2)}`);
