// tests/browser/check_pages.mjs — loads shadowlab's pages in headless Chromium (Debian's
// /usr/bin/chromium, driven by puppeteer-core) and fails on what a reader would see broken:
//   every page:  an image that did not load (naturalWidth 0), a console error, an uncaught
//                script error, a failed request; a relative link to a file that does not
//                exist, or whose #fragment is no element id of the page it opens as the browser
//                loads it (harness.mjs LinkChecker: a target not among the PAGEs is loaded too);
//   a dump (index.html beside passes.json) and a lesson (index.html with <section class=pass>):
//                with --require-state-cards, a pass without its GL state card: in a dump every
//                pass of passes.json must have a "state" list whose lines the page shows,
//                in a lesson every pass section must hold a .state-card that is not
//                .state-card.missing ("state card: not recorded");
//   report.html: it links at least one lesson, and every figure (<article id>) links one
//                (a.lesson);
//   figures and lessons both ways: a link of a page's list of report figures (ul.report-figures)
//                to report.html#F needs F's article to link that page back (a.lesson), and a
//                lesson link of article F needs the lesson's list to link report.html#F.
// A screenshot of every page goes to --shots DIR (the top of the page, 1300 px wide).
//
// usage: node check_pages.mjs [--require-state-cards] [--shots DIR] PAGE.html ...
// Exit status 0 when every check passed, 1 otherwise (one line per failure on stderr).
import fs from 'node:fs';
import path from 'node:path';
import url from 'node:url';
import { LinkChecker, launchChromium } from './harness.mjs';

const kViewport = {width: 1300, height: 1600};
// A page that has not loaded in this time is a failure (file:// pages load in well under 1 s).
const kLoadTimeoutMs = 30000;
// Screenshots: the top of the page, at most this tall (whole reports are tens of thousands of
// pixels; the top shows the layout, and the test's failures name what is below).
const kShotMaxHeight = 2400;

function parseArgs(argv) {
  const out = {requireStateCards: false, shots: null, pages: []};
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--require-state-cards') out.requireStateCards = true;
    else if (argv[i] === '--shots') out.shots = argv[++i];
    else out.pages.push(argv[i]);
  }
  return out;
}

// What kind of page: 'report', 'dump' (index.html with passes.json beside it) or 'lesson'.
function kindOf(file, html) {
  if (path.basename(file) === 'report.html') return 'report';
  if (html.includes('<section class="pass"')) return 'lesson';
  if (fs.existsSync(path.join(path.dirname(file), 'passes.json'))) return 'dump';
  return 'page';
}

let linkSeconds = 0;  // reading the pages' links and ids, and checking them

async function checkPage(browser, checker, file, options, failures) {
  const fail = (what) => failures.push(`${file}: ${what}`);
  const html = fs.readFileSync(file, 'utf8');
  const kind = kindOf(file, html);
  const page = await browser.newPage();
  await page.setViewport(kViewport);
  page.on('console', (m) => { if (m.type() === 'error') fail(`console error: ${m.text()}`); });
  page.on('pageerror', (e) => fail(`script error: ${e.message}`));
  page.on('requestfailed', (r) => fail(`request failed: ${r.url()} (${r.failure().errorText})`));
  await page.goto(url.pathToFileURL(path.resolve(file)).href,
                  {waitUntil: 'load', timeout: kLoadTimeoutMs});
  const result = await page.evaluate(() => {
    const images = Array.from(document.querySelectorAll('img'));
    return {
      images: images.length,
      broken: images.filter((i) => !(i.complete && i.naturalWidth > 0))
                  .map((i) => i.getAttribute('src')),
      links: Array.from(document.querySelectorAll('a[href]')).map((a) => a.getAttribute('href')),
      text: document.body.innerText,
      passes: Array.from(document.querySelectorAll('section.pass')).map((s) => ({
        id: s.id,
        cards: s.querySelectorAll('.state-card').length,
        missing: s.querySelectorAll('.state-card.missing').length,
      })),
    };
  });
  for (const src of result.broken) fail(`broken image ${src} (naturalWidth 0)`);
  const readStart = Date.now();
  const links = await checker.read(file, page);
  linkSeconds += (Date.now() - readStart) / 1000;
  if (kind === 'lesson') {
    if (result.passes.length === 0) fail('a lesson without a pass');
    for (const p of result.passes) {
      if (p.cards !== 1) fail(`pass ${p.id}: ${p.cards} state cards, expected 1`);
      else if (options.requireStateCards && p.missing)
        fail(`pass ${p.id}: state card not recorded`);
    }
  }
  if (kind === 'dump') {
    const passes = JSON.parse(fs.readFileSync(path.join(path.dirname(file), 'passes.json')));
    if (result.images === 0) fail('a dump page without an image');
    if (options.requireStateCards) {
      for (const p of passes.passes) {
        const state = p.state;
        // An empty list is a record too: the pass made no GL call (the ray-traced references).
        if (!Array.isArray(state)) {
          fail(`pass ${p.number} (${p.name}): no state card in passes.json`);
          continue;
        }
        // The page must show the card: every line's text appears on it.
        for (const line of state) {
          const text = typeof line === 'object' && line !== null ? line.text : String(line);
          if (!result.text.includes(text)) {
            fail(`pass ${p.number}: state line not shown on the page: ${text}`);
            break;
          }
        }
      }
    }
  }
  if (kind === 'report') {
    const lessons = result.links.filter((h) => h.startsWith('lessons/'));
    if (lessons.length === 0) fail('report.html links no lesson');
    for (const id of links.articles)
      if (!links.links.some((l) => l.lesson && l.article === id)) fail(`figure ${id} links no lesson`);
  }
  if (options.shots) {
    const dims = await page.evaluate(() => ({h: document.documentElement.scrollHeight}));
    const name = path.relative(process.cwd(), path.resolve(file)).replace(/[\/\\.]+/g, '_');
    await page.screenshot({
      path: path.join(options.shots, name + '.png'),
      clip: {x: 0, y: 0, width: kViewport.width, height: Math.min(dims.h, kShotMaxHeight)},
    });
  }
  await page.close();
  return {kind, images: result.images, passes: result.passes.length};
}

