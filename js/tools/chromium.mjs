// Drives headless Chromium through the Chrome DevTools Protocol over a pipe
// (--remote-debugging-pipe: JSON messages separated by NUL on file descriptors 3 and 4), with
// Node's standard library only: no WebSocket, no port, no npm dependency.
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

/** The Chromium executable: $CHROMIUM, or the Debian package's. */
export function findChromium() {
  for (const p of [process.env.CHROMIUM, '/usr/bin/chromium', '/usr/bin/chromium-browser']) {
    if (p && existsSync(p)) return p;
  }
  return null;
}

/**
 * Launches Chromium headless with a fresh profile and no network beyond 127.0.0.1; returns
 * `{ send(method, params, sessionId), on(event, handler), close() }`.
 */
export async function launch(executable = findChromium()) {
  if (!executable) throw new Error('Chromium not found (apt-get install chromium, or set CHROMIUM)');
  const profile = mkdtempSync(join(tmpdir(), 'warpcore-chromium-'));
  const args = [
    '--headless',
    '--no-sandbox',
    '--disable-gpu',
    '--disable-quic',
    '--no-first-run',
    '--no-default-browser-check',
    '--disable-background-networking',
    '--disable-component-update',
    '--disable-sync',
    '--disable-extensions',
    '--disable-dev-shm-usage',
    '--mute-audio',
    '--hide-scrollbars',
    // Nothing but the local server resolves: no hidden network access.
    '--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1',
    `--user-data-dir=${profile}`,
    '--remote-debugging-pipe',
    'about:blank',
  ];
  const proc = spawn(executable, args, { stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'] });
  let stderr = '';
  proc.stderr.on('data', (d) => (stderr = (stderr + d).slice(-4000)));
  const [toBrowser, fromBrowser] = [proc.stdio[3], proc.stdio[4]];
  let nextId = 1;
  const waiting = new Map();
  const listeners = new Map();
  let buffer = '';
  let exited = null;
  proc.on('exit', (code, signal) => {
    exited = `Chromium exited (${code ?? signal}):\n${stderr}`;
    for (const { fail } of waiting.values()) fail(new Error(exited));
    waiting.clear();
  });
  fromBrowser.on('data', (chunk) => {
    buffer += chunk.toString('utf8');
    let end;
    while ((end = buffer.indexOf('\0')) >= 0) {
      const message = JSON.parse(buffer.slice(0, end));
      buffer = buffer.slice(end + 1);
      if (message.id !== undefined) {
        const w = waiting.get(message.id);
        waiting.delete(message.id);
        if (message.error) w?.fail(new Error(`${w.method}: ${message.error.message}`));
        else w?.ok(message.result);
      } else {
        for (const f of listeners.get(message.method) ?? []) f(message.params, message.sessionId);
      }
    }
  });
  const send = (method, params = {}, sessionId = undefined) =>
    new Promise((ok, fail) => {
      if (exited) return fail(new Error(exited));
      const id = nextId++;
      waiting.set(id, { ok, fail, method });
      toBrowser.write(JSON.stringify({ id, method, params, ...(sessionId ? { sessionId } : {}) }) + '\0');
    });
  const on = (event, f) => listeners.set(event, [...(listeners.get(event) ?? []), f]);
  await send('Browser.getVersion');
  return {
    send,
    on,
    async close() {
      if (!exited) {
        await send('Browser.close').catch(() => {});
        await new Promise((done) => (exited ? done() : proc.once('exit', done)));
      }
      rmSync(profile, { recursive: true, force: true });
    },
  };
}

/** Opens a page in a new tab; returns `{ sessionId, evaluate(expr), screenshot(), errors }`. */
export async function open(browser, url, { width = 1280, height = 760 } = {}) {
  const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await browser.send('Target.attachToTarget', { targetId, flatten: true });
  const s = (method, params) => browser.send(method, params, sessionId);
  const errors = [];
  browser.on('Runtime.consoleAPICalled', (p, sid) => {
    if (sid === sessionId && (p.type === 'error' || p.type === 'assert')) {
      errors.push(`console.${p.type}: ${p.args.map((a) => a.value ?? a.description).join(' ')}`);
    }
  });
  browser.on('Runtime.exceptionThrown', (p, sid) => {
    if (sid === sessionId) errors.push(`exception: ${p.exceptionDetails.exception?.description ?? p.exceptionDetails.text}`);
  });
  browser.on('Log.entryAdded', (p, sid) => {
    if (sid === sessionId && p.entry.level === 'error') errors.push(`log: ${p.entry.text} ${p.entry.url ?? ''}`);
  });
  await s('Runtime.enable');
  await s('Log.enable');
  await s('Page.enable');
  await s('Emulation.setDeviceMetricsOverride', { width, height, deviceScaleFactor: 1, mobile: false });
  const loaded = new Promise((ok) => browser.on('Page.loadEventFired', (_, sid) => sid === sessionId && ok()));
  const nav = await s('Page.navigate', { url });
  if (nav.errorText) throw new Error(`navigating to ${url}: ${nav.errorText}`);
  await loaded;
  return {
    sessionId,
    errors,
    async evaluate(expression) {
      const r = await s('Runtime.evaluate', { expression, awaitPromise: true, returnByValue: true });
      if (r.exceptionDetails) {
        throw new Error(`in the page: ${r.exceptionDetails.exception?.description ?? r.exceptionDetails.text}`);
      }
      return r.result.value;
    },
    async screenshot() {
      const { data } = await s('Page.captureScreenshot', { format: 'png', captureBeyondViewport: false });
      return Buffer.from(data, 'base64');
    },
  };
}
