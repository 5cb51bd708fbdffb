// tests/browser/harness.mjs — what the browser tests share: Debian's headless Chromium through
// puppeteer-core (never a downloaded browser), `shadowlab serve` on a free loopback port, the
// JSON a generated page carries, and the "key=value" lists the link tests compare.
import { spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import puppeteer from 'puppeteer-core';

export const kChromium = process.env.SHADOWLAB_CHROMIUM || '/usr/bin/chromium';
export const kChromiumFlags = [
  '--no-sandbox', '--disable-gpu', '--disable-background-networking',
  '--disable-component-update', '--disable-sync', '--no-first-run',
];
const kStartTimeoutMs = 60000;  // the server prints its URL

// Debian's Chromium, headless.
export function launchChromium() {
  return puppeteer.launch({ executablePath: kChromium, headless: true, args: kChromiumFlags });
}

// `shadowlab serve --port 0`: resolves to { server, url, port } once the server has printed its
// address; rejects if it exits first or prints nothing within kStartTimeoutMs.
export function startLab(binary) {
  const server = spawn(binary, ['serve', '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
  return new Promise((resolve, reject) => {
    let out = '';
    const timer = setTimeout(() => {
      server.kill('SIGINT');
      reject(new Error('no URL from shadowlab serve'));
    }, kStartTimeoutMs);
    server.stdout.on('data', (chunk) => {
      out += chunk;
      const m = out.match(/the lab is at (http:\/\/127\.0\.0\.1:(\d+)\/)/);
      if (m) { clearTimeout(timer); resolve({ server, url: m[1], port: Number(m[2]) }); }
    });
    server.on('error', reject);
    server.on('exit', (code) => reject(new Error('shadowlab serve exited with ' + code)));
  });
}

// The JSON a generated page carries in <script type="application/json" id=ID> (DIR/index.html).
export function embeddedJson(dir, id) {
  const html = readFileSync(path.join(dir, 'index.html'), 'utf8');
  const m = html.match(new RegExp(`<script type="application/json" id=${id}>([\\s\\S]*?)</script>`));
  if (!m) throw new Error(`no ${id} in ${dir}/index.html`);
  return JSON.parse(m[1]);
}

// key=value pairs of a query as sorted "key=value" strings, without the keys in `skip`.
export function pairsOf(search, skip = []) {
  const out = [];
  for (const [k, v] of new URLSearchParams(search)) if (!skip.includes(k)) out.push(k + '=' + v);
  return out.sort();
}

// A render command's options as sorted "key=value" strings, as the API spells them.
export function commandPairs(args) {
  const out = [];
  for (let i = 0; i + 1 < args.length; i += 2) out.push(args[i].replace(/^--/, '') + '=' + args[i + 1]);
  return out.sort();
}

export const sameList = (x, y) => JSON.stringify(x) === JSON.stringify(y);
