// The JavaScript examples of the documentation run on this Node (20 is the documented
// minimum): every fenced ```js block of README.md and docs/*.md is extracted, its
// `from 'warpcore'` import pointed at js/warpcore.mjs (and `load()` at WARPCORE_WASM when
// set), and run as an ES module from the repository root (so `tests/data/...` paths resolve);
// it must exit with status 0 (the blocks check their own results and throw when wrong).
//
// A block that cannot run on its own (it uses names defined elsewhere) is marked by the line
// `<!-- docs-test: fragment -->` right before its fence: it is only syntax-checked
// (`node --check`), which still catches syntax this Node lacks (e.g. `using` declarations).
// The test fails when no block is found, so a renamed file cannot silently skip everything.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = fileURLToPath(new URL('../..', import.meta.url));
const wasmUrl = process.env.WARPCORE_WASM ? pathToFileURL(process.env.WARPCORE_WASM) : new URL('../warpcore.wasm', import.meta.url);
const moduleUrl = pathToFileURL(join(root, 'js/warpcore.mjs')).href;
const FRAGMENT = '<!-- docs-test: fragment -->';

/** The ```js blocks of a Markdown file: { line, code, fragment }. */
export function jsBlocks(markdown) {
  const lines = markdown.split('\n');
  const blocks = [];
  for (let i = 0; i < lines.length; i++) {
    if (!/^```(js|javascript|mjs)\s*$/.test(lines[i])) continue;
    const start = i;
    const body = [];
    for (i++; i < lines.length && !/^```\s*$/.test(lines[i]); i++) body.push(lines[i]);
    assert.ok(i < lines.length, `unclosed block at line ${start + 1}`);
    blocks.push({ line: start + 1, code: body.join('\n') + '\n', fragment: lines[start - 1]?.trim() === FRAGMENT });
  }
  return blocks;
}

const pages = ['README.md', ...readdirSync(join(root, 'docs')).filter((f) => f.endsWith('.md')).map((f) => `docs/${f}`)];
const dir = mkdtempSync(join(tmpdir(), 'warpcore-docs-'));
process.on('exit', () => rmSync(dir, { recursive: true, force: true }));

test('the extractor finds blocks and markers (a wrong extractor would pass everything)', () => {
  const md = ['text', '```js', 'a();', '```', FRAGMENT, '```js', 'b();', '```', '```rust', 'c', '```'].join('\n');
  assert.deepEqual(jsBlocks(md), [
    { line: 2, code: 'a();\n', fragment: false },
    { line: 6, code: 'b();\n', fragment: true },
  ]);
  const all = pages.flatMap((p) => jsBlocks(readFileSync(join(root, p), 'utf8')));
  assert.ok(jsBlocks(readFileSync(join(root, 'docs/quickstart.md'), 'utf8')).length >= 2, 'docs/quickstart.md has its two JS quick starts');
  assert.ok(jsBlocks(readFileSync(join(root, 'docs/javascript.md'), 'utf8')).length >= 3, 'docs/javascript.md has its examples');
  assert.ok(all.filter((b) => !b.fragment).length >= 5, 'most blocks run');
});

test('node --check rejects what Node 20 cannot parse (the check is real)', () => {
  const file = join(dir, 'using.mjs');
  writeFileSync(file, 'const x = 1;\nusing y = { [Symbol.dispose]() {} };\n');
  const major = Number(process.versions.node.split('.')[0]);
  const r = spawnSync(process.execPath, ['--check', file], { encoding: 'utf8' });
  if (major < 22) assert.notEqual(r.status, 0, 'a `using` declaration parses on this Node');
  writeFileSync(file, 'const x = ;\n');
  assert.notEqual(spawnSync(process.execPath, ['--check', file]).status, 0);
});

for (const page of pages) {
  const blocks = jsBlocks(readFileSync(join(root, page), 'utf8'));
  for (const { line, code, fragment } of blocks) {
    test(`${page}:${line} ${fragment ? 'parses (fragment)' : 'runs'} on Node ${process.versions.node}`, () => {
      const file = join(dir, `${page.replace(/\W/g, '_')}_${line}.mjs`);
      const source = code
        .replaceAll("from 'warpcore'", `from '${moduleUrl}'`)
        .replaceAll('await load()', `await load(${JSON.stringify(wasmUrl.href)})`);
      writeFileSync(file, source);
      const args = fragment ? ['--check', file] : [file];
      const r = spawnSync(process.execPath, args, { cwd: root, encoding: 'utf8', timeout: 120_000 });
      assert.equal(r.status, 0, `${page}:${line} exited with ${r.status}\n${r.stdout}\n${r.stderr}`);
    });
  }
}
