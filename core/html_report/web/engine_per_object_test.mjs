// node engine_per_object_test.mjs MODULES_DIR CHROMIUM PER_OBJECT_DIR ONE_ATLAS_DIR SCREENSHOT_DIR: loads a
// `bake --per-object` baked.glb in three.js (headless Chromium, software WebGL) as docs/engines.md tells an
// engine user to (each material's MOZ_lightmap texture as its lightMap on uv1), beside the baked.glb of the
// same bake on one atlas, and checks that each object shows its own lightmap:
//  - every mesh's material names its object's lightmap (extras.cpgi_lightmap, "lightmap-OBJECT") and its
//    lightMap is that texture (the texture's name); as many lightmaps as objects in report.json and as
//    extras.cpgi_lightmap.object_textures;
//  - the picture lit by the per-object lightmaps is the one-atlas picture (same solve, texels copied);
//  - lit by each object's lightmap-OBJECT.exr instead (EXRLoader, rows flipped back), it agrees too;
//  - lit with every object's lightmap moved to the next object's meshes, it does not (the comparison
//    sees a wrong lightmap).
// Saves per-object.png, one-atlas.png in SCREENSHOT_DIR; prints a JSON summary; exits 1 with one line per
// failed check.
import fs from 'node:fs';
import path from 'node:path';
import { Checks, openPage, runSteps, scriptArgs, viewCameraSource, writeBundlePage } from './page_harness.mjs';

const [modules, chromium, perObjectDir, oneAtlasDir, shots] = scriptArgs(
  'engine_per_object_test.mjs', ['NODE_MODULES_DIR', 'CHROMIUM', 'PER_OBJECT_DIR', 'ONE_ATLAS_DIR', 'SCREENSHOT_DIR']);

const report = JSON.parse(fs.readFileSync(path.join(perObjectDir, 'report.json'), 'utf8'));
const objects = report.engine_lightmap.objects;
const files = { glb: path.join(perObjectDir, 'baked.glb'), atlas: path.join(oneAtlasDir, 'baked.glb') };
objects.forEach((o, i) => { files[`exr${i}`] = path.join(perObjectDir, o.exr); });

