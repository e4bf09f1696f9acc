// node engine_directional_test.mjs MODULES_DIR CHROMIUM BAKE_DIR SCREENSHOT_DIR: a bake with --directional
// and --probes in three.js (headless Chromium, software WebGL) as docs/engines.md tells an engine user:
//  - every mesh gets a bumpy normal map (an egg-crate height field, box-projected); lit by the plain
//    irradiance lightmap (three.js's lightMap ignores the normal) the bumps do not show;
//  - lit by the directional lightmap (lightmap_sh_l1x/y/z.exr: E = max(0, V · n), the world normal after
//    the normal map, in place of three.js's lightmap term) they do, and with the normal map flattened the
//    picture is the plain lightmap's (V · n_surface = E);
//  - a sphere lit by the probes of baked.glb's extras (L2 SH, Ramamoorthi & Hanrahan, and band 4 where the
//    probes hold it, as docs/engines.md gives it) stands in the view,
//    not black, brighter on top (towards the room's ceiling lamp) than underneath.
// Saves directional-plain.png, directional-bumps.png, directional-flat.png in SCREENSHOT_DIR; prints a
// JSON summary; exits 1 with one line per failed check.
import path from 'node:path';
import { Checks, openPage, runSteps, scriptArgs, writeBundlePage } from './page_harness.mjs';

const [modules, chromium, bakeDir, shots] = scriptArgs(
  'engine_directional_test.mjs', ['NODE_MODULES_DIR', 'CHROMIUM', 'BAKE_DIR', 'SCREENSHOT_DIR']);

