// One level of the shooter's residual pyramid (common.glsl, Node), from the texels (level 1) or the
// level below: per node the area, the area-weighted centre, the mean unshot radiosity, a bounding
// radius and where the power lies (its mean and variance along the chart's axes, receive.comp's far
// pieces). Receivers far from a node take it as one piece; nearer ones descend (receive.comp), so a
// receiver next to a large shooter pays for the few texels near it, not for the whole chart.
#include "common.glsl"
#include "atlas_buffers.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 15) buffer Nodes { Node nodes[]; };
#ifdef DIRECTIONAL
#include "directional.glsl"
uniform vec3 uShooterNormal;
#endif
uniform int uShooter;
uniform int uLevel;          // >= 1
uniform int uRegionCount;
uniform float uTexelRadius;  // half the longer diagonal of one texel, m

#ifdef BINNED
// The node's bins (directional.glsl): its texels' or children's, each channel weighted by its power (a
// Lambertian's all ones; by area where the node has none of it), summed in a fixed order.
void mixNodeBins(int self, int r, ivec2 node) {
  int out0 = uNodeBins + self * BIN_SLOT_VEC4;
  for (int q = 0; q < BIN_SLOT_VEC4; ++q) nodeLobe[out0 + q] = vec4(0.0);
  vec3 total = vec3(0.0);
  float totalArea = 0.0;
  ivec4 rect = regions[r].rect;
  ivec2 below = uLevel == 1 ? rect.zw - rect.xy : levelDims(rect, uLevel - 1);
  int base = uLevel == 1 ? 0 : regions[r].levelOffset[uLevel - 1];
  ivec2 lo = 2 * node, hi = min(lo + 2, below);
  for (int pass = 0; pass < 2; ++pass)  // by power; again by area for the channels the node has none of
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        vec4 lobe;
        vec3 b;
        float area;
        if (uLevel == 1) {
          int t = texel(rect.xy + ivec2(x, y));
          if (int(normalPatch[t].w) != uShooter) continue;
          b = residual[t].rgb;
          area = posArea[t].w;
          lobe = emissionLobe[t];
        } else {
          int c = base + y * below.x + x;
          Node child = nodes[c];
          b = child.radiosityRadius.rgb;
          area = child.centreArea.w;
          lobe = nodeLobe[c];
        }
        vec3 w = b * area;
        if (pass == 1) {
          if (all(greaterThan(total, vec3(0.0)))) continue;
          w = area * vec3(lessThanEqual(total, vec3(0.0)));
        }
        w = max(w, vec3(0.0));
        if (!(w.r + w.g + w.b > 0.0)) continue;
        if (pass == 0) total += w;
        else totalArea += area;
        bool binned = lobe.w < 0.0;
        int k = int(-lobe.w) - 1;
        int from = uLevel == 1 ? k : uNodeBins + k * BIN_SLOT_VEC4;
        for (int q = 0; q < BIN_SLOT_VEC4; ++q) {
          vec4 f = !binned ? vec4(1.0) : uLevel == 1 ? emissionLobe[from + q] : nodeLobe[from + q];
          nodeLobe[out0 + q] += vec4(w, 0.0) * f;
        }
      }
  vec3 sum = mix(vec3(totalArea), total, greaterThan(total, vec3(0.0)));
  for (int q = 0; q < BIN_SLOT_VEC4; ++q)
    nodeLobe[out0 + q] = vec4(mix(vec3(1.0), nodeLobe[out0 + q].rgb / sum, greaterThan(sum, vec3(0.0))), 1.0);
}
#endif