const entry = `
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
const bytes = (id) => Uint8Array.from(atob(document.getElementById(id).textContent.trim()), (c) => c.charCodeAt(0)).buffer;
${viewCameraSource}
const objects = ${JSON.stringify(objects.map((o) => o.lightmap))};
const meshesOf = (root) => { const list = []; root.traverse((o) => { if (o.isMesh) list.push(o); }); return list; };
window.perObjectTest = async () => {
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true });
  renderer.setSize(640, 480, false);
  renderer.toneMapping = THREE.LinearToneMapping;
  const picture = (scene, camera) => {
    renderer.render(scene, camera);
    const gl = renderer.getContext(), d = new Uint8Array(640 * 480 * 4);
    gl.readPixels(0, 0, 640, 480, gl.RGBA, gl.UNSIGNED_BYTE, d);
    const y = new Float32Array(640 * 480);
    let sum = 0;
    for (let i = 0; i < y.length; ++i) sum += (y[i] = (0.2126 * d[4 * i] + 0.7152 * d[4 * i + 1] + 0.0722 * d[4 * i + 2]) / 255);
    return { y, mean: sum / y.length };
  };
  const correlation = (a, b) => {
    let sab = 0, saa = 0, sbb = 0;
    for (let i = 0; i < a.y.length; ++i) {
      const x = a.y[i] - a.mean, z = b.y[i] - b.mean;
      sab += x * z, saa += x * x, sbb += z * z;
    }
    return sab / Math.sqrt(saa * sbb + 1e-12);
  };
  // The one-atlas bake, as docs/engines.md's first steps.
  const atlas = await new GLTFLoader().parseAsync(bytes('atlas'), '');
  const one = atlas.parser.json.extras.cpgi_lightmap;
  const oneMap = await atlas.parser.getDependency('texture', one.texture);
  oneMap.channel = 1;
  oneMap.colorSpace = THREE.SRGBColorSpace;
  for (const m of meshesOf(atlas.scene)) m.material.lightMap = oneMap, m.material.lightMapIntensity = one.intensity;
  // The per-object bake: each material's own MOZ_lightmap texture.
  const gltf = await new GLTFLoader().parseAsync(bytes('glb'), '');
  const info = gltf.parser.json.extras.cpgi_lightmap;
  const meshes = meshesOf(gltf.scene);
  let named = 0, own = 0;
  const used = new Set();
  for (const m of meshes) {
    const def = gltf.parser.json.materials[gltf.parser.associations.get(m.material).materials];
    const moz = def.extensions && def.extensions.MOZ_lightmap;
    if (!moz) continue;
    const map = await gltf.parser.getDependency('texture', moz.index);
    map.channel = moz.texCoord;
    map.colorSpace = THREE.SRGBColorSpace;
    m.material.lightMap = map;
    m.material.lightMapIntensity = moz.intensity;
    used.add(map.name);
    named += m.material.userData.cpgi_lightmap !== undefined;
    own += m.material.userData.cpgi_lightmap === map.name;
  }
  renderer.toneMappingExposure = 1.5 * Math.PI / info.intensity;
  const camera = viewCamera(THREE, gltf);
  const sceneOf = (root) => { const s = new THREE.Scene(); s.add(root); return s; };
  const oneScene = sceneOf(atlas.scene), perScene = sceneOf(gltf.scene);
  const reference = picture(oneScene, camera);
  const lit = picture(perScene, camera);
  // Each object's EXR on its own meshes.
  const saved = meshes.map((m) => m.material.lightMap);
  const hdr = [];
  for (let i = 0; i < objects.length; ++i) {
    const url = URL.createObjectURL(new Blob([bytes('exr' + i)]));
    const t = await new EXRLoader().loadAsync(url);
    t.channel = 1, t.repeat.set(1, -1), t.offset.set(0, 1);
    hdr.push(t);
  }
  const byName = new Map(objects.map((o, i) => [o, i]));
  for (const m of meshes) {
    const k = byName.get(m.material.userData.cpgi_lightmap);
    if (k === undefined) continue;
    m.material.lightMap = hdr[k], m.material.lightMapIntensity = 1, m.material.needsUpdate = true;
  }
  const exr = picture(perScene, camera);
  // Every object's lightmap on the next object's meshes.
  const maps = new Map();
  meshes.forEach((m, i) => maps.set(m.material.userData.cpgi_lightmap, saved[i]));
  for (const m of meshes) {
    const k = byName.get(m.material.userData.cpgi_lightmap);
    if (k === undefined) continue;
    m.material.lightMap = maps.get(objects[(k + 1) % objects.length]) || null;
    m.material.lightMapIntensity = info.intensity, m.material.needsUpdate = true;
  }
  const shuffled = picture(perScene, camera);
  meshes.forEach((m, i) => { m.material.lightMap = saved[i]; m.material.needsUpdate = true; });
  window.renderPerObject = () => renderer.render(perScene, camera);
  window.renderOneAtlas = () => renderer.render(oneScene, camera);
  return {
    meshes: meshes.length, objects: objects.length, textures: info.object_textures.length, lightmapsUsed: used.size,
    named, own, referenceMean: reference.mean, litMean: lit.mean, litCorrelation: correlation(lit, reference),
    exrMean: exr.mean, exrCorrelation: correlation(exr, reference),
    shuffledMean: shuffled.mean, shuffledCorrelation: correlation(shuffled, reference),
  };
};
`;
const pagePath = path.join(shots, 'per-object-page.html');
writeBundlePage(modules, entry, files, pagePath);

const checks = new Checks();
const { check } = checks;
const { browser, page, errors } = await openPage(modules, chromium, pagePath);
let s = {};
try {
  s = await runSteps(page, shots,
    [['perObjectTest', null], ['renderPerObject', 'per-object.png'], ['renderOneAtlas', 'one-atlas.png']]);
  check(!errors.length, errors.join('; '));
  check(s.meshes > 0 && s.objects > 1, `${s.meshes} meshes, ${s.objects} objects: not a scene of several objects`);
  check(s.textures === s.objects && s.lightmapsUsed === s.objects,
    `${s.objects} objects in report.json, ${s.textures} lightmap textures in the glb, ${s.lightmapsUsed} used by its meshes`);
  check(s.named === s.meshes && s.own === s.meshes, `of ${s.meshes} meshes ${s.named} name their object, ${s.own} show that object's lightmap`);
  check(s.referenceMean > 0.05, `the one-atlas picture is black (mean ${s.referenceMean})`);
  check(Math.abs(s.litMean / s.referenceMean - 1) < 0.02 && s.litCorrelation > 0.99,
    `per object the picture differs from one atlas's: mean ${s.litMean} against ${s.referenceMean}, correlation ${s.litCorrelation}`);
  check(Math.abs(s.exrMean / s.referenceMean - 1) < 0.25 && s.exrCorrelation > 0.9,
    `lit by the objects' EXRs: mean ${s.exrMean} against ${s.referenceMean}, correlation ${s.exrCorrelation} (flipped?)`);
  check(s.shuffledCorrelation < s.litCorrelation - 0.05,
    `with each object's lightmap on the next object the picture still correlates ${s.shuffledCorrelation}: the check cannot see a wrong lightmap`);
} finally {
  await browser.close();
}
console.log(JSON.stringify(s));
checks.exit('FAILED: ');
