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
VoxelSpace buildVoxelSpace(const Scene& scene, double voxelSize, Context& ctx, uint64_t memoryLimit = 0,
                           const Bounds& extent = {});

/// Labels the inside voxels of `space` by the cells of `graph` over `scene` (the scene the graph's triangle
/// indices refer to; it must have the same geometry as the one `space` was made from). A cell with a
/// `cellvolume:` mesh owns the empty voxels (inside or outside: the rooms of an open building are reachable
/// from its bounds) whose centres that closed mesh contains; the others grow
/// breadth-first from the voxels their triangles face (one to three voxels along each normal), blocked by
/// solid voxels and by the voxels within half a voxel of a portal quad, through enclosed space, and
/// through the space outside too when the graph has a cell named "outside" (an open building's rooms lie
/// in space reachable from its bounds); portal voxels join a neighbour afterwards. -1 where no cell reaches.
std::vector<int32_t> labelsFromCells(const Scene& scene, const CellGraph& graph, const GridFrame& frame,
                                     const std::vector<Space>& space);

/// Hubert & Arabie's adjusted Rand index of two labellings over the positions where both are ≥ 0:
/// 1 for identical partitions, ~0 for independent ones. Returns 1 when fewer than two positions count.
double adjustedRandIndex(const std::vector<int32_t>& a, const std::vector<int32_t>& b);

/// For each label of `a` (0 … countA − 1): the best intersection-over-union with any label of `b`, over
/// the positions where both are ≥ 0 (and below their counts); 0 for a label with no such position.
/// A `b` label of `unmatchable` counts in the sizes of the `a` labels it overlaps but is never a match.
std::vector<double> bestMatchIoU(const std::vector<int32_t>& a, int countA, const std::vector<int32_t>& b,
                                 int countB, int unmatchable = -1);

/// Two labellings restricted to the interior: the positions either puts in a room (any label ≥ 0 but its
/// outside). There each keeps its rooms and gives the positions it leaves out (unlabelled, or its
/// outside) one label of their own, its count ("no room"), so that a labelling that misses most of the
/// rooms scores low instead of being compared only where it says something. −1 off the interior.
struct InteriorLabels {
  std::vector<int32_t> a, b;
  size_t interior = 0;          ///< positions in a room of A or of B
  size_t roomA = 0, roomB = 0;  ///< of those, in a room of A; of B
  size_t both = 0;              ///< in a room of both
  double coverageA() const { return interior ? double(roomA) / double(interior) : 0.0; }
  double coverageB() const { return interior ? double(roomB) / double(interior) : 0.0; }
};
/// `outsideA`/`outsideB`: the label of each one's outside cell, −1 when it has none.
InteriorLabels interiorLabels(const std::vector<int32_t>& a, int countA, int outsideA,
                              const std::vector<int32_t>& b, int countB, int outsideB);

struct PortalMatch {
  int reference = -1;        ///< index into the reference portals
  int candidate = -1;        ///< the candidate portal with the nearest centre, -1 when there is none
  float centreDistance = 0;  ///< metres
  float normalAngle = 0;     ///< degrees between the planes (orientation ignored), in [0, 90]
  float areaRatio = 0;       ///< candidate area / reference area
};

/// Each reference portal matched to the candidate portal whose centre is nearest.
std::vector<PortalMatch> matchPortals(const std::vector<PortalQuad>& reference,
                                      const std::vector<PortalQuad>& candidate);

}  // namespace cpgi::decomp
