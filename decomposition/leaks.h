// Stage 6b: no leaks (issue 46). After the portals are fitted, every voxel face between two cells must
// cross a portal joining those two cells; a face that does not is a path for light (and a walker) from
// one cell into the other that no portal carries, which a cell-by-cell bake gets wrong. Each pair of
// cells with such faces is either relabelled by side of its portals (the voxels reachable from the
// first cell's deepest voxel without crossing one of the pair's portals are the first cell's, the rest
// the second's: the interface then lies on the portals) or, when the portals do not cut the two apart
// (or there are none), merged into one cell.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/context.h"
#include "decomposition/distance.h"
#include "decomposition/portals.h"

namespace cpgi::decomp {

struct LeakParams {
  /// Rounds of relabelling; relabelling one pair can uncover faces of another, the next round takes
  /// those. In the last round every pair still leaking is merged, so the result has no leaking face.
  int rounds = 6;
  /// false: pairs that relabelling cannot part keep their leaking faces (counted in leakingFaces) instead
  /// of merging, for cells a user gave (room volumes), which the decomposition must not join.
  bool merge = true;
  /// First drop the portals of a pair that its largest one to three portals make redundant (they alone
  /// part the two cells).
  bool dropRedundant = true;
};

struct ClosedLeaks {
  std::vector<int32_t> cellOf;    ///< per cell before: its index after (a merged cell: the one it joined)
  int cellCount = 0;              ///< cells after
  std::vector<int32_t> keptCell;  ///< per cell after: its index before
  int outsideCell = -1;           ///< after; the outside is never merged away, so it stays the last cell
  int relabelledPairs = 0;        ///< pairs made to meet on their portals
  int mergedPairs = 0;            ///< pairs merged
  int droppedPortals = 0;         ///< redundant portals dropped
  size_t placements = 0;          ///< portal placements flooded (each a pair's portals grown or moved)
};

/// Makes every voxel face between two cells of `set` cross a portal of those two cells, by relabelling
/// or merging as above; `set`'s labels and portals are rewritten in place (cells renumbered densely in
/// their old order, portals between merged cells dropped) and its leakingFaces recounted (0). Merging
/// into the outside keeps the outside. Run after fitPortals.
ClosedLeaks closeLeaks(PortalSet& set, const DistanceGrid& distance, int cellCount, int outsideCell,
                       const LeakParams& params, Context& ctx);

}  // namespace cpgi::decomp
