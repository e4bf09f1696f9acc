#include "decomposition/covered_outside.h"

namespace cpgi::decomp {

CoveredSpace coveredSpace(const GridFrame& frame, const std::vector<Space>& space,
                          const std::vector<int32_t>& voxelCell, int outsideCell) {
  CoveredSpace out;
  if (space.size() != frame.count() || voxelCell.size() != frame.count()) return out;
  for (int z = 0; z < frame.dims.z; ++z)
    for (int x = 0; x < frame.dims.x; ++x) {
      int lowest = -1, highest = -1;
      for (int y = 0; y < frame.dims.y; ++y)
        if (space[frame.index(x, y, z)] == Space::Solid) highest = y, lowest = lowest < 0 ? y : lowest;
      for (int y = lowest + 1; lowest >= 0 && y < highest; ++y) {
        const size_t i = frame.index(x, y, z);
        const Space s = space[i];
        if (s != Space::Inside && s != Space::Outside) continue;
        ++out.coveredVoxels;
        const bool outside =
            (outsideCell >= 0 && voxelCell[i] == outsideCell) || (s == Space::Outside && voxelCell[i] < 0);
        out.outsideVoxels += outside ? 1 : 0;
      }
    }
  return out;
}

}  // namespace cpgi::decomp
