// Splits the shooter into texel blocks (sub-shooters) grouped into visibility regions: per piece the
// area, the area-weighted centre, the mean unshot radiosity and a bounding radius. Receivers far from a
// region take it as one disk; nearer ones use its blocks, then texels (receive.comp).
#include "common.glsl"
#include "atlas_buffers.glsl"
layout(local_size_x = 64) in;
#ifdef DIRECTIONAL
#include "directional.glsl"
shared LobeMix sLobe[64];
uniform vec3 uShooterNormal;
#endif
layout(std430, binding = 6) buffer Blocks { Block blocks[]; };
uniform int uShooter;
uniform ivec4 uRect;         // shooter chart x, y, w, h
uniform ivec2 uBlocks;       // blocks along x and y (at most 8 × 8), a multiple of uRegions
uniform ivec2 uRegions;      // regions along x and y
uniform float uTexelRadius;  // half the diagonal of one texel, m

shared vec4 sCentreArea[64];
shared vec4 sRadiosityRadius[64];
shared int sRegion[64];

void main() {
  uint k = gl_LocalInvocationID.x;
  int count = uBlocks.x * uBlocks.y, regions = uRegions.x * uRegions.y;
  vec4 ca = vec4(0.0), rr = vec4(0.0);
  int region = -1;
  ivec2 per = uBlocks / uRegions;
  if (int(k) < count) {
    ivec2 b = ivec2(int(k) % uBlocks.x, int(k) / uBlocks.x);
    region = (b.x / per.x) + (b.y / per.y) * uRegions.x;
    ivec2 lo = uRect.xy + (uRect.zw * b) / uBlocks;
    ivec2 hi = uRect.xy + (uRect.zw * (b + 1)) / uBlocks;
    vec3 power = vec3(0.0), moment = vec3(0.0);
    float area = 0.0;
#ifdef DIRECTIONAL
    LobeMix lobes = LobeMix(vec4(0.0), vec4(0.0));
#endif
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        ivec2 t = ivec2(x, y);
        if (int(normalPatch[texel(t)].w) != uShooter) continue;
        vec4 pa = posArea[texel(t)];
        power += residual[texel(t)].rgb * pa.w;
        moment += pa.xyz * pa.w;
        area += pa.w;
#ifdef DIRECTIONAL
        vec3 r = residual[texel(t)].rgb;
        lobes = addLobe(lobes, emissionLobe[texel(t)], uShooterNormal, (r.r + r.g + r.b) * pa.w);
#endif
      }
    vec3 centre = area > 0.0 ? moment / area : vec3(0.0);
    float radius = 0.0;
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        ivec2 t = ivec2(x, y);
        if (int(normalPatch[texel(t)].w) != uShooter) continue;
        radius = max(radius, distance(posArea[texel(t)].xyz, centre));
      }
    ca = vec4(centre, area);
    rr = vec4(area > 0.0 ? power / area : vec3(0.0), radius + uTexelRadius);
    // Blocks are stored region by region, so a receiver near one region walks only that region's.
    ivec2 inRegion = b % per;
    uint slot = uint(regions + region * per.x * per.y + inRegion.y * per.x + inRegion.x);
    blocks[slot].centreArea = ca;
    blocks[slot].radiosityRadius = rr;
    blocks[slot].rect = ivec4(lo, hi);
    blocks[slot].region = ivec4(region, 0, 0, 0);
#ifdef DIRECTIONAL
    blocks[slot].lobe = mixedLobe(lobes, uShooterNormal);
    sLobe[k] = lobes;
  } else {
    sLobe[k] = LobeMix(vec4(0.0), vec4(0.0));
#else
    blocks[slot].lobe = vec4(0.0);
#endif
  }
  sCentreArea[k] = ca;
  sRadiosityRadius[k] = rr;
  sRegion[k] = region;
  barrier();
  if (int(k) >= regions) return;
  // Region k from its blocks, summed in block order so the result does not depend on scheduling.
  vec3 power = vec3(0.0), moment = vec3(0.0);
  float area = 0.0;
#ifdef DIRECTIONAL
  LobeMix regionMix = LobeMix(vec4(0.0), vec4(0.0));
#endif
  for (int i = 0; i < count; ++i) {
    if (sRegion[i] != int(k)) continue;
#ifdef DIRECTIONAL
    regionMix.sum += sLobe[i].sum;
    regionMix.second += sLobe[i].second;
#endif
    power += sRadiosityRadius[i].rgb * sCentreArea[i].w;
    moment += sCentreArea[i].xyz * sCentreArea[i].w;
    area += sCentreArea[i].w;
  }
  vec3 centre = area > 0.0 ? moment / area : vec3(0.0);
  float radius = 0.0;
  ivec4 rect = ivec4(1 << 30, 1 << 30, 0, 0);
  for (int i = 0; i < count; ++i) {
    if (sRegion[i] != int(k)) continue;
    ivec2 b = ivec2(i % uBlocks.x, i / uBlocks.x);
    rect.xy = min(rect.xy, uRect.xy + (uRect.zw * b) / uBlocks);
    rect.zw = max(rect.zw, uRect.xy + (uRect.zw * (b + 1)) / uBlocks);
  }
  for (int i = 0; i < count; ++i)
    if (sRegion[i] == int(k) && sCentreArea[i].w > 0.0)
      radius = max(radius, distance(sCentreArea[i].xyz, centre) + sRadiosityRadius[i].w);
  blocks[k].centreArea = vec4(centre, area);
  blocks[k].radiosityRadius = vec4(area > 0.0 ? power / area : vec3(0.0), radius);
  blocks[k].rect = rect;
  blocks[k].region = ivec4(int(k), 0, 0, 0);
#ifdef DIRECTIONAL
  blocks[k].lobe = mixedLobe(regionMix, uShooterNormal);
#else
  blocks[k].lobe = vec4(0.0);
#endif
}
