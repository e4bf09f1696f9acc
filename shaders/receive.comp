// One shot (thesis ch. 6, step 3): every texel of a visible patch gathers ΔB_i = ρ_i Σ_k ΔB_k F(dA_i → A_k)
// with the disk approximation F ≈ A_k cosθ_i cosθ_k / (π r² + A_k) over pieces of the shooter, refined
// where the receiver is near: each visibility region's residual pyramid (shooter_pyramid.comp) is walked
// from its top node down, a node being used whole when the receiver is farther than uFarField × its
// radius, down to texels and 4×4 points per texel. Each region has its own item buffer, seen from its
// centre, so a large shooter is not one point for visibility either.
//
// No shared memory and no barrier here: on llvmpipe a barrier turns every invocation into a coroutine,
// which measured twice as slow for this pass (seed3, 64² per quad).
#include "common.glsl"
#include "atlas_buffers.glsl"
layout(std430, binding = 0) readonly buffer Patches { PatchInfo patches[]; };
#define SEEN_PATCH_COVERS
#include "visibility.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 3) readonly buffer Tiles { ivec4 tiles[]; };
layout(std430, binding = 4) readonly buffer TileList { uint tileCount; uint tileArgs[3]; uint tileList[]; };
layout(std430, binding = 15) readonly buffer Nodes { Node nodes[]; };
// What this shot gave each receiver texel (0 where it gave nothing), so that rescale_shot.comp can take
// back a shot that delivered more than its power.
layout(std430, binding = 21) writeonly buffer ShotGain { vec4 shotGain[]; };
// Per texel: bit 31 set where it does not receive (uMasked: a lamp's shot refined at some texels only),
// the low bits what the lamps' shots found there (uWriteFlags; LampFlag in solve_result.h).
layout(std430, binding = 23) buffer TexelFlags { uint texelFlags[]; };
uniform bool uMasked;
uniform bool uWriteFlags;
#define NOT_RECEIVING 0x80000000u
#define LAMP_EDGE 1u
#define LAMP_NEAR 2u
#define LAMP_PARTLY_SEEN 4u

uniform int uShooter;
uniform int uRegionCount;
uniform bool uLampShot;  // an emitter's own shot: edge and near receivers are resampled (main())
uniform float uRegionShare;  // 1 / replicas: the share of each entry's eye when regions are replicated
uniform vec3 uEyes[MAX_REGIONS];
// Where each region's chart texel (0, 0) samples (m): the shooter's origin moved to the region's corner,
// so that a far piece finds its power's mean without reading the patch and region tables.
uniform vec3 uRegionOrigins[MAX_REGIONS];
uniform mat3 uToShooter;
uniform vec3 uShooterNormal;
// The most sub-disks per edge of a binned texel near a receiver (fromTexel; ray_shot.cpp, kNearBinSubdisks).
#define NEAR_BIN_SUBDISKS 32
uniform vec3 uTexelU, uTexelV;  // the shooter's texel edges (m)
uniform float uTexelRadius;
uniform float uFarField;
// How near (in the receiver's texel edges) a shooter piece must come for the receiver to be resampled.
#define NEAR_TEXELS 2.0

#ifdef DIRECTIONAL
#include "directional.glsl"
vec4 gArrival = vec4(0.0);  // this receiver's arrival moments (noteArrival), stored by main()
float gReceiverArea = 0.0;  // this receiver texel's area (m²), set by main()
uniform bool uShooterLobes;  // false: every texel of this shooter is Lambertian, skip the lobes
#endif

// The directional hook of the kernels below: the contribution f of a shooter piece at receiver + v,
// scaled by the piece's emission lobe towards the receiver, and its direction noted. Without
// DIRECTIONAL, f itself.
vec3 emitted(vec3 f, vec4 lobe, vec3 v, vec3 n) {
#ifdef DIRECTIONAL
  if (uShooterLobes)
#ifdef BINNED
    f *= lobe.w < 0.0 ? binnedFactor(lobe, uShooterNormal, -normalize(v))
                      : vec3(lobeFactor(lobe, uShooterNormal, -normalize(v), receiverBlur(v, n, uShooterNormal, gReceiverArea)));
#else
    f *= lobeFactor(lobe, uShooterNormal, -normalize(v), receiverBlur(v, n, uShooterNormal, gReceiverArea));
#endif
  noteArrival(gArrival, v, n, f);
#endif
  return f;
}

