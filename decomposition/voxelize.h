// Stage 1: the scene as solid voxels (Haumont et al. 2003, §3.1). An unsigned distance field, so open,
// non-manifold and self-intersecting meshes all work: nothing here needs an inside or an outside.
#pragma once

#include <vector>

#include "core/context.h"
#include "core/scene.h"
#include "decomposition/voxel_grid.h"

namespace cpgi::decomp {

struct VoxelizeParams {
  /// Voxel edge, metres; > 0. Openings narrower than ~2 voxels vanish; doors should span ≥ 8.
  double voxelSize = 0.1;
  /// Radius of the morphological closing of the solid, metres; 0 = none. Rounded to whole voxels r; the
  /// closing (dilate r, erode r, face neighbours) fills every gap at most 2r voxels across, i.e. cracks up
  /// to about (2r + 1) voxels wide once the half-voxel thickening of each face is counted.
  double sealRadius = 0.0;
  /// Refuse grids larger than this: the pipeline peaks at ~40 bytes per voxel (the distance transform's
  /// 64-bit working grid, labels, classes), so 250 M voxels is ~10 GB.
  size_t maxVoxels = size_t(250) * 1000 * 1000;
};

struct SolidGrid {
  GridFrame frame;
  std::vector<uint8_t> solid;            ///< 1 where a triangle passes within half a voxel (or sealed)
  /// The closest triangle to each voxel within two voxels of the surface, -1 elsewhere (from OpenVDB's
  /// polygon index grid); lets later stages tell the front of a surface from its back.
  std::vector<int32_t> nearestTriangle;
  int sealVoxels = 0;                    ///< the closing radius actually used, voxels
  size_t sealedVoxels = 0;               ///< voxels the closing turned solid
};

/// Rasterises every triangle by OpenVDB's meshToVolume (unsigned distance, 2-voxel band); a voxel is
/// solid when its centre is within half a voxel of a triangle, which makes any plane at least one face-
/// connected layer thick, so 6-connected empty space cannot leak through it. The grid is the scene's
/// bounds padded by 2 + seal voxels, so its border is always empty.
/// @throws InputError("voxel size", ...) when the grid would exceed params.maxVoxels.
SolidGrid voxelize(const Scene& scene, const VoxelizeParams& params, Context& ctx);

}  // namespace cpgi::decomp
