// node browser_test.mjs MODULES_DIR CHROMIUM REPORT.html SCREENSHOT_DIR: opens a report.html in headless
// Chromium (puppeteer-core, software WebGL through SwiftShader) and checks that the 3D view shows the bake:
//  - the page loads from file:// with no script error and nothing fetched from the network;
//  - the canvas drew the scene: its pixels vary, and where the lightmap holds more light the picture is
//    brighter (rank correlation over a grid of pixels, lit quarter against dark quarter);
//  - colour by cell paints several cells in distinct hues; texel density, portals and (for a comparison)
//    the error heat map change the picture;
//  - the views from inside each cell are readable (exposed for what they see); walking moves the camera;
//  - the tables of report.json are there, and the bench chart when the page has bench rows;
//  - with light probes, the probe-lit sphere shows, lit from above more than from below; set on a probe
//    of a lit room, its shading is that probe's irradiance from probes.json (computed here) at band 4
//    (the bake's L2 + band 4), not at L2 alone; beside a probe of another room it takes its own room's
//    probes alone; with the directional lightmap, the normal-mapped surfaces change the picture.
// Saves light.png, overview.png, cells.png, density.png, portals.png, exposure+2.png, view-NAME.png (one per
// cell) and page.png in SCREENSHOT_DIR; prints a JSON
// summary of the figures; exits 1 with one line per failed check.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

// A probe's irradiance E(n) (W/m², [r, g, b]) from probes.json as the bake convolves it
// (radiosity/lightmap/spherical_harmonics.cpp, probes.json's convention): L2 with A = π, 2π/3, π/4, and at
// band 4 also A_4 = −π/24 times the band-4 basis. Written here apart from the page's shader, which is
// what it checks.
function probeIrradiance(probe, n, band) {
  const [x, y, z] = n, x2 = x * x, y2 = y * y, z2 = z * z, pi = Math.PI;
  const l2 = [pi * 0.282095, (2 * pi / 3) * 0.488603 * y, (2 * pi / 3) * 0.488603 * z, (2 * pi / 3) * 0.488603 * x,
    (pi / 4) * 1.092548 * x * y, (pi / 4) * 1.092548 * y * z, (pi / 4) * 0.315392 * (3 * z2 - 1),
    (pi / 4) * 1.092548 * x * z, (pi / 4) * 0.546274 * (x2 - y2)];
  const l4 = [2.503343 * x * y * (x2 - y2), 1.770131 * y * z * (3 * x2 - y2), 0.946175 * x * y * (7 * z2 - 1),
    0.669046 * y * z * (7 * z2 - 3), 0.105786 * (35 * z2 * z2 - 30 * z2 + 3), 0.669046 * x * z * (7 * z2 - 3),
    0.473087 * (x2 - y2) * (7 * z2 - 1), 1.770131 * x * z * (x2 - 3 * y2),
    0.625836 * (x2 * (x2 - 3 * y2) - y2 * (3 * x2 - y2))].map((v) => (-pi / 24) * v);
  return [0, 1, 2].map((c) => {
    let e = 0;
    for (let k = 0; k < 9; ++k) e += l2[k] * probe.sh[k][c] + (band === 4 ? l4[k] * probe.sh_l4[k][c] : 0);
    return Math.max(e, 0);
  });
}

// Where to look from at `probe` so that the page's sphere (1.5 m ahead of the camera) sits on it: from
// the side of its room's middle (the mean of its cell's probes), 30° above it, so the camera stays in the
// room and sees the sphere's top, which faces the lamp. Null when that eye would leave the box of the
// cell's probes.
function eyeOnProbe(probe, probes) {
  const mates = probes.filter((p) => p.cell === probe.cell);
  const mean = [0, 1, 2].map((a) => mates.reduce((s, p) => s + p.position[a], 0) / mates.length);
  const lo = [0, 1, 2].map((a) => Math.min(...mates.map((p) => p.position[a])));
  const hi = [0, 1, 2].map((a) => Math.max(...mates.map((p) => p.position[a])));
  const [px, py, pz] = probe.position;
  let hx = px - mean[0], hz = pz - mean[2];
  const h = Math.hypot(hx, hz);
  [hx, hz] = h > 1e-3 ? [hx / h, hz / h] : [1, 0];
  const down = Math.PI / 6, ahead = [Math.cos(down) * hx, -Math.sin(down), Math.cos(down) * hz];
  const eye = [px - 1.5 * ahead[0], py - 1.5 * ahead[1], pz - 1.5 * ahead[2]];
  const inside = [0, 1, 2].every((a) => eye[a] >= lo[a] - 1e-3 && eye[a] <= hi[a] + 1e-3);
  return inside ? { eye, look: probe.position, ahead } : null;
}