// A shooter texel's and a pyramid node's lobe (DIRECTIONAL only; else Lambertian).
vec4 texelLobe(ivec2 t) {
#ifdef DIRECTIONAL
  return emissionLobe[texel(t)];
#else
  return vec4(0.0);
#endif
}
vec4 nodeLobeAt(int i) {
#ifdef DIRECTIONAL
  return nodeLobe[i];
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

// A far piece of region r's pyramid by four points at its power's mean ± its standard deviation along
// each of the chart's axes, a quarter of its power at each: the two-point rule of the power's own
// distribution, which for a uniform node is the 2×2 Gauss rule (its error O((R/r)⁴) is what lets uFarField
// be as small as 2). With Gauss points over the node's area at its mean radiosity, the shot of a wall
// that a lamp lights in a band, or a beam in a ring round a door, gathered 0.94–0.97 of its power where
// rays give 1.00 (bench/shot_probe.cpp), and the shot's rescale to its power handed the difference to every
// receiver alike, rooms behind doors included (openings' room C +3 %).
vec3 nodePiece(vec3 x, vec3 n, int r, Node p, vec4 l) {
  vec2 sd = sqrt(p.moments.zw);
  vec3 c = uRegionOrigins[r] + p.moments.x * uTexelU + p.moments.y * uTexelV;
  vec3 hu = sd.x * uTexelU, hv = sd.y * uTexelV;
  float a = 0.25 * p.centreArea.w;
  vec3 rad = p.radiosityRadius.rgb;
  return point(x, n, c - hu - hv, a, rad, l) + point(x, n, c + hu - hv, a, rad, l) +
         point(x, n, c - hu + hv, a, rad, l) + point(x, n, c + hu + hv, a, rad, l);
}

bool far(vec3 x, vec3 c, float radius, vec4 lobe) {
  vec3 d = c - x;
  float f = uFarField * radius;
#ifdef DIRECTIONAL
  if (!lobeResolvesPiece(lobe, uShooterNormal, dot(d, d), radius)) return false;
#endif
  return dot(d, d) > f * f;
}

// How close the receiver came to the pieces it gathered from: the distance to each piece's centre less
// its radius, smallest over the walk (main() resamples a receiver that came near).
float gNearest = 1e30;
void noteNearest(vec3 x, vec3 c, float radius) { gNearest = min(gNearest, distance(x, c) - radius); }

vec3 fromTexel(vec3 x, vec3 n, ivec2 t) {
  vec4 pa = posArea[texel(t)];
  vec3 b = residual[texel(t)].rgb;
  vec4 l = texelLobe(t);
  noteNearest(x, pa.xyz, uTexelRadius);
  if (far(x, pa.xyz, uTexelRadius, l)) {
    // 2×2 Gauss points, as for larger pieces: the disk form's "+ A" would bias a texel 2 radii away
    // by up to 1/(2π) ≈ 16 % low.
    const float g = 0.5773502692;
    vec3 hu = 0.5 * g * uTexelU, hv = 0.5 * g * uTexelV;
    float a = 0.25 * pa.w;
    return point(x, n, pa.xyz - hu - hv, a, b, l) + point(x, n, pa.xyz + hu - hv, a, b, l) +
           point(x, n, pa.xyz - hu + hv, a, b, l) + point(x, n, pa.xyz + hu + hv, a, b, l);
  }
  // Near: k×k sub-disks, where the disk form keeps F finite as r → 0: 4, or for a binned texel enough
  // that their spacing is at most a quarter of the receiver's distance from its plane (its bins are read
  // at each sub-disk's direction, and next to the plane a step along it is a large step in direction:
  // ray_shot.cpp, Gather::nearSubdisks).
  int k = 4;
#ifdef BINNED
  if (l.w < 0.0) {
    float edge = max(length(uTexelU), length(uTexelV));
    float distance = max(abs(dot(x - pa.xyz, uShooterNormal)), 1e-4);
    k = clamp(int(ceil(4.0 * edge / distance)), 4, NEAR_BIN_SUBDISKS);
  }
#endif
  float step = 1.0 / float(k);
  vec3 sum = vec3(0.0);
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      vec3 c = pa.xyz + ((float(i) + 0.5) * step - 0.5) * uTexelU + ((float(j) + 0.5) * step - 0.5) * uTexelV;
      sum += disk(x, n, c, pa.w * step * step, b, l);
    }
  return sum;
}

