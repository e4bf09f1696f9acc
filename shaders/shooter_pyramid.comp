// One level of the shooter's residual pyramid (common.glsl, Node), from the texels (level 1) or the
// level below: per node the area, the area-weighted centre, the mean unshot radiosity and a bounding
// radius. Receivers far from a node take it as one piece; nearer ones descend (receive.comp), so a
// receiver next to a large shooter pays for the few texels near it, not for the whole chart.
#include "common.glsl"
#include "atlas_buffers.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 15) buffer Nodes { Node nodes[]; };
uniform int uShooter;
uniform int uLevel;          // >= 1
uniform int uRegionCount;
uniform float uTexelRadius;  // half the longer diagonal of one texel, m

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
  nodes[regions[r].levelOffset[uLevel] + g] = n;
}