// The probes' L2 and band-4 SH at `point` blended as report.html is to blend them: the eight nearest of
// the nearest probe's room by inverse squared distance (`sameRoom` false: of any room, as before).
function blendedProbe(probes, point, sameRoom = true) {
  const byDistance = probes.map((p) => ({ p, d2: p.position.reduce((s, x, a) => s + (x - point[a]) ** 2, 0) }))
    .sort((a, b) => a.d2 - b.d2);
  const near = byDistance.filter(({ p }) => !sameRoom || p.cell === byDistance[0].p.cell).slice(0, 8);
  const total = near.reduce((s, { d2 }) => s + 1 / (d2 + 1e-4), 0);
  const blend = (key) => Array.from({ length: 9 }, (_, k) => [0, 1, 2].map((c) =>
    near.reduce((s, { p, d2 }) => s + p[key][k][c] / (d2 + 1e-4), 0) / total));
  return { sh: blend('sh'), sh_l4: blend('sh_l4') };
}

const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

// The relative RMS of (measured − expected) over the mean expected, every pixel and channel pooled.
function relativeRms(samples, expected) {
  let se = 0, sum = 0, count = 0;
  samples.forEach((s, i) => s.e.forEach((e, c) => { se += (e - expected[i][c]) ** 2; sum += expected[i][c]; ++count; }));
  return Math.sqrt(se / count) / (sum / count);
}

const [modules, chromium, report, shots] = process.argv.slice(2);
if (!shots) {
  console.error('usage: node browser_test.mjs NODE_MODULES_DIR CHROMIUM REPORT.html SCREENSHOT_DIR');
  process.exit(2);
}
const puppeteer = createRequire(path.join(path.resolve(modules), 'noop.js'))('puppeteer-core');
fs.mkdirSync(shots, { recursive: true });

const failures = [];
const check = (ok, message) => { if (!ok) failures.push(message); };
const summary = {};
const started = Date.now();
const lap = (name) => { (summary.seconds ||= {})[name] = (Date.now() - started) / 1000; };

