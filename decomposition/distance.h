// Stage 3: distance from every empty voxel (inside or outside; not void) to the geometry, the height field
// the watershed floods.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/context.h"
#include "decomposition/classify.h"

namespace cpgi::decomp {

struct DistanceGrid {
  GridFrame frame;
  /// Squared Euclidean distance, in voxel units², from each inside or outside voxel's centre to the
  /// nearest solid voxel's centre; 0 for solid and void voxels (the watershed skips those).
  std::vector<uint32_t> d2;
  uint32_t maxD2 = 0;
  /// Distance in metres of voxel i (centre to nearest solid centre; the surface is ~half a voxel nearer).
  double metres(size_t i) const { return std::sqrt(double(d2[i])) * frame.voxel; }
};

/// Exact Euclidean distance transform over the dense grid (Felzenszwalb & Huttenlocher 2012, "Distance
/// transforms of sampled functions": one lower envelope of parabolas per grid line, x then y then z),
/// lines in parallel with TBB. Exact rather than OpenVDB's fast sweeping because the watershed needs
/// every inside voxel densely anyway and the separable transform is linear in the voxel count.
/// Run after classifySpace.
DistanceGrid distanceToGeometry(const SolidGrid& solid, const SpaceGrid& space, Context& ctx);

}  // namespace cpgi::decomp
