// tests/browser/harness.mjs — what the browser tests share: Debian's headless Chromium through
// puppeteer-core (never a downloaded browser), `shadowlab serve` on a free loopback port, the
// JSON a generated page carries, the "key=value" lists the link tests compare, and the check
// of every relative link and #fragment of a page (LinkChecker).
import { spawn } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import url from 'node:url';
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

// ---------------------------------------------------------------- links and anchors
// The link check every generated page gets (check_pages.mjs, course_links.mjs): a relative link
// (<a href>) names a file that exists, and its #fragment an element id of the page it opens as
// the browser loads that page (the DOM's ids, not a regular expression over the HTML); a link
// that is only a #fragment, an id of its own page. Absolute links (http:, https:, mailto:,
// javascript:) are not checked here: the lab links have their own test (course_links.mjs).
// What each page holds is read once (LinkChecker.read on a page already open, or loaded on
// demand) and cached by file.
export class LinkChecker {
  constructor(browser) {
    this.browser = browser;
    this.pages = new Map();  // absolute file -> { ids: Set, links: [{ href, figureList, article, lesson }], articles: [] }
    this.links = 0;          // relative links checked
    this.fragments = 0;      // of those, with a #fragment (or only one)
  }

  // What `page` (open on `file`) holds: its ids, its links (with whether each sits in a list of
  // report figures, ul.report-figures, or is a lesson link, a.lesson, in which <article id>),
  // and its articles' ids.
  async read(file, page) {
    const info = await page.evaluate(() => ({
      ids: Array.from(document.querySelectorAll('[id]')).map((x) => x.id),
      links: Array.from(document.querySelectorAll('a[href]')).map((a) => ({
        href: a.getAttribute('href'),
        figureList: !!a.closest('ul.report-figures'),
        lesson: a.classList.contains('lesson'),
        article: a.closest('article[id]') ? a.closest('article[id]').id : null,
      })),
      articles: Array.from(document.querySelectorAll('article[id]')).map((x) => x.id),
    }));
    const entry = { ids: new Set(info.ids), links: info.links, articles: info.articles };
    this.pages.set(path.resolve(file), entry);
    return entry;
  }

  // The cached reading of `file`, loading it in the browser the first time.
  async info(file) {
    const key = path.resolve(file);
    if (!this.pages.has(key)) {
      const page = await this.browser.newPage();
      await page.goto(url.pathToFileURL(key).href, { waitUntil: 'load' });
      await this.read(key, page);
      await page.close();
    }
    return this.pages.get(key);
  }

  // { file, fragment } a relative href of `from` points at; null for an absolute link.
  static target(from, href) {
    if (/^[a-z][a-z0-9+.-]*:/i.test(href)) return null;
    const hash = href.indexOf('#');
    const file = hash < 0 ? href : href.slice(0, hash);
    const fragment = hash < 0 ? '' : decodeURIComponent(href.slice(hash + 1));
    return { file: file ? path.resolve(path.dirname(from), decodeURIComponent(file)) : path.resolve(from), fragment };
  }

  // Checks every relative link of `file` (read before); fail(message) for each one with no
  // target.
  async check(file, fail) {
    const name = path.relative(process.cwd(), file) || file;
    for (const { href } of (await this.info(file)).links) {
      const t = LinkChecker.target(file, href);
      if (!t) continue;
      this.links += 1;
      if (!existsSync(t.file)) { fail(`${name}: link to a missing file: ${href}`); continue; }
      if (href.includes('#')) {
        this.fragments += 1;
        if (!/\.html?$/i.test(t.file)) continue;  // a fragment of a picture: nothing to resolve
        if (!(await this.info(t.file)).ids.has(t.fragment))
          fail(`${name}: link to #${t.fragment}, which ${path.basename(t.file)} does not have: ${href}`);
      }
    }
  }
}
