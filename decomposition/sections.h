// Planar cuts for openings whose watershed interface is not a plane: two floors joined by a stair meet
// along a surface that follows the steps, and a quad fitted to it is tilted across the stairwell. The
// opening a person sees is the hole in the floor: the smallest closed cross-section of the two cells'
// empty space across one grid axis, near the interface. Architecture is built along the grid's axes
// (floors, walls), so the three axis directions are the candidates.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/cell_graph.h"
#include "decomposition/voxel_grid.h"

namespace cpgi::decomp {

struct Section {
  int axis = -1;               ///< the grid axis the cut is across
  int layer = 0;               ///< the cut lies between voxel layers `layer` and `layer + 1` along axis
  std::vector<size_t> voxels;  ///< the section's voxels, in layer `layer`
};

/// Across each grid axis, every voxel layer within `searchVoxels` of the interface's extent is cut: the
/// voxels of cells a or b in that layer that are connected (face neighbours, within the layer) to the
/// interface's projection form its section, closed when the walls bound it before it grows past
/// `maxArea` voxels or reaches the grid's border. The narrowest closed section wins; the cut goes through
/// the middle of the run of layers within 2 % of its area (a floor's mid-plane). `interfaceVoxels` are the
/// voxels on both sides of the interface faces. Returns nothing when no layer is closed.
std::optional<Section> narrowestSection(const GridFrame& f, const std::vector<int32_t>& cell, int a, int b,
                                        const std::vector<size_t>& interfaceVoxels, int searchVoxels,
                                        size_t maxArea);

/// The closed sections of closedSections' search as candidates, narrowest first, at most
/// `maxCandidates`: each the middle of the run of near-equal layers round a layer not in an earlier
/// candidate's run. The narrowest closed section need not separate the two cells (a pocket under a
/// stair's flight is closed and small); the caller tries them in turn (relabelAcrossPortals).
std::vector<Section> closedSections(const GridFrame& f, const std::vector<int32_t>& cell, int a, int b,
                                    const std::vector<size_t>& interfaceVoxels, int searchVoxels,
                                    size_t maxArea, size_t maxCandidates);

/// Relabels the voxels of cells a and b by which side of `portals` (those joining a and b) they are on:
/// the voxels reachable from `seedA` without crossing a portal become a, the other voxels of a or b
/// become b. Leaves the labels alone and returns false when `seedB` is reachable too (the portals do not
/// separate the cells) or when `seedA` is not a voxel of a or `seedB` not one of b.
bool relabelAcrossPortals(const GridFrame& f, std::vector<int32_t>& cell, int a, int b, size_t seedA,
                          size_t seedB, const std::vector<const PortalQuad*>& portals);

/// relabelAcrossPortals's flood alone, labels untouched: the voxels of a or b reachable from `seedA` without
/// crossing a portal are appended to `side` (cleared first) and set to 1 in `reached` (f.count() long, all 0
/// on entry; the caller clears the voxels of `side` after). Its cost is the voxels reached, not the grid's,
/// so a caller weighing many portal placements for one pair pays per placement only for the flood. Returns
/// false, as relabelAcrossPortals, when `seedB` is reached or a seed is not its cell's.
bool floodSideOfPortals(const GridFrame& f, const std::vector<int32_t>& cell, int a, int b, size_t seedA,
                        size_t seedB, const std::vector<const PortalQuad*>& portals,
                        std::vector<char>& reached, std::vector<size_t>& side);

}  // namespace cpgi::decomp
