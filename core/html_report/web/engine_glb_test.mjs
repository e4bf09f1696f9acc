// node engine_glb_test.mjs MODULES_DIR CHROMIUM BAKE_DIR SCREENSHOT_DIR [textured]: loads a bake's
// baked.glb in three.js (headless Chromium, software WebGL) exactly as docs/engines.md tells an engine
// user to, and checks that it is the engine's file, lit by its lightmap:
//  - every mesh has a lit MeshStandardMaterial (not the unlit preview's MeshBasicMaterial), TEXCOORD_0 and
//    TEXCOORD_1 (three.js's uv and uv1); no portal:/cellvolume: helper and no punctual lamp;
//  - with `textured`, the scene's own base colour textures are there (material.map);
//  - lit by the glb's lightmap on uv1 (lightMap, lightMapIntensity from extras.cpgi_lightmap) the picture is
//    not black and varies; with the lightmap's intensity at 0 it is black (nothing else lights it);
//  - lit instead by lightmap_irradiance.exr (EXRLoader, rows flipped back) the picture agrees with it.
// Saves engine-png.png, engine-exr.png in SCREENSHOT_DIR; prints a JSON summary; exits 1 with one line per
// failed check.
import path from 'node:path';
import { Checks, openPage, runSteps, scriptArgs, viewCameraSource, writeBundlePage } from './page_harness.mjs';

const [modules, chromium, bakeDir, shots, mode] = scriptArgs(
  'engine_glb_test.mjs', ['NODE_MODULES_DIR', 'CHROMIUM', 'BAKE_DIR', 'SCREENSHOT_DIR'], ['textured']);

// The page's script: three.js, its GLTFLoader and EXRLoader, and the steps of docs/engines.md.
const entry = `
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
const bytes = (id) => Uint8Array.from(atob(document.getElementById(id).textContent.trim()), (c) => c.charCodeAt(0)).buffer;
${viewCameraSource}
window.engineTest = async () => {
  const gltf = await new GLTFLoader().parseAsync(bytes('glb'), '');
  const info = gltf.parser.json.extras.cpgi_lightmap;
  const lightMap = await gltf.parser.getDependency('texture', info.texture);
  lightMap.channel = info.texCoord;
  lightMap.colorSpace = THREE.SRGBColorSpace;
  const meshes = [];
  let helpers = 0, lamps = 0;
  gltf.scene.traverse((o) => {
    if (o.isMesh) meshes.push(o);
    if (/^(portal|cellvolume):/.test(o.name)) helpers += 1;
    if (o.isLight) lamps += 1;
  });
  for (const m of meshes) {
    m.material.lightMap = lightMap;
    m.material.lightMapIntensity = info.intensity;
  }
  const facts = {
    meshes: meshes.length, helpers, lamps,
    standard: meshes.filter((m) => m.material.isMeshStandardMaterial).length,
    uv0: meshes.filter((m) => m.geometry.attributes.uv).length,
    uv1: meshes.filter((m) => m.geometry.attributes.uv1).length,
    maps: meshes.filter((m) => m.material.map).length,
    intensity: info.intensity,
  };
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true });
  renderer.setSize(640, 480, false);
  renderer.toneMapping = THREE.LinearToneMapping;
  // A white surface lit at the lightmap's 8-bit top (E = intensity) shows radiance intensity / pi.
  renderer.toneMappingExposure = 1.5 * Math.PI / info.intensity;
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  const camera = viewCamera(THREE, gltf);
  const picture = () => {
    renderer.render(scene, camera);
    const gl = renderer.getContext(), d = new Uint8Array(640 * 480 * 4);
    gl.readPixels(0, 0, 640, 480, gl.RGBA, gl.UNSIGNED_BYTE, d);
    const y = new Float32Array(640 * 480);
    let sum = 0, sum2 = 0;
    for (let i = 0; i < y.length; ++i) {
      y[i] = (0.2126 * d[4 * i] + 0.7152 * d[4 * i + 1] + 0.0722 * d[4 * i + 2]) / 255;
      sum += y[i], sum2 += y[i] * y[i];
    }
    const mean = sum / y.length;
    return { y, mean, std: Math.sqrt(Math.max(0, sum2 / y.length - mean * mean)) };
  };
  const lit = picture();
  // Without the lightmap (and the lamps' own glow), nothing lights the scene: no lamp, no environment.
  const glow = meshes.map((m) => m.material.emissiveIntensity);
  for (const m of meshes) m.material.lightMapIntensity = 0, m.material.emissiveIntensity = 0;
  const dark = picture();
  meshes.forEach((m, i) => { m.material.emissiveIntensity = glow[i]; });
  // The HDR file beside the glb: rows bottom-up as EXRLoader gives them, so v is flipped back.
  const url = URL.createObjectURL(new Blob([bytes('exr')]));
  const hdr = await new EXRLoader().loadAsync(url);
  hdr.channel = 1;
  hdr.repeat.set(1, -1);
  hdr.offset.set(0, 1);
  for (const m of meshes) {
    m.material.lightMap = hdr;
    m.material.lightMapIntensity = 1;
    m.material.needsUpdate = true;
  }
  const exr = picture();
  let sab = 0, saa = 0, sbb = 0;
  for (let i = 0; i < lit.y.length; ++i) {
    const a = lit.y[i] - lit.mean, b = exr.y[i] - exr.mean;
    sab += a * b, saa += a * a, sbb += b * b;
  }
  window.renderExr = () => renderer.render(scene, camera);
  window.renderPng = () => {
    for (const m of meshes) {
      m.material.lightMap = lightMap;
      m.material.lightMapIntensity = info.intensity;
      m.material.needsUpdate = true;
    }
    renderer.render(scene, camera);
  };
  return {
    ...facts, litMean: lit.mean, litStd: lit.std, darkMean: dark.mean, exrMean: exr.mean,
    exrCorrelation: sab / Math.sqrt(saa * sbb + 1e-12),
  };
};
`;
const pagePath = path.join(shots, 'engine-page.html');
writeBundlePage(modules, entry,
  { glb: path.join(bakeDir, 'baked.glb'), exr: path.join(bakeDir, 'lightmap_irradiance.exr') }, pagePath);

