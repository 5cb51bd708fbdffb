// tests/browser/course_links.mjs — the course (`shadowlab course --out DIR`) in Debian's headless
// Chromium (puppeteer-core, no browser download):
//   1. Every link of the course's pages (DIR/index.html, DIR/teacher.html) resolves: a relative
//      link names a file that exists, and its #anchor an element of the page it opens (loaded
//      in the browser, so the id is what the browser finds; harness.mjs LinkChecker).
//   2. Every lab link (from <script id=course-data>) parses in the lab's URL scheme: opened
//      against `shadowlab serve`, the page names no problem with it, writes the same state back
//      into its own address, and its /api/render requests for A and B carry exactly the
//      options of the exercise's two `shadowlab render` commands. The render requests are
//      answered by the test (HTTP 204) instead of the server: what is checked is the state the
//      link sets, not the frames (browser.lab_links renders the gallery's).
// usage: SHADOWLAB_BINARY=... node course_links.mjs COURSE_DIR
import path from 'node:path';
import url from 'node:url';
import { LinkChecker, commandPairs, embeddedJson, launchChromium, pairsOf, sameList, startLab } from './harness.mjs';

const kStateTimeoutMs = 60000;   // the page has read its URL and asked for both frames
const binary = process.env.SHADOWLAB_BINARY;
const dir = path.resolve(process.argv[2]);

let failures = 0;
function fail(message) {
  console.error('FAIL: ' + message);
  failures += 1;
  process.exitCode = 1;
}

const courseData = () => embeddedJson(dir, 'course-data');

const browser = await launchChromium();
let server = null;
try {
  // ---------------------------------------------------------------- 1. links and anchors
  // (harness.mjs LinkChecker, as check_pages.mjs checks every page of the course)
  const checker = new LinkChecker(browser);
  let labLinks = 0;
  for (const name of ['index.html', 'teacher.html']) {
    const file = path.join(dir, name);
    const page = await browser.newPage();
    await page.goto(url.pathToFileURL(file).href, { waitUntil: 'load' });
    const broken = await page.$$eval('img', (is) => is.filter((i) => !(i.complete && i.naturalWidth > 0))
                                                        .map((i) => i.getAttribute('src')));
    for (const src of broken) fail(`${name}: broken image ${src}`);
    labLinks += (await checker.read(file, page)).links.filter((l) => /^https?:/.test(l.href)).length;
    await page.close();
    await checker.check(file, fail);
  }
  const links = checker.links;
  console.log(`course pages: ${links} relative links, ${labLinks} lab links`);
  if (links < 20) fail('the course pages have only ' + links + ' relative links');

  // ---------------------------------------------------------------- 2. lab links
  const lab = await startLab(binary);
  server = lab.server;
  const base = lab.url;
  const exercises = courseData();
  let opened = 0;
  for (const e of exercises.filter((x) => x.lab)) {
    const before = failures;
    const link = new URL(e.lab_link);
    const page = await browser.newPage();
    const requests = { a: [], b: [] };
    await page.setRequestInterception(true);
    page.on('request', (r) => {
      const u = new URL(r.url());
      if (u.pathname !== '/api/render' && u.pathname !== '/api/error') { r.continue(); return; }
      const lane = u.searchParams.get('lane');
      if (u.pathname === '/api/render' && (lane === 'a' || lane === 'b')) requests[lane].push(u.search);
      r.respond({ status: 204, body: '' });
    });
    await page.goto(base + link.search, { waitUntil: 'load' });
    await page.waitForFunction(() => typeof state !== 'undefined' && state.ready, { timeout: kStateTimeoutMs });
    for (let waited = 0; !(requests.a.length && requests.b.length) && waited < kStateTimeoutMs; waited += 100)
      await new Promise((r) => setTimeout(r, 100));
    const problems = await page.$eval('#link-problems', (x) => (x.hidden ? '' : x.textContent));
    if (problems) fail(`${e.id}: ${problems}`);
    for (const lane of ['a', 'b']) {
      const want = commandPairs(e[lane].arguments);
      if (!requests[lane].length) fail(`${e.id}: no render request for ${lane}`);
      for (const q of requests[lane]) {
        const got = pairsOf(q, ['lane', 'view']);
        if (!sameList(got, want)) fail(`${e.id} ${lane}: request ${got.join('&')}\n  the command says ${want.join('&')}`);
      }
    }
    const written = await page.evaluate(() => location.search);
    if (!sameList(pairsOf(written), pairsOf(link.search))) fail(`${e.id}: the page's URL ${written}\n  the link's ${link.search}`);
    await page.close();
    opened += 1;
    console.log(`lab link ${e.id}: ${failures === before ? 'ok' : 'FAILED'}`);
  }
  if (opened < 10) fail('only ' + opened + ' lab links in the course');
} catch (e) {
  fail(e.stack || String(e));
} finally {
  await browser.close();
  if (server) server.kill('SIGINT');
}
console.log(process.exitCode ? 'course links: FAILED' : 'course links: ok');
