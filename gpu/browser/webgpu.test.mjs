// shaders/warpcore.wgsl in a browser: headless Chromium's WebGPU on its software adapter
// (SwiftShader) evaluates the 28 warps of the library on 16384 points each, away from
// subnormals (SwiftShader flushes them), and every output word must equal the JavaScript
// module's (the crate compiled to wasm). The second test does the same for the 8 solid-angle
// light functions (ordinary lights and some of the fingerprint's extreme ones). The third for
// shaders/warpcore_tables.wgsl with shaders/warpcore_tables.bin bound. `node --test gpu/browser/`; Chromium as for
// js/browser-test (apt-get install chromium, or $CHROMIUM_BIN for the wrapper).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fileURLToPath } from 'node:url';
import { serve } from '../../js/tools/serve.mjs';
import { findChromium, launch, open } from '../../js/tools/chromium.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const wrapper = fileURLToPath(new URL('./chromium-webgpu.sh', import.meta.url));
// CI installs Chromium: there, a missing browser is a failure, not a skip.
const skip = !findChromium() && !process.env.CI && 'Chromium is not installed (apt-get install chromium)';

/**
 * A page of a local server (WebGPU needs a secure context; 127.0.0.1 is one) in Chromium with
 * WebGPU: `call(expr)` evaluates `m.${expr}` with `m` webgpu-check.mjs and prints the rows of
 * its result (`[name, points, mismatches, first, ...more]`); `errors()` the page's errors.
 */
async function checkPage(t) {
  const server = await serve(root);
  t.after(() => server.close());
  const browser = await launch(wrapper);
  t.after(() => browser.close());
  const url = `${server.url}gpu/browser/webgpu-check.mjs`;
  const page = await open(browser, url);
  const call = async (expr, print = true) => {
    const r = await page.evaluate(`import('${url}').then((m) => m.${expr})`);
    if (print) {
      console.log(`adapter: ${r.adapter}`);
      for (const [name, points, mismatches, first, ...more] of r.rows) {
        const extra = more.length ? ` texels ${more[0]} uv ${more[1]} pdf ${more[2]}` : '';
        console.log(`${name.padEnd(42)} ${String(points).padStart(7)} ${String(mismatches).padStart(8)}${extra}${first ? ' ' + JSON.stringify(first) : ''}`);
      }
    }
    return r;
  };
  return { call, errors: () => page.errors.filter((e) => !e.includes('favicon.ico')) };
}

/** The names of the rows with mismatches. */
const failing = (r) => r.rows.filter((row) => row[2] > 0).map((row) => row[0]);

test('warpcore.wgsl on Chromium WebGPU (SwiftShader) equals the crate', { skip, timeout: 240_000 }, async (t) => {
  const page = await checkPage(t);
  const r = await page.call('check()');
  assert.match(r.adapter, /swiftshader|google/i, 'the software adapter');
  assert.equal(r.rows.length, 28);
  assert.deepEqual(failing(r), [], 'functions with mismatches');
  // The comparison is sharp: the sine kernel's leading constant one ulp off is seen.
  const edit = ['const WCI_S0: f32 = 0x1.921fb4p-1f;', 'const WCI_S0: f32 = 0x1.921fb6p-1f;'];
  const w = await page.call(`check(4096, ${JSON.stringify(edit)})`, false);
  const concentric = w.rows.find((row) => row[0] === 'wc_disk_concentric');
  console.log(`S0 + 1 ulp: wc_disk_concentric ${concentric[2]} of ${concentric[1]} points differ`);
  assert.ok(concentric[2] * 10 > concentric[1], 'a one-ulp change is detected');
  assert.deepEqual(page.errors(), []);
});

test('the solid-angle lights of warpcore.wgsl on Chromium WebGPU equal the crate', { skip, timeout: 240_000 }, async (t) => {
  const page = await checkPage(t);
  const r = await page.call('checkSpherical()');
  assert.equal(r.rows.length, 8);
  assert.deepEqual(failing(r), [], 'functions with mismatches');
  // The comparison is sharp: 1 / (4 pi) one ulp higher moves the densities.
  const edit = ['const WCI_INV_4PI: f32 = 0x1.45f306p-4f;', 'const WCI_INV_4PI: f32 = 0x1.45f308p-4f;'];
  const w = await page.call(`checkSpherical(4096, ${JSON.stringify(edit)})`, false);
  const tri = w.rows.find((row) => row[0] === 'wc_spherical_triangle');
  console.log(`1 / (4 pi) + 1 ulp: wc_spherical_triangle ${tri[2]} of ${tri[1]} points differ`);
  assert.ok(tri[2] * 2 > tri[1], 'a one-ulp change is detected');
  assert.deepEqual(page.errors(), []);
});

test('warpcore_tables.wgsl (pmj02bn, the sampler) on Chromium WebGPU equals the crate', { skip, timeout: 240_000 }, async (t) => {
  const page = await checkPage(t);
  const r = await page.call('checkTables()');
  assert.equal(r.rows.length, 7);
  assert.deepEqual(failing(r), [], 'checks with mismatches');
  // The comparison sees the tables: with the top bit of every pmj02bn word flipped, every
  // pmj02bn point differs and the Sobol' paths (which do not read that part) do not.
  const c = await page.call('checkTables(1024, true)', false);
  const moved = Object.fromEntries(c.rows.map((row) => [row[0], row[2] / row[1]]));
  console.log(`corrupted pmj02bn tables: ${JSON.stringify(moved)}`);
  assert.ok(moved['wc_pmj02bn_sample from 0'] === 1 && moved['wc_sampler_* pmj02bn'] === 1, 'pmj02bn sees the tables');
  assert.ok(moved['wc_sampler_* sobol'] === 0 && moved['wc_sampler_* blueSobol'] === 0, 'Sobol reads its own part');
  assert.deepEqual(page.errors(), []);
});

test('warpcore_envmap.wgsl (maps from the JS module) on Chromium WebGPU equals the crate', { skip, timeout: 240_000 }, async (t) => {
  const page = await checkPage(t);
  const r = await page.call('checkEnvmap()');
  assert.equal(r.rows.length, 4);
  assert.deepEqual(failing(r), [], 'functions with mismatches');
  assert.deepEqual(page.errors(), []);
});
