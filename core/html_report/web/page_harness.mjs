// What the browser tests share (engine_glb_test, engine_directional_test, hostile_names_test): the npm
// packages of MODULES_DIR, a page bundling a script with the bake's files embedded, headless Chromium with
// software WebGL whose page errors are collected, and the checks that failed.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

// The script's arguments by `names` (the last required, any after it optional): a missing one prints the
// usage line and exits 2; the folder named by `folder` (SCREENSHOT_DIR) is made.
export function scriptArgs(script, names, optional = [], folder = 'SCREENSHOT_DIR') {
  const args = process.argv.slice(2);
  if (args.length < names.length) {
    console.error(`usage: node ${script} ${[...names, ...optional.map((o) => `[${o}]`)].join(' ')}`);
    process.exit(2);
  }
  const at = names.indexOf(folder);
  if (at >= 0) fs.mkdirSync(args[at], { recursive: true });
  return args;
}

// `require` of the packages installed in `modules` (build/web/node_modules).
export const modulesRequire = (modules) => createRequire(path.join(path.resolve(modules), 'noop.js'));

// Writes to `pagePath` a page of a 640 × 480 canvas (id "view"), each file of `files` ({ id: path }) as
// base64 in a <script id=…> block, and `entry` bundled by esbuild from `modules` (an inline script: the
// page reads its data without a server).
export function writeBundlePage(modules, entry, files, pagePath) {
  const bundle = modulesRequire(modules)('esbuild').buildSync({
    stdin: { contents: entry, resolveDir: path.resolve(modules) },
    bundle: true, format: 'iife', write: false, nodePaths: [path.resolve(modules)], logLevel: 'error',
  }).outputFiles[0].text;
  const blocks = Object.entries(files).map(([id, file]) =>
    `<script id="${id}" type="application/octet-stream">${fs.readFileSync(file).toString('base64')}</script>`);
  fs.writeFileSync(pagePath, `<!doctype html><html><body style="margin:0">` +
    `<canvas id="view" width="640" height="480"></canvas>\n${blocks.join('\n')}\n` +
    `<script>${bundle.replace(/<\/script/gi, '<\\/script')}</script></body></html>`);
}

// Calls the page's functions `steps` ([name, screenshot file or null], in order) and saves each screenshot
// in `shots`; returns the first call's result (the page's figures).
export async function runSteps(page, shots, steps) {
  let first;
  for (const [name, png] of steps) {
    const result = await page.evaluate((f) => window[f](), name);
    if (first === undefined) first = result;
    if (png) await page.screenshot({ path: path.join(shots, png) });
  }
  return first;
}

// In-page source for an entry of writeBundlePage: viewCamera(THREE, gltf), the glb's first camera, else
// one framing its whole scene from above and in front; either at the page's 640 × 480.
export const viewCameraSource = `
const viewCamera = (THREE, gltf) => {
  let camera = gltf.cameras[0];
  if (!camera) {
    const box = new THREE.Box3().setFromObject(gltf.scene), size = box.getSize(new THREE.Vector3());
    camera = new THREE.PerspectiveCamera(60, 4 / 3, 0.01, 1000);
    camera.position.copy(box.getCenter(new THREE.Vector3())).add(new THREE.Vector3(0, size.y * 0.3, size.length() * 0.6));
    camera.lookAt(box.getCenter(new THREE.Vector3()));
  }
  camera.aspect = 640 / 480;
  camera.updateProjectionMatrix();
  return camera;
};`;

// Headless Chromium (software WebGL through SwiftShader) with one page whose script errors, console errors
// and dialogs are collected in `errors`; the caller navigates and closes `browser`.
export async function launchPage(modules, chromium, viewport = { width: 640, height: 480 }) {
  const browser = await modulesRequire(modules)('puppeteer-core').launch({
    executablePath: chromium,
    headless: true,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
      '--disable-dev-shm-usage', '--no-first-run'],
  });
  const page = await browser.newPage();
  await page.setViewport(viewport);
  const errors = [];
  page.on('pageerror', (e) => errors.push('page error: ' + e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push('console error: ' + m.text().slice(0, 600)); });
  page.on('dialog', async (d) => { errors.push('a dialog opened: ' + d.message()); await d.dismiss(); });
  return { browser, page, errors };
}

// launchPage, then the page at `pagePath` loaded (a file: its script has run when this returns).
export async function openPage(modules, chromium, pagePath) {
  const opened = await launchPage(modules, chromium);
  await opened.page.goto('file://' + path.resolve(pagePath), { waitUntil: 'load', timeout: 120000 });
  return opened;
}

// The failed checks, each a line; `exit` prints them with `prefix` and ends the process (1 if any failed).
export class Checks {
  failures = [];
  check = (ok, message) => { if (!ok) this.failures.push(message); };
  exit(prefix) {
    for (const f of this.failures) console.error(prefix + f);
    process.exit(this.failures.length ? 1 : 0);
  }
}
