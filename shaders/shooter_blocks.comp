// Splits the shooter into texel blocks (sub-shooters): per block the area, the area-weighted centre,
// the mean unshot radiosity and a bounding radius; blocks[0] is the whole patch. Near receivers use
// the blocks (and inside a block, its texels) instead of treating the whole patch as one disk.
#include "common.glsl"
layout(local_size_x = 64) in;
layout(binding = 0, rgba32f) readonly uniform image2D uPosArea;
layout(binding = 1, rgba32f) readonly uniform image2D uNormalPatch;
layout(binding = 4, rgba32f) readonly uniform image2D uResidual;
layout(std430, binding = 6) buffer Blocks { Block blocks[]; };
uniform int uShooter;
uniform ivec4 uRect;         // shooter chart x, y, w, h
uniform ivec2 uBlocks;       // blocks along x and y (at most 8 × 8)
uniform float uTexelRadius;  // half the diagonal of one texel, m

shared vec4 sCentreArea[64];
shared vec4 sRadiosityRadius[64];

void main() {
  uint k = gl_LocalInvocationID.x;
  int count = uBlocks.x * uBlocks.y;
  vec4 ca = vec4(0.0), rr = vec4(0.0);
  ivec4 rect = ivec4(0);
  if (int(k) < count) {
    ivec2 b = ivec2(int(k) % uBlocks.x, int(k) / uBlocks.x);
    ivec2 lo = uRect.xy + (uRect.zw * b) / uBlocks;
    ivec2 hi = uRect.xy + (uRect.zw * (b + 1)) / uBlocks;
    rect = ivec4(lo, hi);
    vec3 power = vec3(0.0), moment = vec3(0.0);
    float area = 0.0;
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        ivec2 t = ivec2(x, y);
        if (int(imageLoad(uNormalPatch, t).w) != uShooter) continue;
        vec4 pa = imageLoad(uPosArea, t);
        power += imageLoad(uResidual, t).rgb * pa.w;
        moment += pa.xyz * pa.w;
        area += pa.w;
      }
    vec3 centre = area > 0.0 ? moment / area : vec3(0.0);
    float radius = 0.0;
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        ivec2 t = ivec2(x, y);
        if (int(imageLoad(uNormalPatch, t).w) != uShooter) continue;
        radius = max(radius, distance(imageLoad(uPosArea, t).xyz, centre));
      }
    ca = vec4(centre, area);
    rr = vec4(area > 0.0 ? power / area : vec3(0.0), radius + uTexelRadius);
    blocks[k + 1u].centreArea = ca;
    blocks[k + 1u].radiosityRadius = rr;
    blocks[k + 1u].rect = rect;
  }
  sCentreArea[k] = ca;
  sRadiosityRadius[k] = rr;
  barrier();
  if (k != 0u) return;
  // The whole patch, summed in block order so the result does not depend on scheduling.
  vec3 power = vec3(0.0), moment = vec3(0.0);
  float area = 0.0;
  for (int i = 0; i < count; ++i) {
    power += sRadiosityRadius[i].rgb * sCentreArea[i].w;
    moment += sCentreArea[i].xyz * sCentreArea[i].w;
    area += sCentreArea[i].w;
  }
  vec3 centre = area > 0.0 ? moment / area : vec3(0.0);
  float radius = 0.0;
  for (int i = 0; i < count; ++i)
    if (sCentreArea[i].w > 0.0)
      radius = max(radius, distance(sCentreArea[i].xyz, centre) + sRadiosityRadius[i].w);
  blocks[0].centreArea = vec4(centre, area);
  blocks[0].radiosityRadius = vec4(area > 0.0 ? power / area : vec3(0.0), radius);
  blocks[0].rect = ivec4(uRect.xy, uRect.xy + uRect.zw);
}
