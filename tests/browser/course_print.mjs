// tests/browser/course_print.mjs — the course's pages as a teacher prints them: each page printed
// to PDF on A4 and on US Letter by Debian's headless Chromium (puppeteer-core), its pages counted.
//   index.html:         the order on its own page, then one page per step (steps + 1 pages);
//   teacher.html:       about one page per step, then the graded exercises (at most steps + 2);
//   both:               every step after the first starts a new page (print media's computed
//                       break-before), so the page counts mean one step a page;
//   gallery/index.html: at most one page per artefact (plus the list's page).
// usage: node course_print.mjs COURSE_DIR
import path from 'node:path';
import url from 'node:url';
import { embeddedJson, launchChromium } from './harness.mjs';

const dir = path.resolve(process.argv[2]);
const steps = new Set(embeddedJson(dir, 'course-data').map((e) => e.step)).size;
const artefacts = embeddedJson(path.join(dir, 'gallery'), 'gallery-data').length;
const expectations = [
  { page: 'index.html', min: steps + 1, max: steps + 1, stepPages: true },
  { page: 'teacher.html', min: steps, max: steps + 2, stepPages: true },
  { page: 'gallery/index.html', min: 1, max: artefacts + 1, stepPages: false },
];

let failures = 0;
const browser = await launchChromium();
try {
  for (const { page: file, min, max, stepPages } of expectations) {
    const page = await browser.newPage();
    await page.goto(url.pathToFileURL(path.join(dir, file)).href, { waitUntil: 'load' });
    if (stepPages) {
      await page.emulateMediaType('print');
      // Every section.step (the teacher's graded exercises are one too) but the first.
      const breaks = await page.$$eval('section.step', (xs) =>
        xs.map((x) => ({ id: x.id, before: getComputedStyle(x).breakBefore })));
      const stepSections = breaks.filter((b) => b.id.startsWith('step-')).length;
      const unbroken = breaks.slice(1).filter((b) => b.before !== 'page').length;
      if (stepSections !== steps || unbroken > 0) {
        console.log(`FAIL: ${file}: ${stepSections} of ${steps} steps, ${unbroken} sections ` +
                    'after the first do not start a printed page');
        failures += 1;
      }
      await page.emulateMediaType(null);
    }
    for (const format of ['A4', 'Letter']) {
      const pdf = Buffer.from(await page.pdf({ format }));
      // One "/Type /Page" object per printed page ("/Type /Pages" is the tree, not a page).
      const pages = (pdf.toString('latin1').match(/\/Type\s*\/Page(?![s\w])/g) || []).length;
      const ok = pages >= min && pages <= max;
      console.log(`${ok ? 'ok' : 'FAIL'}: ${file} prints on ${pages} ${format} pages ` +
                  `(expected ${min}-${max})`);
      if (!ok) failures += 1;
    }
    await page.close();
  }
} finally {
  await browser.close();
}
process.exitCode = failures ? 1 : 0;
