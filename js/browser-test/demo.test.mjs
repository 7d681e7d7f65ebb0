// The demo page in a real browser: headless Chromium (Debian's `chromium`) loads
// js/demo/index.html from a local static server, and for every warp of the page (each with a
// sampler, count and strata grid changed through the page's controls, which redraw live) the
// test checks that the canvas holds the expected number of points (a black dot at each point's
// pixel), that the strata carry the report's colours (those of docs/report/strata.svg, drawn
// by the Rust report), and that the page logged no error. Saves a screenshot to
// target/demo.png (docs/demo.png is a copy for the README). That browser runs with
// --disable-gpu, so the page must offer its "computed on the GPU" mode disabled, with the
// reason. The second test launches Chromium with WebGPU on SwiftShader (the wrapper of
// gpu/browser/) and turns the mode on for every warp: every point must have the wasm bits and
// the page must say "N of N points identical" (a one-ulp edit of the WGSL library must lower
// the count); screenshot target/demo-gpu.png.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { serve } from '../tools/serve.mjs';
import { findChromium, launch, open } from '../tools/chromium.mjs';

// Chromium with WebGPU on its software adapter (SwiftShader): the launcher of the WGSL
// library's browser test, which swaps --disable-gpu for the WebGPU flags.
const webgpuChromium = fileURLToPath(new URL('../../gpu/browser/chromium-webgpu.sh', import.meta.url));

const root = fileURLToPath(new URL('../../', import.meta.url));
const chromium = findChromium();
// CI installs Chromium: there, a missing browser is a failure, not a skip.
const skip = !chromium && !process.env.CI && 'Chromium is not installed (apt-get install chromium)';

// The report's 16 stratum colours, as the Rust report drew them.
const reportColours = [...new Set(readFileSync(`${root}docs/report/strata.svg`, 'utf8').match(/fill="#[0-9a-f]{6}"/g))].map((f) => f.slice(7, 13));

// Sets the controls as a user would (input events), waits for the redraw, and measures it.
const driver = (page) => (s) =>
  page.evaluate(`(async () => {
    const s = ${JSON.stringify(s)};
    const frame = window.demo.frame;
    for (const [id, value] of Object.entries(s)) {
      const el = document.getElementById(id);
      if (el.type === 'checkbox') el.checked = Boolean(value);
      else el.value = String(value);
      el.dispatchEvent(new Event('input', { bubbles: true }));
    }
    const t0 = Date.now();
    while (window.demo.frame === frame && !window.demo.error) {
      if (Date.now() - t0 > 60000) throw new Error('no redraw');
      await new Promise((r) => setTimeout(r, 10));
    }
    const canvas = document.getElementById('canvas');
    const img = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    const { positions, drawn, expected, error } = window.demo;
    let black = 0;
    const misses = [];
    for (let i = 0; i < positions.length; i += 2) {
      const o = 4 * (Math.floor(positions[i + 1]) * canvas.width + Math.floor(positions[i]));
      // Black, up to anti-aliasing (the pixel is inside the dot, whose radius is >= 1.5).
      if (Math.max(img[o], img[o + 1], img[o + 2]) <= 32 && img[o + 3] === 255) black++;
      else if (misses.length < 5) misses.push([positions[i], positions[i + 1], ...img.subarray(o, o + 4)]);
    }
    const colours = {};
    for (let o = 0; o < img.length; o += 4) {
      const hex = ((img[o] << 16) | (img[o + 1] << 8) | img[o + 2]).toString(16).padStart(6, '0');
      colours[hex] = (colours[hex] ?? 0) + 1;
    }
    const readout = document.getElementById('gpu-result');
    return { misses, drawn, expected, points: positions.length / 2, black, colours, error,
             caption: document.getElementById('caption').textContent, query: location.search,
             gpu: { ...window.demo.gpu }, readout: readout.textContent, readoutClass: readout.className };
  })()`);

/**
 * The demo page (concentric disk, 256 pmj02bn points, 4 x 4 strata, GPU mode asked for) from a
 * local server in the Chromium of `launcher`, once it has drawn its first frame (or failed)
 * within `wait` ms.
 */
async function openDemo(t, launcher, wait) {
  const server = await serve(root);
  t.after(() => server.close());
  const browser = await launch(launcher);
  t.after(() => browser.close());
  const page = await open(browser, `${server.url}js/demo/index.html?warp=disk:concentric&count=256&sampler=pmj02bn&grid=4x4&seed=7&gpu=1`);
  await page.evaluate('window.demo.ready');
  await page.evaluate(`new Promise((ok, fail) => { const t0 = Date.now(); (function poll() {
    if (window.demo.frame >= 1 || window.demo.error) ok(); else if (Date.now() - t0 > ${wait}) fail(new Error('no frame')); else setTimeout(poll, 20); })(); })`);
  return page;
}

