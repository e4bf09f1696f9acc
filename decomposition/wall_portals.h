// Stage 6d: portals onto the mid-plane of the wall their opening goes through. The portals fitted to the
// voxels lie on a voxel face or centre: up to a voxel off the wall's mid-plane in a thick wall, and as
// far off the plane of a zero-thickness wall (two coincident back-to-back faces, one layer of solid voxels).
// Off the mid-plane, the cut of a door's threshold or a window's sill at the portal leaves a sliver beside
// the scene's own cut, and the voxels of the opening's layer carry the room beyond the wall: the strip of
// a corner wall, of a floor or of a sill between the portal and the wall goes to the other room, its texels
// lit there. The scene's faces say where the wall is; the voxels cannot.
#pragma once

#include "core/context.h"
#include "core/scene.h"
#include "decomposition/portals.h"

namespace cpgi::decomp {

struct WallSnap {
  int moved = 0;            ///< portals moved onto their wall's mid-plane
  double largestShift = 0;  ///< metres
  int fittedToOpening = 0;  ///< portals in their wall's plane with an edge moved onto the opening's
};

/// Moves each portal of `set` along a grid axis (within 8°: a door by a corner is fitted a few degrees askew)
/// onto the mid-plane of the wall around it: the nearest pair of faces of the scene parallel to that axis,
/// overlapping the quad grown by a voxel, one facing back (the wall's face on the portal's back side) and one
/// facing forward at or beyond it, at most `maxThickness` apart, with the quad reaching between them give or
/// take 1.5 voxels and its tilt; the two may be one plane (a zero-thickness wall). The quad is flattened onto
/// that plane as the rectangle round its pressed corners.
/// The voxels of the portal's cells between the old plane and the new, within its quad, are relabelled by the
/// side of the new plane; set.leakingFaces is recounted. Then each portal in its wall's plane as a rectangle
/// along the wall's axes has its edges moved, each by up to a voxel, onto the opening's: a thick wall's
/// reveals (sill, jambs, lintel) or the edges of a zero-thickness wall's faces, unless that uncovers a voxel
/// face between its cells. Run after mergePortalPieces, before assignTriangles.
WallSnap snapPortalsToWalls(const Scene& scene, const GridFrame& frame, double maxThickness, PortalSet& set,
                            Context& ctx);

}  // namespace cpgi::decomp
