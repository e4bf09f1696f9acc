// Scales the last shot to what it should have delivered: every receiver texel of the shot (the same
// tiles and texels receive.comp gathered into) gets uScale × what it gained instead. The solver's
// bookkeeping compares the gathered total with the power times the share of the eyes' hemispheres that
// the item buffers show covered (shot_coverage.comp), which is at most the power (design.md §5:
// received ≤ shot).
#include "common.glsl"
#include "atlas_buffers.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Patches { PatchInfo patches[]; };
layout(std430, binding = 3) readonly buffer Tiles { ivec4 tiles[]; };
layout(std430, binding = 4) readonly buffer TileList { uint tileCount; uint tileArgs[3]; uint tileList[]; };
layout(std430, binding = 21) readonly buffer ShotGain { vec4 shotGain[]; };  // irradiance of the last shot
uniform int uShooter;
uniform float uScale;  // > 0

void main() {
  uint entry = gl_WorkGroupID.y * WORK_LIST_WIDTH + gl_WorkGroupID.x;
  if (entry >= tileCount) return;
  ivec4 tile = tiles[tileList[entry]];
  if (tile.z == uShooter) return;
  ivec4 chart = patches[tile.z].rect;
  ivec2 t = tile.xy + ivec2(gl_LocalInvocationID.xy);
  if (any(greaterThanEqual(t, chart.xy + chart.zw))) return;
  int tx = texel(t);
  if (int(normalPatch[tx].w) != tile.z) return;
  vec3 back = (uScale - 1.0) * shotGain[tx].rgb;
  vec3 lost = albedo[tx].rgb * back;
  incident[tx] = incident[tx] + vec4(back, 0.0);
  radiosity[tx] = radiosity[tx] + vec4(lost, 0.0);
  residual[tx] = residual[tx] + vec4(lost, 0.0);
}
