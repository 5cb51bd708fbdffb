// tests/browser/lab_links.mjs — the lab's links end to end: `shadowlab serve` on a free loopback
// port, its page in Debian's headless Chromium (puppeteer-core, no browser download).
//   1. Every link of the artefact gallery (GALLERY/index.html, its <script id=gallery-data>)
//      opens the lab in the state it names: the /api/render requests the page sends for A and
//      B carry exactly the options of the entry's wrong and right `shadowlab render` commands,
//      the server's reproducing command is that command, and the page's own URL names the same
//      state as the link (zoom and close-up centre included).
//   2. The URL round trip: state set through the controls (techniques, a fine offset, size,
//      view, camera orbit by dragging, zoom by the wheel) is written into the page's URL; that
//      URL opened afresh gives the same state, the same URL and the same render requests.
//   3. The finer offset slider: its first step from 0 is at most 0.01; the error view has a
//      legend naming the grey of the pixels left out.
//   4. A bodiless POST gets 405 (README: "a method other than GET 405"), over a raw socket.
// usage: SHADOWLAB_BINARY=... node lab_links.mjs GALLERY_DIR
// Screenshots go to $SHADOWLAB_SCREENSHOT_DIR.
import { mkdirSync } from 'node:fs';
import net from 'node:net';
import { commandPairs, embeddedJson, launchChromium, pairsOf, sameList, startLab } from './harness.mjs';

// The first frames wait for /api/scenes (it loads every scene) and, behind them on the one
// worker, for the error requests of the previous link (a ray-traced reference each).
const kFrameTimeoutMs = Number(process.env.SHADOWLAB_FRAME_TIMEOUT_MS || 240000);
const kFinestOffsetStep = 0.01;  // the offset slider's first step from 0 (issue: show acne appear)
const binary = process.env.SHADOWLAB_BINARY;
const galleryDir = process.argv[2];
const shots = process.env.SHADOWLAB_SCREENSHOT_DIR || 'out/browser-links';
mkdirSync(shots, { recursive: true });

let failures = 0;
function fail(message) {
  console.error('FAIL: ' + message);
  failures += 1;
  process.exitCode = 1;
}

// The gallery's entries, from the JSON its page carries.
const galleryEntries = (dir) => embeddedJson(dir, 'gallery-data');

const { server, ...base } = await startLab(binary);  // base: { url, port }
console.log('lab at ' + base.url);

// One raw request, the reply's status line.
function rawStatus(bytes) {
  return new Promise((resolve, reject) => {
    const socket = net.connect(base.port, '127.0.0.1', () => socket.write(bytes));
    let reply = '';
    socket.setTimeout(30000, () => { socket.destroy(); reject(new Error('no reply to ' + bytes)); });
    socket.on('data', (d) => {
      reply += d;
      if (reply.includes('\r\n')) { socket.destroy(); resolve(reply.split('\r\n')[0]); }
    });
    socket.on('error', reject);
  });
}

const browser = await launchChromium();

// Opens `url` in a new page and records the /api/render requests of lanes a and b (their
// queries) and the reproducing command each answer names.
async function openLab(url) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 1000 });
  const seen = { requests: { a: [], b: [] }, commands: { a: [], b: [] }, errors: [] };
  page.on('console', (m) => { if (m.type() === 'error') seen.errors.push(m.text()); });
  page.on('pageerror', (e) => seen.errors.push('page error: ' + e.message));
  page.on('request', (r) => {
    const u = new URL(r.url());
    const lane = u.searchParams.get('lane');
    if (u.pathname === '/api/render' && (lane === 'a' || lane === 'b')) seen.requests[lane].push(u.search);
  });
  page.on('response', async (r) => {
    const u = new URL(r.url());
    const lane = u.searchParams.get('lane');
    if (u.pathname === '/api/render' && (lane === 'a' || lane === 'b') && r.status() === 200) {
      seen.commands[lane].push(r.headers()['x-shadowlab-command'] || '');
    }
  });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => Number(document.body.dataset.frames || 0) >= 2,
                             { timeout: kFrameTimeoutMs });
  return { page, seen };
}

