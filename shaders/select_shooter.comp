// Picks the next shooter (thesis ch. 6, step 1) — pending emitters first, then the largest unshot
// power, ties to the lowest index — and totals the energy bookkeeping over all patches, in a fixed
// order so that runs agree to the bit.
#include "common.glsl"
layout(local_size_x = 256) in;
layout(std430, binding = 1) readonly buffer Stats { PatchStats stats[]; };
layout(std430, binding = 7) readonly buffer Pending { uint pending[]; };
layout(std430, binding = 8) buffer Selection {
  int winner;
  int winnerPending;
  int pad0, pad1;
  vec4 winnerUnshot;
  vec4 unshot;
  vec4 incident;
  vec4 absorbed;
};
uniform int uPatches;

shared int sBest[256];
shared vec4 sUnshot[256], sIncident[256], sAbsorbed[256];

// Is patch a a better shooter than patch b?
bool better(int a, int b) {
  if (b < 0) return a >= 0;
  if (a < 0) return false;
  if (pending[a] != pending[b]) return pending[a] > pending[b];
  float pa = stats[a].unshot.w, pb = stats[b].unshot.w;
  if (pa != pb) return pa > pb;
  return a < b;
}

void main() {
  uint k = gl_LocalInvocationID.x;
  int best = -1;
  vec4 u = vec4(0.0), inc = vec4(0.0), ab = vec4(0.0);
  for (int p = int(k); p < uPatches; p += 256) {
    if (better(p, best)) best = p;
    u += stats[p].unshot;
    inc += stats[p].incident;
    ab += stats[p].absorbed;
  }
  sBest[k] = best;
  sUnshot[k] = u;
  sIncident[k] = inc;
  sAbsorbed[k] = ab;
  barrier();
  for (uint s = 128u; s > 0u; s >>= 1) {
    if (k < s) {
      if (better(sBest[k + s], sBest[k])) sBest[k] = sBest[k + s];
      sUnshot[k] += sUnshot[k + s];
      sIncident[k] += sIncident[k + s];
      sAbsorbed[k] += sAbsorbed[k + s];
    }
    barrier();
  }
  if (k == 0u) {
    winner = sBest[0];
    winnerPending = sBest[0] >= 0 ? int(pending[sBest[0]]) : 0;
    winnerUnshot = sBest[0] >= 0 ? stats[sBest[0]].unshot : vec4(0.0);
    unshot = sUnshot[0];
    incident = sIncident[0];
    absorbed = sAbsorbed[0];
  }
}
