// Stage 6d: portals in zero-thickness walls moved onto the wall. A wall of two coincident back-to-back
// faces is one layer of solid voxels, and the portals fitted to the voxels of a door or a window in it lie
// on a voxel face or centre, up to a voxel off the wall's plane (2–5 cm at plan scale). The voxels of the
// opening's layer then carry the cell of the room beyond the wall, and so would the strip of the wall's
// neighbours between the portal and the wall (a wall meeting it at a corner, the floor under a door): a
// column of texels lit in the wrong room. The scene's faces say where the wall is; the voxels cannot.
#pragma once

#include "core/context.h"
#include "core/scene.h"
#include "decomposition/portals.h"

namespace cpgi::decomp {

struct ThinWallSnap {
  int moved = 0;            ///< portals moved onto a zero-thickness wall's plane
  double largestShift = 0;  ///< metres
};

/// Moves each axis-aligned portal of `set` onto the plane of a zero-thickness wall around it: faces of the
/// scene parallel to the portal, facing both ways in one plane (within 0.5 mm), within 1.5 voxels of the
/// portal's plane and overlapping its quad grown by a voxel. A wall with thickness has its two faces in two
/// planes and is left alone. The voxels of the portal's cells between the old plane and the new, within its
/// quad, are relabelled by the side of the new plane; set.leakingFaces is recounted. Run after
/// mergePortalPieces, before assignTriangles.
ThinWallSnap snapPortalsToThinWalls(const Scene& scene, const GridFrame& frame, PortalSet& set, Context& ctx);

}  // namespace cpgi::decomp
