// One shot (thesis ch. 6, step 3): every texel of a visible patch gathers ΔB_i = ρ_i Σ_k ΔB_k F(dA_i → A_k)
// with the disk approximation F ≈ A_k cosθ_i cosθ_k / (π r² + A_k) over pieces of the shooter, refined
// where the receiver is near: a region (one disk) → its texel blocks → texels → 4×4 points per texel,
// each level used when the receiver is farther than uFarField × the piece's radius. Each region has its
// own item buffer, seen from its centre, so a large shooter is not one point for visibility either.
#include "common.glsl"
#include "atlas_buffers.glsl"
#include "visibility.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 3) readonly buffer Tiles { ivec4 tiles[]; };
layout(std430, binding = 4) readonly buffer TileList { uint tileCount; uint tileArgs[3]; uint tileList[]; };
layout(std430, binding = 6) readonly buffer Blocks { Block blocks[]; };

#define MAX_REGIONS 16
uniform int uShooter;
uniform int uRegions;      // blocks[0 .. uRegions) are regions
uniform int uBlockCount;   // blocks[uRegions .. uRegions + uBlockCount) are texel blocks
uniform vec3 uEyes[MAX_REGIONS];
uniform mat3 uToShooter;
uniform vec3 uShooterNormal;
uniform vec3 uTexelU, uTexelV;  // the shooter's texel edges (m)
uniform float uTexelRadius;
uniform float uFarField;

#ifdef DIRECTIONAL
#include "directional.glsl"
vec4 gArrival = vec4(0.0);  // this receiver's arrival moments (noteArrival), stored by main()
float gReceiverArea = 0.0;  // this receiver texel's area (m²), set by main()
#endif

// The directional hook of the kernels below: the contribution f of a shooter piece at receiver + v,
// scaled by the piece's emission lobe towards the receiver, and its direction noted. Without
// DIRECTIONAL, f itself.
vec3 emitted(vec3 f, vec4 lobe, vec3 v, vec3 n) {
#ifdef DIRECTIONAL
  f *= lobeFactor(lobe, uShooterNormal, -normalize(v), receiverBlur(v, n, uShooterNormal, gReceiverArea));
  noteArrival(gArrival, v, n, f);
#endif
  return f;
}

// A shooter texel's lobe (DIRECTIONAL only; else Lambertian).
vec4 texelLobe(ivec2 t) {
#ifdef DIRECTIONAL
  return emissionLobe[texel(t)];
#else
  return vec4(0.0);
#endif
}

// ΔB F(dA_x → disk): the receiver at x with normal n, a disk of `area` at c facing uShooterNormal.
vec3 disk(vec3 x, vec3 n, vec3 c, float area, vec3 unshot, vec4 lobe) {
  vec3 v = c - x;
  float r2 = dot(v, v);
  float ci = dot(n, v), cs = -dot(uShooterNormal, v);
  if (ci <= 0.0 || cs <= 0.0 || r2 <= 0.0) return vec3(0.0);
  return emitted(unshot * (area * ci * cs / (r2 * (PI * r2 + area))), lobe, v, n);
}

// The same piece seen from afar (r > uFarField × its radius): the "+ A" of the disk formula only keeps
// F finite as r → 0, and off the axis it biases F low by about A / (π r²) (3 % for a 0.4 m lamp 1.2 m
// away), so coarse pieces use the point form.
vec3 point(vec3 x, vec3 n, vec3 c, float area, vec3 unshot, vec4 lobe) {
  vec3 v = c - x;
  float r2 = dot(v, v);
  float ci = dot(n, v), cs = -dot(uShooterNormal, v);
  if (ci <= 0.0 || cs <= 0.0 || r2 <= 0.0) return vec3(0.0);
  return emitted(unshot * (area * ci * cs / (PI * r2 * r2)), lobe, v, n);
}

// A far piece (texel rectangle `rect`, uniform mean radiosity) by 2×2 Gauss points: the point form's
// error falls from O((R/r)²) to O((R/r)⁴), which is what lets uFarField be as small as 2.
vec3 piece(vec3 x, vec3 n, Block b) {
  const float g = 0.5773502692;  // 1/√3
  vec3 hu = 0.5 * float(b.rect.z - b.rect.x) * uTexelU, hv = 0.5 * float(b.rect.w - b.rect.y) * uTexelV;
  vec3 c = b.centreArea.xyz;
  float a = 0.25 * b.centreArea.w;
  vec3 rad = b.radiosityRadius.rgb;
  vec4 l = b.lobe;
  return point(x, n, c - g * hu - g * hv, a, rad, l) + point(x, n, c + g * hu - g * hv, a, rad, l) +
         point(x, n, c - g * hu + g * hv, a, rad, l) + point(x, n, c + g * hu + g * hv, a, rad, l);
}