// Depth-first walk of region r's pyramid; a stack entry packs (level, node x, node y).
#define STACK 48
// Whether region r shoots anything (a loose triangle's region may have no texel).
bool blocksOf(int r) { return nodes[regions[r].levelOffset[regions[r].top.x]].centreArea.w > 0.0; }

vec3 fromRegion(vec3 x, vec3 n, int r) {
  ivec4 rect = regions[r].rect;
  int stack[STACK];
  int top = regions[r].top.x;
  stack[0] = top << 26;
  int sp = 1;
  vec3 sum = vec3(0.0);
  while (sp > 0) {
    int e = stack[--sp];
    int k = e >> 26;
    ivec2 at = ivec2(e & 0x1FFF, (e >> 13) & 0x1FFF);
    if (k == 0) {
      ivec2 t = rect.xy + at;
      if (int(normalPatch[texel(t)].w) == uShooter) sum += fromTexel(x, n, t);
      continue;
    }
    ivec2 dims = levelDims(rect, k);
    int index = regions[r].levelOffset[k] + at.y * dims.x + at.x;
    Node p = nodes[index];
    if (p.centreArea.w <= 0.0) continue;
    vec4 lobe = nodeLobeAt(index);
    if (k < top && far(x, p.centreArea.xyz, p.radiosityRadius.w, lobe)) {
      noteNearest(x, p.centreArea.xyz, p.radiosityRadius.w);
      sum += nodePiece(x, n, r, p, lobe);
      continue;
    }
    ivec2 below = k == 1 ? rect.zw - rect.xy : levelDims(rect, k - 1);
    for (int dy = 1; dy >= 0; --dy)
      for (int dx = 1; dx >= 0; --dx) {
        ivec2 c = 2 * at + ivec2(dx, dy);
        if (c.x < below.x && c.y < below.y) stack[sp++] = ((k - 1) << 26) | (c.y << 13) | c.x;
      }
  }
  return sum;
}

// ΔB F from region r, unoccluded, at x with normal n.
vec3 fromRegionWhole(vec3 x, vec3 n, int r) {
  int rootIndex = regions[r].levelOffset[regions[r].top.x];
  Node root = nodes[rootIndex];
  vec4 lobe = nodeLobeAt(rootIndex);
  if (!far(x, root.centreArea.xyz, root.radiosityRadius.w, lobe)) return fromRegion(x, n, r);
  noteNearest(x, root.centreArea.xyz, root.radiosityRadius.w);
  return nodePiece(x, n, r, root, lobe);
}

vec3 gReceiver = vec3(0.0);  // the receiver texel's position (m), set by main()

// Whether gReceiver lies on patch `seen`'s chart (within a quarter texel of its edge): its parallelogram
// origin + [0, w] texelU + [0, h] texelV, in the patch's plane.
bool seenPatchCovers(int seen) {
  PatchInfo q = patches[seen];
  vec3 u = q.texelU.xyz, v = q.texelV.xyz, d = gReceiver - q.origin.xyz;
  float uu = dot(u, u), vv = dot(v, v), uv = dot(u, v), du = dot(d, u), dv = dot(d, v);
  float det = uu * vv - uv * uv;
  if (det <= 0.0) return false;
  vec2 ij = vec2(du * vv - dv * uv, dv * uu - du * uv) / det;
  return all(greaterThanEqual(ij, vec2(-0.25))) && all(lessThanEqual(ij, vec2(q.rect.zw) + 0.25));
}