const checks = new Checks();
const { check } = checks;
const { browser, page, errors } = await openPage(modules, chromium, pagePath);
let summary = {};
try {
  summary = await runSteps(page, shots, [['engineTest', 'engine-exr.png'], ['renderPng', 'engine-png.png']]);
  check(!errors.length, errors.join('; '));
  check(summary.meshes > 0, 'no mesh in baked.glb');
  check(summary.standard === summary.meshes, `${summary.meshes - summary.standard} meshes without a lit MeshStandardMaterial (the unlit preview?)`);
  check(summary.uv0 === summary.meshes && summary.uv1 === summary.meshes, `uv/uv1 on ${summary.uv0}/${summary.uv1} of ${summary.meshes} meshes`);
  check(summary.helpers === 0, `${summary.helpers} portal:/cellvolume: helpers in the engine glb`);
  check(summary.lamps === 0, `${summary.lamps} punctual lamps in the engine glb`);
  if (mode === 'textured') check(summary.maps > 0, 'no mesh shows its base colour texture');
  check(summary.litMean > 0.05 && summary.litStd > 0.02, `lit by the lightmap the picture is black or flat: mean ${summary.litMean}, std ${summary.litStd}`);
  check(summary.darkMean < 0.01, `with the lightmap's intensity at 0 the picture is not black (mean ${summary.darkMean}): something else lights it`);
  check(Math.abs(summary.exrMean / summary.litMean - 1) < 0.25, `lit by the EXR the mean is ${summary.exrMean}, by the glb's PNG ${summary.litMean}`);
  check(summary.exrCorrelation > 0.9, `the EXR-lit picture correlates ${summary.exrCorrelation} with the PNG-lit one (flipped?)`);
} finally {
  await browser.close();
}
console.log(JSON.stringify(summary));
checks.exit('FAILED: ');
