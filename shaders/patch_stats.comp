// Per listed patch: Σ residual × area, Σ irradiance × area and Σ (1 − ρ) irradiance × area, added up
// from its tiles' sums (tile_sums.glsl) in a fixed order so that runs agree to the bit: 64 strided partial
// sums, then a pairwise tree over them. One invocation per patch rather than a work group with barriers:
// on llvmpipe every barrier is a switch of all the group's coroutines, and 7 of them per patch made this
// pass a fifth of a shot.
#include "common.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Patches { PatchInfo patches[]; };
layout(std430, binding = 1) buffer Stats { PatchStats stats[]; };
layout(std430, binding = 5) readonly buffer PatchList { uint patchCount; uint patchArgs[3]; uint patchList[]; };
layout(std430, binding = 7) buffer Pending { uint pending[]; };
layout(std430, binding = 16) readonly buffer TileStats { PatchStats tileStats[]; };
uniform int uShooter;

const int kPartials = 64;

void main() {
  uint entry = (gl_WorkGroupID.y * WORK_LIST_WIDTH + gl_WorkGroupID.x) * 64u + gl_LocalInvocationID.x;
  if (entry >= patchCount) return;
  int p = int(patchList[entry]);
  ivec4 range = patches[p].tiles;
  vec3 unshot[kPartials], incident[kPartials], absorbed[kPartials];
  for (int k = 0; k < kPartials; ++k) {
    vec3 u = vec3(0.0), e = vec3(0.0), a = vec3(0.0);
    for (int i = k; i < range.y; i += kPartials) {
      PatchStats t = tileStats[range.x + i];
      u += t.unshot.rgb;
      e += t.incident.rgb;
      a += t.absorbed.rgb;
    }
    unshot[k] = u;
    incident[k] = e;
    absorbed[k] = a;
  }
  for (int s = kPartials / 2; s > 0; s >>= 1) {
    for (int k = 0; k < s; ++k) {
      unshot[k] += unshot[k + s];
      incident[k] += incident[k + s];
      absorbed[k] += absorbed[k + s];
    }
  }
  vec3 u = unshot[0];
  stats[p].unshot = vec4(u, u.r + u.g + u.b);
  stats[p].incident = vec4(incident[0], 0.0);
  stats[p].absorbed = vec4(absorbed[0], 0.0);
  if (p == uShooter) pending[p] = 0u;
}