const entry = `
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
const bytes = (id) => Uint8Array.from(atob(document.getElementById(id).textContent.trim()), (c) => c.charCodeAt(0)).buffer;
// An EXR of the bake on TEXCOORD_1, rows flipped back (EXRLoader gives them bottom-up).
const exr = async (id) => {
  const t = await new EXRLoader().loadAsync(URL.createObjectURL(new Blob([bytes(id)])));
  t.channel = 1;
  t.repeat.set(1, -1);
  t.offset.set(0, 1);
  return t;
};
// Egg-crate bumps as a tangent-space normal map, slopes up to 0.6.
const bumps = () => {
  const n = 64, data = new Uint8Array(n * n * 4), k = 2 * Math.PI / n;
  for (let y = 0; y < n; ++y)
    for (let x = 0; x < n; ++x) {
      const dx = 0.6 * Math.cos(k * x * 2) * Math.sin(k * y * 2), dy = 0.6 * Math.sin(k * x * 2) * Math.cos(k * y * 2);
      const l = Math.hypot(dx, dy, 1), i = 4 * (y * n + x);
      data.set([(-dx / l * 0.5 + 0.5) * 255, (-dy / l * 0.5 + 0.5) * 255, (1 / l * 0.5 + 0.5) * 255, 255], i);
    }
  const t = new THREE.DataTexture(data, n, n);
  t.wrapS = t.wrapT = THREE.RepeatWrapping;
  t.repeat.set(3, 3);  // 0.33 m bumps
  t.needsUpdate = true;
  return t;
};
const shSphere = /* glsl */ \`
  uniform vec3 sh[9];
  uniform vec3 sh4[9];
  varying vec3 vNormal;
  void main() {
    vec3 n = normalize(vNormal);
    const float pi = 3.14159265;
    vec3 e = pi * 0.282095 * sh[0] + 2.0 * pi / 3.0 * 0.488603 * (sh[1] * n.y + sh[2] * n.z + sh[3] * n.x)
           + pi / 4.0 * (1.092548 * (sh[4] * n.x * n.y + sh[5] * n.y * n.z + sh[7] * n.x * n.z)
                         + 0.315392 * sh[6] * (3.0 * n.z * n.z - 1.0) + 0.546274 * sh[8] * (n.x * n.x - n.y * n.y));
    // docs/engines.md's band 4 (sh_l4): E += -pi/24 * sum Y4m(n) L4m
    float x = n.x, y = n.y, z = n.z, x2 = x * x, y2 = y * y, z2 = z * z;
    float Y4[9] = float[9](2.503343 * x * y * (x2 - y2), 1.770131 * y * z * (3.0 * x2 - y2),
                           0.946175 * x * y * (7.0 * z2 - 1.0), 0.669046 * y * z * (7.0 * z2 - 3.0),
                           0.105786 * (35.0 * z2 * z2 - 30.0 * z2 + 3.0), 0.669046 * x * z * (7.0 * z2 - 3.0),
                           0.473087 * (x2 - y2) * (7.0 * z2 - 1.0), 1.770131 * x * z * (x2 - 3.0 * y2),
                           0.625836 * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2)));
    for (int m = 0; m < 9; ++m) e += -pi / 24.0 * Y4[m] * sh4[m];
    gl_FragColor = vec4(0.8 * max(e, 0.0) / pi, 1.0);
    #include <tonemapping_fragment>
    #include <colorspace_fragment>
  }\`;
window.directionalTest = async () => {
  const gltf = await new GLTFLoader().parseAsync(bytes('glb'), '');
  const info = gltf.parser.json.extras.cpgi_lightmap;
  const irradiance = await exr('e'), shx = await exr('x'), shy = await exr('y'), shz = await exr('z');
  const normalMap = bumps();
  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  const directional = { value: false };
  // seed1 has no texture coordinates of its own (baked.glb's TEXCOORD_0 is zero): the normal map gets a
  // box projection, one metre a tile, along each triangle's dominant axis.
  gltf.scene.updateMatrixWorld(true);
  for (const m of meshes) {
    const g = m.geometry.index ? m.geometry.toNonIndexed() : m.geometry;
    m.geometry = g;
    const pos = g.attributes.position, nor = g.attributes.normal, uv = new Float32Array(pos.count * 2);
    const p = new THREE.Vector3(), n = new THREE.Vector3(), normalMatrix = new THREE.Matrix3().getNormalMatrix(m.matrixWorld);
    for (let i = 0; i < pos.count; ++i) {
      p.fromBufferAttribute(pos, i).applyMatrix4(m.matrixWorld);
      n.fromBufferAttribute(nor, i).applyMatrix3(normalMatrix);
      const a = Math.abs(n.x) > Math.abs(n.y) && Math.abs(n.x) > Math.abs(n.z) ? [p.z, p.y] : Math.abs(n.y) > Math.abs(n.z) ? [p.x, p.z] : [p.x, p.y];
      uv[2 * i] = a[0], uv[2 * i + 1] = a[1];
    }
    g.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
  }
  for (const m of meshes) {
    m.material.lightMap = irradiance;
    m.material.lightMapIntensity = 1;
    m.material.emissiveIntensity = 0;
    m.material.normalMap = normalMap;
    m.material.onBeforeCompile = (shader) => {
      Object.assign(shader.uniforms, { shx: { value: shx }, shy: { value: shy }, shz: { value: shz }, directional });
      const chunk = THREE.ShaderChunk.lights_fragment_maps.replace(
        'vec3 lightMapIrradiance = lightMapTexel.rgb * lightMapIntensity;',
        \`vec3 lightMapIrradiance = lightMapTexel.rgb * lightMapIntensity;
        if (directional) {
          // docs/engines.md: V = (L11, L1-1, L10) / 0.488603 per channel, E = max(0, V . n), n in world space.
          vec3 n = inverseTransformDirection(normal, viewMatrix);
          vec3 lx = texture2D(shx, vLightMapUv).rgb, ly = texture2D(shy, vLightMapUv).rgb, lz = texture2D(shz, vLightMapUv).rgb;
          lightMapIrradiance = max(vec3(0.0), (lx * n.x + ly * n.y + lz * n.z) / 0.488603);
        }\`);
      shader.fragmentShader = 'uniform sampler2D shx, shy, shz;\\nuniform bool directional;\\n' +
        shader.fragmentShader.replace('#include <lights_fragment_maps>', chunk);
    };
    m.material.needsUpdate = true;
  }
  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, preserveDrawingBuffer: true });
  renderer.setSize(640, 480, false);
  renderer.toneMapping = THREE.LinearToneMapping;
  renderer.toneMappingExposure = 1.5 * Math.PI / info.intensity;
  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  const camera = gltf.cameras[0];
  camera.aspect = 640 / 480;
  camera.updateProjectionMatrix();
  // The probe-lit sphere 1.5 m ahead of the camera, lit by the nearest probe.
  const probes = info.probes.probes;
  const ahead = new THREE.Vector3();
  camera.getWorldPosition(ahead);
  const eye = ahead.clone(), forward = new THREE.Vector3();
  camera.getWorldDirection(forward);
  const centre = eye.addScaledVector(forward, 1.5);
  const nearest = probes.reduce((a, p) => {
    const d = centre.distanceTo(new THREE.Vector3(...p.position));
    return d < a.d ? { p, d } : a;
  }, { p: null, d: Infinity }).p;
  const sphere = new THREE.Mesh(new THREE.SphereGeometry(0.15, 48, 24), new THREE.ShaderMaterial({
    uniforms: {
      sh: { value: nearest.sh.map((c) => new THREE.Vector3(...c)) },
      sh4: { value: (nearest.sh_l4 || nearest.sh.map(() => [0, 0, 0])).map((c) => new THREE.Vector3(...c)) },
    },
    vertexShader: 'varying vec3 vNormal; void main() { vNormal = normalize(mat3(modelMatrix) * normal); gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0); }',
    fragmentShader: shSphere, toneMapped: true,
  }));
  sphere.position.copy(centre);
  scene.add(sphere);
  const picture = () => {
    renderer.render(scene, camera);
    const gl = renderer.getContext(), d = new Uint8Array(640 * 480 * 4);
    gl.readPixels(0, 0, 640, 480, gl.RGBA, gl.UNSIGNED_BYTE, d);
    return d;
  };
  const luma = (d, i) => 0.2126 * d[4 * i] + 0.7152 * d[4 * i + 1] + 0.0722 * d[4 * i + 2];
  // Pixels that differ by more than 6 levels, and the mean luminance ratio, away from the sphere.
  const sphereBox = (() => {
    const p = centre.clone().project(camera), x = (p.x + 1) * 320, y = (p.y + 1) * 240;
    return { x, y, r: 90 };
  })();
  const away = (i) => Math.hypot((i % 640) - sphereBox.x, Math.floor(i / 640) - sphereBox.y) > sphereBox.r;
  const compare = (a, b) => {
    let changed = 0, n = 0, sa = 0, sb = 0;
    for (let i = 0; i < 640 * 480; ++i) {
      if (!away(i)) continue;
      const la = luma(a, i), lb = luma(b, i);
      changed += Math.abs(la - lb) > 6, n += 1, sa += la, sb += lb;
    }
    return { changed: changed / n, ratio: sb / Math.max(sa, 1e-9), meanA: sa / n };
  };
  const plainBumps = picture();
  for (const m of meshes) m.material.normalScale.set(0, 0);
  const plainFlat = picture();
  directional.value = true;
  const directionalFlat = picture();
  window.renderFlat = () => renderer.render(scene, camera);
  for (const m of meshes) m.material.normalScale.set(1, 1);
  const directionalBumps = picture();
  window.renderBumps = () => renderer.render(scene, camera);
  window.renderPlain = () => { directional.value = false; renderer.render(scene, camera); };
  // The sphere's top and underside (readPixels rows run bottom-up).
  const sphereAt = (dy) => {
    const p = centre.clone().add(new THREE.Vector3(0, dy, 0)).project(camera);
    return luma(directionalBumps, Math.floor((p.y + 1) * 240) * 640 + Math.floor((p.x + 1) * 320));
  };
  return {
    probes: probes.length, plainNormalMap: compare(plainFlat, plainBumps), flat: compare(plainFlat, directionalFlat),
    bumps: compare(directionalFlat, directionalBumps), sphereTop: sphereAt(0.1), sphereBottom: sphereAt(-0.1),
  };
};
`;
const pagePath = path.join(shots, 'directional-page.html');
const files = {
  glb: 'baked.glb', e: 'lightmap_irradiance.exr', x: 'lightmap_sh_l1x.exr', y: 'lightmap_sh_l1y.exr',
  z: 'lightmap_sh_l1z.exr',
};
writeBundlePage(modules, entry,
  Object.fromEntries(Object.entries(files).map(([id, f]) => [id, path.join(bakeDir, f)])), pagePath);