test('the demo page draws every warp with the expected points and strata', { skip, timeout: 240_000 }, async (t) => {
  assert.equal(reportColours.length, 16, 'docs/report/strata.svg has the 16 palette colours');
  const page = await openDemo(t, chromium, 30000);

  const drive = driver(page);

  // Chromium launched with --disable-gpu has no WebGPU adapter: the GPU mode is offered
  // disabled, with the reason, and the CPU path draws.
  const gpuControl = await page.evaluate(`({ disabled: document.getElementById('gpu').disabled,
    checked: document.getElementById('gpu').checked, note: document.getElementById('gpu-note').textContent,
    gpu: { ...window.demo.gpu } })`);
  assert.equal(gpuControl.gpu.available, false, `no adapter under --disable-gpu: ${JSON.stringify(gpuControl)}`);
  assert.equal(gpuControl.disabled, true, 'the GPU toggle is disabled');
  assert.equal(gpuControl.checked, false, '?gpu=1 without an adapter leaves the mode off');
  assert.match(gpuControl.note, /unavailable: \S/, 'with a reason');
  assert.equal(gpuControl.gpu.on, false);
  t.diagnostic(`GPU toggle: disabled, ${gpuControl.note}`);

  const warps = await page.evaluate(`[...document.querySelectorAll('#warp option')].map((o) => o.value)`);
  assert.equal(warps.length, 17, 'four disk, four triangle, five sphere warps and four env-map ones');
  const samplers = ['random', 'stratified', 'pmj02bn'];
  const counts = [4, 37, 256, 1000, 4096];
  const grids = ['16x1', '8x2', '4x4', '2x8', '1x16'];
  let checked = 0;
  for (const [i, warp] of warps.entries()) {
    const s = { warp, sampler: samplers[i % 3], count: counts[i % counts.length], grid: grids[i % grids.length], seed: 7 + i };
    const r = await drive(s);
    const what = `${JSON.stringify(s)} -> ${r.caption}`;
    assert.equal(r.error, null, what);
    assert.equal(r.expected, s.count, what);
    assert.equal(r.points, s.count, what);
    assert.equal(r.drawn, s.count, `every point inside the picture: ${what}`);
    assert.equal(r.black, s.count, `a black dot at every point's pixel (misses: ${JSON.stringify(r.misses)}): ${what}`);
    if (!warp.startsWith('envmap')) {
      // Disk, triangle and sphere strata are painted in the palette's exact colours; the
      // env-map ones are blended over the map.
      for (const c of reportColours) assert.ok((r.colours[c] ?? 0) > 50, `stratum colour #${c} drawn: ${what}`);
    } else {
      assert.ok(Object.keys(r.colours).length > 200, `the map and its strata: ${what}`);
    }
    assert.match(r.query, new RegExp(`warp=${encodeURIComponent(warp).replace(/%3A/g, '(%3A|:)')}`), 'the query string follows the controls');
    checked++;
  }
  // A count typed in the number field, and the log-scale slider.
  const typed = await drive({ warp: 'disk:polar4', count: 4095, sampler: 'stratified' });
  assert.equal(typed.drawn, 4095);
  assert.equal(typed.black, 4095);
  const slid = await drive({ 'count-range': 5 });
  assert.equal(slid.drawn, 32);
  // The README's picture: pmj02bn through the concentric map, 4 x 4 strata.
  const shot = await drive({ warp: 'disk:concentric', sampler: 'pmj02bn', count: 256, grid: '4x4', seed: 7 });
  assert.equal(shot.black, 256);
  assert.deepEqual(page.errors, [], 'no console errors, exceptions or failed requests');
  mkdirSync(`${root}target`, { recursive: true });
  const png = await page.screenshot();
  assert.deepEqual([...png.subarray(1, 4)], [0x50, 0x4e, 0x47], 'a PNG');
  writeFileSync(`${root}target/demo.png`, png);
  t.diagnostic(`${checked} warps checked; screenshot target/demo.png (${png.length} bytes)`);
});

