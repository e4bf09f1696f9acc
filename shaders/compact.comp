// Appends the tiles and patches of flagged patches to their work lists. The order of the lists varies
// from run to run (atomics) but every entry is processed independently, so results do not.
#include "common.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 2) readonly buffer Visible { uint visible[]; };
layout(std430, binding = 3) readonly buffer Tiles { ivec4 tiles[]; };  // x, y, patch, 1 if none receives
layout(std430, binding = 4) buffer TileList { uint tileCount; uint tileArgs[3]; uint tileList[]; };
layout(std430, binding = 5) buffer PatchList { uint patchCount; uint patchArgs[3]; uint patchList[]; };
uniform uint uTiles;
uniform uint uPatches;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < uTiles && visible[tiles[i].z] != 0u && tiles[i].w == 0) tileList[atomicAdd(tileCount, 1u)] = i;
  if (i < uPatches && visible[i] != 0u) patchList[atomicAdd(patchCount, 1u)] = i;
}
