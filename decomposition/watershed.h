// Stage 4: the 3D watershed of the distance field (Haumont, Debeir & Sillion 2003, §3.2; Recast's
// rcBuildRegions does the same in 2D). Flooding starts at the distance maxima — room centres — and runs
// downward, so basins meet at constrictions (doors), and the height where two basins first meet is the
// constriction's half-width.
#pragma once

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "decomposition/distance.h"

namespace cpgi::decomp {

struct WatershedParams {
  /// Height of one flooding level, voxels; > 0. Distances within one level flood together, the way
  /// Recast steps two distance units at a time: coarser levels give fewer spurious plateau basins and
  /// boundaries nearer the middle of flat regions, finer ones sharper saddles.
  double levelStep = 0.5;
};

/// Where two basins meet.
struct BasinContact {
  int a = -1, b = -1;      ///< basin indices, a < b
  float saddle = 0.0f;     ///< max over touching voxel pairs of min(distance), metres: the half-width
  uint32_t faces = 0;      ///< voxel faces shared by the two basins (× voxel² = interface area)
  uint32_t facesUp = 0;    ///< those crossed along y (up): the interface's area seen from above
};

struct WatershedLabels {
  GridFrame frame;
  std::vector<int32_t> basin;  ///< per voxel: basin index, -1 for solid and void voxels
  std::vector<float> peak;     ///< per basin: its highest distance, metres
  std::vector<uint32_t> volume;  ///< per basin: voxels
  std::vector<BasinContact> contacts;
  /// The basin grown from the grid's border (0), -1 when no border voxel is empty. Its peak is its real
  /// highest distance, but it stands for the unbounded space around the scene: merging treats it as
  /// infinitely high.
  int outsideBasin = -1;
  int basinCount() const { return int(peak.size()); }
};

/// Level by level from the highest distance down: first every existing basin grows breadth-first into
/// the level's voxels it touches (so a plateau is shared out by distance from the basins that reach it),
/// then each remaining connected patch of the level starts a new basin (a local maximum). Every voxel
/// pair of different basins is seen once, when the second voxel is labelled, which records the contact.
///
/// The empty voxels of the grid's border are one marker basin, the outside, labelled before the first
/// level (a marker-controlled watershed, Meyer & Beucher 1990): the padded grid cuts the space around a
/// building off a few voxels from its walls, where the true distance would keep growing, so the outside
/// is given the top of the height field instead. A room whose front door stands open then meets the
/// outside at the door's half-width, like any other constriction, instead of flooding out through it.
/// Run after distanceToGeometry.
WatershedLabels floodWatershed(const DistanceGrid& distance, const WatershedParams& params, Context& ctx);

}  // namespace cpgi::decomp
