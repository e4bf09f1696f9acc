// Stage 5b: space behind the geometry is no room (issue 46). A game level keeps only the faces a player
// sees (Quake III's compiler drops every face towards the void), so the space behind its walls, under its
// floors and inside its brushes is empty and, once the void reaches it, part of the outside. The
// watershed cuts that space into basins like any other; those behind a narrow gap between two walls
// survive the merge as cells that look into the backs of the walls round them: pockets that only the
// outside reaches (which then stands apart from a sealed level's rooms: the graph is not connected), or
// a slab behind a wall that opens into a room through the seams of its faces (dozens of sliver portals).
// A cell most of whose voxels next to the geometry lie behind their nearest face is folded into what it
// opens onto: the outside when it meets the outside, else the room it shares the most voxel faces with.
#pragma once

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "decomposition/merge.h"
#include "decomposition/voxelize.h"

namespace cpgi::decomp {

struct BehindParams {
  /// A cell is behind the geometry when its voxels behind their nearest face outnumber those in front
  /// of it by more than this factor (rooms have almost none behind: ~1 in 100 at a wall's seams; a
  /// pocket behind a level's walls more than 3 in 4). 0 disables the stage.
  double backToFront = 1.0;
  /// The same factor for groups of cells apart from the rooms, once the first pass has folded: closed
  /// (meeting no other cell) or, in a sealed level (its largest group of rooms does not meet the
  /// outside), meeting only the outside. A room has under 1 voxel behind in 12 there (a sealed room a
  /// teleporter reaches: 1 in 14); the inside of a detail brush against a wall, a hollow pillar or a
  /// pocket behind a sealed level's walls looks at the fronts of the faces round it too (the wall, the
  /// floor) and has 1 behind in 2 to 1 in 4. 0 disables the second pass.
  double apartBackToFront = 0.25;
};

struct FoldedCells {
  int folded = 0;               ///< cells behind the geometry folded into another (or dropped)
  bool outsideDropped = false;  ///< the outside met rooms only through such cells: it is no cell now
};

/// Folds the cells of `cells` behind the geometry (BehindParams) into the outside when they (or the
/// pockets behind the geometry they touch) meet the outside's voxels, else into the room they share most
/// voxel faces with; with neither they are dropped (unlabelled). Cells are renumbered in their order, the
/// outside last; an outside that then meets no room is unlabelled too, as mergeBasins leaves the outside
/// of a closed building. `space` tells the outside's unlabelled voxels. Run after mergeBasins.
FoldedCells foldCellsBehindGeometry(CellLabels& cells, const Scene& scene, const SolidGrid& solid,
                                    const std::vector<Space>& space, const BehindParams& params,
                                    Context& ctx);

}  // namespace cpgi::decomp