// The figure <-> lesson links of the pages read, both ways (see the header); returns the
// number of links checked.
async function checkFigureLinks(checker, files, failures) {
  let checked = 0;
  const same = (a, b) => a.file === b.file && a.fragment === b.fragment;
  for (const file of files) {
    const from = path.resolve(file);
    const info = await checker.info(from);
    for (const l of info.links) {
      const t = LinkChecker.target(from, l.href);
      if (!t || !fs.existsSync(t.file)) continue;  // an absolute link; a missing file is failed above
      if (l.figureList && t.fragment) {  // a page's link to a report figure
        checked += 1;
        const report = await checker.info(t.file);
        const back = report.links.some((r) => r.lesson && r.article === t.fragment &&
                                              same(LinkChecker.target(t.file, r.href), {file: from, fragment: ''}));
        if (!back) failures.push(`${file}: links ${l.href}, whose figure does not link this page back`);
      }
      if (l.lesson && l.article) {  // a report figure's link to a lesson
        checked += 1;
        const lesson = await checker.info(t.file);
        const back = lesson.links.some((r) => r.figureList &&
                                              same(LinkChecker.target(t.file, r.href), {file: from, fragment: l.article}));
        if (!back) failures.push(`${file}: figure ${l.article} links ${l.href}, which does not link the figure back`);
      }
    }
  }
  return checked;
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  if (options.pages.length === 0) {
    console.error('usage: node check_pages.mjs [--require-state-cards] [--shots DIR] PAGE.html ...');
    process.exit(2);
  }
  if (options.shots) fs.mkdirSync(options.shots, {recursive: true});
  const started = Date.now();
  const browser = await launchChromium();
  const checker = new LinkChecker(browser);
  const failures = [];
  let pairs = 0;
  try {
    for (const file of options.pages) {
      const before = failures.length;
      const r = await checkPage(browser, checker, file, options, failures);
      console.log(`${failures.length === before ? 'ok  ' : 'FAIL'} ${r.kind} ${file} ` +
                  `(${r.images} images${r.kind === 'lesson' ? `, ${r.passes} passes` : ''})`);
    }
    const checkStart = Date.now();
    for (const file of options.pages)
      await checker.check(path.resolve(file), (what) => failures.push(what));
    pairs = await checkFigureLinks(checker, options.pages, failures);
    linkSeconds += (Date.now() - checkStart) / 1000;
  } finally {
    await browser.close();
  }
  for (const f of failures) console.error(f);
  console.log(`${options.pages.length} pages, ${checker.links} relative links (${checker.fragments} ` +
              `with a #fragment, ${checker.pages.size - options.pages.length} further pages ` +
              `loaded for their ids), ${pairs} figure/lesson links checked both ways, ` +
              `${failures.length} failures, ${((Date.now() - started) / 1000).toFixed(1)} s ` +
              `(the link check's own part: ${linkSeconds.toFixed(1)} s)`);
  process.exit(failures.length === 0 ? 0 : 1);
}

main().catch((e) => {
  console.error(`check_pages.mjs: ${e.stack || e}`);
  process.exit(1);
});
