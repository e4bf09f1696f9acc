// Comparing two cell decompositions of one scene (the `compare-cells` command): both are turned into
// labels of the same empty voxels, then compared as clusterings (adjusted Rand index, best-match IoU)
// and portal by portal.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "decomposition/voxel_grid.h"

namespace cpgi::decomp {

/// The empty space both decompositions are labelled over: the scene's voxels classified as decompose
/// does (same voxel, no seal), so an automatic decomposition's labels fit it voxel for voxel.
struct VoxelSpace {
  GridFrame frame;
  std::vector<Space> space;
};
VoxelSpace buildVoxelSpace(const Scene& scene, double voxelSize, Context& ctx);

/// Labels the inside voxels of `space` by the cells of `graph` over `scene` (the scene the graph's triangle
/// indices refer to; it must have the same geometry as the one `space` was made from). A cell with a
/// `cellvolume:` mesh owns the empty voxels (inside or outside: the rooms of an open building are reachable
/// from its bounds) whose centres that closed mesh contains; the others grow
/// breadth-first from the voxels their triangles face (one to three voxels along each normal), blocked by
/// solid voxels and by the voxels within half a voxel of a portal quad; portal voxels join a neighbour
/// afterwards. -1 where no cell reaches.
std::vector<int32_t> labelsFromCells(const Scene& scene, const CellGraph& graph, const GridFrame& frame,
                                     const std::vector<Space>& space);

/// Hubert & Arabie's adjusted Rand index of two labellings over the positions where both are ≥ 0:
/// 1 for identical partitions, ~0 for independent ones. Returns 1 when fewer than two positions count.
double adjustedRandIndex(const std::vector<int32_t>& a, const std::vector<int32_t>& b);

/// For each label of `a` (0 … countA − 1): the best intersection-over-union with any label of `b`, over
/// the positions where both are ≥ 0; 0 for a label with no such position.
std::vector<double> bestMatchIoU(const std::vector<int32_t>& a, int countA, const std::vector<int32_t>& b, int countB);

struct PortalMatch {
  int reference = -1;       ///< index into the reference portals
  int candidate = -1;       ///< the candidate portal with the nearest centre, -1 when there is none
  float centreDistance = 0; ///< metres
  float normalAngle = 0;    ///< degrees between the planes (orientation ignored), in [0, 90]
  float areaRatio = 0;      ///< candidate area / reference area
};

/// Each reference portal matched to the candidate portal whose centre is nearest.
std::vector<PortalMatch> matchPortals(const std::vector<PortalQuad>& reference, const std::vector<PortalQuad>& candidate);

}  // namespace cpgi::decomp
