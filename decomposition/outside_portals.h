// Portals between a room and the outside, read back from a file. The loader orients a portal from cell A
// into cell B by where each cell's surfaces lie (core/scene_io.cpp); the outside's surfaces (facades,
// roof, the ground) surround the building, so their mean can lie on the room's side of a window and the
// portal comes back facing into the room. A cell solve then sees the portal from behind: no light
// leaves through it.
#pragma once

#include "core/cell_graph.h"
#include "core/scene.h"

namespace cpgi::decomp {

/// Turns every portal joining a cell named "outside" to another cell so that its normal points away
/// from that room's surfaces (the area-weighted mean of its triangle centroids), from cellA into cellB.
/// Returns how many it turned. Portals between two rooms are left as they are.
int orientOutsidePortals(const Scene& scene, CellGraph& graph);

}  // namespace cpgi::decomp
