// Automatic cells and portals (Haumont, Debeir & Sillion, "Volumetric cell-and-portal generation",
// Eurographics 2003), as a pipeline of stages over plain data, Recast style:
//   1 voxelize   scene → solid voxels (OpenVDB unsigned distance, optional closing)     voxelize.h
//   2 classify   empty voxels → outside / inside / void                                 classify.h
//   3 distance   empty voxels → distance to the geometry (exact EDT)                    distance.h
//   4 watershed  distance → basins and the saddles where they meet; the grid's border   watershed.h
//                is the outside's marker, so the outside is a basin like a room's
//   5 merge      basins → cells (keep only real constrictions); the outside is a cell   merge.h
//                ("outside", last) when a room meets it
//   5b behind    cells behind the geometry (a level's space behind its walls) folded  behind.h
//                into the outside or the room they open onto
//   6 portals    cell interfaces → planar quads (CGAL plane fit + min rectangle)        portals.h
//                or across the narrowest closed section (a stair's hole)                sections.h
//   6b leaks     every voxel face between cells on a portal of theirs, or the two merged leaks.h
//   6c merge     pieces of one opening (same cells, one plane, touching) one quad  portal_merge.h
//   6d walls     each portal onto its wall's mid-plane, as the scene's faces give it wall_portals.h
//   7 assign     triangles → the cell each faces, split on portal planes                assign.h
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/cell_graph.h"
#include "core/context.h"
#include "core/scene.h"
#include "decomposition/assign.h"
#include "decomposition/behind.h"
#include "decomposition/classify.h"
#include "decomposition/covered_outside.h"
#include "decomposition/distance.h"
#include "decomposition/leaks.h"
#include "decomposition/merge.h"
#include "decomposition/passages.h"
#include "decomposition/portal_merge.h"
#include "decomposition/portals.h"
#include "decomposition/voxelize.h"
#include "decomposition/watershed.h"

