// Cargo runner for wasm32-wasip1: runs a test or example binary under Node's WASI.
// The host filesystem is preopened at "/", so tests use absolute paths (CARGO_MANIFEST_DIR).
// Usage (set in .cargo/config.toml): node tools/wasi-run.mjs <file.wasm> [args...]
import { readFile } from 'node:fs/promises';
import process from 'node:process';
import { WASI } from 'node:wasi';

const [wasmPath, ...args] = process.argv.slice(2);
const wasi = new WASI({
  version: 'preview1',
  args: [wasmPath, ...args],
  env: process.env,
  preopens: { '/': '/' },
  returnOnExit: true,
});
const module = await WebAssembly.compile(await readFile(wasmPath));
const instance = await WebAssembly.instantiate(module, wasi.getImportObject());
process.exitCode = wasi.start(instance);
