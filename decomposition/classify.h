// Stage 2: what each empty voxel is: outside (reachable from the padded bounds), inside (enclosed, in
// front of the geometry) or void (enclosed, behind it: the inside of a thick wall or of a closed box).
#pragma once

#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "decomposition/voxelize.h"

namespace cpgi::decomp {

struct ClassifyParams {
  /// Enclosed components smaller than this, m³, are void whichever way their surfaces face (a gap
  /// between a cupboard and the wall is not a room).
  double minComponentVolume = 0.05;
};

struct SpaceGrid {
  GridFrame frame;
  std::vector<Space> space;  ///< per voxel
  size_t insideVoxels = 0, outsideVoxels = 0, voidVoxels = 0, solidVoxels = 0;
  int insideComponents = 0;  ///< 6-connected enclosed components kept as inside
  int voidComponents = 0;    ///< enclosed components judged void
};

/// Floods the outside from the grid's border (empty but where open ground runs through it, see
/// voxelize), then splits the rest of the
/// empty space into 6-connected components. A component is void when it lies inside a closed outward-
/// facing solid (generalized winding number > 1/2 at the median of three of its voxels) or when most of its
/// voxels next to the surface lie behind their nearest triangle; inside otherwise. Rooms built of wall
/// boxes (winding 0, in front of the walls) and levels built as inward-facing shells (winding −1) are
/// both inside.
/// Run after voxelize.
SpaceGrid classifySpace(const Scene& scene, const SolidGrid& solid, const ClassifyParams& params, Context& ctx);

}  // namespace cpgi::decomp
