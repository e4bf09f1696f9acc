// Per listed patch: Σ residual × area, Σ irradiance × area and Σ (1 − ρ) irradiance × area, added up
// from its tiles' sums (tile_sums.glsl) in a fixed order (strided loop, then a tree) so that runs agree
// to the bit.
#include "common.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Patches { PatchInfo patches[]; };
layout(std430, binding = 1) buffer Stats { PatchStats stats[]; };
layout(std430, binding = 5) readonly buffer PatchList { uint patchCount; uint patchArgs[3]; uint patchList[]; };
layout(std430, binding = 7) buffer Pending { uint pending[]; };
layout(std430, binding = 16) readonly buffer TileStats { PatchStats tileStats[]; };
uniform int uShooter;

shared vec4 sUnshot[64], sIncident[64], sAbsorbed[64];

void main() {
  uint entry = gl_WorkGroupID.y * WORK_LIST_WIDTH + gl_WorkGroupID.x;
  if (entry >= patchCount) return;  // uniform across the group
  int p = int(patchList[entry]);
  ivec4 range = patches[p].tiles;
  uint k = gl_LocalInvocationID.x;
  vec3 unshotSum = vec3(0.0), incidentSum = vec3(0.0), absorbedSum = vec3(0.0);
  for (int i = int(k); i < range.y; i += 64) {
    PatchStats t = tileStats[range.x + i];
    unshotSum += t.unshot.rgb;
    incidentSum += t.incident.rgb;
    absorbedSum += t.absorbed.rgb;
  }
  sUnshot[k] = vec4(unshotSum, 0.0);
  sIncident[k] = vec4(incidentSum, 0.0);
  sAbsorbed[k] = vec4(absorbedSum, 0.0);
  barrier();
  for (uint s = 32u; s > 0u; s >>= 1) {
    if (k < s) {
      sUnshot[k] += sUnshot[k + s];
      sIncident[k] += sIncident[k + s];
      sAbsorbed[k] += sAbsorbed[k + s];
    }
    barrier();
  }
  if (k == 0u) {
    vec3 u = sUnshot[0].rgb;
    stats[p].unshot = vec4(u, u.r + u.g + u.b);
    stats[p].incident = sIncident[0];
    stats[p].absorbed = sAbsorbed[0];
    if (p == uShooter) pending[p] = 0u;
  }
}