const browser = await puppeteer.launch({
  executablePath: chromium,
  headless: true,
  // No GPU: WebGL through SwiftShader. --no-sandbox because CI runs as root.
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
    '--disable-dev-shm-usage', '--no-first-run'],
});
try {
  lap('launched');
  const page = await browser.newPage();
  await page.setViewport({ width: 960, height: 900 });
  const errors = [], requests = [];
  page.on('pageerror', (e) => errors.push('page error: ' + e.message));
  page.on('console', (m) => { if (m.type() === 'error') errors.push('console error: ' + m.text()); });
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:') && !r.url().startsWith('blob:')) requests.push(r.url()); });
  await page.goto('file://' + path.resolve(report), { waitUntil: 'load', timeout: 120000 });
  await page.waitForFunction(() => window.cpgiViewer !== undefined || document.getElementById('status').textContent, { timeout: 60000 });
  const status = await page.evaluate(() => document.getElementById('status').textContent);
  check(!status, 'status line says: ' + status);
  await page.evaluate(() => window.cpgiViewer.ready);
  lap('loaded');

  // Pixels of the canvas as luminance and hue, after one render with the current settings.
  // The pixels stay in the page (window.shots[name]): sending them over the DevTools protocol is slow.
  const capture = (name) => page.evaluate(async (name) => {
    const v = window.cpgiViewer;
    v.render();
    const c = v.canvas, ctx = document.createElement('canvas').getContext('2d');
    ctx.canvas.width = c.width, ctx.canvas.height = c.height;
    ctx.drawImage(c, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let sum = 0, sum2 = 0;
    const hues = new Array(12).fill(0);
    for (let i = 0; i < d.length; i += 4) {
      const r = d[i] / 255, g = d[i + 1] / 255, b = d[i + 2] / 255;
      const y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
      sum += y, sum2 += y * y;
      const max = Math.max(r, g, b), min = Math.min(r, g, b);
      if (max > 0.15 && max - min > 0.25 * max) {
        let h = max === r ? (g - b) / (max - min) : max === g ? 2 + (b - r) / (max - min) : 4 + (r - g) / (max - min);
        hues[Math.floor((((h * 60) % 360) + 360) % 360 / 30)] += 1;
      }
    }
    const n = d.length / 4, mean = sum / n;
    (window.shots ||= {})[name] = d;
    return { mean, std: Math.sqrt(Math.max(0, sum2 / n - mean * mean)), hues: hues.map((h) => h / n) };
  }, name).then(async (r) => {
    await page.screenshot({ path: path.join(shots, name + '.png'), clip: await canvasBox() });
    return r;
  });
  // Mean absolute difference of two captures, 0-255 per channel; with `fraction`, the share of pixels
  // that differ by more than 24 levels in some channel instead (for small changes such as doors).
  const meanAbsDiff = (first, second, fraction = false) => page.evaluate((first, second, fraction) => {
    const a = window.shots[first], b = window.shots[second];
    let s = 0, changed = 0;
    for (let i = 0; i < a.length; i += 4) {
      const d = [0, 1, 2].map((k) => Math.abs(a[i + k] - b[i + k]));
      s += d[0] + d[1] + d[2];
      changed += Math.max(...d) > 24;
    }
    return fraction ? changed / (a.length / 4) : s / (a.length / 4) / 3;
  }, first, second, fraction);
  const canvasBox = async () => {
    const box = await (await page.$('#scene')).boundingBox();
    return { x: box.x, y: box.y, width: box.width, height: box.height };
  };

  // The sphere set on the probe of probes.json where band 4 changes the irradiance most (seen from the
  // eye eyeOnProbe gives, on normals facing it): its pixels, the tone map and sRGB undone, give E(n) on
  // the sphere's normals; that must be the probe's band-4 irradiance, and clearly not its L2 alone.
  const checkSphereOnAProbe = async (file) => {
    const probes = file.probes || [];
    if (!probes.length || !probes.every((p) => Array.isArray(p.sh_l4))) {
      check(!probes.length, 'probe sphere: probes.json holds no band 4 (sh_l4)');
      return null;
    }
    const golden = Math.PI * (3 - Math.sqrt(5));
    const sphere = Array.from({ length: 400 }, (_, i) => {
      const y = 1 - (2 * (i + 0.5)) / 400, r = Math.sqrt(1 - y * y);
      return [r * Math.cos(golden * i), y, r * Math.sin(golden * i)];
    });
    const brightest = Math.max(...probes.map((p) => probeIrradiance(p, [0, 1, 0], 4)[1]));
    let best = null;
    for (const p of probes) {
      const view = eyeOnProbe(p, probes);
      if (!view) continue;
      const facing = sphere.filter((n) => -(n[0] * view.ahead[0] + n[1] * view.ahead[1] + n[2] * view.ahead[2]) > 0.35);
      const e4 = facing.map((n) => probeIrradiance(p, n, 4)), e2 = facing.map((n) => probeIrradiance(p, n, 2));
      const mean = e4.reduce((s, e) => s + e[1], 0) / e4.length;
      if (mean < 0.1 * brightest) continue;  // a dark probe: the 8-bit pixels would say little
      const gap = relativeRms(e2.map((e) => ({ e })), e4);
      if (!best || gap > best.gap) best = { probe: p, view, gap, top: Math.max(...e4.flat()) };
    }
    if (!best) return check(false, 'probe sphere: no lit probe to set the sphere on'), null;
    const exposure = (1.9 * Math.PI) / (0.8 * best.top);  // the brightest pixel at 1 − e^−1.9 = 0.85
    const saved = await page.evaluate((view, exposure) => {
      const v = window.cpgiViewer, saved = v.exposure;
      const xyz = ([x, y, z]) => ({ x, y, z });
      v.showView({ name: 'on a probe', eye: xyz(view.eye), look: xyz(view.look) });
      v.setExposure(exposure);
      return saved;
    }, best.view, exposure);
    await capture('probe-sphere-on-a-probe');
    const pixels = await page.evaluate(() => {
      const v = window.cpgiViewer, cam = v.camera, c = v.probeSphere.position, w = v.canvas.width, h = v.canvas.height;
      const radius = 0.15, data = window.shots['probe-sphere-on-a-probe'], out = [];
      const centre = c.clone().project(cam), cx = ((centre.x + 1) / 2) * w, cy = ((1 - centre.y) / 2) * h;
      const span = Math.ceil((Math.asin(radius / cam.position.distanceTo(c)) * h) / 2 / Math.tan((cam.fov * Math.PI) / 360) * 1.3);
      for (let y = Math.max(0, Math.floor(cy - span)); y < Math.min(h, cy + span); y += 2)
        for (let x = Math.max(0, Math.floor(cx - span)); x < Math.min(w, cx + span); x += 2) {
          const d = c.clone().set(((x + 0.5) / w) * 2 - 1, 1 - ((y + 0.5) / h) * 2, 0.5).unproject(cam).sub(cam.position).normalize();
          const o = cam.position.clone().sub(c), b = o.dot(d), disc = b * b - (o.lengthSq() - radius * radius);
          if (disc <= 0) continue;
          const n = o.addScaledVector(d, -b - Math.sqrt(disc)).divideScalar(radius);
          if (-n.dot(d) < 0.35) continue;  // the rim: antialiased and tessellated
          const i = 4 * (y * w + x);
          out.push({ n: n.toArray(), rgb: [data[i], data[i + 1], data[i + 2]] });
        }
      return out;
    });
    await page.evaluate((saved) => { window.cpgiViewer.setExposure(saved); }, saved);
    const linear = (v) => (v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4);
    const samples = pixels.filter((s) => s.rgb.every((v) => v > 10 && v < 243))
      .map((s) => ({ n: s.n, e: s.rgb.map((v) => (-Math.log(1 - linear(v / 255)) * Math.PI) / (0.8 * exposure)) }));
    const e4 = samples.map((s) => probeIrradiance(best.probe, s.n, 4)), e2 = samples.map((s) => probeIrradiance(best.probe, s.n, 2));
    const figures = { probe: best.probe.position, cell: best.probe.cell, pixels: samples.length,
      band4VsL2: relativeRms(e2.map((e) => ({ e })), e4), band4: relativeRms(samples, e4), l2: relativeRms(samples, e2) };
    check(samples.length >= 300, `probe sphere on a probe: only ${samples.length} pixels read`);
    check(figures.band4VsL2 > 0.02, `probe sphere on a probe: band 4 and L2 differ by ${figures.band4VsL2} there, too little to tell`);
    check(figures.band4 < 0.02, `probe sphere on a probe: the shading is ${(100 * figures.band4).toFixed(2)} % off the probe's band-4 irradiance`);
    check(figures.l2 > 2 * figures.band4, `probe sphere on a probe: the shading is as near L2 (${figures.l2}) as band 4 (${figures.band4})`);
    figures.besideAWall = await checkSphereBesideAWall(probes);
    return figures;
  };
  // The sphere 0.15 m from the brightest probe, with the darkest probe of another room moved 0.5 m from it
  // (as a probe behind a thin wall can stand): the SH the page gives the sphere must be the blend of its own
  // room's probes, which that probe would otherwise darken.
  const checkSphereBesideAWall = async (probes) => {
    const green = (p) => p.sh[0][1];
    const lit = probes.reduce((a, b) => (green(b) > green(a) ? b : a));
    const others = probes.filter((q) => q.cell !== lit.cell);
    if (!others.length) return null;  // one room
    const dark = others.reduce((a, b) => (green(b) < green(a) ? b : a));
    const dir = [1, 0, 0];
    const moved = probes.map((q) => (q === dark ? { ...q, position: lit.position.map((x, a) => x + 0.5 * dir[a]) } : q));
    const point = lit.position.map((x, a) => x + 0.15 * dir[a]);
    const own = blendedProbe(moved, point), any = blendedProbe(moved, point, false);
    const change = Math.abs(own.sh[0][1] - any.sh[0][1]) / Math.max(own.sh[0][1], 1e-9);
    const eye = point.map((x, a) => x - 1.5 * dir[a]);
    const given = await page.evaluate((eye, look, moved) => {
      const v = window.cpgiViewer, xyz = ([x, y, z]) => ({ x, y, z }), probes = v.probes;
      v.probes = moved;
      v.showView({ name: 'beside a wall', eye: xyz(eye), look: xyz(look) });
      v.render();
      v.probes = probes;
      const u = v.probeSphere.material.uniforms;
      return { at: v.probeSphere.position.toArray(), sh: u.sh.value.map((c) => c.toArray()), sh4: u.sh4.value.map((c) => c.toArray()) };
    }, eye, point, moved);
    let worst = 0;
    for (let k = 0; k < 9; ++k)
      for (let c = 0; c < 3; ++c) {
        const scale = Math.abs(own.sh[0][c]) + 1e-6;
        worst = Math.max(worst, Math.abs(given.sh[k][c] - own.sh[k][c]) / scale, Math.abs(given.sh4[k][c] - own.sh_l4[k][c]) / scale);
      }
    const figures = { point, sphereAt: given.at, movedProbesShare: change, worst };
    check(dist(given.at, point) < 1e-3, `probe sphere beside a wall: it stands at ${given.at}, not ${point}`);
    check(change > 0.01, `probe sphere beside a wall: the moved probe changes its light by ${change} only, too little to tell`);
    check(worst < 1e-4, `probe sphere beside a wall: its SH are off its own room's probes' blend by ${worst} (another room's probe lights it)`);
    return figures;
  };

  // 1. Light: from inside a cell (a view a person would take), where lit walls and shadows both show.
  const views = await page.evaluate(() => window.cpgiViewer.views.map((v) => v.name));
  const inside = views.find((v) => v.startsWith('camera ')) || views.find((v) => v.startsWith('in ')) || views[0];
  await page.evaluate((v) => { window.cpgiViewer.showView(v); window.cpgiViewer.setMode('light'); }, inside);
  const light = await capture('light');
  summary.view = inside;
  summary.light = { mean: light.mean, std: light.std };
  check(light.std > 0.04, `light: the picture hardly varies (luminance std ${light.std.toFixed(3)})`);
  check(light.mean > 0.03, `light: the picture is black (mean luminance ${light.mean.toFixed(3)})`);

  // Where the lightmap is brighter, the pixel is: Spearman correlation over a 32 × 24 grid.
  const pairs = await page.evaluate(() => {
    const v = window.cpgiViewer, w = v.canvas.width, h = v.canvas.height, out = [], pixels = window.shots.light;
    for (let gy = 0; gy < 24; ++gy)
      for (let gx = 0; gx < 32; ++gx) {
        const x = Math.floor(((gx + 0.5) / 32) * w), y = Math.floor(((gy + 0.5) / 24) * h);
        const expected = v.expectedRadianceAt(x + 0.5, y + 0.5);
        if (expected === null || !(expected >= 0)) continue;
        const i = 4 * (y * w + x);
        out.push([expected, 0.2126 * pixels[i] + 0.7152 * pixels[i + 1] + 0.0722 * pixels[i + 2]]);
      }
    return out;
  });
  const ranks = (xs) => {
    const order = xs.map((x, i) => [x, i]).sort((a, b) => a[0] - b[0]), r = new Array(xs.length);
    order.forEach(([, i], k) => { r[i] = k; });
    return r;
  };
  const pearson = (a, b) => {
    const n = a.length, ma = a.reduce((s, x) => s + x, 0) / n, mb = b.reduce((s, x) => s + x, 0) / n;
    let sab = 0, saa = 0, sbb = 0;
    for (let i = 0; i < n; ++i) sab += (a[i] - ma) * (b[i] - mb), saa += (a[i] - ma) ** 2, sbb += (b[i] - mb) ** 2;
    return sab / Math.sqrt(saa * sbb);
  };
  const rho = pairs.length > 10 ? pearson(ranks(pairs.map((p) => p[0])), ranks(pairs.map((p) => p[1]))) : NaN;
  const sorted = [...pairs].sort((a, b) => a[0] - b[0]), q = Math.floor(sorted.length / 4);
  const meanOf = (xs) => xs.reduce((s, p) => s + p[1], 0) / Math.max(1, xs.length);
  const dark = meanOf(sorted.slice(0, q)), lit = meanOf(sorted.slice(sorted.length - q));
  summary.correlation = { samples: pairs.length, spearman: rho, litPixel: lit, darkPixel: dark };
  check(pairs.length >= 100, `light: only ${pairs.length} grid pixels see a baked surface`);
  check(rho > 0.7, `light: pixel brightness follows the lightmap poorly (Spearman ${rho.toFixed(3)})`);
  check(lit > 1.5 * dark + 5, `light: lit surfaces (${lit.toFixed(1)}) not brighter than dark ones (${dark.toFixed(1)})`);

  lap('light');
  // 1b. A bake with light probes: the probe-lit sphere, 1.5 m ahead in the same view, shows, and its top
  // (facing the room's ceiling lamp) is brighter than its underside (facing the floor).
  if (await page.evaluate(() => !!window.cpgiViewer.probeSphere)) {
    await page.click('#probe-sphere');
    const sphere = await capture('probe-sphere');
    const probe = await page.evaluate(() => {
      const v = window.cpgiViewer, s = v.probeSphere, w = v.canvas.width, h = v.canvas.height, pixels = window.shots['probe-sphere'];
      const at = (dy) => {
        const p = s.position.clone();
        p.y += dy;
        p.project(v.camera);
        const x = Math.floor(((p.x + 1) / 2) * w), y = Math.floor(((1 - p.y) / 2) * h), i = 4 * (y * w + x);
        return 0.2126 * pixels[i] + 0.7152 * pixels[i + 1] + 0.0722 * pixels[i + 2];
      };
      return { top: at(0.1), bottom: at(-0.1), probes: v.probes.length };
    });
    summary.probeSphere = { ...probe, changed: await meanAbsDiff('light', 'probe-sphere', true) };
    check(summary.probeSphere.changed > 0.002, `probe sphere: the picture did not change (${summary.probeSphere.changed})`);
    check(probe.top > probe.bottom + 10, `probe sphere: its top (${probe.top.toFixed(1)}) is not brighter than its underside (${probe.bottom.toFixed(1)})`);
    check(probe.bottom > 5, `probe sphere: its underside is black (${probe.bottom.toFixed(1)})`);
    const probesFile = path.join(path.dirname(report), 'probes.json');
    if (fs.existsSync(probesFile)) summary.probeShading = await checkSphereOnAProbe(JSON.parse(fs.readFileSync(probesFile, 'utf8')));
    await page.click('#probe-sphere');
  }
  // 1c. A bake with --directional: the normal-mapped surface shows bumps lit by the directional lightmap.
  if (await page.evaluate(() => !!window.cpgiViewer.lightmap?.vector.length)) {
    await page.click('#bumps');
    await capture('bumps');
    summary.bumps = { changed: await meanAbsDiff('light', 'bumps', true), meanDiff: await meanAbsDiff('light', 'bumps') };
    // The bumps shade most pixels by a few levels (tone-mapped), the dark sides of bumps by more.
    check(summary.bumps.meanDiff > 4, `normal map: the picture changed by only ${summary.bumps.meanDiff} levels`);
    check(summary.bumps.changed > 0.005, `normal map: only ${summary.bumps.changed} of the pixels changed by 24 levels`);
    await page.click('#bumps');
  }
  // 2. Colour by cell, from the overview where every cell shows.
  await page.evaluate(() => { window.cpgiViewer.showView('overview'); });
  const overview = await capture('overview');
  // A building's outside cell is hidden at first, so that the overview shows the rooms, not a dark box.
  if (await page.evaluate(() => window.cpgiViewer.outsideCell >= 0)) {
    check(overview.mean > 0.03, `outside: the overview is black with the outside hidden (mean ${overview.mean.toFixed(3)})`);
    await page.evaluate(() => { document.getElementById('outside').click(); });
    const outside = await capture('outside');
    summary.outside = { hidden: overview.mean, shown: outside.mean, changed: await meanAbsDiff('overview', 'outside') };
    check(summary.outside.changed > 5, 'outside: the toggle did not change the picture');
    await page.evaluate(() => { document.getElementById('outside').click(); });
  }
  await page.evaluate(() => { document.querySelector('input[name=mode][value=cells]').click(); });
  const cells = await capture('cells');
  const cellCount = await page.evaluate(() => window.cpgiViewer.cells.length);
  const hueBins = cells.hues.filter((h) => h > 0.005).length;
  summary.cells = { cells: cellCount, hueBins, changed: await meanAbsDiff('overview', 'cells') };
  check(hueBins >= Math.min(cellCount, 3), `cells: ${hueBins} distinct hues for ${cellCount} cells`);
  check(summary.cells.changed > 5, 'cells: the toggle did not change the picture');

  // 3. Texel density and 4. portals (with their labels).
  await page.evaluate(() => { document.querySelector('input[name=mode][value=density]').click(); });
  const density = await capture('density');
  summary.density = { changed: await meanAbsDiff('overview', 'density') };
  check(summary.density.changed > 5, 'density: the toggle did not change the picture');
  await page.evaluate(() => { document.querySelector('input[name=mode][value=light]').click(); document.getElementById('portals').click(); });
  const portals = await capture('portals');
  const labels = await page.evaluate(() => [...document.querySelectorAll('.portal-label')].filter((l) => l.style.display !== 'none').map((l) => l.textContent));
  const portalCount = await page.evaluate(() => (window.cpgiViewer.data.portals || []).length);
  summary.portals = { portals: portalCount, labels, changedPixels: await meanAbsDiff('overview', 'portals', true) };
  if (portalCount) {
    check(labels.length > 0, 'portals: no label shown');
    check(summary.portals.changedPixels > 0.001, 'portals: the toggle did not change the picture');
  }

  lap('cells, density, portals');
  // 4b. A comparison: the error heat map.
  if (await page.evaluate(() => !!window.cpgiViewer.lightmap?.errorTexture)) {
    await page.evaluate(() => { document.getElementById('portals').checked && document.getElementById('portals').click(); document.querySelector('input[name=mode][value=error]').click(); });
    const error = await capture('error');
    summary.error = { changed: await meanAbsDiff('overview', 'error'), mean: error.mean };
    check(summary.error.changed > 5, 'error: the heat map did not change the picture');
    await page.evaluate(() => { document.querySelector('input[name=mode][value=light]').click(); document.getElementById('portals').click(); });
  }

  // 5. The exposure slider brightens the picture.
  await page.evaluate(() => { const s = document.getElementById('exposure'); s.value = '2'; s.dispatchEvent(new Event('input')); });
  const brighter = await capture('exposure+2');
  summary.exposure = { before: portals.mean, after: brighter.mean };
  check(brighter.mean > portals.mean * 1.1, 'exposure: +2 EV did not brighten the picture');

  // 6. Every view from inside a cell, chosen from the list (which exposes for what the camera sees), is
  // readable: the dark middle room of seed1 as much as the lit ones.
  summary.insideViews = {};
  for (const name of views.filter((v) => v.startsWith('in '))) {
    await page.select('#views', name);
    const shot = await capture('view-' + name.slice(3).replace(/[^A-Za-z0-9_-]/g, '_'));
    summary.insideViews[name] = { mean: shot.mean, std: shot.std };
    check(shot.mean > 0.15 && shot.std > 0.02, `view ${name}: unreadable (mean ${shot.mean.toFixed(3)}, std ${shot.std.toFixed(3)})`);
  }
  lap('inside views');

  // 7. Walk: W moves the camera forward along the floor, at the same height.
  await page.click('#walk');
  const before = await page.evaluate(() => window.cpgiViewer.camera.position.toArray());
  // Held until it has moved or 10 s have passed: a frame of software rendering on a loaded machine can
  // take longer than the 0.4 s the key was once held (CI: one frame, 0.024 m).
  await page.keyboard.down('KeyW');
  let after = before, moved = 0;
  for (const start = Date.now(); moved <= 0.05 && Date.now() - start < 10000;) {
    await new Promise((resolve) => setTimeout(resolve, 200));
    after = await page.evaluate(() => window.cpgiViewer.camera.position.toArray());
    moved = Math.hypot(after[0] - before[0], after[2] - before[2]);
  }
  await page.keyboard.up('KeyW');
  summary.walk = { moved, rise: after[1] - before[1] };
  check(moved > 0.05 && Math.abs(after[1] - before[1]) < 1e-6, `walk: W moved the camera ${moved.toFixed(3)} m along the floor`);
  await page.click('#walk');

  // 8. The numbers.
  const tables = await page.evaluate(() => [...document.querySelectorAll('#panels table')].map((t) => t.id + ':' + t.rows.length));
  summary.tables = tables;
  check(tables.some((t) => t.startsWith('parameters-table')), 'panels: no parameters table');
  if (await page.evaluate(() => !!(window.cpgiViewer.data.report.timings || window.cpgiViewer.data.report.timings_s)))
    check(tables.some((t) => t.startsWith('timings-table')), 'panels: no timings table');
  // A bake's cells have texel figures; a decomposition's, cells.json's; a comparison's, compare-light's
  // error per cell: any makes a table, and a comparison's marks its worst cell.
  const cellFigures = await page.evaluate(() => window.cpgiViewer.cells.some((c) => c.texels !== undefined) ||
    (Array.isArray(window.cpgiViewer.data.report.cells) && window.cpgiViewer.data.report.cells.length > 0));
  if (cellFigures) check(tables.some((t) => t.startsWith('cells-table')), 'panels: no cells table');
  const worst = await page.evaluate(() => window.cpgiViewer.data.report.worst_cell);
  if (worst) {
    const marked = await page.evaluate(() => [...document.querySelectorAll('#cells-table tbody tr')]
      .filter((r) => r.cells[1]?.textContent === 'worst').map((r) => r.cells[0].textContent));
    summary.worstCell = marked;
    check(marked.length === 1 && marked[0] === worst, `panels: worst cell ${worst} marked as ${marked}`);
  }
  // Bench rows given (compare-light --bench): one chart per scene, one line per method through its points.
  const bench = await page.evaluate(() => window.cpgiViewer.data.bench || []);
  if (bench.length) {
    const charts = await page.evaluate(() => [...document.querySelectorAll('.bench-chart')].map((f) => ({
      scene: f.dataset.scene,
      lines: [...f.querySelectorAll('polyline.method')].map((l) => [l.dataset.method, l.points.numberOfItems]),
      points: f.querySelectorAll('circle').length,
    })));
    summary.bench = charts;
    const scenes = new Set(bench.map((r) => String(r.scene)));
    check(charts.length === scenes.size, `bench: ${charts.length} charts for ${scenes.size} scenes`);
    for (const c of charts) {
      const rows = bench.filter((r) => String(r.scene) === c.scene);
      check(c.points === rows.length, `bench: ${c.scene} shows ${c.points} points for ${rows.length} rows`);
      check(c.lines.length === new Set(rows.map((r) => r.method)).size, `bench: ${c.scene} lines ${JSON.stringify(c.lines)}`);
    }
  }
  await page.select('#views', 'overview');
  await page.evaluate(() => window.cpgiViewer.render());
  await page.screenshot({ path: path.join(shots, 'page.png'), fullPage: true });

  lap('done');
  check(!errors.length, errors.join('; '));
  check(!requests.length, 'fetched from the network: ' + requests.join(', '));
} finally {
  await browser.close();
}


console.log(JSON.stringify(summary));
for (const f of failures) console.error('browser test: ' + f);
process.exit(failures.length ? 1 : 0);