void main() {
  int g = int(gl_GlobalInvocationID.x), r = 0;
  for (; r < uRegionCount; ++r) {
    if (uLevel <= regions[r].top.x) {
      ivec2 d = levelDims(regions[r].rect, uLevel);
      if (g < d.x * d.y) break;
      g -= d.x * d.y;
    }
  }
  if (r == uRegionCount) return;
  ivec4 rect = regions[r].rect;
  ivec2 dims = levelDims(rect, uLevel);
  ivec2 node = ivec2(g % dims.x, g / dims.x);
  vec3 power = vec3(0.0), moment = vec3(0.0);
  float area = 0.0, radius = 0.0;
#ifdef DIRECTIONAL
  // The node's lobe: the moment-matched mixture of its texels' (or children's, which gives the same).
  LobeMix lobes = LobeMix(vec4(0.0), vec4(0.0));
#endif
  // Moments about the node's corner in texels, weighted by power and, for a node without any, by area:
  // (Σw, Σw u, Σw v) and (Σw u², Σw v²).
  vec4 byPower = vec4(0.0), byArea = vec4(0.0);
  vec2 squarePower = vec2(0.0), squareArea = vec2(0.0);
  if (uLevel == 1) {
    ivec2 lo = rect.xy + 2 * node, hi = min(lo + 2, rect.zw);
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        int t = texel(ivec2(x, y));
        if (int(normalPatch[t].w) != uShooter) continue;
        vec4 pa = posArea[t];
        power += residual[t].rgb * pa.w;
        moment += pa.xyz * pa.w;
        area += pa.w;
        // A texel is uniform over [i, i + 1]: mean i + ½, second moment (i + ½)² + 1/12.
        vec2 uv = vec2(x - lo.x, y - lo.y) + 0.5;
        vec3 own = residual[t].rgb;
        float w = (own.r + own.g + own.b) * pa.w;
        byPower += w * vec4(1.0, uv, 0.0);
        squarePower += w * (uv * uv + 1.0 / 12.0);
        byArea += pa.w * vec4(1.0, uv, 0.0);
        squareArea += pa.w * (uv * uv + 1.0 / 12.0);
#ifdef DIRECTIONAL
        vec3 b = residual[t].rgb;
        lobes = addLobe(lobes, emissionLobe[t], uShooterNormal, (b.r + b.g + b.b) * pa.w);
#endif
      }
    vec3 centre = area > 0.0 ? moment / area : vec3(0.0);
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        int t = texel(ivec2(x, y));
        if (int(normalPatch[t].w) == uShooter) radius = max(radius, distance(posArea[t].xyz, centre) + uTexelRadius);
      }
  } else {
    ivec2 below = levelDims(rect, uLevel - 1);
    int base = regions[r].levelOffset[uLevel - 1];
    ivec2 lo = 2 * node, hi = min(lo + 2, below);
    // Children summed in a fixed order, so the result does not depend on scheduling.
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        Node c = nodes[base + y * below.x + x];
        power += c.radiosityRadius.rgb * c.centreArea.w;
        moment += c.centreArea.xyz * c.centreArea.w;
        area += c.centreArea.w;
        // The child's moments about this node's corner (parallel axes: no large squares to cancel).
        vec2 m = c.moments.xy - vec2(2 * node << (uLevel - 1));
        vec3 own = c.radiosityRadius.rgb;
        float w = (own.r + own.g + own.b) * c.centreArea.w;
        byPower += w * vec4(1.0, m, 0.0);
        squarePower += w * (m * m + c.moments.zw);
        byArea += c.centreArea.w * vec4(1.0, m, 0.0);
        squareArea += c.centreArea.w * (m * m + c.moments.zw);
#ifdef DIRECTIONAL
        vec3 b = c.radiosityRadius.rgb;
        lobes = addLobe(lobes, nodeLobe[base + y * below.x + x], uShooterNormal, (b.r + b.g + b.b) * c.centreArea.w);
#endif
      }
    vec3 centre = area > 0.0 ? moment / area : vec3(0.0);
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        Node c = nodes[base + y * below.x + x];
        if (c.centreArea.w > 0.0) radius = max(radius, distance(c.centreArea.xyz, centre) + c.radiosityRadius.w);
      }
  }
  Node n;
  n.centreArea = vec4(area > 0.0 ? moment / area : vec3(0.0), area);
  n.radiosityRadius = vec4(area > 0.0 ? power / area : vec3(0.0), radius);
  vec4 sums = byPower.x > 0.0 ? byPower : byArea;
  vec2 squares = byPower.x > 0.0 ? squarePower : squareArea;
  vec2 mean = sums.x > 0.0 ? sums.yz / sums.x : vec2(0.0);
  vec2 variance = sums.x > 0.0 ? max(squares / sums.x - mean * mean, vec2(0.0)) : vec2(0.0);
  n.moments = vec4(vec2(node << uLevel) + mean, variance);
  nodes[regions[r].levelOffset[uLevel] + g] = n;
#ifdef DIRECTIONAL
  int self = regions[r].levelOffset[uLevel] + g;
  nodeLobe[self] = mixedLobe(lobes, uShooterNormal);
#ifdef BINNED
  if (lobes.second.w > 0.0) {
    nodeLobe[self] = vec4(uShooterNormal, -float(self + 1));
    mixNodeBins(self, r, node);
  }
#endif
#endif
}
