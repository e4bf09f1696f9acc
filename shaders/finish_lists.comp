// Turns the work-list counts into indirect dispatch sizes, wrapped at WORK_LIST_WIDTH groups per row
// so that no dimension exceeds GL_MAX_COMPUTE_WORK_GROUP_COUNT's guaranteed 65535.
#include "common.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 4) buffer TileList { uint tileCount; uint tileArgs[3]; uint tileList[]; };
layout(std430, binding = 5) buffer PatchList { uint patchCount; uint patchArgs[3]; uint patchList[]; };

void main() {
  tileArgs[0] = min(tileCount, WORK_LIST_WIDTH);
  tileArgs[1] = (tileCount + WORK_LIST_WIDTH - 1u) / WORK_LIST_WIDTH;
  tileArgs[2] = 1u;
  // patch_stats.comp: 64 patches per work group.
  uint patchGroups = (patchCount + 63u) / 64u;
  patchArgs[0] = min(patchGroups, WORK_LIST_WIDTH);
  patchArgs[1] = (patchGroups + WORK_LIST_WIDTH - 1u) / WORK_LIST_WIDTH;
  patchArgs[2] = 1u;
}
