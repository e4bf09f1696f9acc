// node hostile_names_test.mjs MODULES_DIR CHROMIUM REPORT.html NAMES.json: opens a report.html whose scene
// carries markup in every name it can (cells, portals, cameras, title, warnings, timings, parameters) in
// headless Chromium and checks that none of it runs or becomes markup (issue 49, items 6 and 7):
//  - the page loads with no script error, the viewer starts and the status line is empty;
//  - after ticking "colour by cell" (where the legend lists the cells), and in every mode, no hostile
//    handler ran (window.__pwned stays undefined) and no <img> or extra <script> element exists;
//  - every name of NAMES.json shows as text: in the legend, the tables and the view list.
// Exits 1 with one line per failed check.
import fs from 'node:fs';
import path from 'node:path';
import { Checks, launchPage } from './page_harness.mjs';

const [modules, chromium, report, namesFile] = process.argv.slice(2);
if (!namesFile) {
  console.error('usage: node hostile_names_test.mjs NODE_MODULES_DIR CHROMIUM REPORT.html NAMES.json');
  process.exit(2);
}
const names = JSON.parse(fs.readFileSync(namesFile, 'utf8'));
const checks = new Checks();
const { check } = checks;

const { browser, page, errors } = await launchPage(modules, chromium);
try {
  await page.goto('file://' + path.resolve(report), { waitUntil: 'load', timeout: 120000 });
  await page.waitForFunction(() => window.cpgiViewer !== undefined || document.getElementById('status')?.textContent,
    { timeout: 60000 });
  const status = await page.evaluate(() => document.getElementById('status').textContent);
  check(!status, 'status line says: ' + status);
  await page.evaluate(() => window.cpgiViewer.ready);

  // The user ticks "colour by cell": the legend lists the cells by name.
  await page.click('input[name=mode][value=cells]');
  await new Promise((r) => setTimeout(r, 300));
  const legend = await page.evaluate(() => document.getElementById('legend').textContent);
  for (const n of names.cells) check(legend.includes(n), `legend: cell name ${JSON.stringify(n)} is not shown as text`);
  for (const mode of ['light', 'density', 'cells']) {
    await page.evaluate((m) => { const r = document.querySelector(`input[name=mode][value=${m}]`); if (r) r.click(); }, mode);
  }
  await new Promise((r) => setTimeout(r, 300));

  const seen = await page.evaluate(() => ({
    pwned: window.__pwned,
    images: document.images.length,
    scripts: document.scripts.length,
    panels: document.getElementById('panels').textContent,
    title: document.getElementById('title').textContent,
    views: [...document.querySelectorAll('#views option')].map((o) => o.textContent),
  }));
  check(seen.pwned === undefined, `a handler from a name ran (window.__pwned = ${seen.pwned})`);
  check(seen.images === 0, `${seen.images} <img> elements were made from names`);
  check(seen.scripts === 3, `${seen.scripts} script elements (the page has 3)`);
  check(seen.title === names.title, `title shows ${JSON.stringify(seen.title)}`);
  for (const n of names.tables) check(seen.panels.includes(n), `tables: ${JSON.stringify(n)} is not shown as text`);
  for (const n of names.views) check(seen.views.some((v) => v.includes(n)), `views: ${JSON.stringify(n)} not listed`);
  check(!errors.length, errors.join('; '));
} finally {
  await browser.close();
}
checks.exit('hostile names test: ');
