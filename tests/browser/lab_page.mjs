// tests/browser/lab_page.mjs — the live lab end to end: `shadowlab serve` on a
// free loopback port, its page in Debian's headless Chromium (puppeteer-core, no browser
// download). Loads the page, waits for both frames, changes technique A and a slider, and
// checks that a new image arrived for each change (the canvas changed, the reproducing command
// names the new setting) and that the console showed no error. Screenshots go to
// $SHADOWLAB_SCREENSHOT_DIR for a person to look at.
import { createHash } from 'node:crypto';
import { mkdirSync } from 'node:fs';
import { launchChromium, startLab } from './harness.mjs';

const kFrameTimeoutMs = Number(process.env.SHADOWLAB_FRAME_TIMEOUT_MS || 180000);  // first frames: /api/scenes loads every scene
const binary = process.env.SHADOWLAB_BINARY;
const shots = process.env.SHADOWLAB_SCREENSHOT_DIR || 'out/browser';
mkdirSync(shots, { recursive: true });

function fail(message) {
  console.error('FAIL: ' + message);
  process.exitCode = 1;
}

const { server, url } = await startLab(binary);
console.log('lab at ' + url);

const browser = await launchChromium();
const consoleErrors = [];
try {
  const page = await browser.newPage();
  await page.setViewport({ width: 1280, height: 1000 });
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push('page error: ' + e.message));
  page.on('requestfailed', (r) => consoleErrors.push('request failed: ' + r.url()));
  page.on('response', async (r) => {  // names the request behind a "Failed to load resource"
    if (r.status() >= 400) consoleErrors.push(`HTTP ${r.status()} ${r.url()}: ${await r.text()}`);
  });
  await page.goto(url, { waitUntil: 'load' });

  const frames = () => page.evaluate(() => Number(document.body.dataset.frames || 0));
  const canvasHash = async () => createHash('sha256')
    .update(await page.evaluate(() => document.getElementById('canvas').toDataURL()))
    .digest('hex');
  const waitFrames = (n) => page.waitForFunction(
    (k) => Number(document.body.dataset.frames || 0) >= k, { timeout: kFrameTimeoutMs }, n);
  // Waits until lane A's reproducing command contains `text` (its new frame arrived).
  const waitCommandA = (text) => page.waitForFunction(
    (t) => document.getElementById('command-a').textContent.includes(t),
    { timeout: kFrameTimeoutMs }, text);

  await waitFrames(2);  // A and B
  await page.screenshot({ path: `${shots}/lab-1-loaded.png` });
  const hash1 = await canvasHash();
  const commandA = await page.$eval('#command-a', (e) => e.textContent);
  if (!commandA.startsWith('shadowlab render --scene brabec --technique legacy.hw')) {
    fail('command of A: ' + commandA);
  }

  // Technique A -> modern.pcf: its options are rebuilt from /api/techniques.
  let before = await frames();
  await page.select('#technique-a', 'modern.pcf');
  await waitCommandA('--technique modern.pcf');
  if ((await frames()) <= before) fail('no new frame after changing technique A');
  const hash2 = await canvasHash();
  if (hash2 === hash1) fail('the canvas did not change with technique A');
  const filterSlider = await page.$('#options-a input[data-option="filter"]');
  if (!filterSlider) fail('technique A (modern.pcf) shows no filter slider');

  // A slider: the PCF footprint of A from 2 to 4 (modern.pcf takes 1..4).
  before = await frames();
  await page.$eval('#options-a input[data-option="filter"]', (e) => {
    e.value = '4';
    e.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await waitCommandA('--filter 4');
  if ((await frames()) <= before) fail('no new frame after moving the filter slider');
  const hash3 = await canvasHash();
  if (hash3 === hash2) fail('the canvas did not change with the filter slider');
  // Let the error request land, so the plot shows the current point.
  await page.waitForFunction(() => document.querySelectorAll('#plot circle').length >= 2,
                             { timeout: kFrameTimeoutMs });
  await page.screenshot({ path: `${shots}/lab-2-pcf-filter4.png` });

  // Error view and the passes of A.
  await page.select('#view', 'error');
  await page.waitForFunction(() => document.getElementById('numbers-a').textContent.includes('RMSE'),
                             { timeout: kFrameTimeoutMs });
  await page.click('#load-passes');
  await page.waitForFunction(() => document.querySelectorAll('#pass-strip img').length > 0 &&
                             [...document.querySelectorAll('#pass-strip img')].every((i) => i.complete),
                             { timeout: kFrameTimeoutMs });
  await new Promise((r) => setTimeout(r, 1500));  // the error heat maps follow the frames
  await page.screenshot({ path: `${shots}/lab-3-error-passes.png`, fullPage: true });
  const status = await page.$eval('#status', (e) => e.className);
  if (status.includes('error')) fail('the page shows an error: ' + await page.$eval('#status', (e) => e.textContent));
} catch (e) {
  fail(e.stack || String(e));
} finally {
  await browser.close();
  server.kill('SIGINT');
}
const code = await new Promise((resolve) => server.on('exit', (c) => resolve(c)));
if (code !== 0) fail('shadowlab serve exited with ' + code + ' on SIGINT');
if (consoleErrors.length) fail('console errors:\n  ' + consoleErrors.join('\n  '));
console.log(process.exitCode ? 'lab page: FAILED' : 'lab page: ok (screenshots in ' + shots + ')');