namespace cpgi::decomp {

struct DecomposeParams {
  /// Voxel edge, metres; 0 = choose from the scene: max(minAutoVoxel, cbrt(padded volume /
  /// autoVoxelBudget)), rounded up to a whole millimetre, over the part of the scene where its rooms are
  /// (findRoomExtent: its bounds unless far pieces or open ground lie round them). Explicit values must be
  /// in (0, 10]; the grid spans that part either way.
  double voxelSize = 0.0;
  double minAutoVoxel = 0.05;      ///< metres: finer than needed for 0.7 m doors at 14 voxels
  double autoVoxelBudget = 4.0e6;  ///< voxels the automatic choice aims at
  /// Where the budget's voxel exceeds passageCheckVoxel, the level's narrow passages (measurePassages) are
  /// measured and the voxel made fine enough to span them with voxelsAcrossPassage voxels, up to
  /// maxAutoVoxels over the grid (and within memoryLimit): a large level's corridors then stay rooms
  /// apart, while a small one's voxel (and a house's, always under the check) is the budget's. At
  /// 0.125 m (the voxel whose 8-voxel doors are 1 m) sleekgrinder went from 0.348 to 0.241 m and its
  /// decomposition from 16 to over 200 CPU s.
  double passageCheckVoxel = 0.4;  ///< metres: its 8-voxel doors are 3.2 m, a Quake level's narrowest
  double voxelsAcrossPassage = 8.0;
  double maxAutoVoxels = 16.0e6;  ///< ~640 MB at kDecompositionBytesPerVoxel
  PassageParams passages;
  /// The pass that finds where the rooms are (findRoomExtent) runs at max(minExtentVoxel, sqrt(max(surface
  /// area, footprint) / extentBudget)): its band and its columns each about extentBudget voxels at most,
  /// a fraction of the real pass's, and fine enough for a 1 m gap under a roof in any room.
  double minExtentVoxel = 0.1;  ///< metres
  double extentBudget = 4.0e6;  ///< voxels
  /// See RoomExtentParams::minPartShare.
  double minPartShare = RoomExtentParams().minPartShare;
  double sealRadius = 0.0;   ///< metres, see VoxelizeParams::sealRadius; in [0, 1]
  uint64_t memoryLimit = 0;  ///< bytes, see VoxelizeParams::memoryLimit; 0: no limit
  /// Metres of open space kept around the covered part of the scene, see VoxelizeParams::outsideMargin.
  double outsideMargin = VoxelizeParams().outsideMargin;
  ClassifyParams classify;
  WatershedParams watershed;
  MergeParams merge;
  BehindParams behind;
  PortalParams portals;
  LeakParams leaks;
  PortalMergeParams portalMerge;
  AssignParams assign;
  /// A closed cell (no portal) that no triangle faces is space inside solid matter and is dropped (its
  /// voxels unlabelled): a game level's brush whose inside the compiler left faces round, looking both
  /// ways (a detail brush against a wall, a column of patches), which the behind stage cannot tell from a
  /// room. false keeps them: a user's own rooms (decomposeFromVolumes) are never dropped.
  bool dropUnfacedClosedCells = true;
  std::string sourceName = "scene";  ///< the input's name, for messages
};

struct CellStats {
  double volume = 0.0;  ///< m³ of its empty voxels
  Bounds bounds;        ///< of its empty voxels' cubes
  float peak = 0.0f;    ///< largest distance to the geometry, metres (half the room's smallest extent)
  size_t voxels = 0;
};

/// The automatic cells' names, by storey and floor area: "s1-24m2" is a cell on the lowest storey
/// (floors 1.5 m or more apart make storeys) whose volume over its height is 24 m²; a second such cell
/// is "s1-24m2-2". The outside cell's entry is empty (it is named "outside").
std::vector<std::string> roomNames(const std::vector<CellStats>& stats, int outsideCell);

struct Decomposition {
  Scene scene;      ///< the input, triangles split on portal planes where needed
  CellGraph graph;  ///< cells (named by roomNames, and "outside") and portals, indexing `scene`
  std::vector<CellStats> cellStats;
  std::vector<FittedPortal> portals;  ///< per graph portal: its constriction and fit
  GridFrame frame;
  std::vector<Space> space;        ///< per voxel
  std::vector<int32_t> voxelCell;  ///< per voxel: the final cell, -1 for none
  std::string voxelChoice;         ///< how the voxel size was chosen, in words
  bool enclosed = true;            ///< false: no room was found; the outside is the only cell
  int outsideCell = -1;            ///< the cell named "outside" (always the last), -1 when none
  int basins = 0;                  ///< watershed basins before merging
  int leakMerges = 0;              ///< pairs of cells merged because they met outside any portal
  size_t leakPlacements = 0;       ///< portal placements the leak pass flooded (leaks.h, ClosedLeaks)
  int mergedPortalPieces = 0;      ///< portal pieces folded into another of the same pair (portal_merge.h)
  int foldedBehind = 0;            ///< cells behind the geometry folded into another (behind.h)
  int droppedUnfaced = 0;          ///< closed cells no triangle faces, dropped (dropUnfacedClosedCells)
  /// Per cell: true for a room no portal joins to another cell and no voxel face touches another cell's
  /// (an enclosed space: a sealed room, a closed cupboard bigger than the minimum cell). Never the outside.
  std::vector<char> closedRoom;
  /// Per cell: true for a room reached through portals from the outside but from no room that the
  /// outside does not also reach, in a scene whose other rooms no portal joins to the outside: a sealed
  /// game level's space behind its one-sided walls (Quake maps keep only the faces a player sees).
  std::vector<char> outsidePocket;
  /// Every cell reachable from every other through portals once the closed rooms, and the outside with
  /// its pockets when no portal joins them to the rest (a sealed level), are left out.
  bool connectedOpen = true;
  /// Per cell: reached through portals from the scene's main part (the part of the portal graph holding
  /// the most room volume, a closed room's included: a sealed level's one room is its main part). A closed
  /// room never is: light cannot cross what the geometry seals (a game level's room that only a teleporter
  /// reaches is, for the light, a closed room).
  std::vector<char> reachable;
  /// Every cell reachable or a closed room (each said as one): what "connected" means for a bake, whose
  /// light crosses portals only. An outside pocket, or a group of rooms apart, makes it false.
  bool reachableOrClosed = true;
  int regions = 0;  ///< connected parts of the portal graph, closed rooms and the outside's part included
  size_t leakingFaces = 0;  ///< see PortalSet::leakingFaces
  size_t inputTriangles = 0;
  size_t splitTriangles = 0;
  size_t fallbackTriangles = 0;
  double thinWallArea = 0.0;  ///< m², see Assignment::thinWallArea
  size_t sealedVoxels = 0;
  /// The empty space under a roof and the outside's part of it (covered_outside.h): decompose warns when
  /// the outside holds most of it (a closed level whose playable space leaked out).
  CoveredSpace covered;
};

/// The voxel size and the part of the scene the grid spans.
struct GridChoice {
  double voxel = 0.0;  ///< metres
  RoomExtent extent;
  double passage = 0.0;  ///< the narrow passages' width the voxel spans, metres (0: not measured)
  std::string how;       ///< the rule in words
};
/// Picks the grid for `scene` by the rule in DecomposeParams::voxelSize.
GridChoice chooseGrid(const Scene& scene, const DecomposeParams& params, Context& ctx);
/// chooseGrid's voxel; `how` gets the rule in words.
double chooseVoxelSize(const Scene& scene, const DecomposeParams& params, std::string* how = nullptr);

/// Stages 1–3, shared by decompose and decomposeFromVolumes: the voxel size, the solid grid, empty space
/// classified (inside, outside, sealed) and its distance to the geometry.
struct EmptySpace {
  double voxelSize = 0.0;
  std::string voxelChoice;  ///< how the voxel size was chosen, in words
  SolidGrid solid;
  SpaceGrid space;
  DistanceGrid distance;
};
/// `surfaces`: the triangles the solid is made of (withUnseenSurfaces).
EmptySpace voxelizeEmptySpace(const Scene& surfaces, const DecomposeParams& params, Context& ctx);

/// The surfaces the voxel stages see: `scene`'s triangles with its Scene::buriedPieces put back, so that the
/// solid is that of the faces whole, as if the contact cuts had not run (a piece they judge buried beside a
/// room must not open the wall's voxels, and the pieces cut from a brush must not make the watershed new
/// basins), and its Scene::seal (the solids that close the scene where no face is drawn). Only the
/// triangles are copied; empty when the scene has neither (hasUnseenSurfaces; use `scene` itself).
Scene withUnseenSurfaces(const Scene& scene);
inline bool hasUnseenSurfaces(const Scene& scene) {
  return !scene.buriedPieces.empty() || !scene.seal.empty();
}

/// Runs the seven stages. Warnings (open scene, walls thinner than a voxel, leaks, coarse voxels) go to
/// ctx.warn; each stage's time to ctx's timers.
/// @throws InputError for an empty scene, non-finite coordinates or out-of-range parameters.
Decomposition decompose(const Scene& scene, const DecomposeParams& params, Context& ctx);

/// The checks decompose makes before any work.
/// @throws InputError for an empty scene, non-finite coordinates or out-of-range parameters.
void checkDecomposeInput(const Scene& scene, const DecomposeParams& params);

/// Stages 6 and 7 and the graph, over cells labelled by any means (the watershed and merge of decompose,
/// or a scene's room volumes, volume_cells.h): portals fitted where the cells meet, every triangle given
/// to the cell it faces (split on portal planes), per-cell statistics. `names` holds one name per cell of
/// `cells`; `space` and `distance` are those of `solid`, made from `surfaces` (withUnseenSurfaces: `scene` or
/// its triangles with the buried pieces), on whose walls the portals are snapped; `scene`'s triangles are
/// the ones given to the cells.
Decomposition finishDecomposition(const Scene& scene, const Scene& surfaces, const DecomposeParams& params,
                                  const SolidGrid& solid, std::vector<Space> space,
                                  const DistanceGrid& distance, CellLabels cells,
                                  const std::vector<std::string>& names, Context& ctx);

}  // namespace cpgi::decomp
