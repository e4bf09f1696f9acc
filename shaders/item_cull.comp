// Culls a shot's item buffers per hemicube face: lists, for each of the 5 faces, the triangles that may
// show in it from any of the shot's eyes, in the scene's order, as index lists drawn with
// glDrawElementsIndirect. A triangle is left out only where the rasterizer would clip all of it from every
// eye: all three corners beyond one plane of the face's frustum (item.vert's projection), or behind the
// shooter's plane (its clip distance), by a margin far above the rounding between this shader's arithmetic
// and the vertex shader's. The kept triangles keep their order, so depth ties resolve as when every face
// drew every triangle and the item buffers are bit-identical to that; each face draws a fraction of the
// triangles instead of all of them (bench/RESULTS.md, "Item buffers drawn indexed and culled").
//
// Each plane is a·local > b, local = uToShooter (p − eye); from every eye at once, a·q > b + max over the
// eyes of a·(uToShooter eye) with q = uToShooter p: the C++ side folds the eyes into each plane's threshold.
//
// Three passes over chunks of CHUNK consecutive triangles, one invocation a chunk, no shared memory (a
// barrier is slow on llvmpipe): PASS 0 the face mask of each triangle and each chunk's count per face;
// PASS 1 (one invocation per face) the counts turned into each chunk's first slot and the face's draw
// command; PASS 2 every chunk writing its kept triangles' indices from its slot on.
#include "common.glsl"
#define CHUNK 32u
#if PASS == 1
layout(local_size_x = 1) in;
#else
layout(local_size_x = 64) in;
#endif
layout(std430, binding = 24) readonly buffer ItemPositions { float itemPositions[]; };  // xyz per vertex
layout(std430, binding = 25) readonly buffer ItemIndices { uint itemIndices[]; };
layout(std430, binding = 26) buffer FaceMasks { uint faceMasks[]; };    // per triangle, bit f: face f
layout(std430, binding = 27) buffer ChunkSlots { uint chunkSlots[]; };  // [face * chunks + chunk]
layout(std430, binding = 28) buffer FaceIndices { uint faceIndices[]; };  // face f from f * uIndexCount
// Per face a DrawElementsIndirectCommand: count, instanceCount, firstIndex, baseVertex, baseInstance.
layout(std430, binding = 29) buffer FaceDraws { uint faceDraws[]; };

uniform uint uTriangles;
uniform uint uIndexCount;
uniform mat3 uToShooter;
// Plane 0 the shooter's (a triangle behind it is clipped in every face), then per face 5: x > w, x < −w,
// y > w, y < −w, w < near, as (a, threshold) in shooter coordinates (gl_item_buffers.cpp, cullItemFaces).
uniform vec4 uPlanes[26];
uniform float uScale;  // the largest |uToShooter eye| + near: the size the rounding is relative to (m)

uint chunks() { return (uTriangles + CHUNK - 1u) / CHUNK; }

vec3 corner(uint t, uint k) {
  uint v = itemIndices[3u * t + k];
  return uToShooter * vec3(itemPositions[3u * v], itemPositions[3u * v + 1u], itemPositions[3u * v + 2u]);
}

uint faceMask(uint t) {
  vec3 q[3];
  float margin[3];
  for (uint k = 0u; k < 3u; ++k) {
    q[k] = corner(t, k);
    margin[k] = 3e-5 * (length(q[k]) + uScale);  // |a| ≤ 2√2 < 3
  }
  // out[i]: every corner beyond plane i.
  bool behind = true;
  for (uint k = 0u; k < 3u; ++k) behind = behind && dot(uPlanes[0].xyz, q[k]) - uPlanes[0].w > margin[k];
  if (behind) return 0u;
  uint mask = 0u;
  for (int f = 0; f < 5; ++f) {
    bool culled = false;
    for (int i = 1 + 5 * f; i < 6 + 5 * f; ++i) {
      bool beyond = true;
      for (uint k = 0u; k < 3u; ++k) beyond = beyond && dot(uPlanes[i].xyz, q[k]) - uPlanes[i].w > margin[k];
      culled = culled || beyond;
    }
    if (!culled) mask |= 1u << uint(f);
  }
  return mask;
}

void main() {
#if PASS == 1
  uint f = gl_WorkGroupID.x, n = chunks(), slot = 0u;
  for (uint c = 0u; c < n; ++c) {
    uint count = chunkSlots[f * n + c];
    chunkSlots[f * n + c] = slot;
    slot += count;
  }
  faceDraws[5u * f] = 3u * slot;
  faceDraws[5u * f + 1u] = 1u;
  faceDraws[5u * f + 2u] = f * uIndexCount;
  faceDraws[5u * f + 3u] = 0u;
  faceDraws[5u * f + 4u] = 0u;
#else
  uint c = gl_GlobalInvocationID.x, n = chunks();
  if (c >= n) return;
  uint first = c * CHUNK, end = min(first + CHUNK, uTriangles);
#if PASS == 0
  uint counts[5] = uint[5](0u, 0u, 0u, 0u, 0u);
  for (uint t = first; t < end; ++t) {
    uint mask = faceMask(t);
    faceMasks[t] = mask;
    for (int f = 0; f < 5; ++f) counts[f] += (mask >> uint(f)) & 1u;
  }
  for (uint f = 0u; f < 5u; ++f) chunkSlots[f * n + c] = counts[f];
#else
  for (uint f = 0u; f < 5u; ++f) {
    uint at = f * uIndexCount + 3u * chunkSlots[f * n + c];
    for (uint t = first; t < end; ++t)
      if ((faceMasks[t] & (1u << f)) != 0u) {
        faceIndices[at] = itemIndices[3u * t];
        faceIndices[at + 1u] = itemIndices[3u * t + 1u];
        faceIndices[at + 2u] = itemIndices[3u * t + 2u];
        at += 3u;
      }
  }
#endif
#endif
}