try {
  // ---------------------------------------------------------------- 4. bodiless POST
  for (const target of ['/api/render?technique=legacy.hw', '/']) {
    const status = await rawStatus(`POST ${target} HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n`);
    if (!status.startsWith('HTTP/1.1 405')) fail(`bodiless POST ${target}: ${status}`);
  }

  // ---------------------------------------------------------------- 1. gallery links
  const entries = galleryEntries(galleryDir);
  if (entries.length < 10) fail('the gallery has only ' + entries.length + ' entries');
  for (const e of entries) {
    const failuresBefore = failures;
    const link = new URL(e.lab);
    const { page, seen } = await openLab(base.url + link.search);
    const problems = await page.$eval('#link-problems', (x) => (x.hidden ? '' : x.textContent));
    if (problems) fail(`${e.id}: ${problems}`);
    for (const [lane, side] of [['a', e.wrong], ['b', e.right]]) {
      const want = commandPairs(side.arguments);
      if (!seen.requests[lane].length) fail(`${e.id}: no render request for ${lane}`);
      for (const q of seen.requests[lane]) {
        const got = pairsOf(q, ['lane', 'view']);
        if (!sameList(got, want)) fail(`${e.id} ${lane}: request ${got.join('&')}\n  link says ${want.join('&')}`);
      }
      // The server's reproducing command is the entry's, but for the output file.
      const wantCommand = side.command.replace(/ --out \S+$/, '');
      for (const c of seen.commands[lane]) {
        if (c.replace(/ --out \S+$/, '').split(' ').sort().join(' ') !== wantCommand.split(' ').sort().join(' '))
          fail(`${e.id} ${lane}: the lab reproduces with\n  ${c}\n  the gallery says\n  ${side.command}`);
      }
    }
    // The page names the link's state in its own URL (order aside).
    const written = await page.evaluate(() => location.search);
    if (!sameList(pairsOf(written), pairsOf(link.search))) {
      fail(`${e.id}: the page's URL ${written}\n  the link's ${link.search}`);
    }
    if (seen.errors.length) fail(`${e.id}: console errors: ${seen.errors.join('; ')}`);
    await page.screenshot({ path: `${shots}/gallery-${e.id}.png` });
    await page.close();
    console.log(`gallery link ${e.id}: ${failures === failuresBefore ? 'ok' : 'FAILED'}`);
  }

  // ---------------------------------------------------------------- 2. URL round trip
  const { page, seen } = await openLab(base.url);
  await page.select('#technique-a', 'modern.hw');
  await page.waitForFunction(() => document.getElementById('command-a').textContent.includes('modern.hw'),
                             { timeout: kFrameTimeoutMs });
  // 3. The offset slider's first step from 0.
  const firstStep = await page.$eval('#options-a input[type=range][data-option="param:offset-factor"]', (s) => {
    s.value = '1';
    s.dispatchEvent(new Event('input', { bubbles: true }));
    return Number(document.querySelector('#options-a input[data-value-of="param:offset-factor"]').value);
  });
  if (!(firstStep > 0 && firstStep <= kFinestOffsetStep)) fail('offset-factor slider: first step ' + firstStep);
  // An exact value typed into the box beside the slider.
  await page.$eval('#options-a input[data-value-of="param:offset-units"]', (b) => {
    b.value = '0.5';
    b.dispatchEvent(new Event('change', { bubbles: true }));
  });
  await page.waitForFunction(() => document.getElementById('command-a').textContent.includes('offset-units=0.5'),
                             { timeout: kFrameTimeoutMs });
  await page.select('#technique-b', 'legacy.pcf');
  await page.select('#size', '320x240');
  await page.select('#view', 'error');
  // Orbit: drag the image; zoom: the wheel over it.
  const box = await (await page.$('#canvas')).boundingBox();
  await page.mouse.move(box.x + 100, box.y + 100);
  await page.mouse.down();
  await page.mouse.move(box.x + 160, box.y + 80, { steps: 4 });
  await page.mouse.up();
  await page.mouse.move(box.x + 120, box.y + 90);
  await page.mouse.wheel({ deltaY: -100 });
  await page.waitForFunction(() => document.getElementById('command-a').textContent.includes('--orbit') &&
                             document.getElementById('command-a').textContent.includes('320x240') &&
                             document.getElementById('command-b').textContent.includes('legacy.pcf') &&
                             document.getElementById('command-b').textContent.includes('--orbit'),
                             { timeout: kFrameTimeoutMs });
  // The last request of each lane carries the final orbit (a drag's later moves wait for the
  // frame in flight, then go out as one request).
  const orbitOf = (search) => new URLSearchParams(search).get('orbit');
  for (let waited = 0; ; waited += 200) {
    const orbit = await page.evaluate(() => new URLSearchParams(location.search).get('orbit'));
    if (orbitOf(seen.requests.a.at(-1)) === orbit && orbitOf(seen.requests.b.at(-1)) === orbit) break;
    if (waited > kFrameTimeoutMs) { fail('the last requests never carried the final orbit'); break; }
    await new Promise((r) => setTimeout(r, 200));
  }
  const legend = await page.$eval('#legend', (l) => (l.hidden ? '' : l.textContent));
  if (!legend.includes('grey: not scored')) fail('the error view has no legend for its grey: ' + legend);
  await page.screenshot({ path: `${shots}/roundtrip-1-set.png`, fullPage: true });
  const href = await page.evaluate(() => location.href);
  const query1 = await page.evaluate(() => document.body.dataset.query);
  const last = { a: seen.requests.a.at(-1), b: seen.requests.b.at(-1) };
  for (const want of ['a=modern.hw', 'b=legacy.pcf', 'size=320x240', 'view=error', 'orbit=', 'zoom=',
                      'center=', 'a-param=offset-factor=', 'a-param=offset-units=0.5']) {
    if (!href.includes(want)) fail(`the URL lacks ${want}: ${href}`);
  }
  await page.close();

  const again = await openLab(href);
  const query2 = await again.page.evaluate(() => document.body.dataset.query);
  if (query2 !== query1) fail(`round trip: the reloaded page writes\n  ${query2}\n  before\n  ${query1}`);
  for (const lane of ['a', 'b']) {
    const before = pairsOf(last[lane], ['lane']);
    for (const q of again.seen.requests[lane]) {
      const after = pairsOf(q, ['lane']);
      if (!sameList(after, before)) fail(`round trip ${lane}: request ${after.join('&')}\n  before ${before.join('&')}`);
    }
  }
  const shown = await again.page.evaluate(() => ({
    view: document.getElementById('view').value,
    size: document.getElementById('size').value,
    a: document.getElementById('technique-a').value,
    units: document.querySelector('#options-a input[data-value-of="param:offset-units"]').value,
  }));
  if (!sameList(shown, { view: 'error', size: '320x240', a: 'modern.hw', units: '0.5' })) {
    fail('round trip: the controls show ' + JSON.stringify(shown));
  }
  await again.page.screenshot({ path: `${shots}/roundtrip-2-reloaded.png`, fullPage: true });
  if (again.seen.errors.length) fail('round trip: console errors: ' + again.seen.errors.join('; '));
  await again.page.close();
} catch (e) {
  fail(e.stack || String(e));
} finally {
  await browser.close();
  server.kill('SIGINT');
}
const code = await new Promise((resolve) => server.on('exit', (c) => resolve(c)));
if (code !== 0) fail('shadowlab serve exited with ' + code + ' on SIGINT');
console.log(process.exitCode ? 'lab links: FAILED' : 'lab links: ok (screenshots in ' + shots + ')');
