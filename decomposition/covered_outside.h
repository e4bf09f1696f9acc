// A check after the decomposition: how much of the empty space under a roof the outside holds. A closed
// level (a building, a game level sealed under its sky) has its empty space under a roof in rooms; when the
// outside holds most of it, the level's faces do not close it and the outside flooded its playable space
// through a gap no player sees (issue 46: a Quake III map's drawn faces alone, without its brushes).
#pragma once

#include <cstdint>
#include <vector>

#include "decomposition/voxel_grid.h"

namespace cpgi::decomp {

struct CoveredSpace {
  size_t coveredVoxels = 0;  ///< empty voxels (inside or outside) with a solid voxel below and above them
  size_t outsideVoxels = 0;  ///< of those, in the outside (its cell, or outside space no cell holds)
  /// outsideVoxels / coveredVoxels; 0 when nothing is covered.
  double outsideShare() const { return coveredVoxels ? double(outsideVoxels) / double(coveredVoxels) : 0.0; }
};

/// Counts, column by column (y up), the empty voxels between the column's lowest and highest solid voxel,
/// and those of them in the outside: `space` classified (classify.h), `voxelCell` the final cells
/// (−1 none), `outsideCell` the outside's cell or −1. Open ground and the open sky over a courtyard or a
/// daylit arena are never covered; a porch, an eave or an open hall's overhang are, and are small beside
/// the rooms.
CoveredSpace coveredSpace(const GridFrame& frame, const std::vector<Space>& space,
                          const std::vector<int32_t>& voxelCell, int outsideCell);

/// The share of the covered empty space in the outside above which decompose says the level leaked.
inline constexpr double kLeakedOutsideShare = 0.5;

}  // namespace cpgi::decomp