// Whether patch `seen` lies across the segment from the eye to the receiver (`local`: the receiver from the
// eye, in shooter coordinates): then what the pixel shows is a wall the receiver lies behind, however near
// the receiver's plane it is seen (a partition's edge where the far room's ceiling runs on), not the
// coincident face of a zero-thickness partition or a door's jamb seen edge-on beside the wall it meets.
// Its plane alone is not enough: the jamb's plane lies between an eye in the room and the wall beside the
// door, and hides none of that wall.
bool seenPatchBlocks(int seen, vec3 local) {
  PatchInfo q = patches[seen];
  vec3 u = q.texelU.xyz, v = q.texelV.xyz, n = cross(u, v);
  float slack = uPlaneSlack * length(n);
  vec3 eye = gReceiver - transpose(uToShooter) * local;
  float receiverSide = dot(gReceiver - q.origin.xyz, n), eyeSide = dot(eye - q.origin.xyz, n);
  if (!((receiverSide > slack && eyeSide < -slack) || (receiverSide < -slack && eyeSide > slack))) return false;
  vec3 d = mix(eye, gReceiver, eyeSide / (eyeSide - receiverSide)) - q.origin.xyz;
  float uu = dot(u, u), vv = dot(v, v), uv = dot(u, v), du = dot(d, u), dv = dot(d, v);
  float det = uu * vv - uv * uv;
  if (det <= 0.0) return false;
  vec2 ij = vec2(du * vv - dv * uv, dv * uu - du * uv) / det;
  return all(greaterThanEqual(ij, vec2(0.0))) && all(lessThanEqual(ij, vec2(q.rect.zw)));
}

// Whether region r's eye sees the receiver point x (normal n) of patch `id`.
bool seesPoint(int r, vec3 x, vec3 n, int id) {
  vec3 local = uToShooter * (x - uEyes[r]);
  if (local.z <= 0.0 || dot(n, uEyes[r] - x) <= 0.0) return false;
  gReceiver = x;
  return visibleFromShooter(local, uToShooter * n, id, r);
}

// Sub-point (i, j) of a 4×4 grid over a texel of edges u, v, relative to its centre.
vec3 subPoint(int i, int j, vec3 u, vec3 v) { return (float(i) - 1.5) * 0.25 * u + (float(j) - 1.5) * 0.25 * v; }

