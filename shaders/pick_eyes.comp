// Each visibility region's eye for this shot: a texel of the region drawn with probability proportional
// to its unshot power, by descending the region's residual pyramid (shooter_pyramid.comp) with one
// number per region. One eye stands for the whole region's visibility; a fixed eye chosen clear of
// nearby occluders (shooter_layout.h) sees more than most of the region does and made shots deliver more
// than their power (issue 11). A drawn eye makes the visibility of a region right on average over its
// power, and successive shots draw different eyes (a golden-ratio sequence over the shot count).
#include "common.glsl"
#include "atlas_buffers.glsl"
layout(local_size_x = 16) in;
layout(std430, binding = 0) readonly buffer Patches { PatchInfo patches[]; };
layout(std430, binding = 15) readonly buffer Nodes { Node nodes[]; };
layout(std430, binding = 20) writeonly buffer Eyes { vec4 eyes[]; };  // xyz, w = 1; w = 0: no power
uniform int uShooter;
uniform int uRegionCount;  // entries: uBaseRegions regions, then their replicas (gl_shot_regions.cpp)
uniform int uBaseRegions;
uniform uint uShot;

float power(vec3 b, float area) { return area * (b.r + b.g + b.b); }

void main() {
  int r = int(gl_GlobalInvocationID.x);
  if (r >= uRegionCount) return;
  // The region's number: a hashed offset, then the golden-ratio step per shot, in 32-bit fixed point.
  // Replica i of k of a region takes the region's number plus i / k: the k eyes stratify its power.
  int base = r % uBaseRegions, replica = r / uBaseRegions, replicas = uRegionCount / uBaseRegions;
  uint h = uint(base) * 0x9E3779B9u + 0x7F4A7C15u;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  float u = float((h + uShot * 0x9E3779B9u) >> 8) / 16777216.0;
  u = fract(u + float(replica) / float(replicas));

  ivec4 rect = regions[r].rect;
  int top = regions[r].top.x;
  ivec2 at = ivec2(0);
  if (nodes[regions[r].levelOffset[top]].centreArea.w <= 0.0) {
    eyes[r] = vec4(0.0);
    return;
  }
  // Levels top .. 1: choose one of the (up to) four children by power, keep u uniform within it.
  for (int k = top; k >= 1; --k) {
    ivec2 below = k == 1 ? rect.zw - rect.xy : levelDims(rect, k - 1);
    float w[4];
    float total = 0.0;
    for (int i = 0; i < 4; ++i) {
      ivec2 c = 2 * at + ivec2(i & 1, i >> 1);
      w[i] = 0.0;
      if (c.x >= below.x || c.y >= below.y) continue;
      if (k == 1) {
        int t = texel(rect.xy + c);
        if (int(normalPatch[t].w) == uShooter) w[i] = power(residual[t].rgb, posArea[t].w);
      } else {
        Node n = nodes[regions[r].levelOffset[k - 1] + c.y * levelDims(rect, k - 1).x + c.x];
        w[i] = power(n.radiosityRadius.rgb, n.centreArea.w);
      }
      total += w[i];
    }
    if (!(total > 0.0)) {  // no power below (rounding): the first child with a texel
      for (int i = 0; i < 4; ++i) {
        ivec2 c = 2 * at + ivec2(i & 1, i >> 1);
        if (c.x < below.x && c.y < below.y) { w[i] = 1.0; total = 1.0; break; }
      }
    }
    float target = u * total, sum = 0.0;
    int chosen = 0;
    for (int i = 0; i < 4; ++i) {
      if (w[i] <= 0.0) continue;
      chosen = i;
      if (target < sum + w[i]) break;
      sum += w[i];
    }
    u = clamp((target - sum) / w[chosen], 0.0, 0.99999994);
    at = 2 * at + ivec2(chosen & 1, chosen >> 1);
  }
  int t = texel(rect.xy + at);
  if (int(normalPatch[t].w) != uShooter) {
    eyes[r] = vec4(0.0);
    return;
  }
  vec3 eye = posArea[t].xyz;
  // Replicas also spread over the texel, on a grid centred on it (replicas is a power of two), when the
  // texel is whole (a texel cut by a triangle's edge keeps its centre, which lies on the surface). Centred
  // exactly: a lamp at the back of a housing projects its eyes' mean through the opening magnified, and
  // eyes drawn from a sequence, 5 mm off on average, moved the beam 35 mm across a door frame 3.5 m away.
  vec3 tu = patches[uShooter].texelU.xyz, tv = patches[uShooter].texelV.xyz;
  if (replicas > 1 && posArea[t].w >= 0.99 * length(cross(tu, tv))) {
    int columns = 1 << ((findMSB(replicas) + 1) / 2), rows = replicas / columns;
    vec2 s = (vec2(replica % columns, replica / columns) + 0.5) / vec2(columns, rows) - 0.5;
    eye += s.x * tu + s.y * tv;
  }
  eyes[r] = vec4(eye, 1.0);
}
