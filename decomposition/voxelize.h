// Stage 1: the scene as solid voxels (Haumont et al. 2003, §3.1). An unsigned distance field, so open,
// non-manifold and self-intersecting meshes all work: nothing here needs an inside or an outside.
#pragma once

#include <cstdint>
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
  /// Refuse grids larger than this: the pipeline peaks at ~40 bytes per voxel (kDecompositionBytesPerVoxel),
  /// so 250 M voxels is ~10 GB; voxel indices fit in 32 bits.
  size_t maxVoxels = size_t(250) * 1000 * 1000;
  /// Bytes the whole decomposition may take (decompositionBytes), checked before the first grid is
  /// allocated: InputError naming the voxel size when passed. 0: no limit.
  uint64_t memoryLimit = 0;
  /// Open space kept around the covered part of the scene, metres (see coverHeight); beyond it, across
  /// the horizontal, the grid stops: open ground there (a terrain, a plaza) is outside whatever stands on
  /// it, and voxels over it would only enlarge the outside. Infinite (or when no column is covered): the
  /// grid spans the scene's bounds. At least the portals' search range (0.6 m) beyond an exterior door.
  double outsideMargin = 2.0;
  /// A column of the grid (x, z; y is up) is covered when at least this much empty height, metres, lies
  /// between its lowest and highest solid voxel: a floor under a ceiling, a porch under its roof. A
  /// terrain, a slab or a wall alone never is. Rooms are always covered; a space open to the sky is
  /// reached from the grid's top and is outside anyway.
  double coverHeight = 1.0;
  /// The part of the scene to grid (findRoomExtent); empty: the scene's bounds. Triangles past it (and the
  /// padding) are left out of the grid.
  Bounds extent;
};

/// What one voxel of the grid costs at the decomposition's peak, the assignment of triangles to cells
/// (decompose.cpp, finishDecomposition): solid and nearest triangle (5 bytes), classes (1), squared distance
/// (4), watershed basins (4), merged cells (4), cells around the portals (4), and when a triangle sees no
/// cell the nearest-cell grid (4), its border mask (1) and its breadth-first queue (8, up to 16 with a
/// vector's spare capacity). The watershed (order 4, queue, flags) and the distance transform (in place on
/// its output) peak lower. Measured: 31–38 bytes a voxel (bench/RESULTS.md, "Memory of the decomposition").
inline constexpr double kDecompositionBytesPerVoxel = 40.0;
/// While OpenVDB builds the narrow band (voxelize), only the solid and nearest-triangle grids are dense.
inline constexpr double kVoxelizeBytesPerVoxel = 5.0;
/// What the narrow band costs per voxel face of surface (triangle area / voxel²): the unsigned distance
/// and the nearest-triangle grids (4 + 4 bytes) over a band about three voxels thick, in 8³ leaves that a
/// slanted surface fills to about a third, and meshToVolume's per-thread copies while it builds them
/// (measured: about 100 bytes, 200 planes 0.2 m apart at 0.1 m voxels).
inline constexpr double kBandBytesPerSurfaceVoxel = 120.0;

/// The decomposition's estimated peak for a grid of `voxels` voxels of edge `voxel` metres around
/// triangles of `surfaceArea` m² in all: the later stages' dense grids, or the narrow band beside the
/// first dense grids when the surface is large for the volume (many thin layers), whichever is more.
double decompositionBytes(double voxels, double voxel, double surfaceArea);

struct RoomExtentParams {
  double voxel = 0.1;        ///< the coarse pass's voxel edge, metres: the scene's bounds' automatic one
  double coverHeight = 1.0;  ///< metres, see VoxelizeParams::coverHeight
  /// Metres: covered columns this close are one part, and this much is kept round the kept parts (see
  /// VoxelizeParams::outsideMargin); infinite: the scene's bounds.
  double margin = 2.0;
  /// A part is kept when the triangles whose centre stands over it are at least this share of the most
  /// any part has: a building's wings are kept, a far piece of scenery (a game level's distant set of a
  /// few large faces, a lone box) is not.
  double minPartShare = 0.1;
};

struct RoomExtent {
  Bounds box;               ///< what the grid should span: the scene's bounds unless trimmed
  bool trimmed = false;     ///< box is smaller than the scene's bounds
  int parts = 0;            ///< parts of covered columns found
  int keptParts = 0;        ///< of those, inside box
  size_t farTriangles = 0;  ///< triangles wholly outside box (trimmed only)
};

/// Where the scene's rooms are: a coarse sparse pass (the same unsigned distance band as voxelize) finds
/// the covered columns (a floor under a roof, see coverHeight), joins those within `margin` of each other
/// into parts, and keeps the parts holding at least minPartShare of the triangles the fullest one holds; the
/// box is their columns and the margin round them across, and every solid voxel over those columns up. So a
/// level's far scenery, a terrain around a house or a lone distant object neither coarsens the automatic
/// voxel nor widens the grid. The box is the scene's bounds when nothing is covered, when the margin is
/// infinite, or when the kept parts reach within a coarse voxel of the bounds on every side.
RoomExtent findRoomExtent(const Scene& scene, const RoomExtentParams& params, Context& ctx);

struct SolidGrid {
  GridFrame frame;
  std::vector<uint8_t> solid;  ///< 1 where a triangle passes within half a voxel (or sealed)
  /// The closest triangle to each voxel within two voxels of the surface, -1 elsewhere (from OpenVDB's
  /// polygon index grid); lets later stages tell the front of a surface from its back.
  std::vector<int32_t> nearestTriangle;
  int sealVoxels = 0;       ///< the closing radius actually used, voxels
  size_t sealedVoxels = 0;  ///< voxels the closing turned solid
};

/// Rasterises every triangle by OpenVDB's meshToVolume (unsigned distance, 2-voxel band); a voxel is
/// solid when its centre is within half a voxel of a triangle, which makes any plane at least one face-
/// connected layer thick, so 6-connected empty space cannot leak through it. The grid is params.extent (or
/// the scene's bounds) padded by 2 + seal voxels, cut across the horizontal to params.outsideMargin around
/// the covered columns: its border is empty except where open ground (a terrain) runs through the cut.
/// @throws InputError("voxel size", ...) when the grid would exceed params.maxVoxels, or the decomposition
/// over it params.memoryLimit.
SolidGrid voxelize(const Scene& scene, const VoxelizeParams& params, Context& ctx);

}  // namespace cpgi::decomp