void main() {
  uint entry = gl_WorkGroupID.y * WORK_LIST_WIDTH + gl_WorkGroupID.x;
  if (entry >= tileCount) return;  // uniform across the group
  ivec4 tile = tiles[tileList[entry]];
  // The shooter's own tiles: nothing to gather; tile_stats.comp zeroes them after the shot.
  if (tile.z == uShooter) return;
  ivec4 chart = patches[tile.z].rect;
  ivec2 t = tile.xy + ivec2(gl_LocalInvocationID.xy);
  // Tiles are 8×8 from the chart corner and may overhang the chart: keep only this chart's texels.
  if (any(greaterThanEqual(t, chart.xy + chart.zw))) return;
  int tx = texel(t);
  vec4 np = normalPatch[tx];
  if (int(np.w) != tile.z) return;
  if (uMasked && (texelFlags[tx] & NOT_RECEIVING) != 0u) {
    shotGain[tx] = vec4(0.0);  // rescale_shot.comp reads it for every texel of a listed tile
    return;
  }
  vec3 x = posArea[tx].xyz;
  gReceiver = x;
  vec3 e = vec3(0.0);
#ifdef DIRECTIONAL
  gReceiverArea = posArea[tx].w;
#endif
  // Visibility at the texel's centre; in a lamp's shot also at its outer sub-points, and a texel where
  // they differ because of something farther than a texel away (a shadow or beam edge, not the wall a
  // floor texel touches) is an edge texel. Where the centre is hidden, a point counts as seen only when its
  // pixel shows its own patch: the other rules (what the pixel shows lies behind the receiver's plane)
  // read a crack between a zero-thickness wall and the floor as a view through it, and 20 points a texel
  // found 3× the cracks (EnergyConservation.NoLightOverAWallIntoTheRoomBehind: 6e-5 of the light).
  // In a lamp's shot (at most 16 entries, gl_shot_backend.cpp: shootGl):
  int seenBy = 0;  // bit r: region r's eye sees the receiver's centre
  int shooting = 0;  // bit r: region r shoots something
  bool edge = false;
  vec3 texelU = patches[tile.z].texelU.xyz, texelV = patches[tile.z].texelV.xyz;
  float texelSize = max(length(texelU), length(texelV));
  for (int r = 0; r < uRegionCount; ++r) {
    if (!blocksOf(r)) continue;
    if (uLampShot) shooting |= 1 << r;
    gOccluderGap = 1e30;
    bool seen = seesPoint(r, x, np.xyz, tile.z);
    float centreGap = gOccluderGap;
    for (int c = 0; uLampShot && !edge && c < 4; ++c) {
      gOccluderGap = 1e30;
      bool corner = seesPoint(r, x + subPoint((c & 1) != 0 ? 3 : 0, (c & 2) != 0 ? 3 : 0, texelU, texelV), np.xyz, tile.z);
      edge = seen ? !corner && gOccluderGap > texelSize : corner && gSeenOwn && centreGap > texelSize;
    }
    if (!seen) continue;
    if (uLampShot) seenBy |= 1 << r;
    e += fromRegionWhole(x, np.xyz, r);
  }
  // In a lamp's shot, edge texels and receivers within a few of their own texels of the lamp are
  // resampled at 4×4 points over the texel, whose centre's value is not the texel's mean there. Edge: a
  // lamp's beam out of its housing lit the door frame's texels whole or not at all (spot-door's lit room
  // +4 %, the hemisphere buffer +15 %); each point has its own visibility. Near: the walls of a lamp's
  // tube, a texel from the lamp, gathered 11 % less than their area gets, and the shot's rescale to what
  // its eyes saw covered handed that to everything outside the tube; visibility stays the centre's. The
  // outer points' own visibility darkens contact corners (a floor point millimetres from a wall looks up
  // a pixel showing the wall), hence the occluder's distance above. Lamps only: the reference (and a
  // lightmap read bilinearly) takes a texel's value at its centre, which a mean over the texel leaves
  // on coarse atlases, and in every strong shot this cost 2.7× the CPU (openings, seed1).
  bool near = uLampShot && seenBy != 0 && gNearest < NEAR_TEXELS * texelSize;
  if (uWriteFlags && uLampShot) {
    uint found = (edge ? LAMP_EDGE : 0u) | (near ? LAMP_NEAR : 0u) |
                 (seenBy != 0 && seenBy != shooting ? LAMP_PARTLY_SEEN : 0u);
    if (found != 0u) texelFlags[tx] |= found;
  }
  if (edge || near) {
    e = vec3(0.0);
#ifdef DIRECTIONAL
    gArrival = vec4(0.0);
#endif
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        vec3 xs = x + subPoint(i, j, texelU, texelV);
        for (int r = 0; r < uRegionCount; ++r)
          if (edge ? blocksOf(r) && seesPoint(r, xs, np.xyz, tile.z) && ((seenBy & (1 << r)) != 0 || gSeenOwn)
                   : (seenBy & (1 << r)) != 0)
            e += fromRegionWhole(xs, np.xyz, r);
      }
    e *= 1.0 / 16.0;
#ifdef DIRECTIONAL
    gArrival *= 1.0 / 16.0;
#endif
  }
  e *= uRegionShare;
#ifdef DIRECTIONAL
  gArrival *= uRegionShare;
#endif
  shotGain[tx] = vec4(e, 0.0);
  if (e == vec3(0.0)) return;
#ifdef DIRECTIONAL
  arrivals[tx] += gArrival;
#endif
  vec3 gained = albedo[tx].rgb * e;
  incident[tx] = incident[tx] + vec4(e, 0.0);
  radiosity[tx] = radiosity[tx] + vec4(gained, 0.0);
  residual[tx] = residual[tx] + vec4(gained, 0.0);
}