const checks = new Checks();
const { check } = checks;
const { browser, page, errors } = await openPage(modules, chromium, pagePath);
let s = {};
try {
  s = await runSteps(page, shots,
    [['directionalTest', 'directional-bumps.png'], ['renderPlain', 'directional-plain.png']]);
  check(!errors.length, errors.join('; '));
  check(s.plainNormalMap.changed < 0.01, `the plain lightmap shows the normal map on ${s.plainNormalMap.changed} of the pixels (three.js's lightMap should ignore it)`);
  check(s.plainNormalMap.meanA > 20, `the plain lightmap's picture is dark (mean ${s.plainNormalMap.meanA})`);
  check(Math.abs(s.flat.ratio - 1) < 0.03, `flat, the directional lightmap's picture is ${s.flat.ratio} times the plain one's`);
  check(s.flat.changed < 0.05, `flat, the directional lightmap changes ${s.flat.changed} of the pixels from the plain one`);
  check(s.bumps.changed > 0.2, `the directional lightmap shows the bumps on only ${s.bumps.changed} of the pixels`);
  check(s.sphereBottom > 10, `the probe-lit sphere is black underneath (${s.sphereBottom})`);
  check(s.sphereTop > s.sphereBottom + 10, `the probe-lit sphere's top (${s.sphereTop}) is not brighter than its underside (${s.sphereBottom})`);
} finally {
  await browser.close();
}
console.log(JSON.stringify(s));
checks.exit('FAILED: ');
