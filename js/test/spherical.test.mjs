// Lights by solid angle through the JavaScript API: densities against solid angles computed
// here in float64 (Van Oosterom-Strackee), round trips, domains on stiff input, and `out`.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { pathToFileURL } from 'node:url';
import { load } from '../warpcore.mjs';

const wasmUrl = process.env.WARPCORE_WASM ? pathToFileURL(process.env.WARPCORE_WASM) : new URL('../warpcore.wasm', import.meta.url);
const wc = await load(wasmUrl);

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.sqrt(dot(a, a));
function vos(a, b, c) {
  const det = Math.abs(dot(a, cross(b, c)));
  const [la, lb, lc] = [norm(a), norm(b), norm(c)];
  return 2 * Math.atan2(det, la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la);
}
const at = (l, k) => [l[3 * k], l[3 * k + 1], l[3 * k + 2]];

const TRI = Float32Array.of(0, 0, 1, 1, 0, 1.2, 0, 1, 0.9, 0.2, 0.1, 0);
const RECT = Float32Array.of(-0.5, -0.5, 1, 1, 0, 0, 0, 1, 0, 0.3, 0.2, 0);
const U = Float32Array.from({ length: 64 }, (_, i) => ((i * 0.618034) % 1));

test('triangle: density is 1 / solid angle, round trip, simplex', () => {
  const p = at(TRI, 3);
  const omega = vos(sub(at(TRI, 0), p), sub(at(TRI, 1), p), sub(at(TRI, 2), p));
  assert.ok(Math.abs(wc.sphericalTriangleSolidAngle(TRI) / omega - 1) < 1e-5);
  const out = wc.sphericalTriangle(TRI, U);
  assert.equal(out.length, 128);
  const b = new Float32Array(96);
  for (let i = 0; i < 32; i++) {
    const [b0, b1, b2, pdf] = out.subarray(4 * i, 4 * i + 4);
    assert.ok(b0 >= 0 && b1 >= 0 && b2 >= 0 && Math.abs(b0 + b1 + b2 - 1) < 3e-7);
    assert.ok(Math.abs(pdf * omega - 1) < 1e-5, `${pdf}`);
    b.set([b0, b1, b2], 3 * i);
  }
  const u = wc.sphericalTriangleInverse(TRI, b);
  for (let i = 0; i < 64; i++) {
    if (i % 2 === 0 && U[i + 1] < 0.01) continue; // the apex loses u0
    assert.ok(Math.abs(u[i] - U[i]) < 1e-4, `${i}: ${u[i]} vs ${U[i]}`);
  }
});

test('rectangle: density is 1 / solid angle, round trip, into out', () => {
  const [c, ex, ey, p] = [at(RECT, 0), at(RECT, 1), at(RECT, 2), at(RECT, 3)];
  const a = sub(c, p);
  const exy = [ex[0] + ey[0], ex[1] + ey[1], ex[2] + ey[2]];
  const add = (x, y) => [x[0] + y[0], x[1] + y[1], x[2] + y[2]];
  const omega = vos(a, add(a, ex), add(a, exy)) + vos(a, add(a, exy), add(a, ey));
  assert.ok(Math.abs(wc.sphericalRectangleSolidAngle(RECT) / omega - 1) < 1e-5);
  const out = new Float32Array(96);
  assert.equal(wc.sphericalRectangle(RECT, U, out), out);
  const st = new Float32Array(64);
  for (let i = 0; i < 32; i++) {
    const [s, t, pdf] = out.subarray(3 * i, 3 * i + 3);
    assert.ok(s >= 0 && s <= 1 && t >= 0 && t <= 1);
    assert.ok(Math.abs(pdf * omega - 1) < 1e-5);
    st.set([s, t], 2 * i);
  }
  const u = wc.sphericalRectangleInverse(RECT, st);
  for (let i = 0; i < 64; i++) assert.ok(Math.abs(u[i] - U[i]) < 1e-4);
});

test('stiff lights: no NaN, densities finite and >= 0 (0 for degenerate lights)', () => {
  const lights = [
    Float32Array.of(0, 0, 1, 1, 0, 1, 2, 0, 1, 0, 0, 0), // collinear
    Float32Array.of(0, 0, 1, 1, 0, 1, 0, 1, 1, 0, 0, 1), // p on the plane, at a vertex
    Float32Array.of(NaN, 0, 1, 1, 0, 1, 0, 1, 1, 0, 0, Infinity),
    Float32Array.of(0, 0, 1e6, 1, 0, 1e6, 0, 1, 1e6, 0, 0, 0), // 1e-12 sr: area sampling
  ];
  const u = Float32Array.of(NaN, 2, -1, 0.5, 0.999, Infinity);
  for (const l of lights) {
    const t = wc.sphericalTriangle(l, u);
    const r = wc.sphericalRectangle(l, u);
    for (const x of [...t, ...r]) assert.ok(Number.isFinite(x) && x >= 0);
    const om = wc.sphericalTriangleSolidAngle(l);
    assert.ok(om >= 0 && om <= 2 * Math.PI + 1e-6);
  }
  assert.equal(wc.sphericalTriangle(lights[0], u)[3], 0);
});

test('cosine-aware maps: density is the bilinear cosine fit over the solid angle', () => {
  // The light facing a tilted receiver; the plain map of the warped sample is recovered by
  // the inverse, and the density must be bilinear(u') / omega with the weights computed here.
  const n = [0.3, -0.2, 1];
  const light = Float32Array.of(...TRI, ...n);
  const p = at(TRI, 3);
  const v = [at(TRI, 0), at(TRI, 1), at(TRI, 2)];
  const omega = vos(sub(v[0], p), sub(v[1], p), sub(v[2], p));
  const c = (x) => Math.max(0, dot(n, sub(x, p)) / (norm(n) * norm(sub(x, p))));
  const w = [c(v[1]), c(v[1]), c(v[0]), c(v[2])];
  const bil = ([x, y]) => (4 * ((1 - x) * (1 - y) * w[0] + x * (1 - y) * w[1] + (1 - x) * y * w[2] + x * y * w[3])) / (w[0] + w[1] + w[2] + w[3]);
  const out = wc.sphericalTriangleCosine(light, U);
  assert.equal(out.length, 128);
  for (let i = 0; i < 32; i++) {
    const [b0, b1, b2, pdf] = out.subarray(4 * i, 4 * i + 4);
    assert.ok(b0 >= 0 && b1 >= 0 && b2 >= 0 && Math.abs(b0 + b1 + b2 - 1) < 3e-7);
    const u = wc.sphericalTriangleInverse(TRI, Float32Array.of(b0, b1, b2));
    if (u[1] < 0.01) continue; // the apex loses u0
    assert.ok(Math.abs(pdf * omega - bil(u)) < 1e-3, `${i}: ${pdf * omega} vs ${bil(u)}`);
  }
  // A receiver facing away: every weight 0, the plain map bit for bit.
  const away = Float32Array.of(...TRI, 0, 0, -1);
  assert.deepEqual(wc.sphericalTriangleCosine(away, U), wc.sphericalTriangle(TRI, U));
  const rect = Float32Array.of(...RECT, 0, 0, -1);
  assert.deepEqual(wc.sphericalRectangleCosine(rect, U), wc.sphericalRectangle(RECT, U));
  assert.throws(() => wc.sphericalRectangleCosine(RECT, U), RangeError);
});
