// Stage 5: merging watershed basins into cells. The raw watershed over-segments: every plateau patch and
// every gap between chair legs is a basin. Two basins stay apart only when the place where they meet is
// a real constriction relative to both of them (Haumont et al. 2003, §3.3).
#pragma once

#include <cstdint>
#include <vector>

#include "core/context.h"
#include "decomposition/watershed.h"

namespace cpgi::decomp {

/// Two neighbouring groups of basins A and B (peaks pA ≤ pB, saddle s, shared interface area I,
/// volumes VA ≤ VB) are merged when ANY of these holds:
struct MergeParams {
  /// s / pA > saddleRatio: the opening is nearly as wide as the smaller room is deep. In [0, 1]; higher
  /// keeps more portals. A 1 m door (s ≈ 0.5 m) between 3 m high rooms (p ≈ 1.5 m) has 0.33.
  double saddleRatio = 0.75;
  /// pA − s < minDepth, metres: the dip between them is shallow (furniture, pillars, plateau noise).
  /// The same door has 1.0 m; the space between 0.3 m columns at 0.8 m spacing ~0.15 m.
  double minDepth = 0.2;
  /// I / VA^(2/3) > openingRatio: the interface is as large as the smaller basin's cross-section (a row
  /// of tall pillars 2 m apart: ~1; a door into a 4 × 4 × 3 m room: ~0.16). 0 disables.
  double openingRatio = 0.6;
  /// Any group smaller than this, m³, joins the neighbour it meets at the highest saddle; an isolated
  /// one is dropped (its voxels become unlabelled). 2.5 m³ is under the smallest room (a 0.9 × 1.2 m
  /// WC 2.4 m high holds 2.6 m³) and over the enclosures in rooms that are not rooms: a shower of
  /// 0.9 × 0.9 × 2 m glass holds 1.6 m³, a wardrobe's inside 0.6 × 2 × 2.1 m 2.5 m³.
  double minCellVolume = 2.5;
  /// A group that meets no other (a closed space) whose peak, metres, is under this is dropped too: a
  /// cavity nowhere 0.7 m across (the inside of a hollow platform, a game level's sealed gap under a
  /// floor) is no room, however long. A closed room a person stands in has a peak over 0.45 m. The peak
  /// is taken less half a voxel (the distance to the surface rather than to the solid voxel's centre):
  /// a cavity one voxel thick (a hollow pillar, a brush's inside at a level's 0.3–0.6 m voxel) is one.
  double minClosedPeak = 0.35;
  /// A group that meets no other is dropped too when its peak is under this many voxels: every voxel of
  /// it then touches the solid by a face (the peak is one voxel; the next a grid can give is √2), so it
  /// is nowhere more than two voxels thick and the grid resolves no space inside it. At a game level's
  /// 0.7–1.2 m voxel that is up to 2 m between faces, over minClosedPeak, and it is what such a voxel
  /// makes of a brush whose faces the compiler partly dropped (a platform's glowing band with no top or
  /// bottom, the wedge under a ramp) or of a slot sealed by the voxel's coarseness. Only voxels over
  /// 0.35 m are concerned (under them minClosedPeak drops more); a closed room resolved by the grid,
  /// a cupboard at a house's voxel or a sealed arena, is kept. 0 disables.
  double minClosedPeakVoxels = 1.5;
  /// saddleRatio between a room and the outside, in [0, 1]. Higher than saddleRatio: exterior doors are
  /// wide (a 2 m terrace door into a 2.7 m high room has 1.0 / 1.35 = 0.74), and whether a space is a
  /// room or part of the outside is better told by how much of it is open (openingRatio): a porch open
  /// on three sides merges by that rule.
  double outsideSaddleRatio = 0.9;
  /// Storeys (y is up): two groups lie one above the other when their mean heights are further apart
  /// than storeySpread × the sum of their heights' standard deviations (a room of height H has H/√12;
  /// two 2.7 m storeys over a 0.25 m slab are 2.95 m apart against 1.5 × 1.56 = 2.34 m, a gallery over
  /// a double-height room 1.5 m against 3.6 m). Stacked groups whose interface, seen from above (its
  /// faces crossed along y: a stair's crust along the flight counts its treads, not its risers), is
  /// less than storeyOpening of the smaller one's floor area (its volume over its height) are two floors
  /// joined through a hole —
  /// a stair's, however wide against the storey's height — and the saddle and opening rules do not
  /// merge them (small groups and shallow dips still do). 0 disables.
  double storeySpread = 1.5;
  double storeyOpening = 0.5;
  /// Galleries, metres: two groups side by side whose floors (the mean height of their voxels that rest
  /// on the geometry) stand more than this apart are on two storeys, a landing overlooking a
  /// double-height room over its parapet: an architect's two rooms, and for the light one vertical
  /// portal over the parapet. The opening ratio does not merge them, however long the parapet (the
  /// saddle, depth and size rules still do). 1.5 m as roomNames cuts storeys; a room's floor and its
  /// furniture's tops stay well under it. 0 disables.
  double galleryFloorRise = 1.5;
  /// Metres: the higher group is a gallery only when its space is a storey's, its mean height over its
  /// floor under this (a room of clear height under twice this): a landing 2.7 m high has 1.35 m, a
  /// game level's platform open to the sky box over an arena has tens of metres and is left to the
  /// opening ratio.
  double galleryHeadroom = 2.0;
};

struct CellLabels {
  GridFrame frame;
  std::vector<int32_t> cell;         ///< per voxel: cell index, -1 where no cell
  std::vector<int32_t> cellOfBasin;  ///< per watershed basin, -1 for a dropped one
  std::vector<float> peak;           ///< per cell, metres
  std::vector<uint32_t> volume;      ///< per cell, voxels
  int droppedBasins = 0;
  /// The cell grown from the outside marker (always the last), -1 when there is none: the outside of a
  /// closed building touches no room and is left unlabelled.
  int outsideCell = -1;
  int cellCount() const { return int(peak.size()); }
  int roomCount() const { return cellCount() - (outsideCell >= 0 ? 1 : 0); }
};

/// Greedy agglomeration: candidate contacts from the highest saddle down, each re-tested whenever one of
/// its groups changes (a merge sums volumes and interfaces and keeps the higher peak and saddle). Cells
/// are numbered by their lowest voxel index, so the numbering does not depend on the merge order; the
/// outside (the group of the watershed's outside marker) comes last, and only when it meets a room or
/// when there is no room at all. Against the outside the rules use the room's own volume and peak.
/// Run after floodWatershed. `basins` is taken by value: its per-voxel labels become the cells' (move it
/// in to spare a copy of the grid).
CellLabels mergeBasins(WatershedLabels basins, const MergeParams& params, Context& ctx);

}  // namespace cpgi::decomp