bool far(vec3 x, vec3 c, float radius, vec4 lobe) {
  vec3 d = c - x;
  float f = uFarField * radius;
#ifdef DIRECTIONAL
  if (!lobeResolvesPiece(lobe, uShooterNormal, dot(d, d), radius)) return false;
#endif
  return dot(d, d) > f * f;
}

vec3 fromTexel(vec3 x, vec3 n, ivec2 t) {
  vec4 pa = posArea[texel(t)];
  vec3 b = residual[texel(t)].rgb;
  vec4 l = texelLobe(t);
  if (far(x, pa.xyz, uTexelRadius, l)) {
    // 2×2 Gauss points, as for larger pieces: the disk form's "+ A" would bias a texel 2 radii away
    // by up to 1/(2π) ≈ 16 % low.
    const float g = 0.5773502692;
    vec3 hu = 0.5 * g * uTexelU, hv = 0.5 * g * uTexelV;
    float a = 0.25 * pa.w;
    return point(x, n, pa.xyz - hu - hv, a, b, l) + point(x, n, pa.xyz + hu - hv, a, b, l) +
           point(x, n, pa.xyz - hu + hv, a, b, l) + point(x, n, pa.xyz + hu + hv, a, b, l);
  }
  // Near: 4×4 sub-disks, where the disk form keeps F finite as r → 0.
  vec3 sum = vec3(0.0);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      vec3 c = pa.xyz + (float(i) - 1.5) * 0.25 * uTexelU + (float(j) - 1.5) * 0.25 * uTexelV;
      sum += disk(x, n, c, pa.w / 16.0, b, l);
    }
  return sum;
}

vec3 fromRegion(vec3 x, vec3 n, int r) {
  Block g = blocks[r];
  if (far(x, g.centreArea.xyz, g.radiosityRadius.w, g.lobe))
    return piece(x, n, g);
  vec3 sum = vec3(0.0);
  int per = uBlockCount / uRegions;  // blocks are stored region by region (shooter_blocks.comp)
  for (int k = uRegions + r * per; k < uRegions + (r + 1) * per; ++k) {
    Block b = blocks[k];
    if (b.centreArea.w <= 0.0) continue;
    if (far(x, b.centreArea.xyz, b.radiosityRadius.w, b.lobe)) {
      sum += piece(x, n, b);
      continue;
    }
    for (int ty = b.rect.y; ty < b.rect.w; ++ty)
      for (int tx = b.rect.x; tx < b.rect.z; ++tx) {
        ivec2 t = ivec2(tx, ty);
        if (int(normalPatch[texel(t)].w) == uShooter) sum += fromTexel(x, n, t);
      }
  }
  return sum;
}

void main() {
  uint entry = gl_WorkGroupID.y * WORK_LIST_WIDTH + gl_WorkGroupID.x;
  if (entry >= tileCount) return;
  ivec4 tile = tiles[tileList[entry]];
  ivec2 t = tile.xy + ivec2(gl_LocalInvocationID.xy);
  vec4 np = normalPatch[texel(t)];
  int id = int(np.w);
  // Tiles are 8×8 from the chart corner and may overhang into a neighbour: keep only this tile's patch.
  if (id != tile.z || id == uShooter) return;
  vec3 x = posArea[texel(t)].xyz;
  vec3 e = vec3(0.0);
#ifdef DIRECTIONAL
  gReceiverArea = posArea[texel(t)].w;
#endif
  for (int r = 0; r < uRegions; ++r) {
    if (blocks[r].centreArea.w <= 0.0) continue;
    vec3 local = uToShooter * (x - uEyes[r]);
    if (local.z <= 0.0 || dot(np.xyz, uEyes[r] - x) <= 0.0) continue;
    if (!visibleFromShooter(local, id, r)) continue;
    e += fromRegion(x, np.xyz, r);
  }
  if (e == vec3(0.0)) return;
#ifdef DIRECTIONAL
  arrivals[texel(t)] += gArrival;
#endif
  vec3 gained = albedo[texel(t)].rgb * e;
  incident[texel(t)] = incident[texel(t)] + vec4(e, 0.0);
  radiosity[texel(t)] = radiosity[texel(t)] + vec4(gained, 0.0);
  residual[texel(t)] = residual[texel(t)] + vec4(gained, 0.0);
}
