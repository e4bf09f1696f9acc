// report.html's viewer: the baked scene in 3D (three.js), its cells and portals, and the numbers of
// report.json. Bundled with three.js into one script by esbuild at build time
// (core/html_report/CMakeLists.txt) and inlined by core/html_report/html_report.cpp, so the page opens
// offline from file://.
//
// The page carries two data blocks written by cpgi:
//   #cpgi-data (JSON): kind, title, report (report.json), cells [{name, eye, look}], portals
//     [{name, cell_a, cell_b, corners}], lightmap {width, height, rgb (base64 half floats, RGBA,
//     radiosity W/m²), cell (base64 int16 per texel, -1 for none), area (base64 float32 m² per texel)}
//     probes (probes.json of bake --probes, when written): SH light probes through the rooms (L2, and
//     band 4 in sh_l4 since it was added)
//   #cpgi-glb: baked.glb (or cells.glb) as base64.
// window.cpgiViewer is the handle the browser test (core/html_report/web/browser_test.mjs) drives.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { buildPanels, formatNumber } from './panels.js';

const MODES = ['light', 'cells', 'density', 'error'];
const ERROR_SCALE = 0.5;  // the heat map saturates at ±50 % of the reference's RMS radiosity

function base64Bytes(text) {
  const binary = atob(text.replace(/\s+/g, ''));
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

// Each cell's colour as cpgi gave it (core/cell_palette.h: the same as decomposition.png's), "#rrggbb"
// in sRGB, by the cell's index; grey for no cell.
let cellPalette = [];
export function setCellPalette(cells) {
  const hex = (c) => (typeof c.colour === 'string' && /^#[0-9a-f]{6}$/i.test(c.colour) ? c.colour : null);
  cellPalette = (cells || []).map(hex);
}
export function cellColour(index) {
  const hex = index >= 0 ? cellPalette[index] : null;
  return hex ? new THREE.Color(hex) : new THREE.Color(0.35, 0.35, 0.35);
}

// Radiance of the brightest surfaces a person would look at: the area-weighted 90th percentile of B/π
// over texels that are not lamps, so that a lamp does not set the exposure for the room.
function autoExposure(rgb, area, count) {
  const samples = [];
  for (let i = 0; i < count; ++i) {
    if (!(area[i] > 0)) continue;
    const y = 0.2126 * rgb[4 * i] + 0.7152 * rgb[4 * i + 1] + 0.0722 * rgb[4 * i + 2];
    if (y > 0) samples.push(y / Math.PI);
  }
  if (!samples.length) return 1;
  samples.sort((a, b) => a - b);
  const key = samples[Math.floor(samples.length * 0.9)];
  return key > 0 ? 0.8 / key : 1;
}

function halfToFloat(h) {
  const s = h & 0x8000 ? -1 : 1, e = (h >> 10) & 0x1f, f = h & 0x3ff;
  if (e === 0) return s * f * 2 ** -24;
  if (e === 31) return f ? NaN : s * Infinity;
  return s * (1 + f / 1024) * 2 ** (e - 15);
}

// The lightmap as textures: radiosity (half float, filtered), cell colours and texel density (nearest).
function lightmapTextures(lm, cells) {
  const count = lm.width * lm.height;
  const halves = new Uint16Array(base64Bytes(lm.rgb).buffer);
  const rgb = new Float32Array(4 * count);
  for (let i = 0; i < 4 * count; ++i) rgb[i] = halfToFloat(halves[i]);
  const cell = lm.cell ? new Int16Array(base64Bytes(lm.cell).buffer) : null;
  const area = new Float32Array(base64Bytes(lm.area).buffer);

  const radiosity = new THREE.DataTexture(halves, lm.width, lm.height, THREE.RGBAFormat, THREE.HalfFloatType);
  radiosity.magFilter = radiosity.minFilter = THREE.LinearFilter;
  radiosity.needsUpdate = true;

  const nearest = (bytes) => {
    const t = new THREE.DataTexture(bytes, lm.width, lm.height);
    t.magFilter = t.minFilter = THREE.NearestFilter;
    t.needsUpdate = true;
    return t;
  };
  // Cells per texel when cpgi knew them (a bake); otherwise (a comparison) per mesh, by cell: node names.
  let cellTexture = null;
  if (cell) {
    const cellBytes = new Uint8Array(4 * count);
    const palette = cells.map((_, c) => cellColour(c));
    const none = cellColour(-1);
    for (let i = 0; i < count; ++i) {
      const c = cell[i] >= 0 && cell[i] < palette.length ? palette[cell[i]] : none;
      cellBytes.set([c.r * 255, c.g * 255, c.b * 255, 255], 4 * i);
    }
    cellTexture = nearest(cellBytes);
  }

  // A comparison: signed error per texel, blue where A is darker than the reference, red where brighter.
  let errorTexture = null;
  if (lm.error) {
    const error = new Float32Array(base64Bytes(lm.error).buffer);
    const errorBytes = new Uint8Array(4 * count);
    for (let i = 0; i < count; ++i) {
      if (!(area[i] > 0) || !Number.isFinite(error[i])) continue;
      const t = Math.max(-1, Math.min(1, error[i] / ERROR_SCALE));
      const c = t >= 0 ? [1, 1 - t, 1 - t] : [1 + t, 1 + t, 1];
      errorBytes.set([c[0] * 255, c[1] * 255, c[2] * 255, 255], 4 * i);
    }
    errorTexture = nearest(errorBytes);
  }

  // Texels per metre (1/√area) on a log scale from the sparsest to the densest texel: blue to red.
  let lo = Infinity, hi = 0;
  for (let i = 0; i < count; ++i)
    if (area[i] > 0) lo = Math.min(lo, area[i]), hi = Math.max(hi, area[i]);
  const densityBytes = new Uint8Array(4 * count);
  const span = Math.log(hi / lo) || 1;
  for (let i = 0; i < count; ++i) {
    if (!(area[i] > 0)) continue;
    const t = Math.log(hi / area[i]) / span;  // 0 = largest texel (sparsest), 1 = densest
    const c = new THREE.Color().setHSL(0.66 * (1 - t), 0.9, 0.5);
    densityBytes.set([c.r * 255, c.g * 255, c.b * 255, 255], 4 * i);
  }
  const densityTexture = nearest(densityBytes);

  const density = { min: 1 / Math.sqrt(hi), max: 1 / Math.sqrt(lo) };
  // A bake with --directional: the vector irradiance's x, y, z components (RGB each), filtered.
  const vector = (lm.vector || []).map((b64) => {
    const t = new THREE.DataTexture(new Uint16Array(base64Bytes(b64).buffer), lm.width, lm.height, THREE.RGBAFormat, THREE.HalfFloatType);
    t.magFilter = t.minFilter = THREE.LinearFilter;
    t.needsUpdate = true;
    return t;
  });
  return { radiosity, cellTexture, densityTexture, errorTexture, rgb, cell, area, count, density, vector };
}

const vertexShader = /* glsl */ `
  in vec2 uv1;
  out vec2 vLightmapUv;
  out vec3 vWorld;
  void main() {
    vLightmapUv = uv1;
    vWorld = (modelMatrix * vec4(position, 1.0)).xyz;
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
  }`;

// Radiance B/π times the exposure, tone-mapped (1 − e^−x) and encoded as sRGB. Colour by cell keeps the
// light's shading so that the rooms stay recognisable; the density view draws the texel grid.
const fragmentShader = /* glsl */ `
  uniform sampler2D radiosity, cellColours, density, error, vectorX, vectorY, vectorZ;
  uniform bool cellsPerTexel, bumps;
  in vec3 vWorld;
  uniform vec3 cellColour;
  uniform vec2 atlasSize;
  uniform float exposure;
  uniform int mode;
  in vec2 vLightmapUv;
  out vec4 outColour;
  vec3 toneMap(vec3 x) { return 1.0 - exp(-x); }
  vec3 toSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
  }
  // The normal-mapped test surface (bake --directional): egg-crate bumps 0.3 m across, slopes up to 0.6,
  // lit by the directional lightmap: each channel's light times max(0, V · n_bumped) / (V · n_surface),
  // V the vector irradiance (docs/engines.md).
  vec3 bumped(vec3 b) {
    vec3 n = normalize(cross(dFdx(vWorld), dFdy(vWorld)));
    vec3 vx = texture(vectorX, vLightmapUv).rgb, vy = texture(vectorY, vLightmapUv).rgb, vz = texture(vectorZ, vLightmapUv).rgb;
    vec3 lum = vec3(dot(vx, vec3(1.0)), dot(vy, vec3(1.0)), dot(vz, vec3(1.0)));
    if (dot(lum, n) < 0.0) n = -n;
    vec3 t = normalize(cross(abs(n.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), n)), u = cross(n, t);
    float k = 6.2831853 / 0.3, s = dot(vWorld, t) * k, v = dot(vWorld, u) * k;
    vec3 m = normalize(n - 0.6 * cos(s) * sin(v) * t - 0.6 * sin(s) * cos(v) * u);
    vec3 level = vx * n.x + vy * n.y + vz * n.z, lit = max(vx * m.x + vy * m.y + vz * m.z, 0.0);
    return b * lit / max(level, vec3(1e-6));
  }
  void main() {
    vec3 b = texture(radiosity, vLightmapUv).rgb;
    if (bumps) b = bumped(b);
    vec3 light = toneMap(b / 3.14159265 * exposure);
    vec3 colour = light;
    if (mode == 1) {
      float shade = dot(light, vec3(0.2126, 0.7152, 0.0722));
      vec3 cell = cellsPerTexel ? texture(cellColours, vLightmapUv).rgb : cellColour;
      colour = cell * (0.25 + 0.75 * sqrt(shade));
    } else if (mode == 3) {
      colour = texture(error, vLightmapUv).rgb;
    } else if (mode == 2) {
      vec2 texel = floor(vLightmapUv * atlasSize);
      float checker = mod(texel.x + texel.y, 2.0);
      colour = texture(density, vLightmapUv).rgb * (0.7 + 0.3 * checker);
    }
    outColour = vec4(toSrgb(clamp(colour, 0.0, 1.0)), 1.0);
  }`;

// A sphere lit by the light probes (bake --probes): the SH of the probes around it, blended, give the
// irradiance E(n) on each normal, convolved as the bake does (radiosity/lightmap/spherical_harmonics.cpp):
// Ramamoorthi & Hanrahan's L2, A = π, 2π/3, π/4, plus band 4 (A_4 = −π/24; band 3's A is 0) when the
// probes hold it (sh_l4), since L2 alone misses a lamp's concentrated light by 5–10 % at some probes.
// Shown as a grey of albedo 0.8, radiance 0.8 E/π, with the lightmap's exposure and tone map. SH basis and
// order of probes.json's convention.
const probeVertexShader = /* glsl */ `
  out vec3 vNormal;
  void main() {
    vNormal = normalize(mat3(modelMatrix) * normal);
    gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
  }`;
const probeFragmentShader = /* glsl */ `
  uniform vec3 sh[9];
  uniform vec3 sh4[9];
  uniform float band4;  // 1 when the probes hold band 4, 0 for L2 alone
  uniform float exposure;
  in vec3 vNormal;
  out vec4 outColour;
  vec3 toSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
  }
  void main() {
    vec3 n = normalize(vNormal);
    const float pi = 3.14159265;
    float x = n.x, y = n.y, z = n.z, x2 = x * x, y2 = y * y, z2 = z * z;
    vec3 e = pi * 0.282095 * sh[0]
           + 2.0 * pi / 3.0 * 0.488603 * (sh[1] * y + sh[2] * z + sh[3] * x)
           + pi / 4.0 * (1.092548 * (sh[4] * x * y + sh[5] * y * z + sh[7] * x * z)
                         + 0.315392 * sh[6] * (3.0 * z2 - 1.0) + 0.546274 * sh[8] * (x2 - y2));
    vec3 e4 = 2.503343 * sh4[0] * x * y * (x2 - y2) + 1.770131 * sh4[1] * y * z * (3.0 * x2 - y2)
            + 0.946175 * sh4[2] * x * y * (7.0 * z2 - 1.0) + 0.669046 * sh4[3] * y * z * (7.0 * z2 - 3.0)
            + 0.105786 * sh4[4] * (35.0 * z2 * z2 - 30.0 * z2 + 3.0) + 0.669046 * sh4[5] * x * z * (7.0 * z2 - 3.0)
            + 0.473087 * sh4[6] * (x2 - y2) * (7.0 * z2 - 1.0) + 1.770131 * sh4[7] * x * z * (x2 - 3.0 * y2)
            + 0.625836 * sh4[8] * (x2 * (x2 - 3.0 * y2) - y2 * (3.0 * x2 - y2));
    e += band4 * (-pi / 24.0) * e4;
    vec3 light = 1.0 - exp(-max(e, 0.0) * 0.8 / pi * exposure);
    outColour = vec4(toSrgb(clamp(light, 0.0, 1.0)), 1.0);
  }`;

// The SH band the probes are read at: 4 when every probe holds band 4 (sh_l4, bakes since it was added),
// else 2.
export function probeBand(probes) {
  const holds = (p) => Array.isArray(p.sh_l4) && p.sh_l4.length === 9;
  return probes && probes.length && probes.every(holds) ? 4 : 2;
}

// The probes' SH at `point`: the eight nearest of the nearest probe's room blended by inverse squared
// distance, as { sh, sh4 } (each nine [r, g, b]; sh4 zeros when `band` is 2); null without probes. Probes
// of the room behind a wall are left out: beside a 0.2 m wall they are as near as the room's own, and a
// dark room's would dim a lit one's sphere.
export function probeShAt(probes, point, band = probeBand(probes)) {
  if (!probes || !probes.length) return null;
  const byDistance = probes
    .map((p) => ({ p, d2: (p.position[0] - point.x) ** 2 + (p.position[1] - point.y) ** 2 + (p.position[2] - point.z) ** 2 }))
    .sort((a, b) => a.d2 - b.d2);
  const room = byDistance[0].p.cell;
  const near = byDistance.filter(({ p }) => p.cell === room).slice(0, 8);
  const zeros = () => Array.from({ length: 9 }, () => [0, 0, 0]);
  const sh = zeros(), sh4 = zeros();
  let total = 0;
  for (const { p, d2 } of near) {
    const w = 1 / (d2 + 1e-4);
    total += w;
    for (let k = 0; k < 9; ++k)
      for (let c = 0; c < 3; ++c) {
        sh[k][c] += w * p.sh[k][c];
        if (band === 4) sh4[k][c] += w * p.sh_l4[k][c];
      }
  }
  const normalise = (coefficients) => coefficients.map((v) => v.map((x) => x / total));
  return { sh: normalise(sh), sh4: normalise(sh4) };
}

class Viewer {
  constructor(data, glb) {
    this.data = data;
    this.cells = data.cells || [];
    this.mode = 'light';
    this.walking = false;
    this.openWalls = true;
    // A building's outside cell (its exterior walls, roof and ground) hides the rooms from the overview,
    // and nothing lights it but what leaves through the openings: hidden until asked for.
    this.outsideCell = this.cells.findIndex((c) => c.name === 'outside');
    this.showOutside = false;
    this.keys = new Set();
    this.ready = new Promise((resolve, reject) => { this.resolveReady = resolve; this.rejectReady = reject; });
    this.buildDom();
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x101418);
    this.camera = new THREE.PerspectiveCamera(60, 1, 0.02, 1000);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => this.requestRender());
    if (data.lightmap) this.lightmap = lightmapTextures(data.lightmap, this.cells);
    this.exposure = this.lightmap ? autoExposure(this.lightmap.rgb, this.lightmap.area, this.lightmap.count) : 1;
    this.autoExposureValue = this.exposure;
    this.portalGroup = new THREE.Group();
    this.portalGroup.visible = false;
    this.scene.add(this.portalGroup);
    this.buildProbeSphere();
    this.load(glb);
  }

  // The probe-lit sphere, 0.3 m across, hidden until asked for; it then stands 1.5 m ahead of the camera
  // and follows it (orbit, or walk through the rooms), lit by the probes of the room it is in.
  buildProbeSphere() {
    this.probes = this.data.probes?.probes || [];
    if (!this.probes.length) return;
    this.probeBand = probeBand(this.probes);
    const vectors = () => Array.from({ length: 9 }, () => new THREE.Vector3());
    const uniforms = {
      sh: { value: vectors() }, sh4: { value: vectors() }, band4: { value: this.probeBand === 4 ? 1 : 0 },
      exposure: { value: this.exposure },
    };
    this.probeSphere = new THREE.Mesh(new THREE.SphereGeometry(0.15, 48, 24), new THREE.ShaderMaterial({
      uniforms, vertexShader: probeVertexShader, fragmentShader: probeFragmentShader, glslVersion: THREE.GLSL3,
    }));
    this.probeSphere.visible = false;
    this.scene.add(this.probeSphere);
  }

  // Every surface normal-mapped and lit by the directional lightmap (a bake with --directional).
  setBumps(shown) {
    if (!this.sharedUniforms || !this.lightmap.vector.length) return;
    this.sharedUniforms.bumps.value = shown;
    this.requestRender();
  }

  setProbeSphere(shown) {
    if (!this.probeSphere) return;
    this.probeSphere.visible = shown;
    this.requestRender();
  }

  // Moves the sphere ahead of the camera and lights it from the probes there.
  placeProbeSphere() {
    const ahead = new THREE.Vector3();
    this.camera.getWorldDirection(ahead);
    this.probeSphere.position.copy(this.camera.position).addScaledVector(ahead, 1.5);
    const { sh, sh4 } = probeShAt(this.probes, this.probeSphere.position, this.probeBand);
    const uniforms = this.probeSphere.material.uniforms;
    sh.forEach((c, k) => uniforms.sh.value[k].set(c[0], c[1], c[2]));
    sh4.forEach((c, k) => uniforms.sh4.value[k].set(c[0], c[1], c[2]));
    uniforms.exposure.value = this.exposure;
  }

  buildDom() {
    const view = document.getElementById('view');
    this.canvas = document.createElement('canvas');
    this.canvas.id = 'scene';
    this.canvas.tabIndex = 0;
    view.appendChild(this.canvas);
    this.labels = document.createElement('div');
    this.labels.className = 'labels';
    view.appendChild(this.labels);
    new ResizeObserver(() => this.resize()).observe(view);
    this.canvas.addEventListener('keydown', (e) => { this.keys.add(e.code); this.tick(); });
    this.canvas.addEventListener('keyup', (e) => this.keys.delete(e.code));
    this.canvas.addEventListener('pointerdown', (e) => this.pointerDown(e));
  }

  resize() {
    const view = this.canvas.parentElement;
    const w = Math.max(1, view.clientWidth), h = Math.max(1, view.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  load(glb) {
    new GLTFLoader().parse(glb.buffer, '', (gltf) => {
      try {
        this.setup(gltf);
        this.resolveReady();
      } catch (e) {
        this.fail(e);
      }
    }, (e) => this.fail(e));
  }

  fail(error) {
    document.getElementById('status').textContent = 'Could not show the scene: ' + (error.message || error);
    this.rejectReady(error);
  }

  // The cell a node belongs to: its nearest ancestor named cell:NAME (design.md §3). GLTFLoader strips
  // ':' from object names; the glTF's own name is in userData.name.
  cellOfNode(node) {
    for (let n = node; n; n = n.parent) {
      const nodeName = n.userData.name || '';
      if (nodeName.startsWith('cell:')) {
        const name = nodeName.slice(5).replace(/\.\d{3}$/, '');
        return this.cells.findIndex((c) => c.name === name);
      }
    }
    return -1;
  }

  setup(gltf) {
    const root = gltf.scene;
    this.gltfCameras = gltf.cameras || [];
    const meshes = [];
    root.traverse((o) => { if (o.isMesh) meshes.push(o); });
    for (const mesh of meshes) {
      // Portal quads and cell volumes of the glTF: the page draws portals itself, with their light.
      const helper = [mesh, mesh.parent].some((o) => /^(portal:|cellvolume:)/.test(o?.userData.name || ''));
      if (helper) { mesh.visible = false; continue; }
      mesh.userData.cell = this.cellOfNode(mesh);
      // The atlas is TEXCOORD_1 (uv1); bakes written before it moved there have it as TEXCOORD_0.
      if (this.lightmap && !mesh.geometry.attributes.uv1 && mesh.geometry.attributes.uv)
        mesh.geometry.setAttribute('uv1', mesh.geometry.attributes.uv);
      if (this.lightmap && mesh.geometry.attributes.uv1) {
        mesh.material = this.lightmapMaterial(mesh.userData.cell);
      } else {
        // No lightmap (a decomposition): the albedo, or the cell's colour, under a simple sky light.
        const cell = mesh.userData.cell;
        mesh.userData.albedo = mesh.material.color ? mesh.material.color.clone() : new THREE.Color(0.8, 0.8, 0.8);
        mesh.userData.cellColour = cellColour(cell);
        mesh.material = new THREE.MeshLambertMaterial({ color: mesh.userData.albedo });
      }
    }
    if (!this.lightmap) {
      this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 2.2));
      const sun = new THREE.DirectionalLight(0xffffff, 1.2);
      sun.position.set(0.4, 1, 0.3);
      this.scene.add(sun);
    }
    this.meshes = meshes.filter((m) => m.visible);
    this.setOutside(this.showOutside);
    this.scene.add(root);
    this.bounds = new THREE.Box3().setFromObject(root);
    // The overview frames the building cpgi measured (html_report.h, buildingBounds), not a terrain or
    // sky around it many times its size.
    const f = this.data.frame;
    this.frameBounds = Array.isArray(f) && f.length === 2
      ? new THREE.Box3(new THREE.Vector3(...f[0]), new THREE.Vector3(...f[1]))
      : this.bounds.clone();
    this.buildPortals();
    this.buildCameraList();
    this.home();
    this.resize();
    this.buildControls();
  }

  // One material per mesh over shared uniforms (so exposure and mode are set once), with the mesh's cell
  // colour for when the cells are known per mesh only.
  lightmapMaterial(cell) {
    if (!this.sharedUniforms) {
      const lm = this.data.lightmap;
      this.sharedUniforms = {
        radiosity: { value: this.lightmap.radiosity },
        cellColours: { value: this.lightmap.cellTexture },
        cellsPerTexel: { value: !!this.lightmap.cellTexture },
        density: { value: this.lightmap.densityTexture },
        error: { value: this.lightmap.errorTexture },
        atlasSize: { value: new THREE.Vector2(lm.width, lm.height) },
        exposure: { value: this.exposure },
        mode: { value: 0 },
        bumps: { value: false },
        vectorX: { value: this.lightmap.vector[0] || null },
        vectorY: { value: this.lightmap.vector[1] || null },
        vectorZ: { value: this.lightmap.vector[2] || null },
      };
    }
    return new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader,
      fragmentShader,
      side: THREE.FrontSide,
      uniforms: { ...this.sharedUniforms, cellColour: { value: cellColour(cell) } },
    });
  }

  // Portals as translucent quads, brighter the more light they carried; each labelled with its flows.
  buildPortals() {
    const portals = this.data.portals || [];
    const flows = new Map((this.data.report?.portal_energy || []).map((p) => [p.name, p]));
    let most = 0;
    for (const p of flows.values()) most = Math.max(most, (p.a_to_b_w || 0) + (p.b_to_a_w || 0));
    this.portalLabels = [];
    for (const p of portals) {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(p.corners.flat(), 3));
      geometry.setIndex([0, 1, 2, 0, 2, 3]);
      const flow = flows.get(p.name);
      const carried = flow ? (flow.a_to_b_w || 0) + (flow.b_to_a_w || 0) : 0;
      const strength = most > 0 ? carried / most : 0.5;
      const material = new THREE.MeshBasicMaterial({
        color: new THREE.Color().setHSL(0.55 - 0.45 * strength, 1, 0.55),
        transparent: true, opacity: 0.35 + 0.4 * strength, side: THREE.DoubleSide, depthWrite: false,
      });
      const mesh = new THREE.Mesh(geometry, material);
      mesh.name = p.name;
      this.portalGroup.add(mesh);
      const label = document.createElement('div');
      label.className = 'portal-label';
      label.textContent = flow
        ? `${p.cell_a}→${p.cell_b} ${formatNumber(flow.a_to_b_w)} W · ${p.cell_b}→${p.cell_a} ${formatNumber(flow.b_to_a_w)} W`
        : `${p.cell_a} | ${p.cell_b}`;
      label.style.display = 'none';
      this.labels.appendChild(label);
      const centre = new THREE.Vector3();
      for (const c of p.corners) centre.add(new THREE.Vector3(...c).multiplyScalar(0.25));
      this.portalLabels.push({ label, centre });
    }
  }

  // Views: the scene's own cameras, one inside each cell at eye height, and the overview.
  buildCameraList() {
    this.views = [{ name: 'overview', overview: true }];
    for (const cam of this.gltfCameras) {
      cam.updateMatrixWorld(true);
      const eye = new THREE.Vector3().setFromMatrixPosition(cam.matrixWorld);
      const dir = new THREE.Vector3(0, 0, -1).transformDirection(cam.matrixWorld);
      this.views.push({ name: 'camera ' + (cam.name || this.views.length), eye, look: eye.clone().add(dir) });
    }
    for (const c of this.cells)
      if (c.eye) this.views.push({ name: 'in ' + c.name, eye: new THREE.Vector3(...c.eye), look: new THREE.Vector3(...c.look) });
  }

  home() { this.showView(this.views[0]); }

  showView(v) {
    if (typeof v === 'string') v = this.views.find((x) => x.name === v);
    if (!v) throw new Error('no such view');
    this.currentView = v.name;
    if (v.overview) {
      const size = this.frameBounds.getSize(new THREE.Vector3());
      const centre = this.frameBounds.getCenter(new THREE.Vector3());
      const radius = Math.max(size.length() * 0.5, 0.5);
      this.camera.position.copy(centre).add(new THREE.Vector3(0.6, 1.1, 0.9).normalize().multiplyScalar(radius * 1.8));
      this.controls.target.copy(centre);
    } else {
      this.camera.position.copy(v.eye);
      this.controls.target.copy(v.look);
    }
    this.camera.near = Math.max(0.01, this.bounds.getSize(new THREE.Vector3()).length() * 1e-4);
    this.camera.far = this.bounds.getSize(new THREE.Vector3()).length() * 10 + 10;
    this.camera.updateProjectionMatrix();
    this.camera.lookAt(this.controls.target);
    this.controls.update();
    this.requestRender();
  }

  setMode(mode) {
    if (!MODES.includes(mode)) throw new Error('unknown mode ' + mode);
    this.mode = mode;
    if (this.sharedUniforms) this.sharedUniforms.mode.value = MODES.indexOf(mode);
    for (const m of this.meshes || [])
      if (m.userData.albedo) m.material.color.copy(mode === 'cells' ? m.userData.cellColour : m.userData.albedo);
    this.syncControls();
    this.requestRender();
  }

  setExposure(value) {
    this.exposure = value;
    if (this.sharedUniforms) this.sharedUniforms.exposure.value = value;
    this.syncControls();
    this.requestRender();
  }

  // Surfaces face into the rooms: drawing only their front faces lets the overview look in through the
  // walls and ceilings that face away (a doll's house); both sides show models wound the other way.
  setOpenWalls(open) {
    this.openWalls = open;
    for (const m of this.meshes || []) m.material.side = open ? THREE.FrontSide : THREE.DoubleSide;
    for (const m of this.meshes || []) m.material.needsUpdate = true;
    this.syncControls();
    this.requestRender();
  }

  setOutside(visible) {
    this.showOutside = visible;
    for (const m of this.meshes || []) if (this.outsideCell >= 0 && m.userData.cell === this.outsideCell) m.visible = visible;
    this.syncControls();
    this.requestRender();
  }

  setPortals(visible) {
    this.portalGroup.visible = visible;
    this.syncControls();
    this.requestRender();
  }

  // Walk: drag turns the head, W/A/S/D or the arrows move along the floor, Q/E down and up.
  setWalking(on) {
    this.walking = on;
    this.controls.enabled = !on;
    if (!on) {
      const forward = new THREE.Vector3();
      this.camera.getWorldDirection(forward);
      this.controls.target.copy(this.camera.position).add(forward.multiplyScalar(2));
      this.controls.update();
    }
    this.syncControls();
    this.canvas.focus();
  }

  pointerDown(e) {
    if (!this.walking) return;
    const start = { x: e.clientX, y: e.clientY };
    const euler = new THREE.Euler().setFromQuaternion(this.camera.quaternion, 'YXZ');
    const move = (m) => {
      const yaw = euler.y - (m.clientX - start.x) * 0.004, pitch = euler.x - (m.clientY - start.y) * 0.004;
      this.camera.quaternion.setFromEuler(new THREE.Euler(Math.max(-1.5, Math.min(1.5, pitch)), yaw, 0, 'YXZ'));
      this.requestRender();
    };
    const up = () => { window.removeEventListener('pointermove', move); window.removeEventListener('pointerup', up); };
    window.addEventListener('pointermove', move);
    window.addEventListener('pointerup', up);
  }

  tick() {
    if (!this.walking || !this.keys.size || this.ticking) return;
    this.ticking = true;
    let last = performance.now();
    const step = (now) => {
      const dt = Math.min(0.1, (now - last) / 1000);
      last = now;
      const speed = Math.max(1.5, this.bounds.getSize(new THREE.Vector3()).length() * 0.05) * dt;
      const forward = new THREE.Vector3();
      this.camera.getWorldDirection(forward);
      forward.y = 0;
      forward.normalize();
      const right = new THREE.Vector3().crossVectors(forward, new THREE.Vector3(0, 1, 0));
      const k = this.keys, move = new THREE.Vector3();
      if (k.has('KeyW') || k.has('ArrowUp')) move.add(forward);
      if (k.has('KeyS') || k.has('ArrowDown')) move.sub(forward);
      if (k.has('KeyD') || k.has('ArrowRight')) move.add(right);
      if (k.has('KeyA') || k.has('ArrowLeft')) move.sub(right);
      if (k.has('KeyE')) move.y += 1;
      if (k.has('KeyQ')) move.y -= 1;
      this.camera.position.addScaledVector(move, speed);
      this.render();
      if (this.walking && this.keys.size) requestAnimationFrame(step);
      else this.ticking = false;
    };
    requestAnimationFrame(step);
  }

  buildControls() {
    const bar = document.getElementById('controls');
    bar.innerHTML = '';
    const add = (html) => { const span = document.createElement('span'); span.className = 'control'; span.innerHTML = html; bar.appendChild(span); return span; };
    const modes = add(MODES.map((m) => `<label><input type="radio" name="mode" value="${m}"> ${
      { light: 'light', cells: 'colour by cell', density: 'texel density', error: 'error against the reference' }[m]}</label>`).join(''));
    modes.addEventListener('change', (e) => this.setMode(e.target.value));
    if (!this.lightmap) modes.querySelector('input[value=density]').parentElement.style.display = 'none';
    if (!this.lightmap?.errorTexture) modes.querySelector('input[value=error]').parentElement.style.display = 'none';
    const exposure = add(`exposure <input id="exposure" type="range" min="-8" max="8" step="0.1" value="0">
      <output id="exposure-value"></output> <button id="exposure-auto">auto</button>`);
    if (!this.lightmap) exposure.style.display = 'none';
    exposure.querySelector('input').addEventListener('input', (e) =>
      this.setExposure(this.autoExposureValue * 2 ** Number(e.target.value)));
    exposure.querySelector('button').addEventListener('click', () => this.setExposure(this.viewExposure()));
    const portals = add('<label><input id="portals" type="checkbox"> portals</label>');
    if (!(this.data.portals || []).length) portals.style.display = 'none';
    portals.querySelector('input').addEventListener('change', (e) => this.setPortals(e.target.checked));
    const open = add('<label><input id="open-walls" type="checkbox"> see in through walls</label>');
    open.querySelector('input').addEventListener('change', (e) => this.setOpenWalls(e.target.checked));
    const outside = add('<label><input id="outside" type="checkbox"> the outside</label>');
    if (this.outsideCell < 0) outside.style.display = 'none';
    outside.querySelector('input').addEventListener('change', (e) => this.setOutside(e.target.checked));
    const bumps = add('<label><input id="bumps" type="checkbox"> normal map (directional lightmap)</label>');
    if (!this.lightmap?.vector.length) bumps.style.display = 'none';
    bumps.querySelector('input').addEventListener('change', (e) => this.setBumps(e.target.checked));
    const sphere = add(`<label><input id="probe-sphere" type="checkbox"> probe-lit sphere (1.5 m ahead, ` +
      `${this.probeBand === 4 ? 'L2 + band 4' : 'L2'} SH)</label>`);
    if (!this.probeSphere) sphere.style.display = 'none';
    sphere.querySelector('input').addEventListener('change', (e) => this.setProbeSphere(e.target.checked));
    const walk = add('<label><input id="walk" type="checkbox"> walk (drag to look, W A S D Q E to move)</label>');
    walk.querySelector('input').addEventListener('change', (e) => this.setWalking(e.target.checked));
    const views = add('view <select id="views"></select>');
    const select = views.querySelector('select');
    for (const v of this.views) select.add(new Option(v.name, v.name));
    select.addEventListener('change', () => {
      this.showView(select.value);
      this.setExposure(this.viewExposure());  // a dim room is shown as readable as a lit one
    });
    this.syncControls();
  }

  syncControls() {
    const views = document.getElementById('views');
    if (views && this.currentView) views.value = this.currentView;
    const radio = document.querySelector(`input[name=mode][value=${this.mode}]`);
    if (radio) radio.checked = true;
    const slider = document.getElementById('exposure');
    if (slider) {
      slider.value = Math.log2(this.exposure / this.autoExposureValue).toFixed(1);
      document.getElementById('exposure-value').textContent = `${Number(slider.value) >= 0 ? '+' : ''}${slider.value} EV`;
    }
    const portals = document.getElementById('portals');
    if (portals) portals.checked = this.portalGroup.visible;
    const walk = document.getElementById('walk');
    if (walk) walk.checked = this.walking;
    const outside = document.getElementById('outside');
    if (outside) outside.checked = this.showOutside;
    const open = document.getElementById('open-walls');
    if (open) open.checked = this.openWalls;
    const legend = document.getElementById('legend');
    if (!legend) return;
    // Cell names come from the scene file: text nodes, never markup.
    if (this.mode === 'cells') {
      legend.replaceChildren();
      this.cells.forEach((c, i) => {
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = '#' + cellColour(i).getHexString();
        legend.append(swatch, document.createTextNode(String(c.name) + ' '));
      });
    } else {
      legend.innerHTML = this.legend();
    }
  }

  // The legend of the modes other than 'cells', as markup made only of cpgi's own text and numbers.
  legend() {
    if (this.mode === 'error')
      return `(A − B) / RMS(B), per texel: <span class="swatch" style="background:#00f"></span>−${ERROR_SCALE * 100} % or less
        <span class="swatch" style="background:#fff"></span>0 <span class="swatch" style="background:#f00"></span>+${ERROR_SCALE * 100} % or more`;
    if (this.mode === 'density' && this.lightmap)
      return `texels per metre: <span class="ramp"></span> ${formatNumber(this.lightmap.density.min)} (blue) to ${formatNumber(this.lightmap.density.max)} (red); alternate texels shaded`;
    return this.lightmap ? 'radiance B/π × exposure, tone-mapped 1 − e<sup>−x</sup>' : 'albedo under a sky light (no lightmap)';
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => { this.pending = false; this.render(); });
  }

  render() {
    if (this.probeSphere?.visible) this.placeProbeSphere();
    this.renderer.render(this.scene, this.camera);
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight, v = new THREE.Vector3();
    const visible = this.portalGroup.visible ? this.meshes.filter((m) => m.visible) : [];
    for (const { label, centre } of this.portalLabels || []) {
      v.copy(centre).project(this.camera);
      // A portal behind a wall keeps its label hidden: a label floating on a wall names nothing there.
      const shown = this.portalGroup.visible && v.z < 1 && Math.abs(v.x) < 1 && Math.abs(v.y) < 1 &&
        !this.hidden(centre, visible);
      label.style.display = shown ? '' : 'none';
      if (shown) label.style.transform = `translate(${((v.x + 1) / 2) * w}px, ${((1 - v.y) / 2) * h}px) translate(-50%, -50%)`;
    }
  }

  // Whether a surface among `meshes` stands between the camera and `point` (faces drawn from behind, with
  // "see in through walls", do not count, as on screen).
  hidden(point, meshes) {
    const from = this.camera.position, direction = point.clone().sub(from), distance = direction.length();
    const ray = new THREE.Raycaster(from, direction.normalize(), 0, distance * 0.98);
    return ray.intersectObjects(meshes, false).length > 0;
  }

  // An exposure for what the camera sees: the 90th percentile of the radiance under a 32 × 24 grid of
  // pixels to 0.8 (as autoExposure does for the whole lightmap; cpgi's view-*.png are exposed alike).
  viewExposure() {
    if (!this.lightmap) return this.exposure;
    const seen = [];
    for (let gy = 0; gy < 24; ++gy)
      for (let gx = 0; gx < 32; ++gx) {
        const r = this.expectedRadianceAt(((gx + 0.5) / 32) * this.canvas.clientWidth, ((gy + 0.5) / 24) * this.canvas.clientHeight);
        if (r > 0) seen.push(r);
      }
    if (!seen.length) return this.autoExposureValue;
    seen.sort((a, b) => a - b);
    return 0.8 / seen[Math.floor(0.9 * (seen.length - 1))];
  }

  // For the browser test: the radiance the lightmap holds where pixel (x, y) of the canvas looks,
  // or null where it sees no baked surface.
  expectedRadianceAt(x, y) {
    const ndc = new THREE.Vector2((x / this.canvas.clientWidth) * 2 - 1, 1 - (y / this.canvas.clientHeight) * 2);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    const hit = ray.intersectObjects(this.meshes.filter((m) => m.visible), false)[0];
    if (!hit || !hit.uv1 || !this.lightmap) return null;
    const lm = this.data.lightmap;
    const tx = Math.min(lm.width - 1, Math.floor(hit.uv1.x * lm.width));
    const ty = Math.min(lm.height - 1, Math.floor(hit.uv1.y * lm.height));
    const i = ty * lm.width + tx, rgb = this.lightmap.rgb;
    return (0.2126 * rgb[4 * i] + 0.7152 * rgb[4 * i + 1] + 0.0722 * rgb[4 * i + 2]) / Math.PI;
  }
}

function main() {
  const data = JSON.parse(document.getElementById('cpgi-data').textContent);
  document.title = data.title;
  document.getElementById('title').textContent = data.title;
  buildPanels(document.getElementById('panels'), data);
  if (!window.WebGL2RenderingContext) {
    document.getElementById('status').textContent = 'This browser has no WebGL 2; the numbers are below.';
    return;
  }
  const glb = base64Bytes(document.getElementById('cpgi-glb').textContent);
  setCellPalette(data.cells);
  window.cpgiViewer = new Viewer(data, glb);
  window.cpgiViewer.cellColour = (i) => '#' + cellColour(i).getHexString();
}

main();
