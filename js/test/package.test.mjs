// `npm pack` makes an installable package: the tarball holds the module, its types and the
// wasm; installed into an empty project (offline: it has no dependencies), it imports by name,
// loads its default wasm next to the module, computes, and its types check with tsc.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, writeFileSync, readFileSync, existsSync, rmSync, copyFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const js = fileURLToPath(new URL('..', import.meta.url));
const npm = (args, cwd) => execFileSync('npm', args, { cwd, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

test('npm pack, install the tarball, import it by name, type-check a user', (t) => {
  const dir = mkdtempSync(join(tmpdir(), 'warpcore-pack-'));
  t.after(() => rmSync(dir, { recursive: true, force: true }));
  const [packed] = JSON.parse(npm(['pack', '--json', '--pack-destination', dir], js));
  assert.deepEqual(packed.files.map((f) => f.path).sort(), ['package.json', 'warpcore.d.ts', 'warpcore.mjs', 'warpcore.wasm'].sort());
  const tarball = join(dir, packed.filename);
  assert.ok(existsSync(tarball));

  const app = join(dir, 'app');
  execFileSync('mkdir', [app]);
  writeFileSync(join(app, 'package.json'), JSON.stringify({ name: 'app', private: true, type: 'module' }));
  npm(['install', '--offline', '--no-audit', '--no-fund', '--ignore-scripts', tarball], app);
  const installed = join(app, 'node_modules', 'warpcore');
  assert.deepEqual(readFileSync(join(installed, 'warpcore.wasm')), readFileSync(join(js, 'warpcore.wasm')));

  writeFileSync(
    join(app, 'main.mjs'),
    `import { load } from 'warpcore';
const wc = await load();
const u = wc.pmj02bnSample(0, 42, 16);
const d = wc.diskConcentric(u);
const ok = d.length === 32 && [...d].every((x) => Math.abs(x) <= 1) && wc.diskPolar4(u).length === 128;
let threw = '';
try { wc.diskPolar4(u, -1); } catch (e) { threw = e.constructor.name; }
console.log(JSON.stringify({ ok, threw, first: Array.from(u.subarray(0, 2)) }));
`,
  );
  const out = JSON.parse(execFileSync(process.execPath, ['main.mjs'], { cwd: app, encoding: 'utf8' }));
  assert.equal(out.ok, true);
  assert.equal(out.threw, 'RangeError');
  assert.ok(out.first.every((x) => x >= 0 && x < 1));

  // The types: a user's TypeScript compiles against the installed package (when the dev
  // dependency typescript is installed: `npm ci` in js/).
  const tsc = join(js, 'node_modules', 'typescript', 'bin', 'tsc');
  if (!existsSync(tsc)) {
    t.diagnostic('typescript is not installed (npm ci in js/): types not checked');
    return;
  }
  copyFileSync(join(js, 'test', 'types', 'usage.ts'), join(app, 'usage.ts'));
  const args = ['--noEmit', '--strict', '--target', 'es2022', '--module', 'nodenext', '--moduleResolution', 'nodenext', '--lib', 'es2022,dom,esnext.disposable', 'usage.ts'];
  try {
    execFileSync(process.execPath, [tsc, ...args], { cwd: app, encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
  } catch (e) {
    assert.fail(`tsc failed:\n${e.stdout}${e.stderr}`);
  }
});
