// Stage 6: one planar quad per opening between two cells (Haumont et al. 2003, §3.4): the surface where
// the cells' voxels meet, fitted with a plane (CGAL least squares) and covered by the smallest enclosing
// rectangle in that plane (CGAL min_rectangle_2). Afterwards the voxels near each portal are relabelled
// by the side of its plane, so the cells meet exactly at the quads, and the result is checked.
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/cell_graph.h"
#include "core/context.h"
#include "decomposition/distance.h"
#include "decomposition/merge.h"

namespace cpgi::decomp {

struct PortalParams {
  /// Added to every side of the fitted rectangle, voxels: the empty voxels stop up to about half a voxel
  /// short of the real surface (the solid band is half a voxel thick), so the quad is widened back.
  double marginVoxels = 0.5;
  /// How far along its normal a portal may move to reach the middle of its constriction, metres (the
  /// deepest door reveal expected; the watershed puts the interface anywhere along a door's depth).
  float searchRange = 0.6f;
  /// Rounds of extra portals for interface faces the earlier portals left uncovered.
  int extraRounds = 2;
  /// Closed sections tried per non-planar opening, narrowest first, for one that cuts its two rooms apart.
  int sectionCandidates = 12;
};

struct FittedPortal {
  PortalQuad quad;        ///< cellA < cellB; normal from A into B; name "portal:<A>:<B>" is set by the caller
  float halfWidth = 0.0f; ///< the constriction: max over the interface of min(distance), metres
  uint32_t faces = 0;     ///< voxel faces of the interface it was fitted to
  float depth = 0.0f;     ///< half-thickness of the slab relabelled around its plane, metres
  /// Cut across the narrowest closed section near a non-planar interface (sections.h: a stair's hole in
  /// the floor) rather than fitted to the interface.
  bool section = false;
};

struct PortalSet {
  std::vector<FittedPortal> portals;
  std::vector<int32_t> cell;  ///< the cell labels after relabelling around the portals
  /// Voxel faces between two different cells that do not cross a portal of those two cells (within half
  /// a voxel of its quad): 0 means no path of empty voxels leads from one cell to another except
  /// through a portal.
  size_t leakingFaces = 0;
};

/// Splits the faces between each pair of cells into connected openings (faces within one voxel of each
/// other) and fits one quad to each: to the interface's plane when its faces are crossed along one axis
/// (doors, windows), else across the narrowest closed section near it (sections.h: the hole a stair
/// climbs through), whose two cells are then relabelled by side. Run after mergeBasins. `cells` is taken
/// by value: its labels become PortalSet::cell (move it in to spare a copy of the grid).
PortalSet fitPortals(CellLabels cells, const DistanceGrid& distance, const PortalParams& params, Context& ctx);

/// The portals' quads, for the leak counts below.
std::vector<PortalQuad> quadsOf(const std::vector<FittedPortal>& portals);

/// Counts voxel faces between different cells that cross no portal joining those cells (see PortalSet).
size_t countLeakingFaces(const GridFrame& frame, const std::vector<int32_t>& cell,
                         const std::vector<PortalQuad>& portals);

/// The same faces counted per pair of cells (lower index first); pairs without such faces are absent.
std::map<std::pair<int, int>, size_t> leakingFacesByPair(const GridFrame& frame, const std::vector<int32_t>& cell,
                                                         const std::vector<PortalQuad>& portals);

/// Relabels the voxels of the portal's two cells in the slab around it (its quad, ± fp.depth along the
/// normal) by the side of its plane their centres lie on: cellA behind, cellB in front.
void relabelSlab(const GridFrame& frame, const FittedPortal& fp, std::vector<int32_t>& cell);

/// True when the segment a→b crosses the portal's plane inside its quad grown by `tolerance` metres.
bool segmentCrossesPortal(const PortalQuad& portal, const glm::vec3& a, const glm::vec3& b, float tolerance);

}  // namespace cpgi::decomp