// The "computed on the GPU" mode on Chromium's WebGPU software adapter (SwiftShader, which
// flushes subnormals: the demo's inputs are the samplers' points of the square, whose nonzero
// coordinates lie far above them, or indices).
// Every warp of the page, GPU on: all points have the wasm module's bits and the page says
// so. Where the browser gives no adapter (outside CI), the toggle must be disabled instead.
test('the demo page computes every warp on the GPU (WebGPU, SwiftShader) with the wasm bits', { skip, timeout: 300_000 }, async (t) => {
  const page = await openDemo(t, webgpuChromium, 60000);
  const control = await page.evaluate(`({ disabled: document.getElementById('gpu').disabled,
    checked: document.getElementById('gpu').checked, note: document.getElementById('gpu-note').textContent,
    gpu: { ...window.demo.gpu }, error: window.demo.error })`);
  assert.equal(control.error, null);
  if (!control.gpu.available) {
    // No adapter here: the mode must be offered disabled, with the reason (CI has SwiftShader).
    assert.ok(!process.env.CI, `CI runs Chromium with SwiftShader's WebGPU: ${JSON.stringify(control)}`);
    assert.equal(control.disabled, true, 'the GPU toggle is disabled without an adapter');
    assert.equal(control.checked, false);
    assert.match(control.note, /unavailable: \S/);
    t.diagnostic(`no WebGPU adapter (${control.gpu.reason}): toggle disabled, as required`);
    return;
  }
  t.diagnostic(`adapter: ${control.gpu.adapter}`);
  assert.match(control.gpu.adapter, /swiftshader|google/i, 'the software adapter');
  assert.equal(control.disabled, false, 'the toggle is enabled with an adapter');
  assert.equal(control.checked, true, '?gpu=1 turns the mode on');
  assert.equal(control.gpu.on, true);
  assert.equal(control.gpu.identical, 256);

  const drive = driver(page);
  const warps = await page.evaluate(`[...document.querySelectorAll('#warp option')].map((o) => o.value)`);
  assert.equal(warps.length, 17);
  const samplers = ['random', 'stratified', 'pmj02bn'];
  const counts = [4096, 37, 256, 1000, 4];
  for (const [i, warp] of warps.entries()) {
    const s = { warp, sampler: samplers[i % 3], count: counts[i % counts.length], grid: '4x4', seed: 11 + i, gpu: true };
    const r = await drive(s);
    const what = `${JSON.stringify(s)} -> ${r.caption}`;
    assert.equal(r.error, null, what);
    assert.equal(r.gpu.on, true, `computed on the GPU: ${what}`);
    assert.equal(r.gpu.points, s.count, what);
    assert.equal(r.gpu.identical, s.count, `every point has the wasm bits: ${what}`);
    assert.match(r.readout, new RegExp(`^${s.count} of ${s.count} points identical`), what);
    assert.equal(r.readoutClass, 'same');
    assert.equal(r.drawn, s.count, what);
    assert.equal(r.black, s.count, `a black dot at every GPU point's pixel: ${what}`);
    assert.match(r.query, /gpu=1/);
  }
  // The count is sharp: the sine kernel's leading constant one ulp off (the library edited
  // before the shader is built) moves most concentric points, and the page says so.
  await page.evaluate(`window.demo.gpuEdit = ['const WCI_S0: f32 = 0x1.921fb4p-1f;', 'const WCI_S0: f32 = 0x1.921fb6p-1f;']`);
  const edited = await drive({ warp: 'disk:concentric', sampler: 'random', count: 4096, seed: 5 });
  t.diagnostic(`S0 + 1 ulp: ${edited.readout}`);
  assert.equal(edited.gpu.on, true);
  assert.ok(edited.gpu.identical < 0.9 * 4096, `a one-ulp change is seen: ${edited.readout}`);
  assert.match(edited.readout, new RegExp(`^${edited.gpu.identical} of 4096 points identical`));
  assert.equal(edited.readoutClass, 'differ');
  // A shader that does not compile: the page says so and draws the CPU's points.
  const errorsBefore = page.errors.length;
  await page.evaluate(`window.demo.gpuEdit = ['fn wc_disk_polar(', 'fn wc_disk_polar_gone(']`);
  const broken = await drive({ warp: 'disk:polar', count: 100 });
  assert.equal(broken.error, null, 'the page goes on');
  assert.equal(broken.gpu.on, false);
  assert.match(broken.gpu.failed ?? '', /\S/);
  assert.match(broken.readout, /^the GPU run failed \(.+\): these are the CPU's points$/s);
  assert.equal(broken.readoutClass, 'differ');
  assert.equal(broken.black, 100);
  assert.ok(page.errors.length > errorsBefore, 'the failure is logged');
  page.errors.length = errorsBefore;
  await page.evaluate('window.demo.gpuEdit = null');
  // Off again: the CPU path, no readout.
  const off = await drive({ gpu: false });
  assert.equal(off.gpu.on, false);
  assert.equal(off.readout, '');
  assert.doesNotMatch(off.query, /gpu=1/);
  // The screenshot: pmj02bn through the equal-area sphere map, on the GPU.
  const shot = await drive({ warp: 'sphere:equal_area', sampler: 'pmj02bn', count: 1024, grid: '4x4', seed: 7, gpu: true });
  assert.equal(shot.gpu.identical, 1024);
  assert.equal(shot.black, 1024);
  assert.deepEqual(page.errors, [], 'no console errors, exceptions or failed requests');
  mkdirSync(`${root}target`, { recursive: true });
  const png = await page.screenshot();
  assert.deepEqual([...png.subarray(1, 4)], [0x50, 0x4e, 0x47], 'a PNG');
  writeFileSync(`${root}target/demo-gpu.png`, png);
  t.diagnostic(`${warps.length} warps on the GPU; screenshot target/demo-gpu.png (${png.length} bytes)`);
});
